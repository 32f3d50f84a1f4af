#pragma once
// Plain structs that flow between the platform shims and the modules, and between modules.
// They hold no pointers into other modules; image buffers are allocated once at start-up and
// reused, so passing a message never allocates.

#include <cstdint>

#include <opencv2/core/mat.hpp>

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::core {

// A rectified stereo pair, 8-bit grayscale, both images the same size.
struct StereoFrame {
  std::int64_t timestamp_ns = 0;
  std::uint64_t sequence = 0;  // frame counter of the camera; gaps mean dropped frames
  double pan_rad = 0.0;        // pan unit angle when the pair was taken
  cv::Mat left;
  cv::Mat right;

  // Allocates both images once (start-up); later captures write into them.
  void allocate(int width_px, int height_px) {
    left.create(height_px, width_px, CV_8UC1);
    right.create(height_px, width_px, CV_8UC1);
  }
};

// One wheel odometry reading: the pose integrated by the wheel encoders in the odometry
// frame (it drifts; the filter takes the motion between two readings).
struct OdometryReading {
  std::int64_t timestamp_ns = 0;
  std::uint64_t sequence = 0;
  Pose2 pose;
};

// Velocity command to the differential drive, already within the robot's limits.
struct DriveCommand {
  double linear_mps = 0.0;
  double angular_rad_s = 0.0;
};

}  // namespace stereoscout::core
