#include "stereoscout/explore/shut_gaps.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace stereoscout::explore {
namespace {
// A plan crosses a wall's lethal band (the robot's clearance on either side of the wall's
// cells) in about 10 cells of 0.1 m, diagonally 8 of 0.14 m: a gap's blocked run fits in this.
constexpr std::size_t kGapCells = 16;
// Room for 16 gaps' cells.
constexpr std::size_t kHeldCells = 16 * kGapCells;
}  // namespace

ShutGaps::ShutGaps(const ExploreParams& params, int max_width, int max_height)
    : hold_s_(params.explore.shut_gap_hold_s),
      range_m_(params.explore.shut_gap_range_m),
      robot_radius_m_(params.robot_radius_m),
      lethal_margin_cells_(params.explore.lethal_margin_cells),
      capacity_cells_(static_cast<std::size_t>(std::max(max_width, 0)) * static_cast<std::size_t>(std::max(max_height, 0))),
      driven_(new std::uint8_t[capacity_cells_]()),
      pending_(kGapCells),
      cells_held_(kHeldCells),
      stamped_(new std::uint8_t[capacity_cells_]) {}

void ShutGaps::drove(const GridView& grid, const Eigen::Vector2d& position) {
  if (!enabled() || grid.width <= 0 || grid.height <= 0) return;
  const std::size_t count = static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height);
  if (count > capacity_cells_) return;
  if (grid.width != driven_grid_.width || grid.height != driven_grid_.height ||
      grid.resolution_m != driven_grid_.resolution_m || grid.origin_m != driven_grid_.origin_m) {
    if (driven_grid_.width > 0) ++driven_restarts_;
    std::memset(driven_.get(), 0, count);
    driven_grid_ = grid;
    driven_grid_.cells = driven_.get();
  }
  const Eigen::Vector2i centre = grid.cell_of(position);
  const int reach = static_cast<int>(std::ceil(robot_radius_m_ / grid.resolution_m));
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const int x = centre.x() + dx;
      const int y = centre.y() + dy;
      if (!grid.contains(x, y) || (grid.center(x, y) - position).norm() > robot_radius_m_) continue;
      driven_[grid.index(x, y)] = 1;
    }
  }
}

bool ShutGaps::driven(const Eigen::Vector2d& point) const {
  const Eigen::Vector2i cell = driven_grid_.cell_of(point);
  return driven_grid_.contains(cell.x(), cell.y()) && driven_[driven_grid_.index(cell.x(), cell.y())] != 0;
}

void ShutGaps::blocked(const NavigationMap& map, const Plan& plan, std::size_t blocked, const Eigen::Vector2d& robot) {
  pending_.clear();
  if (!enabled() || blocked >= plan.cells.size()) return;
  pending_far_ = range_m_ > 0.0 && (plan.waypoints[blocked] - robot).norm() > range_m_;
  for (std::size_t k = blocked; k < plan.cells.size() && pending_.size() < kGapCells; ++k) {
    const Eigen::Vector2i& cell = plan.cells[k];
    if (map.passable(cell.x(), cell.y())) break;
    if (in_a_gap(map, plan, k)) pending_.push_back(map.grid().center(cell.x(), cell.y()));
  }
}

// A cell of the plan between obstacles on either side of the way through it that are no
// farther apart across it than a door: the disc's lethal width and a cell either side (1.0 m
// between cell centres on the default robot and grid; a 0.9 m door's jambs are 0.9-1.0 m
// apart). A cell impassable for one obstacle alone (beside a wall, a person's trace in a
// corridor) lies in no such gap, and shutting it could cut a corridor in two.
bool ShutGaps::in_a_gap(const NavigationMap& map, const Plan& plan, std::size_t k) const {
  const std::size_t before = k > 0 ? k - 1 : k;
  const std::size_t after = std::min(k + 1, plan.waypoints.size() - 1);
  const Eigen::Vector2d along = plan.waypoints[after] - plan.waypoints[before];
  if (along.squaredNorm() == 0.0) return false;
  const Eigen::Vector2d across = Eigen::Vector2d(-along.y(), along.x()).normalized();
  const double resolution_m = map.grid().resolution_m;
  const double widest_m = 2.0 * (robot_radius_m_ + (lethal_margin_cells_ + 1.0) * resolution_m);
  Eigen::Vector2d left;
  Eigen::Vector2d right;
  return map.nearest_obstacles_aside(plan.waypoints[k], across, widest_m, left, right) &&
         across.dot(left - right) <= widest_m + 1e-9;
}

bool ShutGaps::shut(double time_s) {
  if (pending_.size() == 0) return false;
  if (pending_far_) {
    ++refused_far_;
    pending_.clear();
    return false;
  }
  std::size_t shut_now = 0;
  for (const Eigen::Vector2d& point : pending_) {
    if (driven(point)) continue;
    if (!cells_held_.push_back(ShutCell{point, time_s + hold_s_})) {
      ++dropped_full_;
      continue;
    }
    if (shut_now == 0) last_shut_at_ = point;
    ++shut_now;
  }
  pending_.clear();
  if (shut_now == 0) {
    ++refused_driven_;
    return false;
  }
  ++gaps_shut_;
  cells_shut_ += shut_now;
  last_shut_cells_ = shut_now;
  return true;
}

GridView ShutGaps::stamp(const GridView& grid, double time_s) {
  for (std::size_t i = 0; i < cells_held_.size();) {
    if (cells_held_[i].until_s > time_s) {
      ++i;
      continue;
    }
    cells_held_[i] = cells_held_[cells_held_.size() - 1];
    cells_held_.pop_back();
  }
  const std::size_t count = static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height);
  if (cells_held_.size() == 0 || count > capacity_cells_) return grid;
  GridEdit edit(grid, stamped_.get());
  for (const ShutCell& held : cells_held_) {
    const Eigen::Vector2i cell = grid.cell_of(held.point);
    if (grid.contains(cell.x(), cell.y()) && grid.at(cell.x(), cell.y()) != CellState::occupied) {
      edit.set(grid.index(cell.x(), cell.y()), CellState::occupied);
    }
  }
  return edit.result();
}

std::size_t ShutGaps::lift() {
  const std::size_t lifted = cells_held_.size();
  cells_held_.clear();
  return lifted;
}

}  // namespace stereoscout::explore
