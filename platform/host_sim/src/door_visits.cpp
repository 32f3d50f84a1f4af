#include "stereoscout/host_sim/door_visits.hpp"

namespace stereoscout::host_sim {

double DoorVisits::distance_to(std::size_t door, const Eigen::Vector2d& centre) const {
  const Eigen::Vector2d& a = doorways_[door].jamb_a;
  const Eigen::Vector2d along = doorways_[door].jamb_b - a;
  const double length_sq = along.squaredNorm();
  const double t = length_sq > 0.0 ? std::clamp((centre - a).dot(along) / length_sq, 0.0, 1.0) : 0.0;
  return (a + t * along - centre).norm();
}

bool DoorVisits::left_of(std::size_t door, const Eigen::Vector2d& centre) const {
  const Eigen::Vector2d along = doorways_[door].jamb_b - doorways_[door].jamb_a;
  const Eigen::Vector2d to_centre = centre - doorways_[door].jamb_a;
  return along.x() * to_centre.y() - along.y() * to_centre.x() > 0.0;
}

void DoorVisits::moved(double time_s, const core::Pose2& pose, double clearance_m) {
  if (!active()) return;
  const Eigen::Vector2d centre = pose.translation();
  if (open_) {
    if (clearance_m < current_.clearance_m) {
      current_.clearance_m = clearance_m;
      current_.time_s = time_s;
      current_.pose = pose;
    }
    if (distance_to(current_.door, centre) < zone_m_ + hysteresis_m_) return;
    finish(centre);
  }
  for (std::size_t door = 0; door < doorways_.size(); ++door) {
    if (distance_to(door, centre) >= zone_m_) continue;
    open_ = true;
    entered_left_ = left_of(door, centre);
    current_ = Visit{time_s, static_cast<std::uint32_t>(door), pose, clearance_m, false, false};
    return;
  }
}

void DoorVisits::touched() {
  if (open_) current_.touched = true;
}

void DoorVisits::finish(const Eigen::Vector2d& centre) {
  open_ = false;
  current_.crossed = left_of(current_.door, centre) != entered_left_;
  if (current_.crossed) ++crossings_;
  if (current_.touched) ++touched_;
  if (completed_ < kLogSize) log_[static_cast<std::size_t>(completed_)] = current_;
  ++completed_;
}

}  // namespace stereoscout::host_sim
