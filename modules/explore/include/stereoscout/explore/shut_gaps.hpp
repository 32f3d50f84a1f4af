#pragma once
// Gaps a view shut, where the robot has never been. From some views a door narrowed by what
// hangs in it (office room N2: a poster in its west half, 1.1-1.9 m high, leaves 0.45 m for
// the 1.2 m robot) or a gap in a blank partition or corridor wall looks open, and the room
// beyond is worth the most on offer. The robot drives there, the next view holds the gap shut,
// and the goal fails; the view after (or the next particle lineage's grid) opens the gap again,
// and the next goal behind it sends the robot back: 440-630 s of each of office seeds 11, 13
// and 14's hours went to N2. A goal blacklisting cannot stop that, since it holds one goal's
// place, not the way in.
//
// So when a goal fails because its kept plan was blocked and no other way was found, the
// plan's blocked cells that lie in a gap (between obstacles on either side of the way no
// farther apart than a door) are shut: marked occupied in the explorer's copy of the grid
// (like contact cells) for shut_gap_hold_s, which keeps every goal behind the gap unreachable.
// With shut_gap_range_m, only when the first blocked cell lies that near the robot. Cells the
// robot's disc has covered are never shut (the driven cells: where its centre has been, all
// run long, within its radius): a door it drove through fits it, whatever a view draws in it
// now, and the robot is never shut in the room it stands in. Like contacts and blacklistings,
// shut gaps are lifted before the explorer concludes that nothing is left or that there is no
// way back.

#include <cstdint>
#include <memory>

#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/explore/grid_view.hpp"
#include "stereoscout/explore/navigation_map.hpp"
#include "stereoscout/explore/path_planner.hpp"

namespace stereoscout::explore {

class ShutGaps {
 public:
  // max_width x max_height: the largest grid the driven cells and stamp() cover (allocated here).
  ShutGaps(const ExploreParams& params, int max_width, int max_height);

  bool enabled() const { return hold_s_ > 0.0; }
  // The robot's centre is at `position` (map frame) on `grid`: the cells within its radius are
  // driven. A grid of another size or origin starts the record afresh.
  void drove(const GridView& grid, const Eigen::Vector2d& position);
  // The kept plan was blocked at its cell `blocked` on `map`: keeps the cells of the run of
  // impassable ones from there on that lie in a gap, to be shut if no other way is found.
  void blocked(const NavigationMap& map, const Plan& plan, std::size_t blocked, const Eigen::Vector2d& robot);
  // No other way was found: shuts the kept gap's undriven cells. True when any was shut.
  bool shut(double time_s);
  // Forgets a kept gap (a plan was found after all, or the goal changed).
  void forget_blocked() { pending_.clear(); }
  // Forgets expired gaps, then returns `grid` with the shut cells occupied (a copy in the
  // memory's own buffer, or `grid` itself when there is none). Valid until the next call.
  GridView stamp(const GridView& grid, double time_s);
  // Forgets every shut gap; returns how many cells it opened.
  std::size_t lift();

  // The first cell the last shut() shut (map frame), and how many it shut.
  const Eigen::Vector2d& last_shut_at() const { return last_shut_at_; }
  std::size_t last_shut_cells() const { return last_shut_cells_; }
  std::size_t held() const { return cells_held_.size(); }
  std::uint64_t gaps_shut() const { return gaps_shut_; }
  std::uint64_t cells_shut() const { return cells_shut_; }
  std::uint64_t refused_driven() const { return refused_driven_; }  // every blocked cell lay where the robot had been
  std::uint64_t refused_far() const { return refused_far_; }        // blocked beyond shut_gap_range_m
  std::uint64_t dropped_full() const { return dropped_full_; }
  std::uint64_t driven_restarts() const { return driven_restarts_; }

 private:
  struct ShutCell {
    Eigen::Vector2d point;
    double until_s = 0.0;
  };
  bool driven(const Eigen::Vector2d& point) const;
  bool in_a_gap(const NavigationMap& map, const Plan& plan, std::size_t k) const;

  double hold_s_;
  double range_m_;
  double robot_radius_m_;
  double lethal_margin_cells_;
  std::size_t capacity_cells_;
  // The driven cells, on the grid they were recorded on.
  std::unique_ptr<std::uint8_t[]> driven_;
  GridView driven_grid_;
  core::FixedVector<Eigen::Vector2d> pending_;
  bool pending_far_ = false;
  core::FixedVector<ShutCell> cells_held_;
  Eigen::Vector2d last_shut_at_ = Eigen::Vector2d::Zero();
  std::size_t last_shut_cells_ = 0;
  std::unique_ptr<std::uint8_t[]> stamped_;
  std::uint64_t gaps_shut_ = 0;
  std::uint64_t cells_shut_ = 0;
  std::uint64_t refused_driven_ = 0;
  std::uint64_t refused_far_ = 0;
  std::uint64_t dropped_full_ = 0;
  std::uint64_t driven_restarts_ = 0;
};

}  // namespace stereoscout::explore
