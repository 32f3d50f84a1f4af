#pragma once
// The robot's stereo camera (platform::Camera) over V4L2: two synchronised devices whose
// frames are paired by timestamp, or one device delivering left|right side by side.
//
// grab() never waits. It takes what the drivers have ready, pairs left and right frames
// whose timestamps agree within the tolerance, drops (and counts) a frame that has no
// partner, counts driver sequence gaps as dropped frames, and reports a timeout once no pair
// has arrived for the configured time. It converts the pair into the frame's images at once
// (the driver's buffers go back to it), so retrieve() has nothing left to do.

#include <cstdint>
#include <string>

#include "stereoscout/core/logging.hpp"
#include "stereoscout/platform/camera.hpp"
#include "stereoscout/robot_pc/video_device.hpp"

namespace stereoscout::robot_pc {

struct StereoCaptureOptions {
  int width_px = 640;   // of one image
  int height_px = 480;
  int buffers = 4;
  std::int64_t pair_tolerance_ns = 10'000'000;
  std::int64_t timeout_ns = 200'000'000;
};

struct StereoCaptureStats {
  std::uint64_t pairs = 0;
  std::uint64_t unpaired_dropped = 0;  // frames discarded for want of a partner
  std::uint64_t driver_dropped = 0;    // frames the driver skipped (sequence gaps)
  std::uint64_t timeouts = 0;          // grab() calls that reported a timeout
  std::uint64_t bad_frames = 0;        // buffers too short for the format
  std::uint64_t device_errors = 0;
  std::uint64_t pan_commands_ignored = 0;
};

class StereoCapture final : public platform::Camera {
 public:
  // Two devices.
  StereoCapture(VideoDevice& left, VideoDevice& right, const core::TimeSource& clock,
                const StereoCaptureOptions& options);
  // One side-by-side device (left image in the left half).
  StereoCapture(VideoDevice& side_by_side, const core::TimeSource& clock, const StereoCaptureOptions& options);

  // Negotiates formats and starts streaming. On failure `error` names the device.
  bool start(std::string& error);
  void stop();

  core::Status grab(core::StereoFrame& frame) override;
  // robot_pc drives no pan unit: the command is counted and the frame reports pan 0.
  void command_pan(double pan_rad) override;

  const StereoCaptureStats& stats() const { return stats_; }

 private:
  struct Side {
    VideoDevice* device = nullptr;
    VideoFormat format;
    RawFrame pending;
    bool has_pending = false;
    bool seen_any = false;
    std::uint32_t last_sequence = 0;
  };
  core::Status fill_pending(Side& side);
  void drop_pending(Side& side);
  core::Status capture_pair(core::StereoFrame& frame);
  core::Status capture_side_by_side(core::StereoFrame& frame);
  core::Status no_pair_yet();
  // Counts a converted pair and stamps it; false (counted as a bad frame) if conversion failed.
  bool finish_pair(bool converted, std::int64_t timestamp_ns, core::StereoFrame& frame);
  void count_sequence(Side& side, std::uint32_t sequence);

  Side left_;
  Side right_;
  bool side_by_side_ = false;
  const core::TimeSource& clock_;
  StereoCaptureOptions options_;
  std::int64_t last_pair_ns_ = 0;
  std::uint64_t pair_sequence_ = 0;
  StereoCaptureStats stats_;
};

}  // namespace stereoscout::robot_pc
