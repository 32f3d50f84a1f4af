#pragma once
// Plain structs that flow between the platform shims and the modules, and between modules.
// They hold no pointers into other modules; image buffers are allocated once at start-up and
// reused, so passing a message never allocates.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

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

// One stereo landmark observation handed from the vision front end to the filter: the
// identity the descriptor index gave it, and its 3D point with covariance in the camera's
// optical frame (paper eq. 3 and 4).
struct LandmarkObservation {
  std::uint32_t landmark_id = 0;
  Eigen::Vector3d point_camera = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
};

// The 2.5D obstacle scan of one stereo pair (paper V): for each image column, the nearest
// point above the floor and below the robot's height, or the farthest floor point seen
// free. Points are on the floor plane in the robot frame at capture time (pan included), so
// the occupancy grid ray-casts from `origin_robot` to each end point.
struct DepthScanColumn {
  enum class Kind : std::uint8_t { invalid = 0, obstacle = 1, free = 2 };
  float x_robot_m = 0.0F;
  float y_robot_m = 0.0F;
  Kind kind = Kind::invalid;
  // Distance on the floor from `origin_robot` at which this column's floor becomes visible:
  // the camera cannot see the floor (nor a low obstacle on it) nearer than that, so the grid
  // does not clear cells there (0: visible from the origin).
  float floor_visible_from_m = 0.0F;
  // An obstacle that also stands at the camera's height (a person, a wall, a cupboard; not a
  // low box nor a table top): it is in view at every range inside the field of view, the
  // blind zone included, so a later view through its cell that does not see it means it has
  // gone (a person walked on).
  bool obstacle_at_camera_height = false;
  // Distance on the floor from `origin_robot` nearer than which this column cannot measure
  // anything at all: the matcher's largest disparity, and near the image's edge the part of
  // the view the other camera does not share. The grid changes no cell nearer than that.
  float measurable_from_m = 0.0F;
  // A free column: the standard deviation of its end point's range from the disparity error
  // (the farthest floor point may lie beyond the wall behind it by about this); 0 otherwise.
  float end_range_sigma_m = 0.0F;
  // An obstacle column put where a blank wall meets the floor, a surface stereo did not
  // measure (it would stand at the camera's height too had it any texture): at its base's
  // brightness step, or where the matched floor ends under a view the matcher found blank
  // (0.3-0.6 m short of the wall, or where stereo was confused).
  enum class BlankWall : std::uint8_t { no = 0, base = 1, floor_end = 2 };
  BlankWall blank_wall = BlankWall::no;
};

struct DepthScan {
  std::int64_t timestamp_ns = 0;
  Eigen::Vector2d origin_robot = Eigen::Vector2d::Zero();  // camera centre on the floor plane
  // Sized once at start-up (one entry per image column) and overwritten in place.
  std::vector<DepthScanColumn> columns;
};

}  // namespace stereoscout::core
