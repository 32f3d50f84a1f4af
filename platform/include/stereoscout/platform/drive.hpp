#pragma once
// Differential drive.
#include "stereoscout/core/messages.hpp"
#include "stereoscout/core/status.hpp"

namespace stereoscout::platform {

class Drive {
 public:
  virtual ~Drive() = default;
  virtual core::Status command(const core::DriveCommand& command) = 0;
  // Zero velocity at once (emergency stop path); must not fail silently.
  virtual core::Status stop() = 0;
};

}  // namespace stereoscout::platform
