#include "stereoscout/occupancy/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "stereoscout/core/check.hpp"

namespace stereoscout::occupancy {
namespace {

float logit(double probability) { return static_cast<float>(std::log(probability / (1.0 - probability))); }

// A ray whose end cell lies further than this many grid spans from the grid is a broken
// measurement (or a units bug), not geometry: skipping it bounds the line walk.
constexpr double kFarLimitInGridSpans = 4.0;
constexpr float kMaxDistanceMm = 65535.0F;
// Origins closer than this fraction of a cell to the same lattice count as on it.
constexpr double kLatticeTolerance = 1e-6;

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
          static_cast<float>(config.log_odds_min), static_cast<float>(config.log_odds_max),
          static_cast<float>(config.in_view_range_m), static_cast<float>(config.looked_over_range_m),
          static_cast<float>(config.free_end_sigmas), static_cast<float>(config.free_end_short_m),
          static_cast<float>(config.hit_full_weight_range_m), static_cast<float>(config.near_hit_hold_range_m),
          static_cast<float>(config.near_hit_hold_end_m), logit(config.free_threshold), config.once_per_scan};
}

CellThresholds CellThresholds::from_config(const core::GridConfig& config) {
  return {config.occupied_threshold, config.free_threshold};
}

namespace {

CellState classify_log_odds(float log_odds, float occupied_above, float free_below) {
  if (log_odds > occupied_above) return CellState::occupied;
  if (log_odds < free_below) return CellState::free;
  return CellState::unknown;
}

}  // namespace

CellState CellThresholds::classify(float log_odds) const {
  return classify_log_odds(log_odds, logit(occupied), logit(free));
}

void classify_cells(const OccupancyGrid& grid, const CellThresholds& thresholds, CellState* cells,
                    std::uint8_t* in_view, std::uint8_t* looked_over) {
  const float occupied_above = logit(thresholds.occupied);
  const float free_below = logit(thresholds.free);
  const float* log_odds = grid.data();
  const std::size_t count = grid.geometry().cell_count();
  for (std::size_t i = 0; i < count; ++i) cells[i] = classify_log_odds(log_odds[i], occupied_above, free_below);
  grid.copy_marks(in_view, looked_over);
}

// Eight cells at a time: each byte of a word shifted down by its flag's bit and masked to 0 or 1.
void OccupancyGrid::copy_marks(std::uint8_t* in_view, std::uint8_t* looked_over) const {
  const std::size_t count = geometry_.cell_count();
  const std::uint8_t* flags = cell_flags_.get();
  auto copy_flag = [&](std::uint8_t* out, int bit) {
    constexpr std::uint64_t kLowBits = 0x0101010101010101ULL;
    constexpr std::size_t kWord = sizeof(std::uint64_t);
    std::size_t i = 0;
    for (; i + kWord <= count; i += kWord) {
      std::uint64_t word = 0;
      std::memcpy(&word, flags + i, kWord);
      word = (word >> bit) & kLowBits;
      std::memcpy(out + i, &word, kWord);
    }
    for (; i < count; ++i) out[i] = static_cast<std::uint8_t>((flags[i] >> bit) & 1U);
  };
  if (in_view != nullptr) copy_flag(in_view, kInViewBit);
  if (looked_over != nullptr) copy_flag(looked_over, kLookedOverBit);
}

OccupancyGrid::OccupancyGrid(const GridGeometry& geometry, const LogOddsModel& model)
    : geometry_(geometry),
      model_(model),
      cells_(new float[geometry.cell_count()]),
      cell_flags_(new std::uint8_t[geometry.cell_count()]),
      miss_stamps_(model.once_per_scan ? new std::uint8_t[geometry.cell_count()] : nullptr) {
  STEREOSCOUT_CHECK(geometry.width_cells > 0 && geometry.height_cells > 0 && geometry.resolution_m > 0.0,
                    "occupancy grid needs a positive size and resolution");
  clear();
}

void OccupancyGrid::clear() {
  std::fill(cells_.get(), cells_.get() + geometry_.cell_count(), 0.0F);
  std::fill(cell_flags_.get(), cell_flags_.get() + geometry_.cell_count(), std::uint8_t{0});
  if (miss_stamps_) std::fill(miss_stamps_.get(), miss_stamps_.get() + geometry_.cell_count(), std::uint8_t{0});
  scan_number_ = 0;
  counts_ = {};
}

void OccupancyGrid::begin_scan() {
  if (!miss_stamps_) return;
  if (scan_number_ == std::numeric_limits<std::uint8_t>::max()) {
    std::fill(miss_stamps_.get(), miss_stamps_.get() + geometry_.cell_count(), std::uint8_t{0});
    scan_number_ = 0;
  }
  ++scan_number_;
}

void OccupancyGrid::clear_at(double origin_x_m, double origin_y_m) {
  geometry_.origin_x_m = origin_x_m;
  geometry_.origin_y_m = origin_y_m;
  clear();
}

void OccupancyGrid::paste(const OccupancyGrid& part) {
  const GridGeometry& from = part.geometry_;
  STEREOSCOUT_CHECK(from.resolution_m == geometry_.resolution_m, "OccupancyGrid::paste needs the same resolution");
  const double shift_x = (from.origin_x_m - geometry_.origin_x_m) / geometry_.resolution_m;
  const double shift_y = (from.origin_y_m - geometry_.origin_y_m) / geometry_.resolution_m;
  const auto cells_x = static_cast<int>(std::lround(shift_x));
  const auto cells_y = static_cast<int>(std::lround(shift_y));
  STEREOSCOUT_CHECK(std::abs(shift_x - cells_x) < kLatticeTolerance && std::abs(shift_y - cells_y) < kLatticeTolerance,
                    "OccupancyGrid::paste needs origins a whole number of cells apart");
  const int first_x = std::max(0, -cells_x);
  const int last_x = std::min(from.width_cells, geometry_.width_cells - cells_x);
  if (first_x >= last_x) return;
  const auto row_length = static_cast<std::size_t>(last_x - first_x);
  for (int y = std::max(0, -cells_y); y < std::min(from.height_cells, geometry_.height_cells - cells_y); ++y) {
    const std::size_t source = part.index(first_x, y);
    const std::size_t target = index(first_x + cells_x, y + cells_y);
    std::memcpy(cells_.get() + target, part.cells_.get() + source, row_length * sizeof(float));
    std::memcpy(cell_flags_.get() + target, part.cell_flags_.get() + source, row_length);
  }
}

void OccupancyGrid::copy_from(const OccupancyGrid& other) {
  STEREOSCOUT_CHECK(geometry_.same_as(other.geometry_), "OccupancyGrid::copy_from needs the same geometry");
  std::memcpy(cells_.get(), other.cells_.get(), geometry_.cell_count() * sizeof(float));
  std::memcpy(cell_flags_.get(), other.cell_flags_.get(), geometry_.cell_count());
  counts_ = other.counts_;
}

bool OccupancyGrid::same_cells_as(const OccupancyGrid& other) const {
  return geometry_.same_as(other.geometry_) &&
         std::memcmp(cells_.get(), other.cells_.get(), geometry_.cell_count() * sizeof(float)) == 0 &&
         std::memcmp(cell_flags_.get(), other.cell_flags_.get(), geometry_.cell_count()) == 0;
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

void OccupancyGrid::hit(int cell_x, int cell_y, bool at_camera_height, float log_odds, bool holds) {
  if (!geometry_.contains(cell_x, cell_y)) return;
  add(cell_x, cell_y, log_odds);
  std::uint8_t& flags = cell_flags_[index(cell_x, cell_y)];
  // A hit at the camera's height (a person) ends a hold; a low one keeps it, or starts it.
  const std::uint8_t marks = flags & (kHitThisScan | kInView | kLookedOver | kWasFree);
  if (at_camera_height) {
    flags = static_cast<std::uint8_t>(marks | kLastHitAtCameraHeight);
  } else {
    const bool held = (flags & kHeldByNearHit) != 0U || (holds && (flags & kWasFree) == 0U);
    flags = static_cast<std::uint8_t>(marks | (held ? kHeldByNearHit : 0U));
  }
}

// Stereo's range error grows with the square of the range: beyond the full-weight range a
// hit's log-odds falls with it, so that one far hit alone does not make its cell occupied.
float OccupancyGrid::hit_log_odds(double range_m) const {
  const double full = model_.hit_full_weight_range_m;
  if (!(full > 0.0) || !(range_m > full)) return model_.hit;
  const double ratio = full / range_m;
  return static_cast<float>(model_.hit * ratio * ratio);
}

// A ray's two ends in cell units (x_m - origin) / resolution; false when an end is not finite
// or absurdly far (the caller counts it if it is a ray of its own).
bool OccupancyGrid::grid_coordinates(double start_x, double start_y, double end_x, double end_y,
                                     GridSegment& segment) const {
  // A small grid (a tile of the scan archive) still takes every plausible ray near it.
  const double size = geometry_.width_cells + geometry_.height_cells;
  const double span = std::max(kFarLimitInGridSpans * size, 2.0 * kMaxPlausibleScanRangeM / geometry_.resolution_m + size);
  segment = {(start_x - geometry_.origin_x_m) / geometry_.resolution_m,
             (start_y - geometry_.origin_y_m) / geometry_.resolution_m,
             (end_x - geometry_.origin_x_m) / geometry_.resolution_m,
             (end_y - geometry_.origin_y_m) / geometry_.resolution_m};
  // Written so that NaN fails every comparison and is rejected.
  if (!(std::abs(segment.x0) < span && std::abs(segment.y0) < span && std::abs(segment.x1) < span &&
        std::abs(segment.y1) < span)) {
    return false;
  }
  return true;
}

bool OccupancyGrid::misses_grid(const GridSegment& segment) const {
  const double low_x = std::floor(std::min(segment.x0, segment.x1));
  const double high_x = std::floor(std::max(segment.x0, segment.x1));
  const double low_y = std::floor(std::min(segment.y0, segment.y1));
  const double high_y = std::floor(std::max(segment.y0, segment.y1));
  return high_x < 0.0 || high_y < 0.0 || low_x >= geometry_.width_cells || low_y >= geometry_.height_cells;
}

namespace {

// Exact cell traversal (Amanatides and Woo): calls pass(cell) for every cell the segment
// crosses, in order, from its start cell up to but not including its end cell. An integer
// line walk between the two end cells strays up to half a cell from the true ray, far enough
// to clear the corner cell of a thin obstacle beside a door the ray went through.
template <typename Pass>
void walk_cells(const GridSegment& segment, Pass&& pass) {
  int x = static_cast<int>(std::floor(segment.x0));
  int y = static_cast<int>(std::floor(segment.y0));
  const int end_x = static_cast<int>(std::floor(segment.x1));
  const int end_y = static_cast<int>(std::floor(segment.y1));
  const double dx = segment.x1 - segment.x0;
  const double dy = segment.y1 - segment.y0;
  const int step_x = dx > 0.0 ? 1 : -1;
  const int step_y = dy > 0.0 ? 1 : -1;
  constexpr double kNever = std::numeric_limits<double>::infinity();
  // Ray parameter at which the next vertical / horizontal cell border is crossed, and per cell.
  const double delta_x = dx != 0.0 ? std::abs(1.0 / dx) : kNever;
  const double delta_y = dy != 0.0 ? std::abs(1.0 / dy) : kNever;
  double next_x = dx != 0.0 ? (step_x > 0 ? x + 1.0 - segment.x0 : segment.x0 - x) * delta_x : kNever;
  double next_y = dy != 0.0 ? (step_y > 0 ? y + 1.0 - segment.y0 : segment.y0 - y) * delta_y : kNever;
  // Exactly |end_x - x| + |end_y - y| steps, so rounding can never walk past the end cell.
  while (x != end_x || y != end_y) {
    pass(x, y);
    const bool along_x = y == end_y || (x != end_x && next_x < next_y);
    if (along_x) {
      x += step_x;
      next_x += delta_x;
    } else {
      y += step_y;
      next_y += delta_y;
    }
  }
}

}  // namespace

bool OccupancyGrid::marked_hit_this_scan(int cell_x, int cell_y) const {
  return (cell_flags_[index(cell_x, cell_y)] & kHitThisScan) != 0U;
}

bool OccupancyGrid::held_by_near_hit(int cell_x, int cell_y) const {
  if (!geometry_.contains(cell_x, cell_y)) return false;
  const std::size_t i = index(cell_x, cell_y);
  return cells_[i] > 0.0F && (cell_flags_[i] & kHeldByNearHit) != 0U;
}

void OccupancyGrid::miss(int cell_x, int cell_y) {
  if (!geometry_.contains(cell_x, cell_y) || marked_hit_this_scan(cell_x, cell_y)) return;
  const std::size_t i = index(cell_x, cell_y);
  if (miss_stamps_) {
    if (miss_stamps_[i] == scan_number_) return;  // held a low obstacle and missed once by this scan
    if (cells_[i] > 0.0F && (cell_flags_[i] & kLastHitAtCameraHeight) == 0U) miss_stamps_[i] = scan_number_;
  }
  add(cell_x, cell_y, model_.miss);
  if (cells_[i] <= 0.0F) cell_flags_[i] = static_cast<std::uint8_t>(cell_flags_[i] & ~kHeldByNearHit);
}

void OccupancyGrid::near_miss(int cell_x, int cell_y) {
  miss(cell_x, cell_y);
  if (!geometry_.contains(cell_x, cell_y)) return;
  const std::size_t i = index(cell_x, cell_y);
  if (cells_[i] < model_.free_below) cell_flags_[i] = static_cast<std::uint8_t>(cell_flags_[i] | kWasFree);
}

void OccupancyGrid::miss_unless_occupied(int cell_x, int cell_y) {
  if (geometry_.contains(cell_x, cell_y) && cells_[index(cell_x, cell_y)] > 0.0F) return;
  miss(cell_x, cell_y);
}

void OccupancyGrid::cast_ray(double start_x, double start_y, double end_x, double end_y, bool end_is_obstacle,
                             const RayRules& rules) {
  GridSegment segment;
  if (!grid_coordinates(start_x, start_y, end_x, end_y, segment)) {
    ++counts_.rays_rejected;
    return;
  }
  ++counts_.rays;
  if (misses_grid(segment)) return;  // a tile of the scan archive, away from this ray
  const double length = std::hypot(segment.x1 - segment.x0, segment.y1 - segment.y0);
  const double firm = rules.firm_m / geometry_.resolution_m;
  const double held_beyond = rules.held_beyond_m / geometry_.resolution_m;
  const double held_from = length - rules.held_within_end_m / geometry_.resolution_m;
  const bool guarded = std::isfinite(firm) || std::isfinite(held_beyond);
  // How far along the ray a cell's centre lies, in cells.
  const auto along = [&](int x, int y) {
    if (length <= 0.0) return 0.0;
    return ((x + 0.5 - segment.x0) * (segment.x1 - segment.x0) + (y + 0.5 - segment.y0) * (segment.y1 - segment.y0)) /
           length;
  };
  const auto pass = [&](int x, int y) {
    if (!guarded) {
      miss(x, y);
      return;
    }
    const double at = along(x, y);
    const bool near = at <= held_beyond;
    if (!near && at >= held_from && held_by_near_hit(x, y)) return;
    if (at > firm) {
      miss_unless_occupied(x, y);
    } else if (near && std::isfinite(held_beyond)) {
      near_miss(x, y);
    } else {
      miss(x, y);
    }
  };
  walk_cells(segment, pass);
  const int x1 = static_cast<int>(std::floor(segment.x1));
  const int y1 = static_cast<int>(std::floor(segment.y1));
  if (end_is_obstacle) {
    hit(x1, y1, rules.at_camera_height, rules.end_log_odds, rules.end_holds);
  } else {
    pass(x1, y1);
  }
}

void OccupancyGrid::clear_camera_height_hits(double start_x, double start_y, double end_x, double end_y) {
  GridSegment segment;
  if (!grid_coordinates(start_x, start_y, end_x, end_y, segment)) {
    ++counts_.rays_rejected;
    return;
  }
  if (misses_grid(segment)) return;
  walk_cells(segment, [this](int x, int y) {
    if (geometry_.contains(x, y) && (cell_flags_[index(x, y)] & kLastHitAtCameraHeight) != 0U) miss(x, y);
  });
}

namespace {

// Whole millimetres, saturated: NaN or negative -> 0 (from the origin), beyond 65.535 m ->
// never (no floor is that far anyway).
std::uint16_t saturated_mm(float distance_m) {
  const float mm = distance_m * 1000.0F;
  const float clamped = mm > 0.0F ? std::min(mm, kMaxDistanceMm) : 0.0F;
  return static_cast<std::uint16_t>(std::lround(clamped));
}

}  // namespace

ScanPoint ScanPoint::from_column(const core::DepthScanColumn& column) {
  return {column.x_robot_m,
          column.y_robot_m,
          column.kind,
          column.obstacle_at_camera_height,
          saturated_mm(column.floor_visible_from_m),
          saturated_mm(column.measurable_from_m),
          saturated_mm(column.end_range_sigma_m)};
}

void OccupancyGrid::insert_column(const Eigen::Vector2d& origin, const Eigen::Vector2d& end, const ScanPoint& point) {
  const bool obstacle = point.kind == core::DepthScanColumn::Kind::obstacle;
  const double measurable_from = point.measurable_from_m();
  const double visible_from = std::max(point.floor_visible_from_m(), measurable_from);
  const Eigen::Vector2d along = end - origin;
  const double length = along.norm();
  if (!std::isfinite(length)) {
    ++counts_.rays_rejected;
    return;
  }
  const double short_of_end = std::max<double>(geometry_.resolution_m, model_.free_end_short_m);
  const double reach = obstacle ? length : length - short_of_end;
  const auto at = [&](double distance) { return Eigen::Vector2d(origin + along * (distance / length)); };
  // The blind zone: only obstacles at the camera's height would have been seen there.
  const double blind_end = std::min(visible_from, reach);
  if (blind_end > measurable_from) {
    const Eigen::Vector2d start = at(measurable_from);
    const Eigen::Vector2d stop = at(blind_end);
    clear_camera_height_hits(start.x(), start.y(), stop.x(), stop.y());
  }
  const double in_view_end = std::min<double>(model_.in_view_range_m, obstacle ? length : model_.in_view_range_m);
  if (in_view_end > visible_from) mark_cells(at(visible_from), at(in_view_end), kInView);
  const double looked_over_end = std::min<double>(model_.looked_over_range_m, length);
  if (looked_over_end > 0.0) mark_cells(origin, at(looked_over_end), kLookedOver);
  RayRules rules;
  rules.at_camera_height = point.obstacle_at_camera_height;
  rules.end_log_odds = hit_log_odds(length);
  const double hold_range = model_.near_hit_hold_range_m;
  rules.end_holds = hold_range > 0.0 && length <= hold_range;
  if (obstacle && length <= visible_from) {
    cast_ray(end.x(), end.y(), end.x(), end.y(), true, rules);  // its own cell only
    return;
  }
  if (!obstacle && !(reach > visible_from)) return;  // no visible floor on this ray
  const Eigen::Vector2d start = at(visible_from);
  const Eigen::Vector2d stop = obstacle ? end : at(reach);
  // A free column's end may lie beyond the wall behind it by its range error (see the header).
  const double uncertain = obstacle ? 0.0 : model_.free_end_sigmas * point.end_range_sigma_m();
  if (uncertain > 0.0) rules.firm_m = length - uncertain - visible_from;
  // A far ray's error across its way is the heading's error times its range (see the header).
  if (hold_range > 0.0) {
    rules.held_beyond_m = hold_range - visible_from;
    rules.held_within_end_m = model_.near_hit_hold_end_m;
  }
  cast_ray(start.x(), start.y(), stop.x(), stop.y(), obstacle, rules);
}

void OccupancyGrid::mark_cells(const Eigen::Vector2d& from, const Eigen::Vector2d& to, std::uint8_t flag) {
  GridSegment segment;
  // Not counted: a rejected end is the column's, counted by its ray.
  if (!grid_coordinates(from.x(), from.y(), to.x(), to.y(), segment) || misses_grid(segment)) return;
  const auto mark = [this, flag](int x, int y) {
    if (geometry_.contains(x, y)) cell_flags_[index(x, y)] |= flag;
  };
  walk_cells(segment, mark);
  mark(static_cast<int>(std::floor(segment.x1)), static_cast<int>(std::floor(segment.y1)));
}

// A scan's frame: rotates and translates robot-frame points into the map frame.
struct OccupancyGrid::ScanFrame {
  double cos_theta;
  double sin_theta;
  core::Pose2 pose;
  Eigen::Vector2d origin;  // the camera centre on the floor, map frame

  ScanFrame(const core::Pose2& robot_pose, double origin_x_robot, double origin_y_robot)
      : cos_theta(std::cos(robot_pose.theta)), sin_theta(std::sin(robot_pose.theta)), pose(robot_pose) {
    origin = to_map(origin_x_robot, origin_y_robot);
  }
  Eigen::Vector2d to_map(double x_robot, double y_robot) const {
    return {pose.x + cos_theta * x_robot - sin_theta * y_robot, pose.y + sin_theta * x_robot + cos_theta * y_robot};
  }
};

void OccupancyGrid::set_hit_marks(const Eigen::Vector2d& end, bool marked) {
  int cell_x = 0;
  int cell_y = 0;
  if (!cell_of(end.x(), end.y(), cell_x, cell_y)) return;
  std::uint8_t& flags = cell_flags_[index(cell_x, cell_y)];
  flags = static_cast<std::uint8_t>(marked ? (flags | kHitThisScan) : (flags & ~kHitThisScan));
}

// Three passes over the valid columns. An obstacle hit wins over the misses of the same scan
// (as in OctoMap's scan update): a cell a column ends in is marked first and the other
// columns' rays pass it without a miss. A 2 cm poster fills a sliver of its 10 cm cell, and
// the rays through the door beside it cross the rest of that cell.
template <typename EachPoint>
void OccupancyGrid::insert_points(const ScanFrame& frame, EachPoint&& each_point) {
  const auto end_of = [&frame](const ScanPoint& point) { return frame.to_map(point.x_robot_m, point.y_robot_m); };
  const auto mark_obstacles = [&](bool marked) {
    each_point([&](const ScanPoint& point) {
      if (point.kind == core::DepthScanColumn::Kind::obstacle) set_hit_marks(end_of(point), marked);
    });
  };
  begin_scan();
  mark_obstacles(true);
  each_point([&](const ScanPoint& point) { insert_column(frame.origin, end_of(point), point); });
  mark_obstacles(false);
}

void OccupancyGrid::insert(const ScanView& scan, const core::Pose2& pose) {
  insert_points(ScanFrame(pose, scan.origin_x_robot_m, scan.origin_y_robot_m), [&scan](auto&& visit) {
    for (std::size_t i = 0; i < scan.count; ++i) {
      if (scan.points[i].kind != core::DepthScanColumn::Kind::invalid) visit(scan.points[i]);
    }
  });
}

void OccupancyGrid::insert(const core::DepthScan& scan, const core::Pose2& pose) {
  insert_points(ScanFrame(pose, scan.origin_robot.x(), scan.origin_robot.y()), [&scan](auto&& visit) {
    for (const core::DepthScanColumn& column : scan.columns) {
      if (column.kind != core::DepthScanColumn::Kind::invalid) visit(ScanPoint::from_column(column));
    }
  });
}

}  // namespace stereoscout::occupancy
