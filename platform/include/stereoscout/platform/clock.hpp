#pragma once
// The scheduler's time: virtual in simulation and replay (results never depend on wall-clock
// time), monotonic on the robot.
#include <cstdint>

#include "stereoscout/core/logging.hpp"

namespace stereoscout::platform {

class Clock : public core::TimeSource {
 public:
  // now_ns() comes from core::TimeSource.
  // Returns when now_ns() >= deadline_ns (a virtual clock jumps there at once).
  virtual void sleep_until(std::int64_t deadline_ns) = 0;
};

}  // namespace stereoscout::platform
