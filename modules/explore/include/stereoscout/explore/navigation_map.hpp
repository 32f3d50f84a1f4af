#pragma once
// The grid as the planner sees it, rebuilt after every observation update: distances to the
// nearest occupied and to the nearest unknown cell (Euclidean distance transform, two passes
// propagating the nearest site), the traversability class of each cell for the robot's
// footprint, step costs for A*, and the set of cells reachable from the robot (flood fill).
//
// Occupied cells deep under the robot's disc where it stands (centre more than a cell inside
// it) are ignored: nothing else can be there; they are traces of a person who walked into the
// robot. A grazed obstacle's cell lies farther out and stays; when it leaves the robot's own
// cell lethal, the cells under the disc that are lethal only for their clearance are passable
// at the highest cost, so that a plan can lead away from it (open_way_out()).
//
// With the grid's looked-over marks (grid.looked_over_range_m), the unknown cells near the
// robot that no scan's ray passed over are kept clear of like occupied cells: they lay beside
// the robot's way, out of the camera's view, where a low box's side may stand.
//
// Unobservable pockets: an unknown region (4-connected, so that a diagonal wall line closes
// it) that does not reach the window's edge and covers at most explore.max_pocket_area_m2 is
// enclosed by what the robot has seen: the inside of a low box or a cupboard, the floor under
// a table behind its edge, single cells along a wall. No view from the free space will make
// it known, so it is not a frontier (GoalValue treats it like an occupied cell); otherwise
// such pockets keep goals above min_goal_value and exploration never ends by itself.
//
// Speed: all work is confined to a window, the bounding box of the known cells grown by the
// ray cap (cells farther out are unknown and worth nothing), so early in a run only a small
// part of the 700 x 700 grid is touched. Buffers are sized at start-up for the full grid;
// rebuilding allocates nothing.

#include <cstdint>
#include <memory>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/explore/grid_view.hpp"
#include "stereoscout/explore/trail_memory.hpp"

namespace stereoscout::explore {

enum class Traversability : std::uint8_t {
  lethal = 0,    // the robot's disc would touch an occupied cell, or unknown too far from the robot
  inflated = 1,  // passable, but within the safety margin of an obstacle (expensive; never a goal)
  safe = 2,
};

struct CellBox {
  int x0 = 0;  // inclusive
  int y0 = 0;
  int x1 = 0;  // exclusive
  int y1 = 0;
  bool contains(int x, int y) const { return x >= x0 && y >= y0 && x < x1 && y < y1; }
};

class NavigationMap {
 public:
  explicit NavigationMap(const ExploreParams& params);

  // Rebuilds everything for `grid`. Unknown cells are passable only within
  // unknown_travel_radius_m of `extra_unknown_centre` (the explorer passes the start pose),
  // of `robot` with unknown_travel_near_robot, and under the robot's disc; with
  // unknown_clearance the others are kept clear of like occupied cells. Returns false (and leaves an empty map) if
  // the grid is larger than the buffers.
  bool rebuild(const GridView& grid, const Eigen::Vector2d& robot, const Eigen::Vector2d& extra_unknown_centre);
  // After rebuild(): the cells along the robot's trail that are lethal only for their
  // clearance, and no nearer an occupied cell than the robot's radius, become passable at the
  // highest obstacle cost (the explorer's last resort, trail_memory.hpp). Returns how many.
  std::size_t open_trail(const TrailMemory& trail);

  const GridView& grid() const { return grid_; }
  const CellBox& window() const { return window_; }
  std::size_t index(int x, int y) const { return grid_.index(x, y); }

  // Distances in metres between cell centres (a large value when there is none in the window).
  // "Occupied" is every cell the robot keeps clear of: occupied cells (not deep under it) and,
  // with explore.unknown_clearance, the unknown cells paths may not cross.
  double occupied_distance_m(int x, int y) const;
  double unknown_distance_m(int x, int y) const;
  Traversability traversability(int x, int y) const;
  bool passable(int x, int y) const;
  // The passable cell nearest to `cell` within `radius_m` with no occupied cell on the straight
  // line between them (not across a wall; ties: the first in row order); false when there is none.
  bool nearest_passable(const Eigen::Vector2i& cell, double radius_m, Eigen::Vector2i& found) const;
  // The point of passable `cell`, on the line across a path of direction `along`, as far from
  // the nearest obstacle cell's centre on one side of the path as from the nearest on the other
  // (both within `reach_m` of the cell's centre; not only straight across, so that the
  // waypoints before and after a doorway in a thin wall are centred on its jambs too), moved
  // by at most half a cell; the cell's centre when either side has none.
  Eigen::Vector2d centred_in_gap(const Eigen::Vector2i& cell, const Eigen::Vector2d& along, double reach_m) const;
  // The centres of the nearest obstacle cells within reach_m of `centre` on either side of a
  // path through it (`across`: a unit vector across the path; left: across.(site - centre) > 0);
  // false unless both sides have one.
  bool nearest_obstacles_aside(const Eigen::Vector2d& centre, const Eigen::Vector2d& across, double reach_m,
                               Eigen::Vector2d& left, Eigen::Vector2d& right) const;
  // Cost of moving between two 8-neighbours (metres times the obstacle and unknown penalties
  // of the cell entered); requires passable(to).
  double step_cost(int from_x, int from_y, int to_x, int to_y) const;

  // An unknown cell of an unobservable pocket (see above).
  bool in_pocket(int x, int y) const;
  // No occupied cell on the straight line between the centres of cells a and b (a itself excepted).
  bool in_sight(const Eigen::Vector2i& a, const Eigen::Vector2i& b) const;
  std::uint64_t pocket_cells() const { return pocket_cells_; }  // in the last rebuild
  // An unknown cell within explore.shadow_depth_m straight behind a seen object's face (an
  // occupied cell with a free neighbour on the other side, in a component no larger than
  // explore.shadow_object_max_m); kept clear of like an occupied cell.
  bool in_shadow(int x, int y) const;
  std::uint64_t shadow_cells() const { return shadow_cells_; }  // in the last rebuild

  // Flood fill (8-connected, over passable cells) from `start`; the start cell counts even if
  // it is not passable (the robot stands there).
  void compute_reachable(const Eigen::Vector2i& start);
  bool reachable(int x, int y) const;
  // Of a reachable cell: the fill's steps from the start times the cell size, the length of a
  // shortest 8-connected path with every step counted as one cell (diagonals under by up to 29%).
  double reach_distance_m(int x, int y) const;

 private:
  void find_window(const Eigen::Vector2d& robot, const Eigen::Vector2d& extra);
  template <typename IsSite>
  void distance_transform(std::int32_t* sites, IsSite&& is_site);
  template <std::size_t kSteps, typename Enter, typename Visit>
  std::size_t breadth_first(std::size_t seed, const int (&steps)[kSteps][2], Enter&& enter, Visit&& visit);
  bool unknown_passable(int x, int y) const;
  bool unswept_near_robot(int x, int y) const;  // of an unknown cell
  bool obstacle_site(int x, int y) const;
  void classify();
  void open_way_out();
  bool open_trail_cell(const Eigen::Vector2d& position);
  double site_distance_m(const std::int32_t* sites, int x, int y) const;
  bool under_robot(int x, int y) const;
  void find_pockets();
  void find_shadows();
  bool part_of_object(int x, int y);
  // Labels the unknown region of `seed` (4-connected) as visited; true when it is a pocket.
  bool label_region(std::size_t seed);

  ExploreParams params_;
  std::size_t capacity_ = 0;
  GridView grid_;
  CellBox window_;
  Eigen::Vector2d robot_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d extra_unknown_centre_ = Eigen::Vector2d::Zero();
  std::unique_ptr<std::int32_t[]> occupied_site_;
  std::unique_ptr<std::int32_t[]> unknown_site_;
  std::unique_ptr<std::uint8_t[]> traversability_;
  std::unique_ptr<float[]> penalty_;  // cost multiplier of entering the cell
  std::unique_ptr<std::uint32_t[]> reached_stamp_;
  std::unique_ptr<std::int32_t[]> reach_steps_;  // valid where reached_stamp_ is current
  std::unique_ptr<std::int32_t[]> queue_;
  std::uint32_t reach_stamp_ = 0;
  // region_stamp_ of a cell: == region_stamp_ visited, == region_stamp_ + 1 in a pocket.
  std::unique_ptr<std::uint32_t[]> region_label_;
  std::uint32_t region_stamp_ = 0;
  std::uint64_t pocket_cells_ = 0;
  std::unique_ptr<std::uint8_t[]> shadow_;       // valid in the window
  std::unique_ptr<std::uint8_t[]> object_size_;  // of occupied cells; see find_shadows
  std::uint64_t shadow_cells_ = 0;
};

}  // namespace stereoscout::explore
