#include "stereoscout/explore/trace_memory.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::explore {
namespace {

constexpr float kNever = -std::numeric_limits<float>::infinity();
// Cells compared a block at a time: between two updates nearly every block is unchanged.
constexpr std::size_t kCompareBlock = 64;

// Visits each cell of `grid` whose centre lies within radius_m of `centre`:
// visit(x, y, index, distance_m).
template <typename Visit>
void for_cells_within(const GridView& grid, const Eigen::Vector2d& centre, double radius_m, Visit&& visit) {
  const int reach = static_cast<int>(std::ceil(radius_m / grid.resolution_m));
  const Eigen::Vector2i middle = grid.cell_of(centre);
  for (int y = middle.y() - reach; y <= middle.y() + reach; ++y) {
    for (int x = middle.x() - reach; x <= middle.x() + reach; ++x) {
      if (!grid.contains(x, y)) continue;
      const double distance_m = (grid.center(x, y) - centre).norm();
      if (distance_m <= radius_m) visit(x, y, grid.index(x, y), distance_m);
    }
  }
}

}  // namespace

TraceMemory::TraceMemory(const core::ExploreConfig& config, int max_width, int max_height)
    : margin_m_(config.fresh_obstacle_margin_m),
      hold_s_(config.fresh_obstacle_hold_s),
      forget_after_s_(config.trace_forget_after_s),
      confirm_radius_m_(config.trace_confirm_radius_m),
      previous_(static_cast<std::size_t>(max_width) * static_cast<std::size_t>(max_height),
                static_cast<std::uint8_t>(CellState::unknown)),
      turned_occupied_s_(previous_.size(), kNever),
      views_(config.trace_view_updates > 0 ? previous_.size() : 0U, 0),
      standing_(views_.size(), 0),
      view_updates_(config.trace_view_updates),
      forgotten_(forget_after_s_ > 0.0 ? previous_.size() : 0U) {}

bool CameraWedge::contains(const Eigen::Vector2d& point) const {
  const Eigen::Vector2d offset = point - position;
  const double range = offset.norm();
  if (range < near_m || range > far_m) return false;
  return std::abs(core::wrap_angle(std::atan2(offset.y(), offset.x()) - heading_rad)) <= half_fov_rad;
}

void TraceMemory::observe(const GridView& grid, double time_s, const CameraWedge* view) {
  const std::size_t count = static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height);
  const bool counting = !views_.empty();
  if (count > previous_.size() || (margin_m_ <= 0.0 && forget_after_s_ <= 0.0 && !counting)) return;
  if (!same_geometry(grid)) {
    // A new grid geometry: nothing to compare with; this grid is the reference.
    width_ = grid.width;
    height_ = grid.height;
    for (std::size_t i = 0; i < count; ++i) {
      previous_[i] = grid.cells[i];
      turned_occupied_s_[i] = kNever;
    }
    if (counting) {
      std::fill(views_.begin(), views_.end(), 0);
      std::fill(standing_.begin(), standing_.end(), 0);
    }
    return;
  }
  const auto free = static_cast<std::uint8_t>(CellState::free);
  const auto occupied = static_cast<std::uint8_t>(CellState::occupied);
  for (std::size_t block = 0; block < count; block += kCompareBlock) {
    const std::size_t end = std::min(count, block + kCompareBlock);
    if (std::memcmp(previous_.data() + block, grid.cells + block, end - block) == 0) continue;
    for (std::size_t i = block; i < end; ++i) {
      if (previous_[i] != occupied && grid.cells[i] == occupied) {
        if (previous_[i] == free) turned_occupied_s_[i] = static_cast<float>(time_s);
        if (counting) views_[i] = 0;
      }
      previous_[i] = grid.cells[i];
    }
  }
  if (counting && view != nullptr) count_views(grid, *view);
}

// Occupied cells in the wedge and in sight (no occupied cell on the way there): one more
// update seen standing; at view_updates_ they are standing obstacles, no traces.
void TraceMemory::count_views(const GridView& grid, const CameraWedge& view) {
  const int reach = static_cast<int>(std::ceil(view.far_m / grid.resolution_m));
  const Eigen::Vector2i camera = grid.cell_of(view.position);
  const auto occupied = static_cast<std::uint8_t>(CellState::occupied);
  for (int y = camera.y() - reach; y <= camera.y() + reach; ++y) {
    for (int x = camera.x() - reach; x <= camera.x() + reach; ++x) {
      if (!grid.contains(x, y)) continue;
      const std::size_t i = grid.index(x, y);
      if (grid.cells[i] != occupied || views_[i] >= view_updates_ || !view.contains(grid.center(x, y))) continue;
      if (!no_occupied_between(grid, camera, {x, y}, false)) continue;
      if (++views_[i] < view_updates_) continue;
      turned_occupied_s_[i] = kNever;
      standing_[i] = 1;
      ++seen_standing_;
    }
  }
}

bool TraceMemory::fresh(const GridView& grid, int x, int y, double time_s) const {
  if (!same_geometry(grid) || !grid.contains(x, y)) return false;
  return time_s - static_cast<double>(turned_occupied_s_[grid.index(x, y)]) <= hold_s_;
}

bool TraceMemory::only_passers_by_near(const GridView& grid, int x, int y, double radius_m, double time_s) const {
  if (forget_after_s_ <= 0.0 || !same_geometry(grid)) return false;
  const int reach = static_cast<int>(std::ceil(radius_m / grid.resolution_m));
  const auto occupied = static_cast<std::uint8_t>(CellState::occupied);
  bool any = false;
  for (int cy = y - reach; cy <= y + reach; ++cy) {
    for (int cx = x - reach; cx <= x + reach; ++cx) {
      if (!grid.contains(cx, cy) || grid.cells[grid.index(cx, cy)] != occupied) continue;
      if ((grid.center(cx, cy) - grid.center(x, y)).norm() >= radius_m) continue;
      const std::size_t i = grid.index(cx, cy);
      const bool passer_by = previous_[i] == occupied && turned_occupied_s_[i] != kNever &&
                             time_s - static_cast<double>(turned_occupied_s_[i]) < forget_after_s_;
      if (!passer_by) return false;
      any = true;
    }
  }
  return any;
}

// Occupied when last observed (a cell seen free again is no trace), and turned so long ago.
bool TraceMemory::trace(std::size_t i, double time_s) const {
  return previous_[i] == static_cast<std::uint8_t>(CellState::occupied) && turned_occupied_s_[i] != kNever &&
         time_s - static_cast<double>(turned_occupied_s_[i]) >= forget_after_s_;
}

bool TraceMemory::occupied_trace(const GridView& grid, std::size_t i, double time_s) const {
  return trace(i, time_s) && grid.cells[i] == static_cast<std::uint8_t>(CellState::occupied);
}

// An occupied neighbour that is no trace: the cell is part of a standing obstacle, such as a
// blank wall whose cells grazing rays erased and the next view restored one by one.
bool TraceMemory::touches_obstacle(const GridView& grid, int x, int y, double time_s) const {
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if ((dx == 0 && dy == 0) || !grid.contains(x + dx, y + dy)) continue;
      const std::size_t i = grid.index(x + dx, y + dy);
      if (grid.cells[i] == static_cast<std::uint8_t>(CellState::occupied) && !trace(i, time_s)) return true;
    }
  }
  return false;
}

GridView TraceMemory::forget_traces(const GridView& grid, double time_s) {
  forgotten_last_ = 0;
  if (forget_after_s_ <= 0.0 || !same_geometry(grid)) return grid;
  const std::size_t count = static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height);
  GridEdit forgotten(grid, forgotten_.data());
  for (std::size_t i = 0; i < count; ++i) {
    if (!occupied_trace(grid, i, time_s)) continue;
    const int x = static_cast<int>(i % static_cast<std::size_t>(grid.width));
    const int y = static_cast<int>(i / static_cast<std::size_t>(grid.width));
    if (touches_obstacle(grid, x, y, time_s)) continue;
    forgotten.set(i, CellState::free);
    ++forgotten_last_;
  }
  return forgotten.result();
}

std::size_t TraceMemory::confirm_near(const GridView& grid, const Eigen::Vector2d& centre, double seen_from_m,
                                      double time_s, double traces_as_of_s) {
  if (forget_after_s_ <= 0.0 || !same_geometry(grid)) return 0;
  std::size_t confirmed = 0;
  for_cells_within(grid, centre, confirm_radius_m_, [&](int, int, std::size_t i, double distance_m) {
    if (distance_m < seen_from_m || !occupied_trace(grid, i, time_s) || !trace(i, traces_as_of_s)) return;
    turned_occupied_s_[i] = kNever;
    ++confirmed;
  });
  confirmed_ += confirmed;
  return confirmed;
}

double TraceMemory::nearest_trace_ahead_m(const GridView& grid, const Eigen::Vector2d& centre,
                                          const Eigen::Vector2d& heading, double radius_m, double time_s) const {
  double nearest_m = std::numeric_limits<double>::infinity();
  if (forget_after_s_ <= 0.0 || !same_geometry(grid)) return nearest_m;
  for_cells_within(grid, centre, radius_m, [&](int x, int y, std::size_t i, double distance_m) {
    if (distance_m >= nearest_m || !occupied_trace(grid, i, time_s)) return;
    if ((grid.center(x, y) - centre).dot(heading) > 0.0) nearest_m = distance_m;
  });
  return nearest_m;
}

}  // namespace stereoscout::explore
