#pragma once
// The robot's clock: CLOCK_MONOTONIC (never jumps with NTP or the user setting the time).
#include "stereoscout/platform/clock.hpp"

namespace stereoscout::robot_pc {

class MonotonicClock final : public platform::Clock {
 public:
  std::int64_t now_ns() const override;
  void sleep_until(std::int64_t deadline_ns) override;
};

}  // namespace stereoscout::robot_pc
