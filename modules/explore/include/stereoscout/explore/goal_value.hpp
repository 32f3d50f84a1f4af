#pragma once
// The exploration value of a goal cell (paper VI): H(s) = sum over rays theta every
// ray_step_deg of V(s, theta). A ray from the centre of s stops at the first cell s' that is
// not free: V = 0 if s' is occupied (or off the grid); V = exp(-0.5 (|s' - s| - r*)^2 /
// sigma^2) if s' is unknown. Rays are cut at r* + ray_cap_sigmas * sigma; a ray that meets
// only free cells up to the cap adds 0.
//
// Goal selection is argmax H over cells that are free, safely traversable (not within the
// robot radius plus the safety margin of an obstacle), reachable from the robot, and not near
// a remembered (blacklisted or visited) goal. With explore.goal_distance_cost > 0 (not in the
// paper) it is argmax H - cost * d instead, d the reachable cell's path distance from the
// robot (NavigationMap::reach_distance_m): a goal across the building has to be worth that
// much more than one nearby. Goal::value stays H, which decides when nothing is left.
// Speed: H is evaluated only on a lattice of candidate_stride_cells spacing and only where an
// unknown cell lies within the ray cap (the distance transform of the navigation map says so,
// H is 0 elsewhere), then at full resolution in the lattice cell around the best candidate.

#include <cstdint>

#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/explore/grid_view.hpp"
#include "stereoscout/explore/navigation_map.hpp"

namespace stereoscout::explore {

struct Goal {
  bool valid = false;
  Eigen::Vector2i cell = Eigen::Vector2i::Zero();
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double value = 0.0;    // H(s)
  double utility = 0.0;  // what selection ranked: H(s) - goal_distance_cost * path distance
};

// Goals that failed, or were reached already: a fixed list. Failures of goals within radius_m
// of each other count as one goal's; with a larger failure_radius_m, so do failures of goals
// within that of the nearest failed one (a place rather than a goal: a room the robot cannot
// enter offers goals all over it). A visited goal excludes candidates within radius_m; a
// blacklisted one within blacklist_radius_m, which may be larger: a room seen through a door
// the robot cannot pass (too narrow, or hung with something at its height) offers one goal
// after another beside the last, and each failure costs a drive there. With a cooldown, a goal
// that failed less than cooldown_s ago also excludes candidates within blacklist_radius_m.
// With a hold, a blacklisting lasts hold_s after its last failure, twice that the second time,
// and so on (explore.blacklist_hold_s); then the goal may be chosen again, its failures counted
// afresh. Without one (0) it lasts for good. A visited goal stays excluded for good either way.
class GoalMemory {
 public:
  GoalMemory(std::size_t capacity, double radius_m, double blacklist_radius_m, int failures_before_blacklist,
             double cooldown_s = 0.0, double hold_s = 0.0, double failure_radius_m = 0.0);
  // Counts a failure at time_s of the goal at `position`; returns true when it is now blacklisted
  // (or still is, from earlier failures).
  bool record_failure(const Eigen::Vector2d& position, double time_s);
  // A reached goal is never chosen again (it was looked around from).
  void record_visit(const Eigen::Vector2d& position);
  // True when a candidate at `position` is near a blacklisted or visited goal, or at time_s
  // near one that failed within the cooldown.
  bool excluded(const Eigen::Vector2d& position, double time_s) const;
  // Lifts the hold at time_s of every goal blacklisted at most max_blacklistings times (not of
  // one blacklisted for good, without a hold); they may be chosen again, their failures counted
  // afresh, and their next blacklisting holds twice as long. Returns how many.
  std::size_t release_held(double time_s, int max_blacklistings);
  std::uint64_t blacklisted() const { return blacklisted_; }
  std::uint64_t forgotten() const { return forgotten_; }  // memory was full

 private:
  struct Entry {
    Eigen::Vector2d position;
    int failures = 0;
    bool visited = false;
    double last_failure_s = 0.0;
    int blacklistings = 0;  // times it has been blacklisted
  };
  Entry* find(const Eigen::Vector2d& position);
  Entry* nearest_failed(const Eigen::Vector2d& position);  // within failure_radius_m, not visited
  bool held(const Entry& entry, double time_s) const;  // blacklisted at time_s
  core::FixedVector<Entry> entries_;
  double radius2_;
  double blacklist_radius2_;
  double failure_radius2_;
  int failures_before_blacklist_;
  double cooldown_s_;
  double hold_s_;
  std::uint64_t blacklisted_ = 0;
  std::uint64_t forgotten_ = 0;
};

class GoalValue {
 public:
  explicit GoalValue(const ExploreParams& params);

  // V(s, theta) for ray `ray_index` (theta = ray_index * ray_step) from cell (x, y).
  double ray_value(const GridView& grid, int x, int y, std::size_t ray_index) const;
  // H(s).
  double value(const GridView& grid, int x, int y) const;
  // H(s) on the map's grid, an unknown cell of an unobservable pocket counting as occupied
  // (NavigationMap::in_pocket). What select() and the explorer use.
  double value(const NavigationMap& map, int x, int y) const;
  std::size_t ray_count() const { return directions_.size(); }

  // argmax H over the candidates (see above); `map` must have compute_reachable() done.
  // Returns an invalid goal when no candidate is worth more than zero.
  // time_s is now, for the memory's cooldown.
  Goal select(const NavigationMap& map, const GoalMemory& memory, double time_s) const;
  bool is_candidate(const NavigationMap& map, const GoalMemory& memory, double time_s, int x, int y) const;
  std::uint64_t values_computed() const { return values_computed_; }

 private:
  // pockets: null to treat every unknown cell as a frontier.
  double ray_value(const GridView& grid, const NavigationMap* pockets, int x, int y, std::size_t ray_index) const;

  ExploreParams params_;
  core::FixedVector<Eigen::Vector2d> directions_;
  mutable std::uint64_t values_computed_ = 0;
};

}  // namespace stereoscout::explore
