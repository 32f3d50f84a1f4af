#include "stereoscout/explore/door_sighting.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stereoscout::explore {
namespace {
// Scan columns this far from the throat's line, either way, belong to its wall: a grid
// cell's depth and a half, for a thin wall seen at its base.
constexpr double kWallDepth_m = 0.15;
// A side counts when this many columns see it: one stray match does not move the robot.
constexpr int kMinSidePoints = 3;
// A side whose offset is more than this many times door_sighting_max_shift_m is something
// else: a person in the door, or the wall beyond a jamb the matcher could not see.
constexpr double kPlausibleShifts = 2.0;
// Throats nearer than this to each other are the same gap, found again on a new plan.
constexpr double kSameThroat_m = 0.3;
// Sightings needed before the follower moves: one scan's jamb is off by 0.03-0.05 m.
constexpr int kMinSightings = 2;
// The disc keeps this much more than its radius from the grid's cell on either side.
constexpr double kRoomMargin_m = 0.01;
}  // namespace

Eigen::Vector2d PassageShift::at(const Eigen::Vector2d& waypoint) const {
  if (!active || (waypoint - throat).squaredNorm() > radius_m * radius_m) return Eigen::Vector2d::Zero();
  return offset;
}

void DoorSighting::reset() {
  has_throat_ = false;
  offset_sum_m_ = 0.0;
  offset_count_ = 0;
  shift_ = PassageShift();
}

bool DoorSighting::next_throat(const Plan& plan, std::size_t progress, const NavigationMap& map,
                               const Eigen::Vector2d& robot, Throat& throat) const {
  const double reach = params_.explore.gap_centring_reach_m;
  const std::size_t count = plan.waypoints.size();
  double travelled = 0.0;
  Eigen::Vector2d previous = robot;
  bool in_stretch = false;
  double narrowest = std::numeric_limits<double>::infinity();
  for (std::size_t k = progress; k + 1 < count; ++k) {
    travelled += (plan.waypoints[k] - previous).norm();
    previous = plan.waypoints[k];
    if (!plan.narrow[k]) {
      if (in_stretch) break;  // the next narrow stretch ends here
      if (travelled > params_.explore.door_sighting_far_m) break;
      continue;
    }
    in_stretch = true;
    if (k == 0) continue;
    const Eigen::Vector2d along = plan.waypoints[k + 1] - plan.waypoints[k - 1];
    if (along.squaredNorm() == 0.0) continue;
    const Eigen::Vector2d position = plan.waypoints[k];
    Eigen::Vector2d left;
    Eigen::Vector2d right;
    if (!map.nearest_obstacles_aside(position, Eigen::Vector2d(-along.y(), along.x()).normalized(), reach, left, right)) {
      continue;
    }
    const double gap = (left - right).norm();
    if (gap >= narrowest) continue;
    // On the line between the two cells: the waypoints before and after a thin wall's door
    // find the same jamb cells as the one in it.
    narrowest = gap;
    throat.across = (left - right) / gap;
    throat.position = right + throat.across.dot(position - right) * throat.across;
    throat.left_m = (left - throat.position).norm();
    throat.right_m = (right - throat.position).norm();
  }
  return std::isfinite(narrowest);
}

// Both ends of where the jamb may be (door_sighting_max_shift_m either way of the grid's) lie
// inside the camera's field of view and no nearer than door_sighting_near_m: otherwise the
// scan's nearest column on that side may be the wall beyond it, and would pull the robot
// towards the jamb it did not see.
bool DoorSighting::jamb_in_view(const Eigen::Vector2d& jamb, const Eigen::Vector2d& across,
                                const core::Pose2& pose) const {
  const Eigen::Vector2d heading(std::cos(pose.theta), std::sin(pose.theta));
  const Eigen::Vector2d camera = Eigen::Vector2d(pose.x, pose.y) + params_.camera_forward_m * heading;
  const double most = params_.explore.door_sighting_max_shift_m;
  for (double end : {-most, most}) {
    const Eigen::Vector2d to_jamb = jamb + end * across - camera;
    if (to_jamb.norm() < params_.explore.door_sighting_near_m) return false;
    const double bearing = core::wrap_angle(std::atan2(to_jamb.y(), to_jamb.x()) - pose.theta);
    if (std::abs(bearing) > params_.camera_half_fov_rad) return false;
  }
  return true;
}

bool DoorSighting::sight(const Throat& throat, const SeenObstacles& seen, const core::Pose2& pose,
                         double& offset_m) const {
  const double plausible = kPlausibleShifts * params_.explore.door_sighting_max_shift_m;
  const bool left_in_view = jamb_in_view(throat.position + throat.left_m * throat.across, throat.across, pose);
  const bool right_in_view = jamb_in_view(throat.position - throat.right_m * throat.across, throat.across, pose);
  if (!left_in_view && !right_in_view) return false;
  const Eigen::Vector2d along(throat.across.y(), -throat.across.x());
  double nearest_left = std::numeric_limits<double>::infinity();
  double nearest_right = nearest_left;
  int left_points = 0;
  int right_points = 0;
  for (std::size_t i = 0; i < seen.any_height_count; ++i) {
    const Eigen::Vector2d relative = seen.any_height[i] - throat.position;
    if (std::abs(along.dot(relative)) > kWallDepth_m) continue;
    const double across = throat.across.dot(relative);
    if (across > 0.0 && std::abs(across - throat.left_m) <= plausible) {
      nearest_left = std::min(nearest_left, across);
      ++left_points;
    } else if (across < 0.0 && std::abs(-across - throat.right_m) <= plausible) {
      nearest_right = std::min(nearest_right, -across);
      ++right_points;
    }
  }
  double sum = 0.0;
  int sides = 0;
  if (left_in_view && left_points >= kMinSidePoints) {
    sum += nearest_left - throat.left_m;  // the left side nearer than the grid has it: the gap lies to the right
    ++sides;
  }
  if (right_in_view && right_points >= kMinSidePoints) {
    sum += throat.right_m - nearest_right;
    ++sides;
  }
  if (sides == 0) return false;
  offset_m = sum / sides;
  return true;
}

void DoorSighting::start(const Throat& throat, double resolution_m) {
  reset();
  has_throat_ = true;
  throat_ = throat;
  shift_.throat = throat.position;
  // The narrow stretch reaches the safe distance from the jambs on either side of the throat.
  shift_.radius_m = params_.safe_distance_m(resolution_m) + resolution_m;
}

void DoorSighting::update_shift() {
  shift_.active = offset_count_ >= kMinSightings;
  if (!shift_.active) return;
  const double radius = params_.robot_radius_m + kRoomMargin_m;
  const double to_left = std::max(0.0, throat_.left_m - radius);
  const double to_right = std::max(0.0, throat_.right_m - radius);
  const double most = params_.explore.door_sighting_max_shift_m;
  const double mean = offset_sum_m_ / offset_count_;
  shift_.offset = std::clamp(mean, -std::min(most, to_right), std::min(most, to_left)) * throat_.across;
}

bool DoorSighting::observe(const Plan& plan, std::size_t progress, const NavigationMap& map,
                           const SeenObstacles& seen, const core::Pose2& pose) {
  const Eigen::Vector2d robot(pose.x, pose.y);
  Throat throat;
  if (!next_throat(plan, progress, map, robot, throat)) {
    if (has_throat_ && (robot - throat_.position).norm() > params_.explore.door_sighting_far_m) reset();
    return false;
  }
  if (!has_throat_ || (throat.position - throat_.position).norm() > kSameThroat_m) start(throat, map.grid().resolution_m);
  const double distance = (robot - throat_.position).norm();
  if (distance < params_.explore.door_sighting_near_m || distance > params_.explore.door_sighting_far_m) return false;
  double offset = 0.0;
  if (!sight(throat_, seen, pose, offset)) return false;
  const bool was_active = shift_.active;
  offset_sum_m_ += offset;
  ++offset_count_;
  ++sightings_;
  update_shift();
  return shift_.active && !was_active;
}

}  // namespace stereoscout::explore
