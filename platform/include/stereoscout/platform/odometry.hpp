#pragma once
// Wheel odometry source.
#include "stereoscout/core/messages.hpp"
#include "stereoscout/core/status.hpp"

namespace stereoscout::platform {

class Odometry {
 public:
  virtual ~Odometry() = default;
  // The next reading, if one arrived since the last call (else not_available).
  virtual core::Status read(core::OdometryReading& reading) = 0;
};

}  // namespace stereoscout::platform
