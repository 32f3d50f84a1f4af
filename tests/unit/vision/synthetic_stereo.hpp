#pragma once
// A tiny ray-casting renderer for vision tests: a textured floor (z = 0) and axis-aligned
// boxes in the world frame, seen by the rectified stereo head on a robot at a known pose.
// The texture is smooth value noise of the 3D surface point, so both cameras see the same
// surface pattern and every pixel has a known depth. Independent of the simulator.

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"
#include "stereoscout/vision/calibration.hpp"

namespace stereoscout::vision::test {

struct Box {
  Eigen::Vector3d min_corner;
  Eigen::Vector3d max_corner;
};

struct Scene {
  bool has_floor = true;
  std::vector<Box> boxes;
  std::uint32_t texture_seed = 1;
};

struct Rendering {
  core::StereoFrame frame;
  cv::Mat right_depth;  // CV_64F: optical-frame Z of the right camera's pixel, 0 where nothing is hit
  cv::Mat left_depth;
  Eigen::Isometry3d world_from_right_camera = Eigen::Isometry3d::Identity();
};

// Texture intensity (0..255) of a surface point.
double surface_texture(const Scene& scene, const Eigen::Vector3d& point);

// Renders both images for a robot at `robot_pose` (world frame) with the camera on `mount`
// turned by `pan_rad`.
Rendering render(const Scene& scene, const StereoCalibration& calibration, const core::CameraMount& mount,
                 const core::Pose2& robot_pose, double pan_rad = 0.0);

// A room-like scene: floor, textured walls around, and a few boxes; used by several tests.
Scene textured_room();

}  // namespace stereoscout::vision::test
