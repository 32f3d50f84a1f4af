#include "stereoscout/explore/door_standoff.hpp"

#include <cmath>

#include "stereoscout/explore/door_sighting.hpp"
#include "stereoscout/explore/path_follower.hpp"

namespace stereoscout::explore {
namespace {
// A door stood off for (or given up) is remembered while the robot stays this near it: a plan
// that loses the door for a tick, or a new plan through it, brings no second standoff.
constexpr double kForget_m = 3.0;
}  // namespace

DoorStandoff::DoorStandoff(const ExploreParams& params) : params_(params), standoff_m_(params.explore.door_standoff_m) {}

void DoorStandoff::reset() {
  door_ = DoorPassage();
  phase_ = Phase::none;
}

Eigen::Vector2d DoorStandoff::point(const DoorPassage& passage) const {
  return passage.middle - standoff_m_ * passage.along;
}

bool DoorStandoff::wants_grid(const DoorPassage& passage) const {
  return phase_ == Phase::none || phase_ == Phase::approach || !same_door(passage, door_);
}

void DoorStandoff::begin(const DoorPassage& passage, bool in_a_wall, const core::Pose2& pose, double time_s) {
  door_ = passage;
  phase_start_s_ = time_s;
  if (!in_a_wall) {
    give_up(counters_.not_in_a_wall);
    return;
  }
  ++counters_.doors;
  const double ahead = passage.along.dot(pose.translation() - passage.middle);
  // A robot that passed the door and turns round to pass it again faces the point.
  const bool facing_away = passage.along.dot(Eigen::Vector2d(std::cos(pose.theta), std::sin(pose.theta))) < 0.0;
  if (ahead <= -(standoff_m_ - kReached_m) || facing_away) {
    phase_ = Phase::approach;
  } else if (ahead + params_.camera_forward_m < -DoorSighting::kMinAhead_m) {
    ++counters_.stood_off;
    phase_ = Phase::face;
  } else {
    give_up(counters_.too_near);
  }
}

// The approach's limit, or twice the time a half turn takes.
double DoorStandoff::phase_limit_s() const {
  return phase_ == Phase::approach ? kApproachLimit_s : 2.0 * core::kPi / params_.max_turn_rate_rad_s;
}

void DoorStandoff::give_up(std::uint64_t& reason) {
  ++reason;
  phase_ = Phase::done;
}

bool DoorStandoff::steer(const DoorPassage& passage, bool sighted, const GridAnswers& grid, const core::Pose2& pose,
                         double time_s, core::DriveCommand& command) {
  if (!enabled()) return false;
  if (!passage.known) {
    if (phase_ != Phase::none && (pose.translation() - door_.middle).norm() > kForget_m) reset();
    return false;
  }
  if (phase_ == Phase::none || !same_door(passage, door_)) begin(passage, grid.in_a_wall, pose, time_s);
  if (phase_ == Phase::done) return false;
  if (time_s - phase_start_s_ > phase_limit_s()) {
    give_up(counters_.timed_out);
    return false;
  }
  if (phase_ == Phase::approach) {
    const Eigen::Vector2d standoff = point(passage);
    if ((pose.translation() - standoff).norm() > kReached_m) {
      if (!grid.way_clear) {
        give_up(counters_.way_shut);
        return false;
      }
      command = pursue(standoff, pose, params_);
      return true;
    }
    ++counters_.stood_off;
    phase_ = Phase::face;
    phase_start_s_ = time_s;
  }
  const double error_rad = core::wrap_angle(std::atan2(passage.along.y(), passage.along.x()) - pose.theta);
  if (std::abs(error_rad) < kFacing_rad) {
    if (sighted) ++counters_.sighted;
    phase_ = Phase::done;
    return false;
  }
  command = turn_in_place(error_rad, params_);
  return true;
}

}  // namespace stereoscout::explore
