#pragma once
// Door visits: the robot's centre comes within a zone around a doorway (world.hpp: the segment
// between its jambs) and leaves it again. Each visit keeps the least clearance of the disc
// from a static obstacle meanwhile, whether the robot left on the other side of the door's
// line, and whether it ran into something static. Contacts and near misses count only the tail
// of how closely doors are passed (a few an hour); every visit gives a clearance, so runs can
// be compared on the whole spread (docs/architecture.md, "Door visits").
// A visit ends when the centre is `hysteresis_m` beyond the zone (the simulator gives its
// contacts' own, 2 cm). Fixed storage: the first kLogSize visits are logged.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/host_sim/world.hpp"

namespace stereoscout::host_sim {

class DoorVisits {
 public:
  struct Visit {
    double time_s = 0.0;         // when the clearance was least
    std::uint32_t door = 0;      // index into World::doorways
    core::Pose2 pose;            // the true pose then
    double clearance_m = 0.0;    // the least clearance of the disc from a static obstacle
    bool crossed = false;        // left on the other side of the door's line than it came
    bool touched = false;        // ran into something static during the visit
  };
  static constexpr std::size_t kLogSize = 256;

  // `doorways` must outlive this. A visit's zone is the centre within `zone_m` of the segment
  // between the jambs; zone_m <= 0 counts none.
  DoorVisits(const std::vector<Doorway>& doorways, double zone_m, double hysteresis_m)
      : doorways_(doorways), zone_m_(zone_m), hysteresis_m_(hysteresis_m) {}

  // The robot moved to `pose`, its disc `clearance_m` from the nearest static obstacle.
  void moved(double time_s, const core::Pose2& pose, double clearance_m);
  // The robot ran into a static obstacle: the visit under way, if any, touched it.
  void touched();

  bool active() const { return zone_m_ > 0.0 && !doorways_.empty(); }
  double zone_m() const { return zone_m_; }
  // Visits so far, one still under way included; those that crossed; those that touched.
  std::uint64_t count() const { return completed_ + (open_ ? 1 : 0); }
  std::uint64_t crossings() const { return crossings_; }
  std::uint64_t touched_count() const { return touched_ + (open_ && current_.touched ? 1 : 0); }
  std::size_t log_size() const { return static_cast<std::size_t>(std::min<std::uint64_t>(completed_, kLogSize)); }
  const Visit& log(std::size_t i) const { return log_[i]; }

 private:
  // Distance of `centre` from doorway `door`'s segment, and which side of its line it is on.
  double distance_to(std::size_t door, const Eigen::Vector2d& centre) const;
  bool left_of(std::size_t door, const Eigen::Vector2d& centre) const;
  void finish(const Eigen::Vector2d& centre);

  const std::vector<Doorway>& doorways_;
  double zone_m_;
  double hysteresis_m_;
  bool open_ = false;           // a visit is under way
  bool entered_left_ = false;   // the side of the door's line it began on
  Visit current_;
  std::uint64_t completed_ = 0;
  std::uint64_t crossings_ = 0;
  std::uint64_t touched_ = 0;
  std::array<Visit, kLogSize> log_{};
};

}  // namespace stereoscout::host_sim
