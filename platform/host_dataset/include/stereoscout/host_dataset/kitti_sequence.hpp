#pragma once
// A folder in the KITTI odometry layout (Geiger et al., CVPR 2012):
//
//   image_0/NNNNNN.png  left camera (cam0), rectified 8-bit grey
//   image_1/NNNNNN.png  right camera (cam1), same size
//   calib.txt           "P0: ..." and "P1: ...", 3x4 rectified projections, row-major
//   times.txt           seconds since the start, one line per frame, increasing
//   poses.txt           optional ground truth: 3x4 [R|t] row-major per frame, the pose of cam0
//                       in the world (world = cam0 at frame 0; x right, y down, z forward)
//
// Frame conventions. Our stereo reference is the RIGHT camera (vision/calibration.hpp), so
// the robot of a dataset run IS the right camera projected onto the ground plane: robot
// x forward = camera z, robot y left = -camera x, robot z up = -camera y, yaw about the
// camera's -y axis. Ground truth is moved from cam0 to cam1 (a baseline to the right) before
// it is projected. Host tool code: it reads whole files into vectors and may allocate.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::host_dataset {

// The rectified stereo head of calib.txt: fx of P0, principal point of P0, baseline from
// P1[0][3] = -f B. Image size comes from the first image.
struct KittiCalibration {
  double focal_px = 0.0;
  double principal_x_px = 0.0;
  double principal_y_px = 0.0;
  double baseline_m = 0.0;
  int width_px = 0;
  int height_px = 0;
};

struct KittiSequence {
  std::string folder;
  KittiCalibration calibration;
  std::vector<double> times_s;                        // one per frame
  std::vector<Eigen::Isometry3d> world_from_cam0;     // empty when poses.txt is absent
  bool has_ground_truth() const { return !world_from_cam0.empty(); }
  std::size_t frames() const { return times_s.size(); }
};

// Parsers of the three text files. On failure they return false and set `error` to
// "<file>:<line>: <what is wrong>" (`name` is the file name used in the message).
bool parse_kitti_calibration(const std::string& text, const std::string& name, KittiCalibration& calibration,
                             std::string& error);
bool parse_kitti_times(const std::string& text, const std::string& name, std::vector<double>& times_s,
                       std::string& error);
bool parse_kitti_poses(const std::string& text, const std::string& name, std::vector<Eigen::Isometry3d>& poses,
                       std::string& error);

// Reads calib.txt, times.txt, poses.txt (if present) and the size of frame 0's images.
// `max_frames` > 0 keeps only that prefix. Fails with a message naming the file (and line).
bool load_kitti_sequence(const std::string& folder, std::size_t max_frames, KittiSequence& sequence,
                         std::string& error);

// "<folder>/image_0/000042.png" (camera 0 = left) or image_1 (right).
std::string kitti_image_path(const std::string& folder, int camera, std::size_t frame);

// The ground-plane pose of a camera whose optical frame is `world_from_camera` in KITTI's
// world (x right, y down, z forward): x = z_cam, y = -x_cam, yaw about -y.
core::Pose2 ground_pose_from_camera(const Eigen::Isometry3d& world_from_camera);

// The right camera (cam1) of a KITTI ground-truth pose of cam0: a baseline along cam0's x.
Eigen::Isometry3d right_camera_from_left(const Eigen::Isometry3d& world_from_cam0, double baseline_m);

// Ground-truth robot poses (right camera on the ground plane), one per frame.
std::vector<core::Pose2> ground_truth_robot_poses(const KittiSequence& sequence);

}  // namespace stereoscout::host_dataset
