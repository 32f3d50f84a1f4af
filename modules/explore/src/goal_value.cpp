#include "stereoscout/explore/goal_value.hpp"

#include <algorithm>
#include <cmath>

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::explore {
namespace {

double squared(double value) { return value * value; }

// A blacklisting's hold doubles at most this many times: 2^20 holds outlast any run.
constexpr int kMaxHoldDoublings = 20;

}  // namespace

GoalMemory::GoalMemory(std::size_t capacity, double radius_m, double blacklist_radius_m,
                       int failures_before_blacklist, double cooldown_s, double hold_s, double failure_radius_m)
    : entries_(capacity),
      radius2_(squared(radius_m)),
      // Never below the visited radius: failures add up within it.
      blacklist_radius2_(squared(std::max(radius_m, blacklist_radius_m))),
      failure_radius2_(squared(failure_radius_m)),
      failures_before_blacklist_(failures_before_blacklist),
      cooldown_s_(cooldown_s),
      hold_s_(hold_s) {}

GoalMemory::Entry* GoalMemory::find(const Eigen::Vector2d& position) {
  for (Entry& entry : entries_) {
    if ((entry.position - position).squaredNorm() <= radius2_) return &entry;
  }
  return nullptr;
}

GoalMemory::Entry* GoalMemory::nearest_failed(const Eigen::Vector2d& position) {
  Entry* nearest = nullptr;
  double nearest2 = failure_radius2_;
  for (Entry& entry : entries_) {
    const double distance2 = (entry.position - position).squaredNorm();
    if (!entry.visited && distance2 <= nearest2) {
      nearest = &entry;
      nearest2 = distance2;
    }
  }
  return nearest;
}

bool GoalMemory::record_failure(const Eigen::Vector2d& position, double time_s) {
  Entry* entry = find(position);
  if (entry == nullptr && failure_radius2_ > radius2_) entry = nearest_failed(position);
  if (entry == nullptr) {
    entry = entries_.emplace_back(Entry{position, 0});
    if (entry == nullptr) {
      ++forgotten_;
      return false;
    }
  }
  if (entry->visited || held(*entry, time_s)) return true;
  if (entry->failures >= failures_before_blacklist_) entry->failures = 0;  // its hold is over
  entry->last_failure_s = time_s;
  if (++entry->failures < failures_before_blacklist_) return false;
  ++entry->blacklistings;
  ++blacklisted_;
  return true;
}

bool GoalMemory::held(const Entry& entry, double time_s) const {
  if (entry.failures < failures_before_blacklist_) return false;
  if (hold_s_ <= 0.0) return true;
  const int doublings = std::clamp(entry.blacklistings - 1, 0, kMaxHoldDoublings);
  const double hold_s = std::ldexp(hold_s_, doublings);
  return time_s - entry.last_failure_s < hold_s;
}

std::size_t GoalMemory::release_held(double time_s, int max_blacklistings) {
  if (hold_s_ <= 0.0) return 0;
  std::size_t released = 0;
  for (Entry& entry : entries_) {
    if (entry.visited || entry.blacklistings > max_blacklistings || !held(entry, time_s)) continue;
    entry.failures = 0;
    ++released;
  }
  return released;
}

void GoalMemory::record_visit(const Eigen::Vector2d& position) {
  Entry* entry = find(position);
  if (entry == nullptr) entry = entries_.emplace_back(Entry{position, 0});
  if (entry == nullptr) {
    ++forgotten_;
    return;
  }
  entry->visited = true;  // excluded for good, whatever its failures
}

bool GoalMemory::excluded(const Eigen::Vector2d& position, double time_s) const {
  for (const Entry& entry : entries_) {
    if (entry.visited) {
      if ((entry.position - position).squaredNorm() <= radius2_) return true;
      continue;
    }
    const bool cooling = entry.failures > 0 && time_s - entry.last_failure_s < cooldown_s_;
    if (!held(entry, time_s) && !cooling) continue;
    if ((entry.position - position).squaredNorm() <= blacklist_radius2_) return true;
  }
  return false;
}

GoalValue::GoalValue(const ExploreParams& params)
    : params_(params),
      directions_(static_cast<std::size_t>(std::max(1L, std::lround(360.0 / params.explore.ray_step_deg)))) {
  const double step = core::degrees_to_radians(params.explore.ray_step_deg);
  for (std::size_t k = 0; k < directions_.capacity(); ++k) {
    const double theta = step * static_cast<double>(k);
    directions_.push_back(Eigen::Vector2d(std::cos(theta), std::sin(theta)));
  }
}

// Marches from the centre of s (march_cells); |s' - s| is the distance between the two cell
// centres.
double GoalValue::ray_value(const GridView& grid, int x, int y, std::size_t ray_index) const {
  return ray_value(grid, nullptr, x, y, ray_index);
}

double GoalValue::ray_value(const GridView& grid, const NavigationMap* pockets, int x, int y,
                            std::size_t ray_index) const {
  double value = 0.0;
  march_cells(x, y, directions_[ray_index], params_.ray_cap_m() / grid.resolution_m, [&](int cx, int cy) {
    if (!grid.contains(cx, cy)) return false;
    const CellState state = grid.at(cx, cy);
    if (state == CellState::free) return true;
    if (state == CellState::occupied) return false;
    if (pockets != nullptr && pockets->in_pocket(cx, cy)) return false;  // nothing to see there
    if (params_.explore.in_view_ends_goal_rays && grid.was_in_view(cx, cy)) return false;  // seen, not measurable
    const double dx = cx - x;
    const double dy = cy - y;
    const double distance_m = grid.resolution_m * std::sqrt(dx * dx + dy * dy);
    const double error = (distance_m - params_.explore.preferred_distance_m) / params_.explore.distance_sigma_m;
    value = std::exp(-0.5 * error * error);
    return false;
  });
  return value;
}

double GoalValue::value(const GridView& grid, int x, int y) const {
  ++values_computed_;
  double sum = 0.0;
  for (std::size_t k = 0; k < directions_.size(); ++k) sum += ray_value(grid, nullptr, x, y, k);
  return sum;
}

double GoalValue::value(const NavigationMap& map, int x, int y) const {
  ++values_computed_;
  double sum = 0.0;
  for (std::size_t k = 0; k < directions_.size(); ++k) sum += ray_value(map.grid(), &map, x, y, k);
  return sum;
}

bool GoalValue::is_candidate(const NavigationMap& map, const GoalMemory& memory, double time_s, int x,
                             int y) const {
  const GridView& grid = map.grid();
  return grid.contains(x, y) && grid.at(x, y) == CellState::free &&
         map.traversability(x, y) == Traversability::safe && map.reachable(x, y) &&
         map.unknown_distance_m(x, y) <= params_.ray_cap_m() && !memory.excluded(grid.center(x, y), time_s);
}

Goal GoalValue::select(const NavigationMap& map, const GoalMemory& memory, double time_s) const {
  const GridView& grid = map.grid();
  const CellBox& box = map.window();
  const int stride = params_.explore.candidate_stride_cells;
  Goal best;
  const double distance_cost = params_.explore.goal_distance_cost;
  auto consider = [&](int x, int y) {
    if (!is_candidate(map, memory, time_s, x, y)) return;
    const double h = value(map, x, y);
    if (h <= 0.0) return;
    const double utility = distance_cost > 0.0 ? h - distance_cost * map.reach_distance_m(x, y) : h;
    if (!best.valid || utility > best.utility) {
      best.valid = true;
      best.value = h;
      best.utility = utility;
      best.cell = Eigen::Vector2i(x, y);
    }
  };
  // Lattice aligned to the grid (not the window) so that candidates do not move as it grows.
  const int first_x = (box.x0 + stride - 1) / stride * stride;
  const int first_y = (box.y0 + stride - 1) / stride * stride;
  for (int y = first_y; y < box.y1; y += stride) {
    for (int x = first_x; x < box.x1; x += stride) consider(x, y);
  }
  if (!best.valid) return best;
  const Eigen::Vector2i lattice_best = best.cell;
  const int half = stride / 2;
  for (int y = lattice_best.y() - half; y <= lattice_best.y() + half; ++y) {
    for (int x = lattice_best.x() - half; x <= lattice_best.x() + half; ++x) {
      if (x != lattice_best.x() || y != lattice_best.y()) consider(x, y);
    }
  }
  best.position = grid.center(best.cell.x(), best.cell.y());
  return best;
}

}  // namespace stereoscout::explore
