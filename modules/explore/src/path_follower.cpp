#include "stereoscout/explore/path_follower.hpp"

#include <algorithm>
#include <cmath>

namespace stereoscout::explore {
namespace {
// The nearest waypoint is searched this many waypoints ahead of the last one (progress only
// moves forward, so a path that doubles back is not short-cut).
constexpr std::size_t kProgressWindow = 12;
// Gain of the in-place turn (rad/s per rad), limited by the turn rate.
constexpr double kTurnGain = 2.0;
}  // namespace

core::DriveCommand turn_in_place(double error_rad, const ExploreParams& params) {
  core::DriveCommand command;
  const double max_turn = params.max_turn_rate_rad_s;
  command.angular_rad_s = std::clamp(kTurnGain * error_rad, -max_turn, max_turn);
  return command;
}

core::DriveCommand pursue(const Eigen::Vector2d& target, const core::Pose2& pose, const ExploreParams& params) {
  const Eigen::Vector2d to_target = target - Eigen::Vector2d(pose.x, pose.y);
  const double alpha = core::wrap_angle(std::atan2(to_target.y(), to_target.x()) - pose.theta);
  if (std::abs(alpha) > core::degrees_to_radians(params.explore.turn_in_place_deg)) return turn_in_place(alpha, params);
  // Pure pursuit: the arc through the target point has curvature 2 sin(alpha) / L.
  const double max_turn = params.max_turn_rate_rad_s;
  const double length = std::max(to_target.norm(), 1e-3);
  const double curvature = 2.0 * std::sin(alpha) / length;
  double speed = params.max_speed_mps;
  if (std::abs(curvature) * speed > max_turn) speed = max_turn / std::abs(curvature);
  core::DriveCommand command;
  command.linear_mps = speed;
  command.angular_rad_s = std::clamp(speed * curvature, -max_turn, max_turn);
  return command;
}

// The first waypoint from the nearest one on that is at least `lookahead_m` away (the last
// one when none is).
std::size_t PathFollower::lookahead_point(const Plan& plan, const Eigen::Vector2d& position, double lookahead_m) const {
  std::size_t target = progress_;
  while (target + 1 < plan.waypoints.size() && (plan.waypoints[target] - position).norm() < lookahead_m) ++target;
  return target;
}

bool PathFollower::narrow_ahead(const Plan& plan, std::size_t target) const {
  for (std::size_t k = progress_; k <= target; ++k) {
    if (plan.narrow[k]) return true;
  }
  return false;
}

FollowResult PathFollower::follow(const Plan& plan, const core::Pose2& pose, const DoorPassage& door) {
  FollowResult result;
  if (plan.empty()) {
    result.reached = true;
    return result;
  }
  const Eigen::Vector2d position(pose.x, pose.y);
  const std::size_t count = plan.waypoints.size();
  progress_ = std::min(progress_, count - 1);
  std::size_t nearest = progress_;
  double nearest_distance = (plan.waypoints[progress_] - position).norm();
  for (std::size_t k = progress_ + 1; k < std::min(count, progress_ + kProgressWindow); ++k) {
    const double distance = (plan.waypoints[k] - position).norm();
    if (distance < nearest_distance) {
      nearest = k;
      nearest_distance = distance;
    }
  }
  progress_ = nearest;
  result.progress = progress_;
  if ((plan.waypoints[count - 1] - position).norm() <= params_.explore.goal_tolerance_m) {
    result.reached = true;
    return result;
  }
  std::size_t target = lookahead_point(plan, position, params_.explore.lookahead_m);
  const double narrow_lookahead_m = params_.explore.narrow_lookahead_m;
  if (narrow_lookahead_m > 0.0 && narrow_lookahead_m < params_.explore.lookahead_m && narrow_ahead(plan, target)) {
    target = lookahead_point(plan, position, narrow_lookahead_m);
  }
  Eigen::Vector2d target_point = plan.waypoints[target];
  const double axis_lookahead_m = narrow_lookahead_m > 0.0 ? narrow_lookahead_m : params_.explore.lookahead_m;
  door.axis_target(position, axis_lookahead_m, params_.explore.door_axis_before_m, target_point);
  result.command = pursue(target_point, pose, params_);
  return result;
}

}  // namespace stereoscout::explore
