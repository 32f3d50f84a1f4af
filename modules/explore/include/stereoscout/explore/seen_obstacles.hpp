#pragma once
// What the latest obstacle scan saw standing at the camera's height, for the explorer's safety
// check (explore.scan_guard_min_points).

#include <cstddef>

#include <Eigen/Core>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"

namespace stereoscout::explore {

// What the latest obstacle scan saw standing at the camera's height (a person, a textured wall
// or cupboard; not the blank-wall rules' guesses), as points in the map frame placed with the
// pose the grid used for that scan. With scan_guard_min_points the safety check holds the
// robot for them as well as stopping it for the grid's occupied cells: the grid turns a cell
// it saw free many times occupied only after several updates (log-odds clamped at -4, +0.85 a
// hit), and a walking person covers 1-2 m meanwhile.
// Must stay valid during the call only; count 0 when there is no scan.
struct SeenObstacles {
  const Eigen::Vector2d* points = nullptr;
  std::size_t count = 0;
  double time_s = 0.0;  // when the scan's stereo pair was captured
  // The scan itself (robot frame), and the odometry pose and the estimate's pose at its
  // capture, for the recent obstacle layer (recent_obstacles.hpp); null when there is none.
  const core::DepthScan* scan = nullptr;
  core::Pose2 odometry;
  core::Pose2 pose;
  double pan_rad = 0.0;  // the pan unit's angle at the capture (where the left camera was)
};

// Writes into `points` (room for `capacity`) the scan's obstacle columns that stand at the
// camera's height, in the map frame of `pose` (the robot's pose at the scan's capture); returns
// how many. The columns are in the robot frame on the floor plane (core::DepthScan).
std::size_t seen_obstacles_from_scan(const core::DepthScan& scan, const core::Pose2& pose, Eigen::Vector2d* points,
                                     std::size_t capacity);

}  // namespace stereoscout::explore
