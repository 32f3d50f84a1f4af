#pragma once
// The door's axis (explore.door_axis_before_m). A 0.7 m robot has 0.10 m to spare on either
// side in a 0.9 m door, and the plan does not always pass it in the middle: the grid often
// holds such a door a cell wider on either side (the cells its jambs' edges lie in seen
// free), A* may then run through the passable cell nearest a jamb, 0.15 m off the middle,
// and gap centring moves a waypoint by half a cell only. Pure pursuit also cuts the turn into
// the door.
//
// The door is found on the plan: of the next narrow stretch (Plan::narrow) within
// door_axis_before_m plus half a metre along the plan, the narrow waypoint whose nearest
// obstacle cells on either side are nearest together; the door lies between those two cells.
// Its axis runs through their midpoint, square to the line between them, the way the plan
// passes. From door_axis_before_m before the middle (and no farther aside) until the disc
// has cleared the jambs (the safe distance past the middle), the follower steers at the point
// on the axis narrow_lookahead_m ahead of the robot's foot on it. A door found again on a new
// plan keeps its axis; one the robot has not begun to pass and no longer on the plan is
// dropped.
//
// All state is fixed-size; update() allocates nothing.

#include <cstddef>

#include <Eigen/Core>

#include "stereoscout/explore/grid_view.hpp"
#include "stereoscout/explore/navigation_map.hpp"
#include "stereoscout/explore/path_planner.hpp"

namespace stereoscout::explore {

struct DoorPassage {
  bool known = false;
  Eigen::Vector2d middle = Eigen::Vector2d::Zero();  // between the grid's two jamb cells
  Eigen::Vector2d along = Eigen::Vector2d::UnitX();  // unit, the way the plan passes
  double width_m = 0.0;                              // between the grid's two jamb cells' centres
  double clear_after_m = 0.0;                        // past the middle, the disc has cleared the jambs

  // From `before_m` before the middle (and no farther aside) to clear_after_m past it: the
  // point on the axis `lookahead_m` ahead of the robot's foot on it. False (target unchanged)
  // elsewhere.
  bool axis_target(const Eigen::Vector2d& robot, double lookahead_m, double before_m, Eigen::Vector2d& target) const;
};

// The door of the plan's next stretch of narrow waypoints (`narrow_only`, Plan::narrow) or of
// waypoints with obstacle cells on both sides within reach, beginning within `search_m` along
// the plan from `robot` (the follower at `progress`); false when there is none.
bool find_door(const Plan& plan, std::size_t progress, const NavigationMap& map, const Eigen::Vector2d& robot,
               double search_m, bool narrow_only, double clear_after_m, DoorPassage& door);

// The axes of one door found again lie within this angle of each other. The axis of a door
// found between other pairs of cells turns by about 6 degrees a cell over its width. A gap
// between a jamb and something beyond the door (a person in the corridor, 0.3 m past the wall)
// has its middle within 0.1-0.2 m of the door's but its axis 20-30 degrees off it; an axis or a
// sighting kept from it steered the robot into the jamb once the person had gone (office
// seed 4 at S2, docs/results.md).
inline constexpr double kSameDoorAngle_deg = 15.0;

// Both known, their middles within 0.3 m of each other, their axes within kSameDoorAngle_deg
// of each other, passed the same way: one door, found again on another plan or in another grid.
bool same_door(const DoorPassage& a, const DoorPassage& b);

class DoorAxis {
 public:
  explicit DoorAxis(const ExploreParams& params) : params_(params) {}

  void reset() { passage_ = DoorPassage(); }
  // With the plan being followed (`progress`: the follower's) and the map it was made on.
  void update(const Plan& plan, std::size_t progress, const NavigationMap& map, const Eigen::Vector2d& robot);
  const DoorPassage& passage() const { return passage_; }
  // The door a held door sighting measured the pose against (DoorSighting::door()): when it is
  // the passage's door, the axis runs through it from now on. The sighting's correction puts
  // the robot right against that door; the grid's jamb cells move between plans, and an axis
  // kept from an earlier plan 0.05-0.1 m aside of it spent the correction (office seed 3 at
  // N3's door). A sighting is held until the door is passed, so with no passage known (the
  // plan no longer passes the door, or not yet near enough) it brings back no axis.
  void follow_sighting(const DoorPassage& sighted);

  // The door of the plan's next narrow stretch; false when it has none near enough.
  bool next_door(const Plan& plan, std::size_t progress, const NavigationMap& map, const Eigen::Vector2d& robot,
                 DoorPassage& door) const;

 private:
  ExploreParams params_;
  DoorPassage passage_;
};

}  // namespace stereoscout::explore
