#pragma once
// What the exploration module needs from the occupancy grid: a plain, read-only view of cell
// states. The stack converts the ML grid with the ROS map_server thresholds; nothing here
// depends on the occupancy module's internals. Also the derived settings of the module.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include <Eigen/Core>

#include "stereoscout/core/config/camera.hpp"
#include "stereoscout/core/config/explore.hpp"
#include "stereoscout/core/config/robot.hpp"
#include "stereoscout/core/config/vision.hpp"

namespace stereoscout::explore {

enum class CellState : std::uint8_t { unknown = 0, free = 1, occupied = 2 };

// Row-major cells, row 0 at the lowest y; cell (x, y) covers
// [origin + resolution * (x, y), origin + resolution * (x + 1, y + 1)).
struct GridView {
  int width = 0;
  int height = 0;
  double resolution_m = 0.1;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  const std::uint8_t* cells = nullptr;  // CellState values
  // Optional, same layout: nonzero where the cell was in view of the camera (the occupancy
  // grid's in_view). Unknown and in view: a surface stereo could not measure, never crossed.
  const std::uint8_t* in_view = nullptr;
  // Optional, same layout: nonzero where a scan column's ray passed over the cell (the
  // occupancy grid's looked_over, grid.looked_over_range_m). Given, an unknown cell near the
  // robot is passable only if looked over, and kept clear of if not (NavigationMap).
  const std::uint8_t* looked_over = nullptr;
  // Optional, same layout: nonzero where the explorer saw the cell standing (occupied through
  // explore.trace_view_updates updates in the camera's view; TraceMemory). Where the grid now
  // holds such a cell free, paths pay explore.remembered_obstacle_cost to cross it.
  const std::uint8_t* seen_standing = nullptr;

  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
  }
  CellState at(int x, int y) const { return static_cast<CellState>(cells[index(x, y)]); }
  bool was_in_view(int x, int y) const { return in_view != nullptr && in_view[index(x, y)] != 0; }
  bool marks_looked_over() const { return looked_over != nullptr; }
  bool was_looked_over(int x, int y) const { return looked_over != nullptr && looked_over[index(x, y)] != 0; }
  bool was_seen_standing(int x, int y) const { return seen_standing != nullptr && seen_standing[index(x, y)] != 0; }
  Eigen::Vector2d center(int x, int y) const { return origin_m + resolution_m * Eigen::Vector2d(x + 0.5, y + 0.5); }
  Eigen::Vector2i cell_of(const Eigen::Vector2d& point) const {
    const Eigen::Vector2d local = (point - origin_m) / resolution_m;
    return {static_cast<int>(std::floor(local.x())), static_cast<int>(std::floor(local.y()))};
  }
};

// `grid` with some cells changed: copied into `buffer` (room for all its cells) at the first
// change only, so that a grid with nothing to change is handed on as it is.
class GridEdit {
 public:
  GridEdit(const GridView& grid, std::uint8_t* buffer) : grid_(grid), buffer_(buffer) {}

  void set(std::size_t index, CellState state) {
    if (!copied_) {
      std::memcpy(buffer_, grid_.cells, static_cast<std::size_t>(grid_.width) * static_cast<std::size_t>(grid_.height));
      copied_ = true;
    }
    buffer_[index] = static_cast<std::uint8_t>(state);
  }
  GridView result() const {
    GridView edited = grid_;
    if (copied_) edited.cells = buffer_;
    return edited;
  }

 private:
  GridView grid_;
  std::uint8_t* buffer_;
  bool copied_ = false;
};

// floor() of a value well inside int's range, as an int: one conversion and a compare, where
// std::floor on the x86-64 baseline (no SSE4.1 rounding) is a longer sequence of conversions
// and masks back to a double. The ray march's inner loop.
inline int floor_to_int(double value) {
  const int truncated = static_cast<int>(value);
  return value < static_cast<double>(truncated) ? truncated - 1 : truncated;
}

// Visits the cells a ray from the centre of cell (x, y) along the unit vector `direction`
// crosses within length_cells, in order and each once, the start cell excepted. It marches
// in quarter-cell steps, so no cell the ray crosses is skipped (corners grazed aside). Stops
// early when visit(cell_x, cell_y) returns false.
template <typename Visit>
void march_cells(int x, int y, const Eigen::Vector2d& direction, double length_cells, Visit&& visit) {
  const double step_cells = 0.25;
  const double start_x = x + 0.5;
  const double start_y = y + 0.5;
  int last_x = x;
  int last_y = y;
  for (double t = step_cells; t <= length_cells; t += step_cells) {
    const int cx = floor_to_int(start_x + t * direction.x());
    const int cy = floor_to_int(start_y + t * direction.y());
    if (cx == last_x && cy == last_y) continue;
    last_x = cx;
    last_y = cy;
    if (!visit(cx, cy)) return;
  }
}

// No occupied cell on the straight line from the centre of cell a to that of cell b; a itself
// is not checked, b only with check_end (a camera at a sees an obstacle at b, but not past one).
inline bool no_occupied_between(const GridView& grid, const Eigen::Vector2i& a, const Eigen::Vector2i& b,
                                bool check_end) {
  const Eigen::Vector2d span = (b - a).cast<double>();
  const double length_cells = span.norm();
  if (length_cells == 0.0) return true;
  bool clear = true;
  march_cells(a.x(), a.y(), span / length_cells, length_cells, [&](int x, int y) {
    if (!check_end && x == b.x() && y == b.y()) return false;
    clear = !(grid.contains(x, y) && grid.at(x, y) == CellState::occupied);
    return clear;
  });
  return clear;
}

// Everything the module uses, in SI units, derived once from the config sections.
struct ExploreParams {
  core::ExploreConfig explore;
  double robot_radius_m = 0.35;
  double max_speed_mps = 0.12;
  double max_turn_rate_rad_s = 0.0;
  bool has_pan_unit = true;
  // Where the camera sees: its distance ahead of the robot's centre, half its horizontal field
  // of view, and the range from which it sees the floor (nearer, a person's cell may be out of
  // the other camera's view or the matcher's range, and no ray would clear it).
  double camera_forward_m = 0.1;
  double camera_half_fov_rad = 0.675;
  double camera_near_m = 1.0;
  // Nearer the camera than this the dense matcher measures nothing (focal * baseline over its
  // largest disparity): a look clears no cell there, not even a gone person's.
  double camera_measurable_m = 0.63;
  // The left camera's distance to the left of the right one, whose columns the scan has.
  double camera_baseline_m = 0.1;
  int max_width = 700;   // grid size the buffers are allocated for
  int max_height = 700;

  static ExploreParams from_config(const core::ExploreConfig& explore, const core::RobotConfig& robot,
                                   const core::CameraConfig& camera, const core::VisionConfig& vision, int max_width,
                                   int max_height);
  // A cell centre closer than this to an occupied cell centre is a collision: the robot radius
  // plus lethal_margin_cells of a cell for the discretisation of the obstacle's true surface.
  double lethal_distance_m(double resolution_m) const {
    return robot_radius_m + explore.lethal_margin_cells * resolution_m;
  }
  // Goals keep this clearance; paths pay a high cost below it.
  double safe_distance_m(double resolution_m) const { return lethal_distance_m(resolution_m) + explore.safety_margin_m; }
  // A cell nearer the robot's centre than this may lie where the camera sees no floor or
  // measures nothing: no view from here clears it, so a look says nothing about it.
  double unseen_floor_radius_m() const { return camera_forward_m + std::max(camera_near_m, camera_measurable_m); }
  double ray_cap_m() const {
    return explore.preferred_distance_m + explore.ray_cap_sigmas * explore.distance_sigma_m;
  }
};

}  // namespace stereoscout::explore
