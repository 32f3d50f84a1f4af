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

CellState CellThresholds::classify(float log_odds) const {
  const double probability = 1.0 - 1.0 / (1.0 + std::exp(static_cast<double>(log_odds)));
  if (probability > occupied) return CellState::occupied;
  if (probability < free) return CellState::free;
  return CellState::unknown;
}

OccupancyGrid::OccupancyGrid(const GridGeometry& geometry, const LogOddsModel& model)
    : geometry_(geometry), model_(model), cells_(new float[geometry.cell_count()]) {
  STEREOSCOUT_CHECK(geometry.width_cells > 0 && geometry.height_cells > 0 && geometry.resolution_m > 0.0,
                    "occupancy grid needs a positive size and resolution");
  clear();
}

void OccupancyGrid::clear() {
  std::fill(cells_.get(), cells_.get() + geometry_.cell_count(), 0.0F);
  counts_ = {};
}

void OccupancyGrid::copy_from(const OccupancyGrid& other) {
  STEREOSCOUT_CHECK(geometry_.same_as(other.geometry_), "OccupancyGrid::copy_from needs the same geometry");
  std::memcpy(cells_.get(), other.cells_.get(), geometry_.cell_count() * sizeof(float));
  counts_ = other.counts_;
}

bool OccupancyGrid::same_cells_as(const OccupancyGrid& other) const {
  return geometry_.same_as(other.geometry_) &&
         std::memcmp(cells_.get(), other.cells_.get(), geometry_.cell_count() * sizeof(float)) == 0;
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

// Integer line walk (Bresenham) from the start cell to the end cell: every cell but the last
// is passed through (miss); the last is where the column ends.
void OccupancyGrid::cast_ray(double start_x, double start_y, double end_x, double end_y, bool end_is_obstacle) {
  const double span = kFarLimitInGridSpans * (geometry_.width_cells + geometry_.height_cells);
  const double fx0 = std::floor((start_x - geometry_.origin_x_m) / geometry_.resolution_m);
  const double fy0 = std::floor((start_y - geometry_.origin_y_m) / geometry_.resolution_m);
  const double fx1 = std::floor((end_x - geometry_.origin_x_m) / geometry_.resolution_m);
  const double fy1 = std::floor((end_y - geometry_.origin_y_m) / geometry_.resolution_m);
  // Written so that NaN fails every comparison and is rejected.
  if (!(std::abs(fx0) < span && std::abs(fy0) < span && std::abs(fx1) < span && std::abs(fy1) < span)) {
    ++counts_.rays_rejected;
    return;
  }
  ++counts_.rays;
  int x = static_cast<int>(fx0);
  int y = static_cast<int>(fy0);
  const int x1 = static_cast<int>(fx1);
  const int y1 = static_cast<int>(fy1);
  const int dx = std::abs(x1 - x);
  const int dy = -std::abs(y1 - y);
  const int step_x = x < x1 ? 1 : -1;
  const int step_y = y < y1 ? 1 : -1;
  int error = dx + dy;
  while (x != x1 || y != y1) {
    add(x, y, model_.miss);
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
  add(x1, y1, end_is_obstacle ? model_.hit : model_.miss);
}

void OccupancyGrid::insert(const ScanView& scan, const core::Pose2& pose) {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  const double start_x = pose.x + c * scan.origin_x_robot_m - s * scan.origin_y_robot_m;
  const double start_y = pose.y + s * scan.origin_x_robot_m + c * scan.origin_y_robot_m;
  for (std::size_t i = 0; i < scan.count; ++i) {
    const ScanPoint& point = scan.points[i];
    if (point.kind == core::DepthScanColumn::Kind::invalid) continue;
    const double px = point.x_robot_m;
    const double py = point.y_robot_m;
    cast_ray(start_x, start_y, pose.x + c * px - s * py, pose.y + s * px + c * py,
             point.kind == core::DepthScanColumn::Kind::obstacle);
  }
}

void OccupancyGrid::insert(const core::DepthScan& scan, const core::Pose2& pose) {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  const double ox = scan.origin_robot.x();
  const double oy = scan.origin_robot.y();
  const double start_x = pose.x + c * ox - s * oy;
  const double start_y = pose.y + s * ox + c * oy;
  for (const core::DepthScanColumn& column : scan.columns) {
    if (column.kind == core::DepthScanColumn::Kind::invalid) continue;
    const double px = column.x_robot_m;
    const double py = column.y_robot_m;
    cast_ray(start_x, start_y, pose.x + c * px - s * py, pose.y + s * px + c * py,
             column.kind == core::DepthScanColumn::Kind::obstacle);
  }
}

}  // namespace stereoscout::occupancy
