#pragma once
// Pure-pursuit path following within the robot's limits (paper: 0.12 m/s, 8 deg/s). The
// follower steers to the point lookahead_m ahead along the path; when that point is more
// than turn_in_place_deg off the heading it turns in place (A* paths have 45-degree corners
// and a 0.12 m/s robot turning at 8 deg/s cannot bend tighter than 0.86 m, so cutting a
// corner at speed would leave the planned corridor). When the curvature needs more than
// the turn-rate limit, the speed drops so that the arc is kept. Where the path runs within
// an obstacle's safety margin (Plan::narrow) up to the lookahead point, the lookahead shrinks
// to explore.narrow_lookahead_m, so that the robot keeps to the path through a doorway. With
// explore.door_axis_before_m it steers along the axis of the door it is passing instead
// (door_axis.hpp). With explore.gaze_ahead_m the explorer points the camera at the waypoint
// that far ahead (point_ahead).

#include <cstddef>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"
#include "stereoscout/explore/door_axis.hpp"
#include "stereoscout/explore/grid_view.hpp"
#include "stereoscout/explore/path_planner.hpp"

namespace stereoscout::explore {

// The command that takes `pose` towards `target`: a turn in place while the target lies more
// than turn_in_place_deg off the heading, else the pure-pursuit arc through it, slowed so that
// the turn-rate limit keeps the arc.
core::DriveCommand pursue(const Eigen::Vector2d& target, const core::Pose2& pose, const ExploreParams& params);
// A turn in place by `error_rad`, proportional to it within the turn-rate limit.
core::DriveCommand turn_in_place(double error_rad, const ExploreParams& params);

struct FollowResult {
  core::DriveCommand command;
  bool reached = false;         // within goal_tolerance_m of the last waypoint
  std::size_t progress = 0;     // index of the waypoint the robot is nearest to
};

class PathFollower {
 public:
  explicit PathFollower(const ExploreParams& params) : params_(params) {}
  void reset() { progress_ = 0; }
  FollowResult follow(const Plan& plan, const core::Pose2& pose, const DoorPassage& door = DoorPassage());
  std::size_t progress() const { return progress_; }
  // The first waypoint from the nearest one (as the last follow() found it) on that lies at
  // least `distance_m` from `position`; the last one when none does. `plan` must not be empty.
  const Eigen::Vector2d& point_ahead(const Plan& plan, const Eigen::Vector2d& position, double distance_m) const {
    return plan.waypoints[lookahead_point(plan, position, distance_m)];
  }

 private:
  std::size_t lookahead_point(const Plan& plan, const Eigen::Vector2d& position, double lookahead_m) const;
  // A narrow waypoint from the nearest one up to `target`.
  bool narrow_ahead(const Plan& plan, std::size_t target) const;

  ExploreParams params_;
  std::size_t progress_ = 0;
};

}  // namespace stereoscout::explore
