#include "stereoscout/vision/obstacle_scan.hpp"

#include <algorithm>
#include <cmath>

#include "stereoscout/core/check.hpp"
#include "stereoscout/vision/dense_disparity.hpp"

namespace stereoscout::vision {

ObstacleScanParams scan_params_from_config(const core::VisionConfig& vision, const core::RobotConfig& robot) {
  ObstacleScanParams params;
  params.floor_tolerance_m = vision.floor_tolerance_m;
  params.robot_height_m = robot.height_m;
  params.max_range_m = vision.scan_max_range_m;
  params.min_obstacle_pixels = vision.scan_min_obstacle_pixels;
  return params;
}

ObstacleScanner::ObstacleScanner(const ObstacleScanParams& params, const StereoCalibration& calibration,
                                 const core::CameraMount& mount)
    : params_(params),
      calibration_(calibration),
      mount_(mount),
      nearest_(static_cast<std::size_t>(std::max(params.min_obstacle_pixels, 1))) {}

void ObstacleScanner::allocate(core::DepthScan& scan) const {
  scan.columns.assign(static_cast<std::size_t>(calibration_.width_px), core::DepthScanColumn{});
}

// Keeps the nearest_.capacity() nearest obstacle points, sorted by range (insertion sort).
void ObstacleScanner::keep_nearest(const Candidate& candidate) {
  if (nearest_.full()) {
    if (candidate.range_m >= nearest_.back().range_m) {
      return;
    }
    nearest_.pop_back();
  }
  nearest_.push_back(candidate);
  for (std::size_t i = nearest_.size() - 1; i > 0 && nearest_[i].range_m < nearest_[i - 1].range_m; --i) {
    std::swap(nearest_[i], nearest_[i - 1]);
  }
}

void ObstacleScanner::compute(const cv::Mat& disparity, double pan_rad, std::int64_t timestamp_ns,
                              core::DepthScan& scan) {
  STEREOSCOUT_CHECK(disparity.type() == CV_32FC1 && disparity.cols == calibration_.width_px &&
                        scan.columns.size() == static_cast<std::size_t>(disparity.cols),
                    "ObstacleScanner::compute: disparity or scan not sized for this camera");
  const Eigen::Isometry3d robot_from_camera = core::robot_from_camera(mount_, pan_rad);
  const Eigen::Vector3d origin = robot_from_camera.translation();
  scan.timestamp_ns = timestamp_ns;
  scan.origin_robot = origin.head<2>();
  for (int x = 0; x < disparity.cols; ++x) {
    nearest_.clear();
    bool has_floor = false;
    Candidate farthest_floor;
    for (int y = disparity.rows - 1; y >= 0; --y) {
      const float d = disparity.at<float>(y, x);
      if (!(d > 0.0F)) {
        continue;  // invalid (kInvalidDisparity) or at infinity
      }
      const Eigen::Vector3d point = robot_from_camera * triangulate_point(calibration_, x - static_cast<double>(d), y, d);
      const double dx = point.x() - origin.x();
      const double dy = point.y() - origin.y();
      const double range = std::hypot(dx, dy);
      if (std::fabs(point.z()) <= params_.floor_tolerance_m) {
        if (!has_floor || range > farthest_floor.range_m) {
          has_floor = true;
          const double capped = std::min(range, params_.max_range_m);
          const double scale = range > 0.0 ? capped / range : 0.0;
          farthest_floor = {capped, origin.x() + dx * scale, origin.y() + dy * scale};
        }
      } else if (point.z() > params_.floor_tolerance_m && point.z() < params_.robot_height_m &&
                 range <= params_.max_range_m) {
        keep_nearest({range, point.x(), point.y()});
      }
    }
    core::DepthScanColumn& column = scan.columns[static_cast<std::size_t>(x)];
    if (nearest_.full()) {
      column = {static_cast<float>(nearest_.back().x_m), static_cast<float>(nearest_.back().y_m),
                core::DepthScanColumn::Kind::obstacle};
    } else if (has_floor) {
      column = {static_cast<float>(farthest_floor.x_m), static_cast<float>(farthest_floor.y_m),
                core::DepthScanColumn::Kind::free};
    } else {
      column = {0.0F, 0.0F, core::DepthScanColumn::Kind::invalid};
    }
  }
}

}  // namespace stereoscout::vision
