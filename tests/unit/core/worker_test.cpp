#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <thread>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/core/worker.hpp"

namespace stereoscout::core {
namespace {

struct Tally {
  std::uint64_t runs = 0;
  std::uint64_t sum = 0;
  std::thread::id ran_on;
};

void count(void* context) {
  auto* tally = static_cast<Tally*>(context);
  tally->ran_on = std::this_thread::get_id();
  ++tally->runs;
  for (std::uint64_t i = 1; i <= 1000; ++i) tally->sum += i;
}

TEST(Worker, RunsTheJobOnItsOwnThreadAndWaitSeesWhatItWrote) {
  Worker worker;
  Tally tally;
  worker.start(count, &tally);
  worker.wait();
  EXPECT_FALSE(worker.busy());
  EXPECT_EQ(tally.runs, 1U);
  EXPECT_EQ(tally.sum, 500500U);
  EXPECT_NE(tally.ran_on, std::this_thread::get_id());
}

TEST(Worker, JobAfterJobNoneLostAndNoAllocation) {
  Worker worker;
  Tally tally;
  const AllocationScope scope;
  for (int i = 0; i < 2000; ++i) {
    worker.start(count, &tally);
    worker.wait();
    ASSERT_EQ(tally.runs, static_cast<std::uint64_t>(i + 1));
  }
  EXPECT_EQ(scope.allocations(), 0U);
  EXPECT_EQ(tally.sum, 2000U * 500500U);
}

TEST(Worker, WaitWithoutAJobReturnsAtOnce) {
  Worker worker;
  worker.wait();
  EXPECT_FALSE(worker.busy());
}

// The caller goes on while the job runs: the job blocks until the caller releases it, then
// works a little longer before it says it has finished.
struct Gate {
  std::atomic<bool> started{false};
  std::atomic<bool> released{false};
  std::atomic<bool> finished{false};
};

void wait_for_release(void* context) {
  auto* gate = static_cast<Gate*>(context);
  gate->started = true;
  while (!gate->released.load()) std::this_thread::yield();
  for (int i = 0; i < 100; ++i) std::this_thread::yield();
  gate->finished = true;
}

TEST(Worker, TheCallerGoesOnWhileTheJobRunsAndTheDestructorWaitsForIt) {
  Gate gate;
  {
    Worker worker;
    worker.start(wait_for_release, &gate);
    EXPECT_TRUE(worker.busy());  // the job cannot end before the release below
    EXPECT_FALSE(gate.finished.load());
    gate.released = true;
  }  // the destructor waits for the job, then stops the thread
  EXPECT_TRUE(gate.released.load());
  EXPECT_TRUE(gate.finished.load());  // the job has finished when the destructor returns
}

TEST(WorkerDeathTest, SecondStartWhileBusyIsAProgrammingError) {
  // The default ("fast") style forks without re-executing the binary, which the "threadsafe"
  // style needs and an emulated cross build cannot do. Forking while the worker's thread holds
  // the worker's lock would deadlock the child, so the fork waits until the job runs: from then
  // until the release the thread holds nothing.
  Gate gate;
  Worker worker;
  worker.start(wait_for_release, &gate);
  while (!gate.started.load()) std::this_thread::yield();
  EXPECT_DEATH(worker.start(wait_for_release, &gate), "still running");
  gate.released = true;
  worker.wait();
  EXPECT_TRUE(gate.finished.load());
}

}  // namespace
}  // namespace stereoscout::core
