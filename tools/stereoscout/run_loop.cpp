#include "run_loop.hpp"

#include <chrono>
#include <cstdio>

#include <unistd.h>

namespace stereoscout::cli {
namespace {

constexpr double kProgressPeriodS = 1.0;  // wall seconds between two progress lines

void show_progress(const stack::Stack& stack, const LoopHooks& hooks, double wall_s) {
  char coverage[32] = "-";
  if (hooks.coverage) std::snprintf(coverage, sizeof coverage, "%.1f%%", 100.0 * hooks.coverage());
  const double updates = static_cast<double>(stack.counters().updates);
  std::fprintf(stderr, "\r  t %7.1f s   coverage %6s   landmarks %6zu   updates %6.0f (%.1f/s wall)   %-12s",
               stack.time_s(), coverage, stack.landmark_count(), updates, wall_s > 0.0 ? updates / wall_s : 0.0,
               explore::to_string(stack.explorer().state()));
  std::fflush(stderr);
}

}  // namespace

void run_to_end(stack::Stack& stack, const LoopHooks& hooks) {
  const bool on_terminal = ::isatty(STDERR_FILENO) == 1;
  const auto wall_start = std::chrono::steady_clock::now();
  double next_progress_s = 0.0;
  double next_sample_s = 0.0;
  while (stack.tick()) {
    if (hooks.should_stop && hooks.should_stop()) stack.request_stop();
    if (hooks.after_tick) hooks.after_tick(stack.time_s());
    if (hooks.sample && stack.time_s() >= next_sample_s) {
      hooks.sample(stack.time_s());
      next_sample_s += hooks.sample_period_s;
    }
    if (!on_terminal) continue;
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    if (wall_s >= next_progress_s) {
      show_progress(stack, hooks, wall_s);
      next_progress_s = wall_s + kProgressPeriodS;
    }
  }
  if (hooks.sample) hooks.sample(stack.time_s());
  if (on_terminal) std::fprintf(stderr, "\n");
}

}  // namespace stereoscout::cli
