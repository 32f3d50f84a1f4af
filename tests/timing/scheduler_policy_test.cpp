// The scheduler's overload policy and accounting, on a virtual clock: every task "takes"
// the time the test injects by advancing the clock, so results are exact and repeatable.
#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <string>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/scheduler/scheduler.hpp"

namespace stereoscout::scheduler {
namespace {

constexpr std::int64_t kMs = 1'000'000;

class VirtualClock final : public core::TimeSource {
 public:
  std::int64_t now_ns() const override { return now_; }
  void advance(std::int64_t ns) { now_ += ns; }
  void advance_to(std::int64_t ns) {
    if (ns > now_) {
      now_ = ns;
    }
  }

 private:
  std::int64_t now_ = 0;
};

// A task whose cost is chosen per run by the test.
struct InjectedTask {
  VirtualClock* clock = nullptr;
  std::int64_t cost_ns = 100'000;                        // default 0.1 ms
  std::function<std::int64_t(std::uint64_t)> cost_of_run;  // run index -> cost, if set
  std::uint64_t runs = 0;
  core::Status status = core::Status::success();

  static core::Status run(void* context) {
    auto* self = static_cast<InjectedTask*>(context);
    self->clock->advance(self->cost_of_run ? self->cost_of_run(self->runs) : self->cost_ns);
    ++self->runs;
    return self->status;
  }
};

enum TaskIndex { safety, capture, odometry, observation_update, replan, logging, kTaskCount };

// The stack's tick table in miniature, with the stack's rates and budgets.
struct Fixture {
  VirtualClock clock;
  std::array<InjectedTask, kTaskCount> tasks;
  std::array<TaskSpec, kTaskCount> table;

  Fixture() {
    for (InjectedTask& task : tasks) {
      task.clock = &clock;
    }
    table[safety] = {"safety", 50.0, 200, OverloadPolicy::never_skip, &InjectedTask::run, &tasks[safety]};
    table[capture] = {"capture", 15.0, 5000, OverloadPolicy::never_skip, &InjectedTask::run, &tasks[capture]};
    table[odometry] = {"odometry", 5.0, 500, OverloadPolicy::never_skip, &InjectedTask::run, &tasks[odometry]};
    table[observation_update] = {"observation_update", 5.0, 200'000, OverloadPolicy::deferrable, &InjectedTask::run,
                                 &tasks[observation_update]};
    table[replan] = {"replan", 2.0, 100'000, OverloadPolicy::deferrable, &InjectedTask::run, &tasks[replan]};
    table[logging] = {"logging", 15.0, 2000, OverloadPolicy::never_skip, &InjectedTask::run, &tasks[logging]};
  }

  // Runs the loop on the virtual clock until `end_ns`.
  void run_until(Scheduler& scheduler, std::int64_t end_ns) {
    while (clock.now_ns() < end_ns) {
      clock.advance_to(scheduler.run_due());
    }
  }
};

std::uint64_t periods_in(double seconds, double rate_hz) { return static_cast<std::uint64_t>(seconds * rate_hz); }

TEST(SchedulerPolicy, NominalLoadRunsEveryTaskAtItsRate) {
  Fixture fixture;
  Scheduler scheduler(fixture.table.data(), kTaskCount, fixture.clock, fixture.clock);
  fixture.run_until(scheduler, 10'000 * kMs);
  for (std::size_t i = 0; i < kTaskCount; ++i) {
    const TaskStats stats = scheduler.stats(i);
    EXPECT_NEAR(static_cast<double>(stats.runs), static_cast<double>(periods_in(10.0, fixture.table[i].rate_hz)), 1.0)
        << stats.name;
    EXPECT_EQ(stats.overruns, 0u) << stats.name;
    EXPECT_EQ(stats.deferred, 0u) << stats.name;
    EXPECT_EQ(stats.missed_periods, 0u) << stats.name;
    EXPECT_EQ(stats.median_us, 100) << stats.name;
    EXPECT_EQ(stats.max_us, 100) << stats.name;
  }
}

TEST(SchedulerPolicy, OverloadDefersUpdatesButNeverCaptureOdometrySafetyOrLogging) {
  Fixture fixture;
  // 150% of the CPU: captures (a slow camera driver) take 75%, updates 75% more.
  fixture.tasks[capture].cost_ns = 50 * kMs;
  fixture.tasks[observation_update].cost_ns = 150 * kMs;
  fixture.tasks[replan].cost_ns = 100 * kMs;
  Scheduler scheduler(fixture.table.data(), kTaskCount, fixture.clock, fixture.clock);
  fixture.run_until(scheduler, 20'000 * kMs);

  const TaskStats update = scheduler.stats(observation_update);
  EXPECT_GT(update.deferred, 0u);
  EXPECT_GT(scheduler.stats(replan).deferred, 0u);
  EXPECT_EQ(update.max_us, 150'000);
  for (std::size_t i = 0; i < kTaskCount; ++i) {
    const TaskStats stats = scheduler.stats(i);
    if (fixture.table[i].policy == OverloadPolicy::never_skip) {
      EXPECT_EQ(stats.deferred, 0u) << stats.name;
    }
    // Accounting: every period up to the next due time either ran or is counted as missed.
    EXPECT_EQ(static_cast<std::int64_t>(stats.runs + stats.missed_periods), stats.next_due_ns / stats.period_ns)
        << stats.name;
  }
  // Between two heavy runs the loop catches up: capture runs at least once per update.
  EXPECT_GE(scheduler.stats(capture).runs, update.runs);
}

TEST(SchedulerPolicy, StuckTaskIsCountedAndTheLoopRecovers) {
  Fixture fixture;
  fixture.tasks[replan].cost_of_run = [](std::uint64_t run) { return run == 2 ? 5'000 * kMs : 100'000; };
  Scheduler scheduler(fixture.table.data(), kTaskCount, fixture.clock, fixture.clock);
  fixture.run_until(scheduler, 10'000 * kMs);
  const TaskStats replan_stats = scheduler.stats(replan);
  EXPECT_EQ(replan_stats.overruns, 1u);
  EXPECT_EQ(replan_stats.max_us, 5'000'000);
  const TaskStats safety_stats = scheduler.stats(safety);
  EXPECT_NEAR(static_cast<double>(safety_stats.missed_periods), 5.0 * 50.0, 2.0);  // the 5 s stall
  // After the stall everything runs at its rate again: the last 4 s look nominal.
  const std::uint64_t safety_runs_before = safety_stats.runs;
  const std::uint64_t update_runs_before = scheduler.stats(observation_update).runs;
  fixture.run_until(scheduler, 14'000 * kMs);
  EXPECT_NEAR(static_cast<double>(scheduler.stats(safety).runs - safety_runs_before), 4.0 * 50.0, 1.0);
  EXPECT_NEAR(static_cast<double>(scheduler.stats(observation_update).runs - update_runs_before), 4.0 * 5.0, 1.0);
  EXPECT_EQ(scheduler.stats(safety).missed_periods, safety_stats.missed_periods);
}

TEST(SchedulerPolicy, BurstOfFramesDefersDeferrableWorkUntilCaughtUp) {
  Fixture fixture;
  // Ten captures in a row each drain a backlog of frames: 90 ms against a 66 ms period.
  fixture.tasks[capture].cost_of_run = [](std::uint64_t run) {
    return run >= 20 && run < 30 ? 90 * kMs : 100'000;
  };
  Scheduler scheduler(fixture.table.data(), kTaskCount, fixture.clock, fixture.clock);
  fixture.run_until(scheduler, 10'000 * kMs);
  EXPECT_EQ(scheduler.stats(capture).overruns, 10u);
  EXPECT_GT(scheduler.stats(observation_update).deferred, 0u);
  EXPECT_EQ(scheduler.stats(capture).deferred, 0u);
  EXPECT_GT(scheduler.stats(safety).missed_periods, 0u);
  // Afterwards updates run at their rate: far more runs than the burst took away.
  EXPECT_GT(scheduler.stats(observation_update).runs, 40u);
}

TEST(SchedulerPolicy, FailuresAreCountedPerTask) {
  Fixture fixture;
  fixture.tasks[capture].status = {core::StatusCode::timeout, "camera timeout"};
  Scheduler scheduler(fixture.table.data(), kTaskCount, fixture.clock, fixture.clock);
  fixture.run_until(scheduler, 1'000 * kMs);
  EXPECT_EQ(scheduler.stats(capture).failures, scheduler.stats(capture).runs);
  EXPECT_EQ(scheduler.stats(safety).failures, 0u);
}

TEST(SchedulerPolicy, SameCostsGiveIdenticalAccounting) {
  auto run_once = [] {
    Fixture fixture;
    fixture.tasks[observation_update].cost_of_run = [](std::uint64_t run) { return (run % 7) * 60 * kMs; };
    Scheduler scheduler(fixture.table.data(), kTaskCount, fixture.clock, fixture.clock);
    fixture.run_until(scheduler, 30'000 * kMs);
    std::string summary;
    for (std::size_t i = 0; i < kTaskCount; ++i) {
      const TaskStats stats = scheduler.stats(i);
      summary += std::to_string(stats.runs) + "/" + std::to_string(stats.deferred) + "/" +
                 std::to_string(stats.missed_periods) + "/" + std::to_string(stats.overruns) + " ";
    }
    return summary;
  };
  EXPECT_EQ(run_once(), run_once());
}

TEST(SchedulerPolicy, RunningTheLoopDoesNotAllocate) {
  Fixture fixture;
  Scheduler scheduler(fixture.table.data(), kTaskCount, fixture.clock, fixture.clock);
  fixture.run_until(scheduler, 100 * kMs);
  core::AllocationScope scope;
  fixture.run_until(scheduler, 5'000 * kMs);
  EXPECT_EQ(scope.allocations(), 0u);
}

}  // namespace
}  // namespace stereoscout::scheduler
