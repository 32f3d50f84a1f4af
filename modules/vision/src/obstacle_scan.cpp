#include "stereoscout/vision/obstacle_scan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stereoscout/core/check.hpp"
#include "stereoscout/vision/dense_disparity.hpp"

namespace stereoscout::vision {

ObstacleScanParams scan_params_from_config(const core::VisionConfig& vision, const core::RobotConfig& robot) {
  ObstacleScanParams params;
  params.floor_tolerance_m = vision.floor_tolerance_m;
  params.robot_height_m = robot.height_m;
  params.max_range_m = vision.scan_max_range_m;
  params.min_obstacle_pixels = vision.scan_min_obstacle_pixels;
  params.same_surface_depth_m = vision.scan_same_surface_depth_m;
  params.max_disparity_px = vision.dense_num_disparities - 1;
  params.unmatched_border_px = vision.dense_window_px / 2 + detail::kCensusRadius;
  params.blank_wall_within_m = vision.scan_blank_wall_within_m;
  params.blank_wall_untextured_fraction = vision.scan_blank_wall_untextured_fraction;
  params.wall_base_min_step_grey = vision.scan_wall_base_min_step;
  params.wall_base_within_m = vision.scan_wall_base_within_m;
  params.sigma_d_px = vision.sigma_d_px;
  params.floor_onto_plane = vision.scan_floor_onto_plane;
  params.near_min_matches = vision.scan_near_min_matches;
  params.max_near_matches = vision.max_features;
  params.near_max_dense_valid = vision.scan_near_max_dense_valid;
  params.near_uniqueness = vision.scan_near_uniqueness;
  params.near_window_px = vision.scan_near_window_px;
  return params;
}

namespace {

// Floor distance from the camera centre's foot to where the bottom row's ray in `column` meets
// the floor; +infinity when that ray does not go down (the column never sees the floor).
float floor_visible_from(const StereoCalibration& calibration, const core::CameraMount& mount, int column) {
  const Eigen::Isometry3d robot_from_camera = core::robot_from_camera(mount, 0.0);
  const Eigen::Vector3d origin = robot_from_camera.translation();
  const Eigen::Vector3d direction =
      robot_from_camera.linear() *
      Eigen::Vector3d((column - calibration.principal_x_px) / calibration.focal_px,
                      (calibration.height_px - 1 - calibration.principal_y_px) / calibration.focal_px, 1.0);
  if (!(direction.z() < 0.0)) return std::numeric_limits<float>::infinity();
  const double scale = -origin.z() / direction.z();
  return static_cast<float>(scale * direction.head<2>().norm());
}

// Floor distance from the camera centre's foot to the nearest point `column` can measure (at
// the principal row): the depth of the largest disparity the matcher gives there. +infinity
// when it gives none.
float measurable_from(const ObstacleScanParams& params, const StereoCalibration& calibration,
                      const core::CameraMount& mount, int column) {
  const int last_matched_left = calibration.width_px - 1 - params.unmatched_border_px;
  const int largest_disparity = std::min(params.max_disparity_px, last_matched_left - column);
  if (largest_disparity < 1) return std::numeric_limits<float>::infinity();
  const double depth = calibration.focal_px * calibration.baseline_m / largest_disparity;
  const Eigen::Vector3d offset =
      core::robot_from_camera(mount, 0.0).linear() *
      Eigen::Vector3d(depth * (column - calibration.principal_x_px) / calibration.focal_px, 0.0, depth);
  return static_cast<float>(offset.head<2>().norm());
}

}  // namespace

ObstacleScanner::ObstacleScanner(const ObstacleScanParams& params, const StereoCalibration& calibration,
                                 const core::CameraMount& mount)
    : params_(params),
      calibration_(calibration),
      mount_(mount),
      per_column_(static_cast<std::size_t>(std::max(params.min_obstacle_pixels, 1))),
      columns_(static_cast<std::size_t>(calibration.width_px)),
      nearest_(static_cast<std::size_t>(calibration.width_px) * per_column_),
      floor_visible_from_m_(static_cast<std::size_t>(calibration.width_px)),
      measurable_from_m_(static_cast<std::size_t>(calibration.width_px)),
      near_(static_cast<std::size_t>(params.near_min_matches > 0 ? std::max(params.max_near_matches, 0) : 0)),
      horizon_row_(std::clamp(static_cast<int>(std::ceil(calibration.principal_y_px -
                                                          calibration.focal_px * std::tan(mount.tilt_rad))),
                              0, calibration.height_px - 1)) {
  for (int column = 0; column < calibration.width_px; ++column) {
    floor_visible_from_m_[static_cast<std::size_t>(column)] = floor_visible_from(calibration, mount, column);
    measurable_from_m_[static_cast<std::size_t>(column)] = measurable_from(params, calibration, mount, column);
  }
}

void ObstacleScanner::allocate(core::DepthScan& scan) const {
  scan.columns.assign(static_cast<std::size_t>(calibration_.width_px), core::DepthScanColumn{});
}

void ObstacleScanner::reset_columns() {
  for (ColumnState& state : columns_) {
    state = ColumnState{};
  }
}

// Keeps a column's per_column_ nearest obstacle points, sorted by range (insertion sort).
void ObstacleScanner::keep_nearest(ColumnState& state, Candidate* nearest, const Candidate& candidate) const {
  auto used = static_cast<std::size_t>(state.obstacle_points);
  if (used == per_column_) {
    if (candidate.range_m >= nearest[used - 1].range_m) {
      return;
    }
    --used;
  }
  nearest[used] = candidate;
  for (std::size_t i = used; i > 0 && nearest[i].range_m < nearest[i - 1].range_m; --i) {
    std::swap(nearest[i], nearest[i - 1]);
  }
  state.obstacle_points = static_cast<int>(used + 1);
}

void ObstacleScanner::add_point(int column, int x_left, int row, const Eigen::Vector3d& point,
                                const Eigen::Vector3d& origin) {
  ColumnState& state = columns_[static_cast<std::size_t>(column)];
  const double dx = point.x() - origin.x();
  const double dy = point.y() - origin.y();
  const double range = std::hypot(dx, dy);
  const bool on_floor = std::fabs(point.z()) <= params_.floor_tolerance_m;
  if (!on_floor) state.farthest_off_floor_m = std::max(state.farthest_off_floor_m, range);  // any height
  if (on_floor) {
    // A floor point measured below the floor lies beyond where its ray meets the floor by its
    // disparity error alone: the ray's meeting point is the better range.
    const double onto_floor =
        point.z() < 0.0 && params_.floor_onto_plane ? origin.z() / (origin.z() - point.z()) : 1.0;
    const double floor_range = range * onto_floor;
    if (!state.has_floor || floor_range > state.farthest_floor.range_m) {
      state.has_floor = true;
      const double capped = std::min(floor_range, params_.max_range_m);
      const double scale = range > 0.0 ? capped / range : 0.0;
      state.farthest_floor = {floor_range, origin.x() + dx * scale, origin.y() + dy * scale};
      state.floor_end_x_left = x_left;
      state.floor_end_row = row;
    }
  } else if (point.z() > params_.floor_tolerance_m && point.z() < params_.robot_height_m &&
             range <= params_.max_range_m) {
    keep_nearest(state, &nearest_[static_cast<std::size_t>(column) * per_column_], {range, point.x(), point.y()});
    if (std::fabs(point.z() - origin.z()) <= params_.floor_tolerance_m) {
      state.nearest_at_camera_height_m = std::min(state.nearest_at_camera_height_m, range);
    }
  }
  // Points below the floor or above the robot are ignored.
}

// No floor and no other point of the column was seen beyond range_m (give or take a surface's
// depth): a blank surface standing there would hide everything behind it.
bool ObstacleScanner::nothing_seen_beyond(const ColumnState& state, double range_m) const {
  const double beyond = range_m + params_.same_surface_depth_m;
  return state.farthest_off_floor_m <= beyond && (!state.has_floor || state.farthest_floor.range_m <= beyond);
}

// The floor stops within range and nothing is seen beyond it, at any height: the view ends
// at a surface stereo cannot measure (a blank wall).
bool ObstacleScanner::floor_ends_at_unseen_surface(const ColumnState& state) const {
  return state.farthest_floor.range_m < std::min(params_.blank_wall_within_m, params_.max_range_m) &&
         nothing_seen_beyond(state, state.farthest_floor.range_m);
}

// A wall base stands where stereo saw nothing beyond it; beyond the floor-end rule's range
// it also needs floor matched before it, not a view that stereo could not measure at all.
bool ObstacleScanner::wall_base_agrees_with_stereo(const ColumnState& state) const {
  return nothing_seen_beyond(state, state.wall_base.range_m) &&
         (state.wall_base.range_m < params_.blank_wall_within_m || state.has_floor);
}

// Files the base of a blank wall found in each left-image column under its right-image
// column: on the floor plane, the base row's ray gives the depth, hence the disparity a floor
// point there has and the right column it is seen in.
void ObstacleScanner::add_wall_bases(const cv::Mat& disparity, const cv::Mat& left,
                                     const Eigen::Isometry3d& robot_from_camera) {
  const WallBaseParams wall_base{params_.wall_base_min_step_grey, params_.blank_wall_untextured_fraction};
  const Eigen::Vector3d origin = robot_from_camera.translation();
  const double within_m = std::min(params_.wall_base_within_m, params_.max_range_m);
  for (int x = 0; x < left.cols; ++x) {
    const double row = find_wall_base_row(left, disparity, x, horizon_row_, wall_base);
    if (row < 0.0) continue;
    const Eigen::Vector3d down =
        robot_from_camera.linear() * Eigen::Vector3d(0.0, (row - calibration_.principal_y_px) / calibration_.focal_px, 1.0);
    if (!(down.z() < 0.0)) continue;
    const double depth = -origin.z() / down.z();
    const double d = calibration_.focal_px * calibration_.baseline_m / depth;
    const double x_right = x - d;
    const auto column = static_cast<int>(std::lround(x_right));
    if (column < 0 || column >= left.cols) continue;
    const Eigen::Vector3d point = robot_from_camera * triangulate_point(calibration_, x_right, row, d);
    const double range = std::hypot(point.x() - origin.x(), point.y() - origin.y());
    ColumnState& state = columns_[static_cast<std::size_t>(column)];
    if (range >= within_m || (state.has_wall_base && range >= state.wall_base.range_m)) continue;
    state.has_wall_base = true;
    state.wall_base = {range, point.x(), point.y()};
  }
}

// The standard deviation of the farthest floor point's range: Z = f B / d, so an error of
// sigma_d in d moves the point along its ray by range * sigma_d / d (first order).
double ObstacleScanner::free_end_range_sigma(const cv::Mat& disparity, const ColumnState& state) const {
  const double d = disparity.ptr<float>(state.floor_end_row)[state.floor_end_x_left];
  return d > 0.0 ? state.farthest_floor.range_m * params_.sigma_d_px / d : 0.0;
}

// The left image above the floor's end, up to the horizon row, is mostly a surface without
// texture (where a wall at or beyond that end shows; farther walls stand higher in the image).
bool ObstacleScanner::blank_above_floor_end(const cv::Mat& disparity, const ColumnState& state) const {
  if (params_.blank_wall_untextured_fraction <= 0.0) return true;
  int pixels = 0;
  int untextured = 0;
  for (int row = state.floor_end_row - 1; row >= horizon_row_; --row, ++pixels) {
    untextured += disparity.ptr<float>(row)[state.floor_end_x_left] == kUntexturedDisparity ? 1 : 0;
  }
  return pixels > 0 && untextured >= params_.blank_wall_untextured_fraction * pixels;
}

void ObstacleScanner::compute(const cv::Mat& disparity, const cv::Mat& left, double pan_rad,
                              std::int64_t timestamp_ns, core::DepthScan& scan) {
  STEREOSCOUT_CHECK(disparity.type() == CV_32FC1 && disparity.cols == calibration_.width_px &&
                        scan.columns.size() == static_cast<std::size_t>(disparity.cols),
                    "ObstacleScanner::compute: disparity or scan not sized for this camera");
  STEREOSCOUT_CHECK(left.empty() || (left.type() == CV_8UC1 && left.size() == disparity.size()),
                    "ObstacleScanner::compute: the left image must be 8-bit grey of the disparity's size");
  const Eigen::Isometry3d robot_from_camera = core::robot_from_camera(mount_, pan_rad);
  const Eigen::Vector3d origin = robot_from_camera.translation();
  scan.timestamp_ns = timestamp_ns;
  scan.origin_robot = origin.head<2>();
  reset_columns();
  for (int y = disparity.rows - 1; y >= 0; --y) {  // bottom row up
    const float* row = disparity.ptr<float>(y);
    for (int x = 0; x < disparity.cols; ++x) {
      const float d = row[x];
      if (!(d > 0.0F)) {
        continue;  // invalid (kInvalidDisparity) or at infinity
      }
      const double x_right = x - static_cast<double>(d);
      const auto column = static_cast<int>(std::lround(x_right));
      if (column < 0 || column >= disparity.cols) {
        continue;
      }
      add_point(column, x, y, robot_from_camera * triangulate_point(calibration_, x_right, y, d), origin);
    }
  }
  if (!left.empty()) add_wall_bases(disparity, left, robot_from_camera);
  for (std::size_t column = 0; column < columns_.size(); ++column) {
    const ColumnState& state = columns_[column];
    core::DepthScanColumn& out = scan.columns[column];
    const float visible_from = floor_visible_from_m_[column];
    const float measurable = measurable_from_m_[column];
    if (!(measurable < params_.max_range_m)) {
      out = {0.0F, 0.0F, core::DepthScanColumn::Kind::invalid, visible_from, false, measurable};
    } else if (static_cast<std::size_t>(state.obstacle_points) == per_column_) {
      // The farthest of the nearest min_obstacle_pixels points: confirmed by that many.
      const Candidate& confirmed = nearest_[column * per_column_ + per_column_ - 1];
      const bool at_camera_height = state.nearest_at_camera_height_m <= confirmed.range_m + params_.same_surface_depth_m;
      out = {static_cast<float>(confirmed.x_m), static_cast<float>(confirmed.y_m), core::DepthScanColumn::Kind::obstacle,
             visible_from, at_camera_height, measurable};
    } else if (state.has_wall_base && wall_base_agrees_with_stereo(state)) {
      out = {static_cast<float>(state.wall_base.x_m), static_cast<float>(state.wall_base.y_m),
             core::DepthScanColumn::Kind::obstacle, visible_from, false, measurable};
      out.blank_wall = core::DepthScanColumn::BlankWall::base;
    } else if (state.has_floor && floor_ends_at_unseen_surface(state) && blank_above_floor_end(disparity, state)) {
      out = {static_cast<float>(state.farthest_floor.x_m), static_cast<float>(state.farthest_floor.y_m),
             core::DepthScanColumn::Kind::obstacle, visible_from, false, measurable};
      out.blank_wall = core::DepthScanColumn::BlankWall::floor_end;
    } else if (state.has_floor) {
      out = {static_cast<float>(state.farthest_floor.x_m), static_cast<float>(state.farthest_floor.y_m),
             core::DepthScanColumn::Kind::free, visible_from, false, measurable};
      out.end_range_sigma_m = static_cast<float>(free_end_range_sigma(disparity, state));
    } else {
      out = {0.0F, 0.0F, core::DepthScanColumn::Kind::invalid, visible_from, false, measurable};
    }
  }
}

bool ObstacleScanner::dense_matcher_found_little(const cv::Mat& disparity, const NearMatch& match) const {
  const auto cx = static_cast<int>(std::lround(match.x_left_px));
  const auto cy = static_cast<int>(std::lround(match.y_px));
  const int radius = params_.near_window_px / 2;
  int pixels = 0;
  int valid = 0;
  for (int y = std::max(cy - radius, 0); y <= std::min(cy + radius, disparity.rows - 1); ++y) {
    const float* row = disparity.ptr<float>(y);
    for (int x = std::max(cx - radius, 0); x <= std::min(cx + radius, disparity.cols - 1); ++x) {
      ++pixels;
      valid += row[x] > 0.0F ? 1 : 0;
    }
  }
  return pixels > 0 && valid <= params_.near_max_dense_valid * pixels;
}

namespace {

// Sum of absolute differences between the square patches of `radius` around (x, y) in `left`
// and (x - d, y) in `right`; the caller keeps both inside their images.
int patch_difference(const cv::Mat& left, const cv::Mat& right, int x, int y, int d, int radius) {
  int sum = 0;
  for (int row = y - radius; row <= y + radius; ++row) {
    const std::uint8_t* l = left.ptr<std::uint8_t>(row) + x - radius;
    const std::uint8_t* r = right.ptr<std::uint8_t>(row) + x - d - radius;
    for (int i = 0; i <= 2 * radius; ++i) sum += std::abs(static_cast<int>(l[i]) - static_cast<int>(r[i]));
  }
  return sum;
}

}  // namespace

bool ObstacleScanner::matches_only_that_near(const cv::Mat& left, const cv::Mat& right, const NearMatch& match) const {
  const int radius = params_.near_window_px / 2;
  const auto x = static_cast<int>(std::lround(match.x_left_px));
  const auto y = static_cast<int>(std::lround(match.y_px));
  const auto d = static_cast<int>(std::lround(match.disparity_px));
  if (y - radius < 0 || y + radius >= left.rows || x + radius >= left.cols || x - d - 1 - radius < 0) return false;
  int near = patch_difference(left, right, x, y, d, radius);
  near = std::min(near, patch_difference(left, right, x, y, d - 1, radius));
  near = std::min(near, patch_difference(left, right, x, y, d + 1, radius));
  const int widest = std::min(params_.max_disparity_px, x - radius);
  for (int in_range = 0; in_range <= widest; ++in_range) {
    if (near >= params_.near_uniqueness * patch_difference(left, right, x, y, in_range, radius)) return false;
  }
  return true;
}

// The matches nearer than the dense matcher reaches, above the floor and below the robot,
// where it found little and that match only that near, as points on the floor plane filed
// under their right-image columns; returns how many.
std::size_t ObstacleScanner::near_points_of(const NearMatch* matches, std::size_t count, const cv::Mat& disparity,
                                            const cv::Mat& left, const cv::Mat& right,
                                            const Eigen::Isometry3d& robot_from_camera) {
  const Eigen::Vector3d origin = robot_from_camera.translation();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < count && kept < near_.size(); ++i) {
    const NearMatch& match = matches[i];
    if (!(match.disparity_px > static_cast<float>(params_.max_disparity_px))) continue;
    const double x_right = static_cast<double>(match.x_left_px) - match.disparity_px;
    const auto column = static_cast<int>(std::lround(x_right));
    if (column < 0 || column >= calibration_.width_px || !dense_matcher_found_little(disparity, match) ||
        !matches_only_that_near(left, right, match)) {
      continue;
    }
    const Eigen::Vector3d point =
        robot_from_camera * triangulate_point(calibration_, x_right, match.y_px, match.disparity_px);
    if (!(point.z() > params_.floor_tolerance_m && point.z() < params_.robot_height_m)) continue;
    const double range = std::hypot(point.x() - origin.x(), point.y() - origin.y());
    const bool at_camera_height = std::fabs(point.z() - origin.z()) <= params_.floor_tolerance_m;
    near_[kept++] = {column, range, point.x(), point.y(), at_camera_height};
  }
  return kept;
}

// At least near_min_matches of the first `count` near points (`point` among them) lie within
// same_surface_depth_m of it on the floor.
bool ObstacleScanner::near_point_supported(const NearPoint& point, std::size_t count) const {
  const double reach2 = params_.same_surface_depth_m * params_.same_surface_depth_m;
  int agreeing = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const double dx = near_[i].x_m - point.x_m;
    const double dy = near_[i].y_m - point.y_m;
    if (dx * dx + dy * dy <= reach2 && ++agreeing >= params_.near_min_matches) return true;
  }
  return false;
}

std::size_t ObstacleScanner::add_near_matches(const NearMatch* matches, std::size_t count, const cv::Mat& disparity,
                                              const cv::Mat& left, const cv::Mat& right, double pan_rad,
                                              core::DepthScan& scan) {
  if (params_.near_min_matches <= 0) return 0;
  const auto camera_sized = [this](const cv::Mat& image, int type) {
    return image.type() == type && image.cols == calibration_.width_px && image.rows == calibration_.height_px;
  };
  STEREOSCOUT_CHECK(scan.columns.size() == static_cast<std::size_t>(calibration_.width_px) &&
                        camera_sized(disparity, CV_32FC1) && camera_sized(left, CV_8UC1) && camera_sized(right, CV_8UC1),
                    "ObstacleScanner::add_near_matches: images, disparity or scan not sized for this camera");
  const Eigen::Isometry3d robot_from_camera = core::robot_from_camera(mount_, pan_rad);
  const Eigen::Vector2d origin = robot_from_camera.translation().head<2>();
  const std::size_t near_count = near_points_of(matches, count, disparity, left, right, robot_from_camera);
  std::size_t columns = 0;
  for (std::size_t i = 0; i < near_count; ++i) {
    const NearPoint& point = near_[i];
    if (!near_point_supported(point, near_count)) continue;
    core::DepthScanColumn& out = scan.columns[static_cast<std::size_t>(point.column)];
    // A measured obstacle at least as near stays (a guessed blank wall does not).
    const bool measured_obstacle =
        out.kind == core::DepthScanColumn::Kind::obstacle && out.blank_wall == core::DepthScanColumn::BlankWall::no;
    if (measured_obstacle && (Eigen::Vector2d(out.x_robot_m, out.y_robot_m) - origin).norm() <= point.range_m) continue;
    const float visible_from = out.floor_visible_from_m;
    const auto range = static_cast<float>(point.range_m);
    out = {static_cast<float>(point.x_m), static_cast<float>(point.y_m), core::DepthScanColumn::Kind::obstacle,
           visible_from, point.at_camera_height, std::min(out.measurable_from_m, range)};
    ++columns;  // a column taken twice (a nearer match in it) is counted twice
  }
  return columns;
}

}  // namespace stereoscout::vision
