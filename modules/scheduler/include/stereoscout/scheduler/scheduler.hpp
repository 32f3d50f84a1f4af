#pragma once
// The static tick scheduler (ArduPilot's AP_Scheduler is the model): one fixed table of
// tasks, each with a rate and a time budget, run in table order when due.
//
// Two clocks, so that results never depend on how fast the machine is:
//  - `clock` decides what is due and whether the loop is behind. It is virtual in simulation
//    and replay (the caller advances it), monotonic on the robot.
//  - `stopwatch` measures how long each run took, for the statistics, overruns and report.
//    In simulation it is the wall clock, and nothing it reads changes what runs.
//
// Overload policy: when a task that must never be skipped (safety, capture, odometry,
// drive, logging) is a whole period late, the loop is behind, and deferrable tasks
// (observation update, grid roll-up, replanning) that are due wait, counted, until it has
// caught up. A run longer than its budget is an overrun, counted per task.

#include <cstddef>
#include <cstdint>

#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/core/logging.hpp"
#include "stereoscout/core/status.hpp"
#include "stereoscout/scheduler/duration_histogram.hpp"

namespace stereoscout::scheduler {

enum class OverloadPolicy : std::uint8_t { never_skip, deferrable };

struct TaskSpec {
  const char* name = "";
  double rate_hz = 1.0;
  std::int64_t budget_us = 1000;
  OverloadPolicy policy = OverloadPolicy::never_skip;
  core::Status (*run)(void* context) = nullptr;
  void* context = nullptr;
};

struct TaskStats {
  const char* name = "";
  std::uint64_t runs = 0;
  std::uint64_t overruns = 0;      // runs longer than the budget
  std::uint64_t deferred = 0;      // times a due deferrable task waited because the loop was behind
  std::uint64_t missed_periods = 0;  // periods that passed without a run (the loop was late)
  std::uint64_t failures = 0;      // runs that returned a status other than ok
  std::int64_t median_us = 0;
  std::int64_t p99_us = 0;
  std::int64_t max_us = 0;
  std::int64_t budget_us = 0;
  std::int64_t period_ns = 0;
  // Accounting: runs + missed_periods == periods from the start up to next_due_ns.
  std::int64_t next_due_ns = 0;
};

class Scheduler {
 public:
  // The table is copied; its size is the capacity. Tasks first fall due at clock.now_ns().
  Scheduler(const TaskSpec* tasks, std::size_t count, const core::TimeSource& clock,
            const core::TimeSource& stopwatch);

  // Runs, in table order, every task due at the clock's time. Returns the clock time at
  // which the next task falls due (sleep until then).
  std::int64_t run_due();
  std::int64_t next_due_ns() const;
  // True when the last pass deferred work because the loop was behind.
  bool behind() const { return behind_; }

  std::size_t task_count() const { return tasks_.size(); }
  TaskStats stats(std::size_t task) const;

 private:
  struct Task {
    TaskSpec spec;
    std::int64_t period_ns = 0;
    std::int64_t next_due_ns = 0;
    TaskStats counters;
    DurationHistogram durations;
  };
  bool loop_is_behind(std::int64_t now_ns) const;
  void run_task(Task& task);
  void schedule_next(Task& task, std::int64_t now_ns);

  core::FixedVector<Task> tasks_;
  const core::TimeSource& clock_;
  const core::TimeSource& stopwatch_;
  bool behind_ = false;
};

}  // namespace stereoscout::scheduler
