#pragma once
// Obstacles that appeared where the grid held free floor: usually a person walking. Cells
// that turn occupied from unknown (a first sighting) are not counted; a static obstacle seen
// for the first time is an ordinary obstacle. Two uses:
//
// Fresh (the person is there now). The grid changes only at observation updates (after 7 cm
// of motion, at most 2 Hz in the stack), and a person walking at 0.5 m/s moves 0.3 m in
// between, so the safety check can keep explore.fresh_obstacle_margin_m more clearance from
// cells that turned occupied within fresh_obstacle_hold_s. Off by default (margin 0): at
// 0.3 m it did not reduce the robot's contacts with walking people in the three worlds, and it
// added safety stops (docs/results.md).
//
// Traces (the person has walked on). The grid clears a person's cells only when a later ray
// passes through them, and from inside a room the robot does not see the corridor beyond its
// door: a person who walked past the door while the robot looked out left cells that shut it in
// (the office). So a cell that turned occupied at least explore.trace_forget_after_s ago (0:
// never) is a trace, and where the explorer would otherwise conclude "no plan" or "nothing
// left", it plans on the grid with the traces free (forget_traces()). The safety check does
// not: it still stops the robot before the cell, and the look that follows re-observes it.
// Traces within trace_confirm_radius_m that are still occupied after a look are obstacles from
// then on (confirm_near()), but for those where the camera sees no floor (near the robot): a
// look cannot clear them, and the explorer backs off before it looks (nearest_trace_ahead_m()).
// With explore.trace_confirm_before_look, only those that were traces when the look began: a
// cell that turned occupied while the robot looked is what the look watched appear.
// Not every trace is a person: the grid also first holds free, then occupied, the cells of a
// blank wall that grazing rays erased; crossing traces always, not only when stuck, led plans
// through the office's corridor walls (docs/results.md). So a trace next to an occupied cell
// that is no trace is part of that obstacle, not forgotten. And a cell that stayed occupied
// through trace_view_updates observation updates in the camera's view is a standing obstacle,
// never a trace: when a person has gone, the rays through their cell clear it within a few
// updates; a blank wall's restored cell stays (without this, plans that crossed traces ran back
// through the office wall the robot had just seen, and in clutter between two blocked routes).
//
// observe() compares the grid with the one it saw last; it runs after every observation
// update. All buffers are sized for the largest grid at construction; nothing is allocated
// after that.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "stereoscout/explore/grid_view.hpp"

namespace stereoscout::explore {

// Where the camera looked at an observation update, and the part of its view in which a
// cell that stays occupied counts as seen standing (ExploreParams' camera fields).
struct CameraWedge {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double heading_rad = 0.0;
  double half_fov_rad = 0.0;
  double near_m = 0.0;
  double far_m = 0.0;
  bool contains(const Eigen::Vector2d& point) const;
};

class TraceMemory {
 public:
  TraceMemory(const core::ExploreConfig& config, int max_width, int max_height);

  // With `view`, also counts the updates in which each occupied cell stood in sight within
  // it (trace_view_updates): a cell that turned occupied is then no trace, and every such
  // cell is remembered (standing_cells()).
  void observe(const GridView& grid, double time_s, const CameraWedge* view = nullptr);
  // True when cell (x, y) of the grid last observed turned from free to occupied within
  // fresh_obstacle_hold_s before time_s.
  bool fresh(const GridView& grid, int x, int y, double time_s) const;
  // True when `grid` (the grid last observed, or a copy with more cells occupied) has occupied
  // cells within radius_m of cell (x, y), and every one of them is a cell the observed grid
  // turned from free to occupied less than trace_forget_after_s before time_s and that was
  // not seen standing since: most likely a person walking by (explore.wait_for_walkers).
  bool only_passers_by_near(const GridView& grid, int x, int y, double radius_m, double time_s) const;
  double margin_m() const { return margin_m_; }

  // `grid` (the grid last observed, or a copy of it with more cells occupied) with its traces
  // free, except those next to an occupied cell that is no trace (8-neighbours): a copy in
  // the memory's own buffer, or `grid` itself when there is no such trace (or forgetting is
  // off, or the geometry is not the one observed). Valid until the next call.
  GridView forget_traces(const GridView& grid, double time_s);
  // Trace cells from seen_from_m out to trace_confirm_radius_m of `centre` that `grid` still
  // holds occupied, and that were traces already at traces_as_of_s (at most time_s), become
  // obstacles; returns how many. Nearer ones stay traces: the camera sees no floor there, so a
  // look could not have cleared them (a person who passed right in front of the robot). So do
  // cells that turned occupied too late to be traces at traces_as_of_s: a look that began then
  // watched them appear, it did not find them still there.
  std::size_t confirm_near(const GridView& grid, const Eigen::Vector2d& centre, double seen_from_m, double time_s,
                           double traces_as_of_s);
  // The distance from `centre` to the nearest trace cell that `grid` still holds occupied and
  // that lies ahead (along the unit vector `heading`), if one lies within radius_m; infinity
  // otherwise.
  double nearest_trace_ahead_m(const GridView& grid, const Eigen::Vector2d& centre, const Eigen::Vector2d& heading,
                               double radius_m, double time_s) const;

  std::size_t forgotten_last() const { return forgotten_last_; }  // cells freed by the last forget_traces()
  std::uint64_t confirmed() const { return confirmed_; }  // by looks
  std::uint64_t seen_standing() const { return seen_standing_; }  // by trace_view_updates
  // Nonzero per cell (the observed grid's layout) where a cell was ever seen standing; for
  // GridView::seen_standing. Null when view counting is off.
  const std::uint8_t* standing_cells() const { return standing_.empty() ? nullptr : standing_.data(); }

 private:
  bool trace(std::size_t i, double time_s) const;
  bool occupied_trace(const GridView& grid, std::size_t i, double time_s) const;  // and `grid` holds it occupied
  bool touches_obstacle(const GridView& grid, int x, int y, double time_s) const;
  void count_views(const GridView& grid, const CameraWedge& view);
  bool same_geometry(const GridView& grid) const { return grid.width == width_ && grid.height == height_; }

  double margin_m_;
  double hold_s_;
  double forget_after_s_;
  double confirm_radius_m_;
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> previous_;  // CellState of the last grid observed
  std::vector<float> turned_occupied_s_;  // when the cell last turned from free to occupied
  std::vector<std::uint16_t> views_;  // updates in view since it last turned occupied, while occupied
  std::vector<std::uint8_t> standing_;  // seen standing at some time
  int view_updates_ = 0;
  std::vector<std::uint8_t> forgotten_;  // forget_traces()'s copy
  std::size_t forgotten_last_ = 0;
  std::uint64_t confirmed_ = 0;
  std::uint64_t seen_standing_ = 0;
};

}  // namespace stereoscout::explore
