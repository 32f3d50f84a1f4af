#pragma once
// A* on the navigation map (paper VI): 8-connected, passable cells only (the grid inflated by
// the robot radius), step cost = length x (1 + obstacle penalty + unknown penalty) of the cell
// entered, octile-distance heuristic (admissible and consistent because every penalty factor
// is at least 1), so the path found is a cheapest one. The open list is an indexed binary heap
// and the closed set a per-cell stamp, both sized for the whole grid at start-up: planning
// allocates nothing. Ties are broken by cell index, so plans are deterministic.

#include <cstdint>
#include <memory>
#include <utility>

#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/explore/navigation_map.hpp"

namespace stereoscout::explore {

// A path in the map frame: cell centres from the start cell to the goal cell; with
// explore.gap_centring_reach_m, a waypoint in a narrow gap lies up to half a cell from its
// cell's centre, in the gap's middle. `narrow` marks the waypoints whose cell lay within the
// safety margin of an obstacle, or nearer than explore.narrow_clearance_m to one, when the
// plan was made (a doorway, a gap between furniture): there the follower keeps closer to the
// path (explore.narrow_lookahead_m). With explore.refit_kept_plans both are set again on
// each map rebuild (PathPlanner::refit).
struct Plan {
  explicit Plan(std::size_t capacity) : cells(capacity), waypoints(capacity), narrow(capacity) {}
  void clear() {
    cells.clear();
    waypoints.clear();
    narrow.clear();
    cost = 0.0;
  }
  bool empty() const { return waypoints.empty(); }
  void swap(Plan& other) noexcept {
    cells.swap(other.cells);
    waypoints.swap(other.waypoints);
    narrow.swap(other.narrow);
    std::swap(cost, other.cost);
  }
  core::FixedVector<Eigen::Vector2i> cells;
  core::FixedVector<Eigen::Vector2d> waypoints;
  core::FixedVector<bool> narrow;
  double cost = 0.0;  // sum of step costs (metres, penalised)
};

enum class PlanResult : std::uint8_t { found, start_outside, goal_blocked, no_path, plan_full };
const char* to_string(PlanResult result);

class PathPlanner {
 public:
  explicit PathPlanner(const ExploreParams& params);

  // Plans from `start` (the robot's cell; it may itself be non-passable) to `goal`.
  PlanResult plan(const NavigationMap& map, const Eigen::Vector2i& start, const Eigen::Vector2i& goal, Plan& plan);
  std::uint64_t expansions() const { return expansions_; }  // cells closed, all plans
  // The plan's cells from `first` on, judged again on a rebuilt map: `narrow` and the
  // waypoints' places in the gaps as planning on this map would set them. A plan made while a
  // door's jambs were not yet in the map runs through the door at its cells' centres.
  void refit(const NavigationMap& map, Plan& plan, std::size_t first) const;
  // What the plan's cells from `first` on cost on this map (the sum of step_cost), or
  // infinity if one of them is no longer passable.
  static double remaining_cost(const NavigationMap& map, const Plan& plan, std::size_t first);
  // A cell within the safety margin of an obstacle, or nearer than explore.narrow_clearance_m
  // to one (Plan::narrow).
  bool narrow(const NavigationMap& map, int x, int y) const;

 private:
  void push_or_decrease(std::int32_t cell, float cost);
  std::int32_t pop();
  bool before(std::int32_t a, std::int32_t b) const;
  void sift_up(std::size_t position);
  void sift_down(std::size_t position);
  float heuristic(std::int32_t cell) const;
  // Moves the waypoints in narrow gaps to their middle (explore.gap_centring_reach_m).
  void centre_in_gaps(const NavigationMap& map, Plan& plan, std::size_t first) const;

  std::size_t capacity_;
  int width_ = 0;
  double resolution_m_ = 0.1;
  Eigen::Vector2i goal_ = Eigen::Vector2i::Zero();
  std::unique_ptr<float[]> cost_;            // g
  std::unique_ptr<float[]> estimate_;        // f = g + h
  std::unique_ptr<std::int32_t[]> parent_;
  std::unique_ptr<std::int32_t[]> heap_position_;  // -1 when not in the heap (valid if stamped)
  std::unique_ptr<std::uint32_t[]> seen_stamp_;
  std::unique_ptr<std::uint32_t[]> closed_stamp_;
  std::unique_ptr<std::int32_t[]> heap_;
  std::size_t heap_size_ = 0;
  std::uint32_t stamp_ = 0;
  std::uint64_t expansions_ = 0;
  double gap_centring_reach_m_;
  double narrow_clearance_m_;
};

}  // namespace stereoscout::explore
