#include "stereoscout/stack/odometry_history.hpp"

namespace stereoscout::stack {

core::Pose2 interpolate_pose(const core::Pose2& a, const core::Pose2& b, double f) {
  const double turn = core::wrap_angle(b.theta - a.theta);
  return core::Pose2{a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), core::wrap_angle(a.theta + f * turn)};
}

bool OdometryHistory::add(const core::OdometryReading& reading) {
  if (!readings_.empty() && reading.timestamp_ns <= readings_.back().timestamp_ns) return false;
  readings_.push_overwrite(reading);
  return true;
}

bool OdometryHistory::pose_at(std::int64_t timestamp_ns, core::Pose2& pose) const {
  if (readings_.empty() || timestamp_ns < readings_.front().timestamp_ns ||
      timestamp_ns > readings_.back().timestamp_ns) {
    return false;
  }
  std::size_t after = 0;
  while (readings_[after].timestamp_ns < timestamp_ns) ++after;
  if (readings_[after].timestamp_ns == timestamp_ns || after == 0) {
    pose = readings_[after].pose;
    return true;
  }
  const core::OdometryReading& before = readings_[after - 1];
  const core::OdometryReading& next = readings_[after];
  const double f = static_cast<double>(timestamp_ns - before.timestamp_ns) /
                   static_cast<double>(next.timestamp_ns - before.timestamp_ns);
  pose = interpolate_pose(before.pose, next.pose, f);
  return true;
}

}  // namespace stereoscout::stack
