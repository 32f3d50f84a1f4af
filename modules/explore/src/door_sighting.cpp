#include "stereoscout/explore/door_sighting.hpp"

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

}  // namespace

DoorSighting::DoorSighting(const ExploreParams& params)
    : range_m_(params.explore.door_sighting_range_m),
      max_offset_m_(params.explore.door_sighting_max_offset_m),
      wall_from_scan_(params.explore.door_wall_from_scan),
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
  DoorGap gap;
  if (!measure(*seen.scan, seen.pose, seen.pan_rad, door, gap)) return;
  if (!wall_in_grid && !wall_in_scan(*seen.scan, seen.pose, door, gap)) {
    ++counters_.not_in_a_wall;
    return;
  }
  const Eigen::Vector2d across = left_of(door.along);
  offset_ = (door.middle - 0.5 * (gap.left + gap.right)).dot(across) * across;
  if (!held_) ++counters_.doors_sighted;
  ++counters_.sightings;
  held_ = true;
  door_ = door;
  sighted_pose_ = core::Pose2{seen.pose.x + offset_.x(), seen.pose.y + offset_.y(), seen.pose.theta};
  sighted_odometry_ = seen.odometry;
}

void DoorSighting::release() { held_ = false; }

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
