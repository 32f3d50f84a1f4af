#include "stereoscout/explore/fresh_obstacles.hpp"

#include <limits>

namespace stereoscout::explore {

FreshObstacles::FreshObstacles(const core::ExploreConfig& config, int max_width, int max_height)
    : margin_m_(config.fresh_obstacle_margin_m),
      hold_s_(config.fresh_obstacle_hold_s),
      previous_(static_cast<std::size_t>(max_width) * static_cast<std::size_t>(max_height),
                static_cast<std::uint8_t>(CellState::unknown)),
      turned_occupied_s_(previous_.size(), -std::numeric_limits<float>::infinity()) {}

void FreshObstacles::observe(const GridView& grid, double time_s) {
  const std::size_t count = static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height);
  if (count > previous_.size() || margin_m_ <= 0.0) return;
  if (grid.width != width_ || grid.height != height_) {
    // A new grid geometry: nothing to compare with; this grid is the reference.
    width_ = grid.width;
    height_ = grid.height;
    for (std::size_t i = 0; i < count; ++i) {
      previous_[i] = grid.cells[i];
      turned_occupied_s_[i] = -std::numeric_limits<float>::infinity();
    }
    return;
  }
  const auto free = static_cast<std::uint8_t>(CellState::free);
  const auto occupied = static_cast<std::uint8_t>(CellState::occupied);
  for (std::size_t i = 0; i < count; ++i) {
    if (previous_[i] == free && grid.cells[i] == occupied) turned_occupied_s_[i] = static_cast<float>(time_s);
    previous_[i] = grid.cells[i];
  }
}

bool FreshObstacles::fresh(const GridView& grid, int x, int y, double time_s) const {
  if (grid.width != width_ || grid.height != height_ || !grid.contains(x, y)) return false;
  return time_s - static_cast<double>(turned_occupied_s_[grid.index(x, y)]) <= hold_s_;
}

}  // namespace stereoscout::explore
