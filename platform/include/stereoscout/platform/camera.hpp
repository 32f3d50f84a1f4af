#pragma once
// A rectified stereo camera. One implementation per target (simulator, log replay, V4L2).
#include "stereoscout/core/messages.hpp"
#include "stereoscout/core/status.hpp"

namespace stereoscout::platform {

class Camera {
 public:
  virtual ~Camera() = default;
  // Takes the newest pair: its timestamp, sequence and pan angle into `frame`, and its images
  // unless the camera defers them to retrieve(). The stack keeps one pair in several (only
  // when the camera moved, paper section II), so a camera whose images cost work of their
  // own (the simulator renders them) does that work only for the pairs asked for.
  // not_available: no new pair yet; timeout / io_error: the device failed, counted by the caller.
  virtual core::Status grab(core::StereoFrame& frame) = 0;
  // Fills `frame`'s images (allocated at start-up) with the pair of the last successful grab()
  // into it, before the next grab(). A camera whose grab() fills them already does nothing.
  virtual core::Status retrieve(core::StereoFrame& frame) {
    static_cast<void>(frame);
    return core::Status::success();
  }
  // grab() and retrieve(): the newest pair, whole.
  core::Status capture(core::StereoFrame& frame) {
    const core::Status grabbed = grab(frame);
    return grabbed.ok() ? retrieve(frame) : grabbed;
  }
  // Points the pan unit (if any) at `pan_rad`; the frame reports the angle actually reached.
  virtual void command_pan(double pan_rad) = 0;
};

}  // namespace stereoscout::platform
