#pragma once
// The robot's own recent path in the map frame: floor it has driven over. A passage the robot
// came in by can close behind it in the grid (a smeared cell at its edge leaves no cell of it
// a lethal distance from every occupied one) and box it in, with the way out known to be
// passable. So before concluding "explored" or "no way back", the explorer lets plans follow
// the trail (NavigationMap::open_trail); never otherwise, and never nearer an occupied cell
// than the safety check lets the robot go.
//
// A point is kept every kTrailSpacing_m of travel, the last explore.trail_length_m of it. A
// step between two points much longer than that is the pose estimate jumping (another particle
// became the most likely), not driving, so the trail is not joined across it. The buffer is
// allocated by the constructor; record() allocates nothing.

#include <cstddef>

#include <Eigen/Core>

#include "stereoscout/core/config/explore.hpp"
#include "stereoscout/core/ring_buffer.hpp"

namespace stereoscout::explore {

struct TrailPoint {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  bool joined = false;  // driven to from the previous point (not a jump of the estimate)
};

class TrailMemory {
 public:
  // Half a 0.1 m navigation cell: the path through a door is followed to within a few
  // centimetres (NavigationMap::open_trail() steps along each segment a quarter cell at a time).
  static constexpr double kTrailSpacing_m = 0.05;
  // The robot moves 6 mm a control tick; the estimate jumps by decimetres when the most likely
  // particle changes.
  static constexpr double kTrailJump_m = 0.25;

  explicit TrailMemory(const core::ExploreConfig& config);

  // The robot's position now (map frame); kept when it is kTrailSpacing_m from the last point.
  void record(const Eigen::Vector2d& position);

  bool enabled() const { return enabled_; }
  std::size_t size() const { return points_.size(); }
  const TrailPoint& operator[](std::size_t i) const { return points_[i]; }  // 0 = oldest kept

 private:
  bool enabled_ = false;
  core::RingBuffer<TrailPoint> points_;
};

}  // namespace stereoscout::explore
