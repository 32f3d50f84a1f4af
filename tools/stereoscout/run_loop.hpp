#pragma once
// Runs a started stack until it ends, showing progress on a terminal (simulated or robot
// time, coverage where the ground truth is known, landmarks, updates and their rate) and
// staying quiet when stderr is not a terminal (CI, scripts, pipes).

#include <functional>

#include "stereoscout/stack/stack.hpp"

namespace stereoscout::cli {

struct LoopHooks {
  std::function<double()> coverage;          // fraction 0..1, or empty when unknown
  std::function<bool()> should_stop;         // e.g. a replayed log ran out, Ctrl-C
  // Called every `sample_period_s` of the run's clock (and at the end): e.g. the coverage
  // curve of report.json. The clock is virtual in simulation, so the samples are too.
  std::function<void(double time_s)> sample;
  double sample_period_s = 30.0;
  // Called after every tick, outside the tick's allocation scope: e.g. snapshots of the
  // navigation grid at chosen times (stereoscout explore --snapshot-at).
  std::function<void(double time_s)> after_tick;
};

void run_to_end(stack::Stack& stack, const LoopHooks& hooks);

}  // namespace stereoscout::cli
