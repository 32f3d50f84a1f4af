#pragma once
// Digital lines: emergency stop input, motor enable output.
#include "stereoscout/core/status.hpp"

namespace stereoscout::platform {

class Gpio {
 public:
  virtual ~Gpio() = default;
  // True while the emergency stop is pressed (or its line cannot be read: fail safe).
  virtual bool emergency_stop_active() = 0;
  virtual core::Status set_motor_enable(bool enabled) = 0;
};

}  // namespace stereoscout::platform
