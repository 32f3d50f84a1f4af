#include "stereoscout/occupancy/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "stereoscout/core/check.hpp"

namespace stereoscout::occupancy {
namespace {

// A ray whose end cell lies further than this many grid spans from the grid is a broken
// measurement (or a units bug), not geometry: skipping it bounds the line walk.
constexpr double kFarLimitInGridSpans = 4.0;
constexpr float kMaxFloorVisibleMm = 65535.0F;

}  // namespace

GridGeometry GridGeometry::centred_on(const core::GridConfig& config, const core::Pose2& centre) {
  GridGeometry geometry;
  geometry.width_cells = config.width_cells;
  geometry.height_cells = config.height_cells;
  geometry.resolution_m = config.resolution_m;
  geometry.origin_x_m = centre.x - 0.5 * config.width_cells * config.resolution_m;
  geometry.origin_y_m = centre.y - 0.5 * config.height_cells * config.resolution_m;
  return geometry;
}

bool GridGeometry::same_as(const GridGeometry& other) const {
  return width_cells == other.width_cells && height_cells == other.height_cells &&
         resolution_m == other.resolution_m && origin_x_m == other.origin_x_m && origin_y_m == other.origin_y_m;
}

LogOddsModel LogOddsModel::from_config(const core::GridConfig& config) {
  return {static_cast<float>(config.log_odds_hit), static_cast<float>(config.log_odds_miss),
          static_cast<float>(config.log_odds_min), static_cast<float>(config.log_odds_max)};
}

CellThresholds CellThresholds::from_config(const core::GridConfig& config) {
  return {config.occupied_threshold, config.free_threshold};
}

namespace {

float logit(double probability) { return static_cast<float>(std::log(probability / (1.0 - probability))); }

CellState classify_log_odds(float log_odds, float occupied_above, float free_below) {
  if (log_odds > occupied_above) return CellState::occupied;
  if (log_odds < free_below) return CellState::free;
  return CellState::unknown;
}

}  // namespace

CellState CellThresholds::classify(float log_odds) const {
  return classify_log_odds(log_odds, logit(occupied), logit(free));
}

void classify_cells(const OccupancyGrid& grid, const CellThresholds& thresholds, CellState* cells) {
  const float occupied_above = logit(thresholds.occupied);
  const float free_below = logit(thresholds.free);
  const float* log_odds = grid.data();
  const std::size_t count = grid.geometry().cell_count();
  for (std::size_t i = 0; i < count; ++i) cells[i] = classify_log_odds(log_odds[i], occupied_above, free_below);
}

OccupancyGrid::OccupancyGrid(const GridGeometry& geometry, const LogOddsModel& model)
    : geometry_(geometry),
      model_(model),
      cells_(new float[geometry.cell_count()]),
      hit_at_camera_height_(new std::uint8_t[geometry.cell_count()]) {
  STEREOSCOUT_CHECK(geometry.width_cells > 0 && geometry.height_cells > 0 && geometry.resolution_m > 0.0,
                    "occupancy grid needs a positive size and resolution");
  clear();
}

void OccupancyGrid::clear() {
  std::fill(cells_.get(), cells_.get() + geometry_.cell_count(), 0.0F);
  std::fill(hit_at_camera_height_.get(), hit_at_camera_height_.get() + geometry_.cell_count(), std::uint8_t{0});
  counts_ = {};
}

void OccupancyGrid::copy_from(const OccupancyGrid& other) {
  STEREOSCOUT_CHECK(geometry_.same_as(other.geometry_), "OccupancyGrid::copy_from needs the same geometry");
  std::memcpy(cells_.get(), other.cells_.get(), geometry_.cell_count() * sizeof(float));
  std::memcpy(hit_at_camera_height_.get(), other.hit_at_camera_height_.get(), geometry_.cell_count());
  counts_ = other.counts_;
}

bool OccupancyGrid::same_cells_as(const OccupancyGrid& other) const {
  return geometry_.same_as(other.geometry_) &&
         std::memcmp(cells_.get(), other.cells_.get(), geometry_.cell_count() * sizeof(float)) == 0 &&
         std::memcmp(hit_at_camera_height_.get(), other.hit_at_camera_height_.get(), geometry_.cell_count()) == 0;
}

bool OccupancyGrid::cell_of(double x_m, double y_m, int& cell_x, int& cell_y) const {
  const double fx = std::floor((x_m - geometry_.origin_x_m) / geometry_.resolution_m);
  const double fy = std::floor((y_m - geometry_.origin_y_m) / geometry_.resolution_m);
  if (!(fx >= 0.0 && fy >= 0.0 && fx < geometry_.width_cells && fy < geometry_.height_cells)) return false;
  cell_x = static_cast<int>(fx);
  cell_y = static_cast<int>(fy);
  return true;
}

void OccupancyGrid::add(int cell_x, int cell_y, float delta) {
  if (!geometry_.contains(cell_x, cell_y)) return;
  float& cell = cells_[index(cell_x, cell_y)];
  cell = std::clamp(cell + delta, model_.min, model_.max);
}

void OccupancyGrid::hit(int cell_x, int cell_y, bool at_camera_height) {
  if (!geometry_.contains(cell_x, cell_y)) return;
  add(cell_x, cell_y, model_.hit);
  hit_at_camera_height_[index(cell_x, cell_y)] = at_camera_height ? 1U : 0U;
}

// Start and end cells of a ray; false (counted) when an end is not finite or absurdly far.
bool OccupancyGrid::cells_of(double start_x, double start_y, double end_x, double end_y, int& x0, int& y0, int& x1,
                             int& y1) {
  const double span = kFarLimitInGridSpans * (geometry_.width_cells + geometry_.height_cells);
  const double fx0 = std::floor((start_x - geometry_.origin_x_m) / geometry_.resolution_m);
  const double fy0 = std::floor((start_y - geometry_.origin_y_m) / geometry_.resolution_m);
  const double fx1 = std::floor((end_x - geometry_.origin_x_m) / geometry_.resolution_m);
  const double fy1 = std::floor((end_y - geometry_.origin_y_m) / geometry_.resolution_m);
  // Written so that NaN fails every comparison and is rejected.
  if (!(std::abs(fx0) < span && std::abs(fy0) < span && std::abs(fx1) < span && std::abs(fy1) < span)) {
    ++counts_.rays_rejected;
    return false;
  }
  x0 = static_cast<int>(fx0);
  y0 = static_cast<int>(fy0);
  x1 = static_cast<int>(fx1);
  y1 = static_cast<int>(fy1);
  return true;
}

namespace {

// Integer line walk (Bresenham) from (x, y) to (x1, y1): calls pass(cell) for every cell but
// the last.
template <typename Pass>
void walk_line(int x, int y, int x1, int y1, Pass&& pass) {
  const int dx = std::abs(x1 - x);
  const int dy = -std::abs(y1 - y);
  const int step_x = x < x1 ? 1 : -1;
  const int step_y = y < y1 ? 1 : -1;
  int error = dx + dy;
  while (x != x1 || y != y1) {
    pass(x, y);
    const int twice_error = 2 * error;
    if (twice_error >= dy) {
      error += dy;
      x += step_x;
    }
    if (twice_error <= dx) {
      error += dx;
      y += step_y;
    }
  }
}

}  // namespace

// Every cell but the last is passed through (miss); the last is where the column ends.
void OccupancyGrid::cast_ray(double start_x, double start_y, double end_x, double end_y, bool end_is_obstacle,
                             bool at_camera_height) {
  int x0 = 0;
  int y0 = 0;
  int x1 = 0;
  int y1 = 0;
  if (!cells_of(start_x, start_y, end_x, end_y, x0, y0, x1, y1)) return;
  ++counts_.rays;
  walk_line(x0, y0, x1, y1, [this](int x, int y) { add(x, y, model_.miss); });
  if (end_is_obstacle) {
    hit(x1, y1, at_camera_height);
  } else {
    add(x1, y1, model_.miss);
  }
}

void OccupancyGrid::clear_camera_height_hits(double start_x, double start_y, double end_x, double end_y) {
  int x0 = 0;
  int y0 = 0;
  int x1 = 0;
  int y1 = 0;
  if (!cells_of(start_x, start_y, end_x, end_y, x0, y0, x1, y1)) return;
  walk_line(x0, y0, x1, y1, [this](int x, int y) {
    if (geometry_.contains(x, y) && hit_at_camera_height_[index(x, y)] != 0U) add(x, y, model_.miss);
  });
}

ScanPoint ScanPoint::from_column(const core::DepthScanColumn& column) {
  // Whole millimetres, saturated: NaN or negative -> 0 (visible from the origin), beyond
  // 65.535 m -> never (no floor is that far anyway).
  const float mm = column.floor_visible_from_m * 1000.0F;
  const float clamped = mm > 0.0F ? std::min(mm, kMaxFloorVisibleMm) : 0.0F;
  return {column.x_robot_m, column.y_robot_m, column.kind, column.obstacle_at_camera_height,
          static_cast<std::uint16_t>(std::lround(clamped))};
}

void OccupancyGrid::insert_column(const Eigen::Vector2d& origin, const Eigen::Vector2d& end, const ScanPoint& point) {
  const bool obstacle = point.kind == core::DepthScanColumn::Kind::obstacle;
  const double visible_from = point.floor_visible_from_m();
  const Eigen::Vector2d along = end - origin;
  const double length = along.norm();
  if (!std::isfinite(length)) {
    ++counts_.rays_rejected;
    return;
  }
  const double reach = obstacle ? length : length - geometry_.resolution_m;
  const auto at = [&](double distance) { return Eigen::Vector2d(origin + along * (distance / length)); };
  // The blind zone: only obstacles at the camera's height would have been seen there.
  const double blind_end = std::min(visible_from, reach);
  if (blind_end > 0.0) {
    const Eigen::Vector2d stop = at(blind_end);
    clear_camera_height_hits(origin.x(), origin.y(), stop.x(), stop.y());
  }
  if (obstacle && length <= visible_from) {
    cast_ray(end.x(), end.y(), end.x(), end.y(), true, point.obstacle_at_camera_height);  // its own cell only
    return;
  }
  if (!obstacle && !(reach > visible_from)) return;  // no visible floor on this ray
  const Eigen::Vector2d start = at(visible_from);
  const Eigen::Vector2d stop = obstacle ? end : at(reach);
  cast_ray(start.x(), start.y(), stop.x(), stop.y(), obstacle, point.obstacle_at_camera_height);
}

void OccupancyGrid::insert(const ScanView& scan, const core::Pose2& pose) {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  const Eigen::Vector2d origin(pose.x + c * scan.origin_x_robot_m - s * scan.origin_y_robot_m,
                               pose.y + s * scan.origin_x_robot_m + c * scan.origin_y_robot_m);
  for (std::size_t i = 0; i < scan.count; ++i) {
    const ScanPoint& point = scan.points[i];
    if (point.kind == core::DepthScanColumn::Kind::invalid) continue;
    const double px = point.x_robot_m;
    const double py = point.y_robot_m;
    insert_column(origin, Eigen::Vector2d(pose.x + c * px - s * py, pose.y + s * px + c * py), point);
  }
}

void OccupancyGrid::insert(const core::DepthScan& scan, const core::Pose2& pose) {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  const double ox = scan.origin_robot.x();
  const double oy = scan.origin_robot.y();
  const Eigen::Vector2d origin(pose.x + c * ox - s * oy, pose.y + s * ox + c * oy);
  for (const core::DepthScanColumn& column : scan.columns) {
    if (column.kind == core::DepthScanColumn::Kind::invalid) continue;
    const ScanPoint point = ScanPoint::from_column(column);
    const double px = point.x_robot_m;
    const double py = point.y_robot_m;
    insert_column(origin, Eigen::Vector2d(pose.x + c * px - s * py, pose.y + s * px + c * py), point);
  }
}

}  // namespace stereoscout::occupancy
