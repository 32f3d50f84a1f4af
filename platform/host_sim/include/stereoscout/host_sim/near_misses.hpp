#pragma once
// Near misses: the robot's disc comes within sim.near_miss_m of a static obstacle and moves
// clear again without touching it. Contacts are all-or-nothing and rare (a few an hour), so a
// change that moves the robot nearer to or farther from door jambs shows in them only over
// many runs; the near misses add events of the same kind, about as many again in the office
// (docs/architecture.md, "Near misses").
// An approach begins when the clearance falls below the threshold and ends when it is
// `hysteresis_m` above it again (the simulator gives its contacts' own, 2 cm); it is a near
// miss if the robot touched nothing static in between. Fixed storage: the first kLogSize near
// misses are logged.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::host_sim {

class NearMisses {
 public:
  struct Event {
    double time_s = 0.0;           // when the clearance was least
    core::Pose2 pose;              // the true pose then
    double clearance_m = 0.0;      // the least clearance of the disc from a static obstacle
  };
  static constexpr std::size_t kLogSize = 64;

  // threshold_m <= 0 counts none.
  NearMisses(double threshold_m, double hysteresis_m) : threshold_m_(threshold_m), hysteresis_m_(hysteresis_m) {}

  // The robot moved to `pose`, its disc `clearance_m` from the nearest static obstacle.
  void moved(double time_s, const core::Pose2& pose, double clearance_m);
  // The robot ran into a static obstacle: the approach under way is no near miss.
  void touched();

  // Near misses so far, an approach still under way and untouched included.
  std::uint64_t count() const { return completed_ + (open_ && !touched_ ? 1 : 0); }
  std::size_t log_size() const { return static_cast<std::size_t>(std::min<std::uint64_t>(completed_, kLogSize)); }
  const Event& log(std::size_t i) const { return log_[i]; }
  double threshold_m() const { return threshold_m_; }

 private:
  double threshold_m_;
  double hysteresis_m_;
  bool open_ = false;      // an approach is under way
  bool touched_ = false;   // and it ran into something
  Event closest_;          // its closest point so far
  std::uint64_t completed_ = 0;
  std::array<Event, kLogSize> log_{};
};

}  // namespace stereoscout::host_sim
