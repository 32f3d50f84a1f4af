#include "stereoscout/scheduler/scheduler.hpp"

#include <cmath>
#include <limits>

#include "stereoscout/core/check.hpp"

namespace stereoscout::scheduler {
namespace {
constexpr double kNanosecondsPerSecond = 1e9;
constexpr std::int64_t kNanosecondsPerMicrosecond = 1000;
}  // namespace

Scheduler::Scheduler(const TaskSpec* tasks, std::size_t count, const core::TimeSource& clock,
                     const core::TimeSource& stopwatch)
    : tasks_(count), clock_(clock), stopwatch_(stopwatch) {
  const std::int64_t start_ns = clock.now_ns();
  for (std::size_t i = 0; i < count; ++i) {
    STEREOSCOUT_CHECK(tasks[i].run != nullptr, "scheduler task without a function");
    STEREOSCOUT_CHECK(tasks[i].rate_hz > 0.0 && std::isfinite(tasks[i].rate_hz), "scheduler task rate must be > 0");
    Task* task = tasks_.emplace_back();
    task->spec = tasks[i];
    task->period_ns = static_cast<std::int64_t>(std::llround(kNanosecondsPerSecond / tasks[i].rate_hz));
    task->next_due_ns = start_ns;
    task->counters.name = tasks[i].name;
    task->counters.budget_us = tasks[i].budget_us;
  }
}

bool Scheduler::loop_is_behind(std::int64_t now_ns) const {
  for (const Task& task : tasks_) {
    if (task.spec.policy == OverloadPolicy::never_skip && now_ns - task.next_due_ns >= task.period_ns) {
      return true;
    }
  }
  return false;
}

std::int64_t Scheduler::run_due() {
  behind_ = false;
  for (Task& task : tasks_) {
    const std::int64_t now_ns = clock_.now_ns();  // earlier tasks of this pass moved it
    if (now_ns < task.next_due_ns) {
      continue;
    }
    // Checked just before each deferrable task: a long task earlier in this pass can have
    // made the loop late.
    if (task.spec.policy == OverloadPolicy::deferrable && loop_is_behind(now_ns)) {
      behind_ = true;
      ++task.counters.deferred;
      continue;  // stays due: it runs once the loop has caught up
    }
    run_task(task);
    schedule_next(task, clock_.now_ns());
  }
  return next_due_ns();
}

void Scheduler::run_task(Task& task) {
  const std::int64_t started_ns = stopwatch_.now_ns();
  const core::Status status = task.spec.run(task.spec.context);
  const std::int64_t took_us = (stopwatch_.now_ns() - started_ns) / kNanosecondsPerMicrosecond;
  ++task.counters.runs;
  if (!status.ok()) {
    ++task.counters.failures;
  }
  if (took_us > task.spec.budget_us) {
    ++task.counters.overruns;
  }
  task.durations.add(took_us);
}

void Scheduler::schedule_next(Task& task, std::int64_t now_ns) {
  task.next_due_ns += task.period_ns;
  if (task.next_due_ns <= now_ns) {
    // Late by whole periods: those runs are not made up (a burst of stale captures helps
    // nobody); count them and keep the phase.
    const std::int64_t missed = (now_ns - task.next_due_ns) / task.period_ns + 1;
    task.counters.missed_periods += static_cast<std::uint64_t>(missed);
    task.next_due_ns += missed * task.period_ns;
  }
}

std::int64_t Scheduler::next_due_ns() const {
  std::int64_t earliest = std::numeric_limits<std::int64_t>::max();
  for (const Task& task : tasks_) {
    if (task.next_due_ns < earliest) {
      earliest = task.next_due_ns;
    }
  }
  return earliest;
}

TaskStats Scheduler::stats(std::size_t task) const {
  const Task& entry = tasks_[task];
  TaskStats result = entry.counters;
  result.median_us = entry.durations.quantile_us(0.5);
  result.p99_us = entry.durations.quantile_us(0.99);
  result.max_us = entry.durations.max_us();
  result.period_ns = entry.period_ns;
  result.next_due_ns = entry.next_due_ns;
  return result;
}

}  // namespace stereoscout::scheduler
