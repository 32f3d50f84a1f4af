#include "stereoscout/explore/recent_obstacles.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace stereoscout::explore {
namespace {

constexpr std::uint8_t kMaxCount = 255;

std::size_t cells_of(int width, int height) {
  return static_cast<std::size_t>(std::max(width, 0)) * static_cast<std::size_t>(std::max(height, 0));
}

}  // namespace

RecentObstacles::RecentObstacles(const core::ExploreConfig& config, int max_width, int max_height)
    : keep_s_(config.recent_obstacle_s),
      travel_m_(config.recent_obstacle_travel_m),
      range_m_(config.recent_obstacle_range_m),
      min_points_(std::max(1, config.recent_obstacle_min_points)),
      estimate_heading_(config.recent_obstacle_estimate_heading),
      blank_walls_(config.recent_obstacle_blank_walls),
      capacity_(config.recent_obstacle_s > 0.0 ? static_cast<std::size_t>(std::max(1, config.recent_obstacle_capacity)) : 0),
      points_(new Point[capacity_ == 0 ? 1 : capacity_]),
      cell_capacity_(capacity_ == 0 ? 0 : cells_of(max_width, max_height)),
      counts_(new std::uint8_t[cell_capacity_ == 0 ? 1 : cell_capacity_]()),
      cells_(new std::uint8_t[cell_capacity_ == 0 ? 1 : cell_capacity_]),
      touched_(new std::size_t[capacity_ == 0 ? 1 : capacity_]),
      blank_previous_(new Eigen::Vector2d[blank_walls_ ? kMaxBlankPerScan : 1]),
      blank_current_(new Eigen::Vector2d[blank_walls_ ? kMaxBlankPerScan : 1]) {}

int RecentObstacles::bin_of(double bearing_rad) {
  const double turns = (bearing_rad + core::kPi) / (2.0 * core::kPi);
  const int bin = static_cast<int>(std::floor(turns * kBearingBins));
  return std::clamp(bin, 0, kBearingBins - 1);
}

core::Pose2 RecentObstacles::layer_pose(const core::Pose2& pose, const core::Pose2& odometry) const {
  if (!estimate_heading_) return odometry;
  if (last_scan_time_s_ < 0.0) return pose;
  // The stretch's chord in the robot's frame at the last scan is exact for any path the
  // odometry drove; only its heading there is taken from the estimate.
  const Eigen::Vector2d chord = last_scan_odometry_.inverse().transform_point(odometry.translation());
  const Eigen::Vector2d moved = last_scan_layer_.transform_point(chord);
  return core::Pose2{moved.x(), moved.y(), pose.theta};
}

void RecentObstacles::observe(const SeenObstacles& seen) {
  if (!enabled() || seen.scan == nullptr || seen.time_s <= last_scan_time_s_) return;
  const core::Pose2 layer = layer_pose(seen.pose, seen.odometry);
  if (last_scan_time_s_ >= 0.0) driven_m_ += (seen.odometry.translation() - last_scan_odometry_.translation()).norm();
  last_scan_time_s_ = seen.time_s;
  last_scan_odometry_ = seen.odometry;
  last_scan_layer_ = layer;
  forget_seen_past(*seen.scan, layer);
  keep_columns(*seen.scan, layer, seen.time_s);
  std::swap(blank_previous_, blank_current_);
  blank_previous_size_ = blank_current_size_;
}

// Per bearing bin the nearest range any of its columns measured (an obstacle's, or a free
// column's end less its uncertainty): a kept point nearer than that by kSeenPastMargin_m, and
// beyond every column's near limit, was seen past.
void RecentObstacles::forget_seen_past(const core::DepthScan& scan, const core::Pose2& layer) {
  if (size_ == 0) return;
  for (BearingBin& bin : bins_) bin = BearingBin{};
  for (const core::DepthScanColumn& column : scan.columns) {
    if (column.kind == core::DepthScanColumn::Kind::invalid) continue;
    const Eigen::Vector2d ray = Eigen::Vector2d(column.x_robot_m, column.y_robot_m) - scan.origin_robot;
    const double uncertainty = column.kind == core::DepthScanColumn::Kind::free ? 2.0 * column.end_range_sigma_m : 0.0;
    const float seen_m = static_cast<float>(ray.norm() - uncertainty);
    BearingBin& bin = bins_[bin_of(std::atan2(ray.y(), ray.x()))];
    bin.seen_past_m = bin.measured ? std::min(bin.seen_past_m, seen_m) : seen_m;
    bin.measurable_m = std::max(bin.measurable_m, column.measurable_from_m);
    bin.measured = true;
  }
  // Compacted in place, oldest first still.
  const core::Pose2 robot_from_layer = layer.inverse();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < size_; ++i) {
    const Eigen::Vector2d ray = robot_from_layer.transform_point(points_[i].layer_xy) - scan.origin_robot;
    const BearingBin& bin = bins_[bin_of(std::atan2(ray.y(), ray.x()))];
    const double range = ray.norm();
    if (bin.measured && range >= bin.measurable_m && bin.seen_past_m > range + kSeenPastMargin_m) {
      ++seen_past_;
      continue;
    }
    points_[kept++] = points_[i];
  }
  size_ = kept;
}

void RecentObstacles::drop_oldest(std::size_t count) {
  std::copy(points_.get() + count, points_.get() + size_, points_.get());
  size_ -= count;
}

void RecentObstacles::keep_columns(const core::DepthScan& scan, const core::Pose2& layer, double time_s) {
  Eigen::Vector2d last = Eigen::Vector2d::Constant(1e9);
  blank_current_size_ = 0;
  for (const core::DepthScanColumn& column : scan.columns) {
    if (column.kind != core::DepthScanColumn::Kind::obstacle) continue;
    const bool blank = blank_walls_ && !column.obstacle_at_camera_height &&
                       column.blank_wall != core::DepthScanColumn::BlankWall::no;
    if (!column.obstacle_at_camera_height && !blank) continue;
    const Eigen::Vector2d robot_xy(column.x_robot_m, column.y_robot_m);
    if ((robot_xy - scan.origin_robot).norm() > range_m_) continue;
    if (blank && !confirmed_blank(layer.transform_point(robot_xy))) continue;
    if ((robot_xy - last).norm() < kPointSpacing_m) continue;
    last = robot_xy;
    if (size_ == capacity_) {
      // Full: the oldest quarter goes at once (one move, not one per point).
      const std::size_t drop = std::max<std::size_t>(1, capacity_ / 4);
      drop_oldest(drop);
      dropped_full_ += drop;
    }
    points_[size_++] = Point{layer.transform_point(robot_xy), time_s, driven_m_};
    ++kept_;
  }
}

// Remembers a blank-wall point of the scan being kept; true when the previous scan had one
// within kBlankConfirm_m of it.
bool RecentObstacles::confirmed_blank(const Eigen::Vector2d& layer_xy) {
  if (blank_current_size_ < kMaxBlankPerScan) blank_current_[blank_current_size_++] = layer_xy;
  for (std::size_t i = 0; i < blank_previous_size_; ++i) {
    if ((blank_previous_[i] - layer_xy).squaredNorm() <= kBlankConfirm_m * kBlankConfirm_m) return true;
  }
  ++blank_unconfirmed_;
  return false;
}

bool RecentObstacles::outlived(const Point& point, double time_s) const {
  return time_s - point.time_s > keep_s_ || (travel_m_ > 0.0 && driven_m_ - point.driven_m > travel_m_);
}

GridView RecentObstacles::stamp(const GridView& grid, const core::Pose2& pose, const core::Pose2& odometry,
                                double time_s) {
  if (!enabled()) return grid;
  std::size_t first = 0;
  // Kept in time order, so both limits expire a prefix.
  while (first < size_ && outlived(points_[first], time_s)) ++first;
  drop_oldest(first);
  expired_ += first;
  if (size_ == 0) return grid;
  if (cells_of(grid.width, grid.height) > cell_capacity_) {
    ++grid_too_large_;
    return grid;
  }
  const core::Pose2 map_from_layer = pose.compose(layer_pose(pose, odometry).inverse());
  std::size_t touched = 0;
  for (std::size_t i = 0; i < size_; ++i) {
    const Eigen::Vector2i cell = grid.cell_of(map_from_layer.transform_point(points_[i].layer_xy));
    if (!grid.contains(cell.x(), cell.y())) continue;
    const std::size_t index = grid.index(cell.x(), cell.y());
    if (counts_[index] == 0) touched_[touched++] = index;
    if (counts_[index] < kMaxCount) ++counts_[index];
  }
  GridEdit stamped(grid, cells_.get());
  for (std::size_t k = 0; k < touched; ++k) {
    const std::size_t index = touched_[k];
    const bool counts = counts_[index] >= min_points_;
    counts_[index] = 0;
    if (!counts || grid.cells[index] == static_cast<std::uint8_t>(CellState::occupied)) continue;
    stamped.set(index, CellState::occupied);
    ++cells_stamped_;
  }
  return stamped.result();
}

namespace {

// Keeps the `count` points of least `key` seen so far in `best` (ascending), `held` of them.
void keep_least(const Eigen::Vector2d& point, double key, int count, Eigen::Vector2d* best, double* keys, int& held) {
  if (held == count && key >= keys[held - 1]) return;
  int k = held < count ? held++ : held - 1;
  for (; k > 0 && keys[k - 1] > key; --k) {
    keys[k] = keys[k - 1];
    best[k] = best[k - 1];
  }
  keys[k] = key;
  best[k] = point;
}

}  // namespace

bool RecentObstacles::gap_ahead(const core::Pose2& pose, const core::Pose2& odometry, double behind_m, double ahead_m,
                                double aside_m, int support, Gap& gap) const {
  if (!enabled() || support < 1 || support > kMaxGapSupport) return false;
  const core::Pose2 robot_from_layer = layer_pose(pose, odometry).inverse();
  Eigen::Vector2d left[kMaxGapSupport];
  Eigen::Vector2d right[kMaxGapSupport];
  double left_keys[kMaxGapSupport];
  double right_keys[kMaxGapSupport];
  int lefts = 0;
  int rights = 0;
  for (std::size_t i = 0; i < size_; ++i) {
    const Eigen::Vector2d point = robot_from_layer.transform_point(points_[i].layer_xy);
    if (point.x() < -behind_m || point.x() > ahead_m || std::abs(point.y()) > aside_m) continue;
    if (point.y() > 0.0) {
      keep_least(point, point.y(), support, left, left_keys, lefts);
    } else {
      keep_least(point, -point.y(), support, right, right_keys, rights);
    }
  }
  if (lefts < support || rights < support) return false;
  gap.left = left[support - 1];
  gap.right = right[support - 1];
  return true;
}

}  // namespace stereoscout::explore
