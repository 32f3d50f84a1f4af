#include "stereoscout/explore/door_sighting.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace stereoscout::explore {
namespace {
// A jamb's ray must meet the door's line at least this steeply (cosine to the axis): a ray
// along the wall meets it anywhere.
constexpr double kMinRayAlongAxis = 0.25;

Eigen::Vector2d left_of(const Eigen::Vector2d& direction) { return {-direction.y(), direction.x()}; }

// Where the ray from `origin` through `point` meets the door's line; false when it meets it
// too obliquely or behind the origin.
bool meet_door_line(const Eigen::Vector2d& origin, const Eigen::Vector2d& point, const DoorPassage& door,
                    Eigen::Vector2d& met) {
  const Eigen::Vector2d ray = (point - origin).normalized();
  const double steepness = ray.dot(door.along);
  if (steepness < kMinRayAlongAxis) return false;
  const double distance = (door.middle - origin).dot(door.along) / steepness;
  if (distance <= 0.0) return false;
  met = origin + distance * ray;
  return true;
}

// A least-squares line through points given relative to a reference point.
class LineFit {
 public:
  void add(const Eigen::Vector2d& point) {
    ++count_;
    sum_ += point;
    sxx_ += point.x() * point.x();
    sxy_ += point.x() * point.y();
    syy_ += point.y() * point.y();
  }
  int count() const { return count_; }
  // The points' centroid and the line's direction (unit; its sign arbitrary); false for fewer
  // than two points.
  bool line(Eigen::Vector2d& centroid, Eigen::Vector2d& direction) const {
    if (count_ < 2) return false;
    centroid = sum_ / count_;
    const double cxx = sxx_ / count_ - centroid.x() * centroid.x();
    const double cxy = sxy_ / count_ - centroid.x() * centroid.y();
    const double cyy = syy_ / count_ - centroid.y() * centroid.y();
    const double angle = core::principal_axis_angle(cxx, cxy, cyy);
    direction = {std::cos(angle), std::sin(angle)};
    return true;
  }

 private:
  int count_ = 0;
  Eigen::Vector2d sum_ = Eigen::Vector2d::Zero();
  double sxx_ = 0.0;
  double sxy_ = 0.0;
  double syy_ = 0.0;
};

// The line through the wall points `for_each_point(visit)` hands to `visit` (relative to the
// door's middle): fitted to all, then twice to those within `tolerance_m` of the last fit. Its
// direction's angle (map frame) in `angle_rad`, a point on it in `through`; false with fewer
// than `min_points` kept or spread less than DoorSighting::kHeadingMinSpan_m along it.
template <typename ForEachPoint>
bool fit_wall_line(ForEachPoint for_each_point, double tolerance_m, int min_points, double& angle_rad,
                   Eigen::Vector2d& through) {
  LineFit fit;
  for_each_point([&](const Eigen::Vector2d& point) { fit.add(point); });
  Eigen::Vector2d centroid;
  Eigen::Vector2d direction;
  for (int refit = 0; refit < 2; ++refit) {
    if (!fit.line(centroid, direction)) return false;
    const Eigen::Vector2d normal = left_of(direction);
    LineFit closer;
    for_each_point([&](const Eigen::Vector2d& point) {
      if (std::abs((point - centroid).dot(normal)) <= tolerance_m) closer.add(point);
    });
    fit = closer;
  }
  if (fit.count() < min_points || !fit.line(centroid, direction)) return false;
  double lowest = 0.0;
  double highest = 0.0;
  const Eigen::Vector2d normal = left_of(direction);
  for_each_point([&](const Eigen::Vector2d& point) {
    if (std::abs((point - centroid).dot(normal)) > tolerance_m) return;
    const double along = (point - centroid).dot(direction);
    lowest = std::min(lowest, along);
    highest = std::max(highest, along);
  });
  if (highest - lowest < DoorSighting::kHeadingMinSpan_m) return false;
  angle_rad = std::atan2(direction.y(), direction.x());
  through = centroid;
  return true;
}

// Whether `point` (relative to the door's middle) lies where the wall beside `door` is looked
// for: beyond either jamb up to kHeadingWallReach_m across, within kHeadingBand_m of its line.
bool beside_door(const Eigen::Vector2d& point, const DoorPassage& door) {
  const double across = std::abs(point.dot(left_of(door.along)));
  return std::abs(point.dot(door.along)) <= DoorSighting::kHeadingBand_m && across >= 0.5 * door.width_m &&
         across <= DoorSighting::kHeadingWallReach_m;
}

}  // namespace

DoorSighting::DoorSighting(const ExploreParams& params)
    : range_m_(params.explore.door_sighting_range_m),
      max_offset_m_(params.explore.door_sighting_max_offset_m),
      wall_from_scan_(params.explore.door_wall_from_scan),
      correct_heading_(params.explore.door_sighting_heading),
      baseline_m_(params.camera_baseline_m) {}

bool DoorSighting::wants(const SeenObstacles& seen) const {
  return enabled() && seen.scan != nullptr && seen.time_s > last_scan_time_s_;
}

void DoorSighting::observe(const SeenObstacles& seen, const DoorPassage& door, const GridView& grid) {
  if (!wants(seen)) return;
  last_scan_time_s_ = seen.time_s;
  if (held_ && door.known && !same_door(door, door_)) release();  // the plan passes another door now
  if (!door.known) return;
  const Eigen::Vector2d camera = seen.pose.transform_point(seen.scan->origin_robot);
  if ((camera - door.middle).norm() > range_m_ || (camera - door.middle).dot(door.along) > -kMinAhead_m) return;
  ++counters_.scans_at_doors;
  const bool wall_in_grid = in_a_wall(door, grid);
  if (!wall_in_grid && !wall_from_scan_) {
    ++counters_.not_in_a_wall;
    return;
  }
  core::Pose2 pose = seen.pose;
  const HeadingSource heading = correct_heading_ ? scan_heading(seen, door, grid, pose) : HeadingSource::none;
  DoorGap gap;
  if (!measure(*seen.scan, pose, seen.pan_rad, door, gap)) return;
  if (!wall_in_grid && !wall_in_scan(*seen.scan, pose, door, gap)) {
    ++counters_.not_in_a_wall;
    return;
  }
  const Eigen::Vector2d across = left_of(door.along);
  offset_ = (door.middle - 0.5 * (gap.left + gap.right)).dot(across) * across;
  heading_correction_rad_ = core::wrap_angle(pose.theta - seen.pose.theta);
  if (!held_) ++counters_.doors_sighted;
  ++counters_.sightings;
  count_heading(heading);
  heading_held_ = heading == HeadingSource::wall || heading == HeadingSource::held;
  held_ = true;
  door_ = door;
  sighted_pose_ = core::Pose2{pose.x + offset_.x(), pose.y + offset_.y(), pose.theta};
  sighted_odometry_ = seen.odometry;
}

void DoorSighting::release() {
  held_ = false;
  heading_held_ = false;
}

// The heading from the wall beside the door; else, while a sighting of this door whose heading
// was corrected is held, the heading it carries by the odometry (nearer than about 1.1 m the
// matcher measures no wall in the image's outer band, and a wall's heading that jumps from it
// is not the wall's); else the estimate's.
DoorSighting::HeadingSource DoorSighting::scan_heading(const SeenObstacles& seen, const DoorPassage& door,
                                                       const GridView& grid, core::Pose2& pose) {
  const bool carried = held_ && heading_held_ && same_door(door, door_);
  const double carried_rad = carried ? sighted_pose_.compose(sighted_odometry_.between(seen.odometry)).theta : 0.0;
  double correction_rad = 0.0;
  if (heading_error(*seen.scan, seen.pose, door, grid, correction_rad)) {
    const double measured_rad = core::wrap_angle(seen.pose.theta + correction_rad);
    if (!carried || std::abs(core::wrap_angle(measured_rad - carried_rad)) <= core::degrees_to_radians(kMaxHeadingJump_deg)) {
      pose.theta = measured_rad;
      return HeadingSource::wall;
    }
    ++counters_.heading_jumps;
  }
  if (carried) {
    pose.theta = carried_rad;
    return HeadingSource::held;
  }
  return HeadingSource::unmeasured;
}

void DoorSighting::count_heading(HeadingSource heading) {
  switch (heading) {
    case HeadingSource::none: break;
    case HeadingSource::wall: ++counters_.headings_corrected; break;
    case HeadingSource::held: ++counters_.headings_carried; break;
    case HeadingSource::unmeasured: ++counters_.heading_unmeasured; break;
  }
}

core::Pose2 DoorSighting::navigation_pose(const core::Pose2& pose, const core::Pose2& odometry) {
  if (!held_) return pose;
  const core::Pose2 moved = sighted_pose_.compose(sighted_odometry_.between(odometry));
  const bool cleared = (moved.translation() - door_.middle).dot(door_.along) > door_.clear_after_m;
  const bool driven_far = (odometry.translation() - sighted_odometry_.translation()).norm() > kHoldTravelFactor * range_m_;
  if (cleared || driven_far) {
    release();
    return pose;
  }
  return moved;
}

bool DoorSighting::measured_point(const core::DepthScan& scan, const core::Pose2& pose, int column,
                                  Eigen::Vector2d& point) {
  const core::DepthScanColumn& seen = scan.columns[static_cast<std::size_t>(column)];
  if (seen.kind == core::DepthScanColumn::Kind::invalid) return false;
  point = pose.transform_point({seen.x_robot_m, seen.y_robot_m});
  return true;
}

bool DoorSighting::sees_past(const core::DepthScan& scan, const core::Pose2& pose, const DoorPassage& door, int column,
                             Eigen::Vector2d& point) {
  return measured_point(scan, pose, column, point) && (point - door.middle).dot(door.along) > kPastLine_m;
}

bool DoorSighting::wall_in_scan(const core::DepthScan& scan, const core::Pose2& pose, const DoorPassage& door,
                                const DoorGap& gap) {
  const Eigen::Vector2d across = left_of(door.along);
  const int columns = static_cast<int>(scan.columns.size());
  // Columns run from the image's left to its right: outward from the gap's first column lies
  // the wall left of the way through (across > 0), from its last the wall right of it.
  bool wall_seen = false;
  for (const int step : {-1, 1}) {
    const double side = step < 0 ? 1.0 : -1.0;
    const Eigen::Vector2d& jamb = step < 0 ? gap.left : gap.right;
    int on_line = 0;
    int off_line = 0;
    bool reached = false;
    Eigen::Vector2d point;
    for (int column = step < 0 ? gap.first_column - 1 : gap.last_column + 1;
         column >= 0 && column < columns && !reached; column += step) {
      if (!measured_point(scan, pose, column, point)) continue;
      const double beyond_jamb = side * (point - jamb).dot(across);
      if (std::abs((point - door.middle).dot(door.along)) > kWallOnLine_m) {
        ++off_line;
      } else if (beyond_jamb > -kWallOnLine_m) {
        ++on_line;
        reached = beyond_jamb >= kWallBeside_m;
      }
    }
    if (kWallOffLineShare * off_line > on_line) return false;
    wall_seen = wall_seen || reached;
  }
  return wall_seen;
}

bool DoorSighting::measure(const core::DepthScan& scan, const core::Pose2& pose, double pan_rad,
                           const DoorPassage& door, DoorGap& gap) {
  const Eigen::Vector2d camera = pose.transform_point(scan.origin_robot);
  // The scan's columns are the right camera's. Just right of the left jamb's edge in its image
  // lies a band of the background that the left camera does not see past the jamb, so the
  // matcher measures nothing there (at 1.5 m, with the floor beyond at 3.6 m, 15 columns:
  // 0.05 m). The first column past it is the first background the left camera sees beside
  // the jamb: the jamb lies on the left camera's ray to it, which is to the camera's left.
  const Eigen::Vector2d camera_left(-std::sin(pan_rad), std::cos(pan_rad));
  const Eigen::Vector2d left_camera = pose.transform_point(scan.origin_robot + baseline_m_ * camera_left);
  const double middle_bearing = std::atan2(door.middle.y() - camera.y(), door.middle.x() - camera.x());
  const auto side_of_middle = [&](const Eigen::Vector2d& point) {
    return core::wrap_angle(std::atan2(point.y() - camera.y(), point.x() - camera.x()) - middle_bearing);
  };
  const int columns = static_cast<int>(scan.columns.size());
  // Runs of columns that see past the door's line, in image order (left to right), each
  // bridging up to kMaxSplitColumns columns that do not (a floor's seam on the threshold
  // seen as a surface); the one whose bearings span the middle's.
  Eigen::Vector2d point;
  for (int column = 0; column < columns; ++column) {
    if (!sees_past(scan, pose, door, column, point)) continue;
    const int first = column;
    const Eigen::Vector2d first_point = point;
    int last = column;
    Eigen::Vector2d last_point = point;
    for (int next = column + 1; next < columns && next - last <= kMaxSplitColumns + 1; ++next) {
      if (sees_past(scan, pose, door, next, point)) {
        last = next;
        last_point = point;
      }
    }
    column = last;
    const double first_side = side_of_middle(first_point);
    const double last_side = side_of_middle(last_point);
    if (first_side * last_side > 0.0) continue;  // both ends on one side of the middle: not this door's run
    if (touches_image_edge(first, last, columns)) {
      ++counters_.jamb_at_image_edge;
      return false;
    }
    gap.first_column = first;
    gap.last_column = last;
    // Columns run from the image's left to its right: the run's first end is the left jamb.
    if (!meet_door_line(left_camera, first_point, door, gap.left) || !meet_door_line(camera, last_point, door, gap.right)) {
      ++counters_.no_gap;
      return false;
    }
    if (std::abs((gap.left - gap.right).norm() - door.width_m) > kWidthTolerance_m) {
      ++counters_.width_disagrees;
      return false;
    }
    const Eigen::Vector2d across = left_of(door.along);
    if (std::abs((door.middle - 0.5 * (gap.left + gap.right)).dot(across)) > max_offset_m_) {
      ++counters_.offset_too_large;
      return false;
    }
    return true;
  }
  ++counters_.no_gap;
  return false;
}

template <typename Visit>
void DoorSighting::for_each_scan_point(const core::DepthScan& scan, const core::Pose2& pose, const DoorPassage& door,
                                       Visit visit) {
  // The pose's sine and cosine once (as measured_point() places a column): the heading's
  // search walks the scan once for each turn it tries.
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  for (const core::DepthScanColumn& column : scan.columns) {
    if (column.kind == core::DepthScanColumn::Kind::invalid) continue;
    const double x = column.x_robot_m;
    const double y = column.y_robot_m;
    const Eigen::Vector2d point = Eigen::Vector2d(pose.x + c * x - s * y, pose.y + s * x + c * y) - door.middle;
    if (beside_door(point, door)) visit(point);
  }
}

bool DoorSighting::heading_error(const core::DepthScan& scan, const core::Pose2& pose, const DoorPassage& door,
                                 const GridView& grid, double& correction_rad) {
  double grid_angle = 0.0;
  Eigen::Vector2d grid_through;
  if (!grid_wall_line(door, grid, grid_angle, grid_through)) return false;
  // The turn about the robot that brings the most of the scan's points beside the door onto
  // one line along the grid's wall and near it (the pose may be off along the door's axis
  // too): points seen through the door into the room beyond, or of a chair before the wall,
  // lie off it.
  const Eigen::Vector2d grid_normal(-std::sin(grid_angle), std::cos(grid_angle));
  const Eigen::Vector2d robot = pose.translation() - door.middle;
  const int steps = static_cast<int>(std::lround(kMaxHeadingError_deg / kHeadingSearchStep_deg));
  HeadingSearch best;
  for (int step = -steps; step <= steps; ++step) {
    const double turn = core::degrees_to_radians(step * kHeadingSearchStep_deg);
    const Eigen::Rotation2Dd rotation(turn);
    std::array<int, kHeadingOffsetBins> bins{};
    for_each_scan_point(scan, pose, door, [&](const Eigen::Vector2d& point) {
      const double offset = (robot + rotation * (point - robot) - grid_through).dot(grid_normal);
      const int bin = static_cast<int>(std::floor((offset + kHeadingLineGap_m) / kHeadingFitTolerance_m));
      if (bin >= 0 && bin < kHeadingOffsetBins) ++bins[static_cast<std::size_t>(bin)];
    });
    for (std::size_t bin = 0; bin + 1 < bins.size(); ++bin) {
      const int on_line = bins[bin] + bins[bin + 1];
      if (on_line <= best.on_line) continue;
      best.on_line = on_line;
      best.turn_rad = turn;
      best.offset_m = -kHeadingLineGap_m + (static_cast<double>(bin) + 1.0) * kHeadingFitTolerance_m;
    }
  }
  if (best.on_line < kHeadingMinColumns) return false;
  // The line through those points, fitted in the scan's own frame, and its spread.
  const Eigen::Rotation2Dd rotation(best.turn_rad);
  LineFit fit;
  double lowest = 0.0;
  double highest = 0.0;
  const Eigen::Vector2d grid_along(std::cos(grid_angle), std::sin(grid_angle));
  for_each_scan_point(scan, pose, door, [&](const Eigen::Vector2d& point) {
    const Eigen::Vector2d turned = robot + rotation * (point - robot) - grid_through;
    if (std::abs(turned.dot(grid_normal) - best.offset_m) > kHeadingFitTolerance_m) return;
    fit.add(point);
    lowest = std::min(lowest, turned.dot(grid_along));
    highest = std::max(highest, turned.dot(grid_along));
  });
  Eigen::Vector2d centroid;
  Eigen::Vector2d direction;
  if (highest - lowest < kHeadingMinSpan_m || !fit.line(centroid, direction)) return false;
  // Lines have no direction: the turn lies within a quarter turn either way.
  const double turn = core::wrap_centred(grid_angle - std::atan2(direction.y(), direction.x()), core::kPi);
  if (std::abs(turn) > core::degrees_to_radians(kMaxHeadingError_deg)) return false;
  correction_rad = turn;
  return true;
}

bool DoorSighting::grid_wall_line(const DoorPassage& door, const GridView& grid, double& angle_rad,
                                  Eigen::Vector2d& through) {
  const double reach = kHeadingWallReach_m + kHeadingBand_m;
  const Eigen::Vector2i low = grid.cell_of(door.middle - Eigen::Vector2d(reach, reach));
  const Eigen::Vector2i high = grid.cell_of(door.middle + Eigen::Vector2d(reach, reach));
  const auto grid_cells = [&](const auto& visit) {
    for (int y = std::max(low.y(), 0); y <= std::min(high.y(), grid.height - 1); ++y) {
      for (int x = std::max(low.x(), 0); x <= std::min(high.x(), grid.width - 1); ++x) {
        const Eigen::Vector2d point = grid.center(x, y) - door.middle;
        if (grid.at(x, y) == CellState::occupied && beside_door(point, door)) visit(point);
      }
    }
  };
  return fit_wall_line(grid_cells, std::max(kHeadingFitTolerance_m, kHeadingCellTolerance * grid.resolution_m),
                       kHeadingMinCells, angle_rad, through);
}

bool DoorSighting::in_a_wall(const DoorPassage& door, const GridView& grid) {
  const Eigen::Vector2d across = left_of(door.along);
  for (double side : {-1.0, 1.0}) {
    const Eigen::Vector2d jamb = door.middle + side * 0.5 * door.width_m * across;
    int occupied = 0;
    for (int k = 1; k <= kWallCells; ++k) {
      const Eigen::Vector2i cell = grid.cell_of(jamb + side * k * grid.resolution_m * across);
      occupied += grid.contains(cell.x(), cell.y()) && grid.at(cell.x(), cell.y()) == CellState::occupied ? 1 : 0;
    }
    if (occupied < kWallCellsOccupied) return false;
  }
  return true;
}

bool DoorSighting::touches_image_edge(int first, int last, int columns) {
  return first < kEdgeColumns || last > columns - 1 - kEdgeColumns;
}

}  // namespace stereoscout::explore
