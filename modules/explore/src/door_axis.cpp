#include "stereoscout/explore/door_axis.hpp"

#include <cmath>
#include <limits>

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::explore {
namespace {
// A door's sides are looked for this far from each narrow waypoint: a gap up to 1.5 m wide as
// the grid holds it (a 0.9 m door whose jambs' edge cells are seen free is 1.1 m wide in it,
// and a waypoint beside its middle is 0.15 m nearer one side).
constexpr double kSideReach_m = 0.75;
// The next door is looked for this much farther along the plan than door_axis_before_m: the
// plan bends towards a door before it reaches its axis.
constexpr double kSearchBeyond_m = 0.5;
// Doors whose middles lie nearer than this to each other (and whose axes lie within
// kSameDoorAngle_deg) are the same door, found again on a new plan.
constexpr double kSameDoor_m = 0.3;
}  // namespace

bool DoorPassage::axis_target(const Eigen::Vector2d& robot, double lookahead_m, double before_m,
                              Eigen::Vector2d& target) const {
  if (!known || before_m <= 0.0) return false;
  const Eigen::Vector2d relative = robot - middle;
  const double ahead = along.dot(relative);
  const double aside = std::abs(relative.x() * along.y() - relative.y() * along.x());
  if (ahead < -before_m || ahead > clear_after_m || aside > before_m) return false;
  target = middle + (ahead + lookahead_m) * along;
  return true;
}

bool DoorAxis::next_door(const Plan& plan, std::size_t progress, const NavigationMap& map,
                         const Eigen::Vector2d& robot, DoorPassage& door) const {
  return find_door(plan, progress, map, robot, params_.explore.door_axis_before_m + kSearchBeyond_m,
                   !params_.explore.door_axis_all_gaps,
                   params_.safe_distance_m(map.grid().resolution_m), door);
}

bool find_door(const Plan& plan, std::size_t progress, const NavigationMap& map, const Eigen::Vector2d& robot,
               double search_m, bool narrow_only, double clear_after_m, DoorPassage& door) {
  const std::size_t count = plan.waypoints.size();
  double travelled = 0.0;
  Eigen::Vector2d previous = robot;
  bool in_stretch = false;
  double narrowest = std::numeric_limits<double>::infinity();
  for (std::size_t k = progress; k + 1 < count; ++k) {
    travelled += (plan.waypoints[k] - previous).norm();
    previous = plan.waypoints[k];
    const bool candidate = !narrow_only || plan.narrow[k];
    Eigen::Vector2d left;
    Eigen::Vector2d right;
    bool aside = false;
    if (candidate && k > 0) {
      const Eigen::Vector2d way = plan.waypoints[k + 1] - plan.waypoints[k - 1];
      if (way.squaredNorm() > 0.0) {
        const Eigen::Vector2d across = Eigen::Vector2d(-way.y(), way.x()).normalized();
        aside = map.nearest_obstacles_aside(plan.waypoints[k], across, kSideReach_m, left, right);
      }
    }
    // A narrow stretch is one of narrow waypoints; without narrow_only, one of waypoints with
    // obstacle cells on both sides.
    if (narrow_only ? !candidate : !aside) {
      if (in_stretch || travelled > search_m) break;  // past the next stretch, or too far
      continue;
    }
    in_stretch = true;
    if (!aside) continue;
    const double gap = (left - right).norm();
    if (gap >= narrowest) continue;
    narrowest = gap;
    // `left` lies to the left of the way the plan passes: the axis is the line between the two
    // cells turned a quarter clockwise.
    const Eigen::Vector2d left_of_way = (left - right) / gap;
    door.known = true;
    door.middle = 0.5 * (left + right);
    door.along = Eigen::Vector2d(left_of_way.y(), -left_of_way.x());
    door.width_m = gap;
    door.clear_after_m = clear_after_m;
  }
  return std::isfinite(narrowest);
}

bool same_door(const DoorPassage& a, const DoorPassage& b) {
  return a.known && b.known && (a.middle - b.middle).norm() <= kSameDoor_m &&
         a.along.dot(b.along) >= std::cos(core::degrees_to_radians(kSameDoorAngle_deg));
}

void DoorAxis::follow_sighting(const DoorPassage& sighted) {
  if (same_door(sighted, passage_)) passage_ = sighted;
}

void DoorAxis::update(const Plan& plan, std::size_t progress, const NavigationMap& map, const Eigen::Vector2d& robot) {
  DoorPassage door;
  if (next_door(plan, progress, map, robot, door)) {
    // A door found again, passed the same way, keeps its axis: the robot steers by one line
    // through it.
    if (!same_door(door, passage_)) passage_ = door;
    return;
  }
  // No door ahead on this plan: the one the robot is passing is kept until the disc has
  // cleared it (the plan's narrow waypoints there may lie behind the follower's progress);
  // one it has not reached yet is not on this plan.
  if (!passage_.known) return;
  const double ahead = passage_.along.dot(robot - passage_.middle);
  if (ahead < -passage_.clear_after_m || ahead > passage_.clear_after_m) reset();
}

}  // namespace stereoscout::explore
