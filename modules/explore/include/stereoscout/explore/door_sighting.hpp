#pragma once
// Door sighting (explore.door_sighting_far_m). The pose the explorer steers by can be
// 0.1-0.2 m off at a door (its heading a few degrees off since the door was mapped), and a
// 0.7 m robot has 0.10 m to spare in a 0.9 m door. A scan measures the jambs from the robot
// itself and is placed in the map with the pose the robot steers by, so where the scan sees
// a gap's sides against where the grid holds them is that pose's error at the gap, whatever
// caused it.
//
// The gap ("throat") lies between the two obstacle cells nearest together that a narrow
// waypoint (Plan::narrow) of the plan's next narrow stretch has nearest on either side, where
// that waypoint meets the line through them. Each new scan taken while the robot is between door_sighting_near_m and
// door_sighting_far_m of the throat is a sighting: the scan's obstacle columns (any height)
// within a wall's depth of that line give the distance along it to the nearest on each side.
// A side counts only with its jamb well inside the camera's field of view (otherwise the
// nearest column may be the wall beyond it, which would pull the robot towards the jamb it
// did not see). A side seen gives the throat's offset as the scan's distance against the grid's; a sighting
// is the mean of its sides. While the follower's target is a narrow waypoint near the throat,
// it moves along the line by the sightings' mean, at most door_sighting_max_shift_m and never
// so far that the disc would touch the grid's cell at either side (the safety check still
// checks the grid: a shift it would stop for helps no one). A throat that differs from the
// one sighted starts afresh; one the robot is farther from than door_sighting_far_m, with no
// narrow stretch ahead, is forgotten.
//
// All state is fixed-size; observe() allocates nothing.

#include <cstddef>
#include <cstdint>

#include <Eigen/Core>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/explore/grid_view.hpp"
#include "stereoscout/explore/navigation_map.hpp"
#include "stereoscout/explore/path_planner.hpp"
#include "stereoscout/explore/seen_obstacles.hpp"

namespace stereoscout::explore {

// How far the follower moves a narrow waypoint's target (zero but near a sighted throat).
struct PassageShift {
  bool active = false;
  Eigen::Vector2d throat = Eigen::Vector2d::Zero();
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  double radius_m = 0.0;  // the narrow waypoints this near the throat move

  Eigen::Vector2d at(const Eigen::Vector2d& waypoint) const;
};

class DoorSighting {
 public:
  explicit DoorSighting(const ExploreParams& params) : params_(params) {}

  void reset();
  // With a scan newer than the last one observed; `progress` is the follower's. True when
  // this scan made the shift active (once a throat).
  bool observe(const Plan& plan, std::size_t progress, const NavigationMap& map, const SeenObstacles& seen,
               const core::Pose2& pose);
  const PassageShift& shift() const { return shift_; }
  std::uint64_t sightings() const { return sightings_; }

  struct Throat {
    Eigen::Vector2d position = Eigen::Vector2d::Zero();  // on the line between the two cells
    Eigen::Vector2d across = Eigen::Vector2d::UnitY();  // unit, from the right side to the left
    double left_m = 0.0;   // the grid's nearest obstacle cell to the left, along `across`
    double right_m = 0.0;  // ... to the right, against it
  };
  // The throat of the plan's next narrow stretch within door_sighting_far_m along the plan.
  bool next_throat(const Plan& plan, std::size_t progress, const NavigationMap& map, const Eigen::Vector2d& robot,
                   Throat& throat) const;
  // The throat's offset along `across` that the scan from `pose` shows; false when it shows
  // no side (a side counts only with its jamb well inside the camera's view).
  bool sight(const Throat& throat, const SeenObstacles& seen, const core::Pose2& pose, double& offset_m) const;

 private:
  bool jamb_in_view(const Eigen::Vector2d& jamb, const Eigen::Vector2d& across, const core::Pose2& pose) const;
  void start(const Throat& throat, double resolution_m);
  void update_shift();

  ExploreParams params_;
  bool has_throat_ = false;
  Throat throat_;
  double offset_sum_m_ = 0.0;
  int offset_count_ = 0;
  PassageShift shift_;
  std::uint64_t sightings_ = 0;
};

}  // namespace stereoscout::explore
