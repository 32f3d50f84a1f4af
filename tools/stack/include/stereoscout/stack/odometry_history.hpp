#pragma once
// The newest odometry readings, so that the pose at a stereo pair's time can be
// interpolated between the readings around it (pairs come at 15 Hz, odometry at 5.4 Hz: taking
// the nearest reading would misplace every observation by up to half an odometry period of
// motion, 1 cm and 0.7 deg at the paper's speeds).

#include <cstddef>
#include <cstdint>

#include "stereoscout/core/messages.hpp"
#include "stereoscout/core/ring_buffer.hpp"

namespace stereoscout::stack {

class OdometryHistory {
 public:
  explicit OdometryHistory(std::size_t capacity) : readings_(capacity) {}

  // Readings must come in time order; an older or equal timestamp is refused (false).
  bool add(const core::OdometryReading& reading);
  bool empty() const { return readings_.empty(); }
  const core::OdometryReading& newest() const { return readings_.back(); }
  // The pose at `timestamp_ns`, linear in translation and in the wrapped heading change
  // between the two readings around it. False when the time is not inside the history.
  bool pose_at(std::int64_t timestamp_ns, core::Pose2& pose) const;

 private:
  core::RingBuffer<core::OdometryReading> readings_;
};

// Linear interpolation of two poses at fraction `f` in [0, 1] (heading along the shorter arc).
core::Pose2 interpolate_pose(const core::Pose2& a, const core::Pose2& b, double f);

}  // namespace stereoscout::stack
