#pragma once
// A rectified stereo camera. One implementation per target (simulator, log replay, V4L2).
#include "stereoscout/core/messages.hpp"
#include "stereoscout/core/status.hpp"

namespace stereoscout::platform {

class Camera {
 public:
  virtual ~Camera() = default;
  // Fills `frame` (whose images were allocated at start-up) with the newest pair.
  // not_available: no new pair yet; timeout / io_error: the device failed, counted by the caller.
  virtual core::Status capture(core::StereoFrame& frame) = 0;
  // Points the pan unit (if any) at `pan_rad`; the frame reports the angle actually reached.
  virtual void command_pan(double pan_rad) = 0;
};

}  // namespace stereoscout::platform
