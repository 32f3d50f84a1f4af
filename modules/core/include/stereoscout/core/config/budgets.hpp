#pragma once
// Config section `budgets`: rate and time budget of every task in the tick table. The
// scheduler counts a run longer than its budget as an overrun; see docs/architecture.md.
#include <array>

#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

struct TaskBudget {
  double rate_hz;
  std::int64_t budget_us;
};

struct BudgetsConfig {
  // One entry per task, in the order of the tick table.
  static constexpr std::size_t kTaskCount = 8;
  static constexpr std::array<const char*, kTaskCount> kTaskNames = {
      "safety", "capture", "odometry", "observation_update", "grid_rollup", "replan", "drive", "logging"};
  std::array<TaskBudget, kTaskCount> tasks = {{
      {50.0, 200},       // safety: e-stop line and motor enable
      {15.0, 5000},      // capture: one stereo pair into a preallocated buffer
      {5.4, 500},        // odometry: read and integrate one reading
      // observation_update: SIFT, matching, RBPF. At most 2 Hz: the paper's robot managed
      // about 1.1 Hz, and its 7 cm trigger fires at 1.7 Hz at full speed; faster only adds
      // views while the pan unit turns (docs/results.md: 5 Hz doubled the work, same ATE).
      {2.0, 700000},
      {2.0, 50000},      // grid_rollup: just-in-time grid for the ML particle, after each update
      {2.0, 100000},     // replan: plan check, A*, goal selection
      {20.0, 1000},      // drive: path follower
      {15.0, 2000},      // logging: hand records to the log writer
  }};
};

inline void describe(ConfigVisitor& v, BudgetsConfig& c) {
  v.begin_section("budgets", "Rate and worst-case time of each task of the tick table; runs over budget are counted as overruns.");
  for (std::size_t i = 0; i < BudgetsConfig::kTaskCount; ++i) {
    v.begin_section(BudgetsConfig::kTaskNames[i], "One task of the tick table.");
    v.number("rate_hz", c.tasks[i].rate_hz, {0.01, 1000.0, "Hz", "How often the task runs."});
    v.integer_field("budget_us", c.tasks[i].budget_us, {1, 100000000, "us", "Worst-case time allowed for one run."});
    v.end_section();
  }
  v.end_section();
}

}  // namespace stereoscout::core
