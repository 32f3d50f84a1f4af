#include "stereoscout/explore/path_planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stereoscout::explore {
namespace {
constexpr double kDiagonalExtra = 0.41421356237309515;  // sqrt(2) - 1
}

const char* to_string(PlanResult result) {
  switch (result) {
    case PlanResult::found: return "found";
    case PlanResult::start_outside: return "start outside the map";
    case PlanResult::goal_blocked: return "goal not passable";
    case PlanResult::no_path: return "no path";
    case PlanResult::plan_full: return "path longer than the plan capacity";
  }
  return "?";
}

PathPlanner::PathPlanner(const ExploreParams& params)
    : capacity_(static_cast<std::size_t>(params.max_width) * static_cast<std::size_t>(params.max_height)),
      cost_(new float[capacity_]),
      estimate_(new float[capacity_]),
      parent_(new std::int32_t[capacity_]),
      heap_position_(new std::int32_t[capacity_]),
      seen_stamp_(new std::uint32_t[capacity_]()),
      closed_stamp_(new std::uint32_t[capacity_]()),
      heap_(new std::int32_t[capacity_]),
      gap_centring_reach_m_(params.explore.gap_centring_reach_m),
      narrow_clearance_m_(params.explore.narrow_clearance_m) {}

float PathPlanner::heuristic(std::int32_t cell) const {
  const int dx = std::abs(cell % width_ - goal_.x());
  const int dy = std::abs(cell / width_ - goal_.y());
  const int straight = std::max(dx, dy);
  const int diagonal = std::min(dx, dy);
  // Rounded down a little so that float rounding never makes it exceed the true cost.
  return static_cast<float>(resolution_m_ * (straight + kDiagonalExtra * diagonal) * (1.0 - 1e-6));
}

bool PathPlanner::before(std::int32_t a, std::int32_t b) const {
  const std::size_t ia = static_cast<std::size_t>(a);
  const std::size_t ib = static_cast<std::size_t>(b);
  if (estimate_[ia] != estimate_[ib]) return estimate_[ia] < estimate_[ib];
  if (cost_[ia] != cost_[ib]) return cost_[ia] > cost_[ib];  // deeper first
  return a < b;
}

void PathPlanner::sift_up(std::size_t position) {
  const std::int32_t cell = heap_[position];
  while (position > 0) {
    const std::size_t parent = (position - 1) / 2;
    if (!before(cell, heap_[parent])) break;
    heap_[position] = heap_[parent];
    heap_position_[static_cast<std::size_t>(heap_[position])] = static_cast<std::int32_t>(position);
    position = parent;
  }
  heap_[position] = cell;
  heap_position_[static_cast<std::size_t>(cell)] = static_cast<std::int32_t>(position);
}

void PathPlanner::sift_down(std::size_t position) {
  const std::int32_t cell = heap_[position];
  while (true) {
    std::size_t child = 2 * position + 1;
    if (child >= heap_size_) break;
    if (child + 1 < heap_size_ && before(heap_[child + 1], heap_[child])) ++child;
    if (!before(heap_[child], cell)) break;
    heap_[position] = heap_[child];
    heap_position_[static_cast<std::size_t>(heap_[position])] = static_cast<std::int32_t>(position);
    position = child;
  }
  heap_[position] = cell;
  heap_position_[static_cast<std::size_t>(cell)] = static_cast<std::int32_t>(position);
}

void PathPlanner::push_or_decrease(std::int32_t cell, float cost) {
  const auto i = static_cast<std::size_t>(cell);
  cost_[i] = cost;
  estimate_[i] = cost + heuristic(cell);
  if (seen_stamp_[i] != stamp_) {
    seen_stamp_[i] = stamp_;
    heap_[heap_size_] = cell;
    sift_up(heap_size_++);
  } else {
    sift_up(static_cast<std::size_t>(heap_position_[i]));
  }
}

std::int32_t PathPlanner::pop() {
  const std::int32_t top = heap_[0];
  heap_[0] = heap_[--heap_size_];
  if (heap_size_ > 0) sift_down(0);
  return top;
}

PlanResult PathPlanner::plan(const NavigationMap& map, const Eigen::Vector2i& start, const Eigen::Vector2i& goal,
                             Plan& plan) {
  plan.clear();
  const GridView& grid = map.grid();
  if (!map.window().contains(start.x(), start.y()) ||
      static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height) > capacity_) {
    return PlanResult::start_outside;
  }
  if (!map.passable(goal.x(), goal.y())) return PlanResult::goal_blocked;
  ++stamp_;
  heap_size_ = 0;
  width_ = grid.width;
  resolution_m_ = grid.resolution_m;
  goal_ = goal;
  const auto start_cell = static_cast<std::int32_t>(map.index(start.x(), start.y()));
  const auto goal_cell = static_cast<std::int32_t>(map.index(goal.x(), goal.y()));
  parent_[static_cast<std::size_t>(start_cell)] = -1;
  push_or_decrease(start_cell, 0.0F);
  bool found = false;
  while (heap_size_ > 0) {
    const std::int32_t cell = pop();
    const auto ci = static_cast<std::size_t>(cell);
    closed_stamp_[ci] = stamp_;
    ++expansions_;
    if (cell == goal_cell) {
      found = true;
      break;
    }
    const int x = cell % width_;
    const int y = cell / width_;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if ((dx == 0 && dy == 0) || !map.passable(x + dx, y + dy)) continue;
        const auto next = static_cast<std::int32_t>(map.index(x + dx, y + dy));
        const auto ni = static_cast<std::size_t>(next);
        if (closed_stamp_[ni] == stamp_) continue;
        const float cost = cost_[ci] + static_cast<float>(map.step_cost(x, y, x + dx, y + dy));
        if (seen_stamp_[ni] == stamp_ && cost >= cost_[ni]) continue;
        parent_[ni] = cell;
        push_or_decrease(next, cost);
      }
    }
  }
  if (!found) return PlanResult::no_path;
  std::size_t length = 0;
  for (std::int32_t cell = goal_cell; cell >= 0; cell = parent_[static_cast<std::size_t>(cell)]) ++length;
  if (length > plan.cells.capacity()) return PlanResult::plan_full;
  for (std::size_t k = 0; k < length; ++k) {
    plan.cells.push_back(Eigen::Vector2i::Zero());
    plan.waypoints.push_back(Eigen::Vector2d::Zero());
    plan.narrow.push_back(false);
  }
  std::size_t k = length;
  for (std::int32_t cell = goal_cell; cell >= 0; cell = parent_[static_cast<std::size_t>(cell)]) {
    --k;
    plan.cells[k] = Eigen::Vector2i(cell % width_, cell / width_);
    plan.waypoints[k] = grid.center(cell % width_, cell / width_);
    plan.narrow[k] = narrow(map, cell % width_, cell / width_);
  }
  centre_in_gaps(map, plan, 1);
  plan.cost = static_cast<double>(cost_[static_cast<std::size_t>(goal_cell)]);
  return PlanResult::found;
}

// Within the safety margin of an obstacle, or nearer than narrow_clearance_m to one.
bool PathPlanner::narrow(const NavigationMap& map, int x, int y) const {
  return map.traversability(x, y) != Traversability::safe || map.occupied_distance_m(x, y) < narrow_clearance_m_;
}

void PathPlanner::refit(const NavigationMap& map, Plan& plan, std::size_t first) const {
  for (std::size_t k = first; k < plan.cells.size(); ++k) plan.narrow[k] = narrow(map, plan.cells[k].x(), plan.cells[k].y());
  centre_in_gaps(map, plan, std::max<std::size_t>(first, 1));
}

double PathPlanner::remaining_cost(const NavigationMap& map, const Plan& plan, std::size_t first) {
  double cost = 0.0;
  for (std::size_t k = first; k + 1 < plan.cells.size(); ++k) {
    const Eigen::Vector2i& from = plan.cells[k];
    const Eigen::Vector2i& to = plan.cells[k + 1];
    if (!map.passable(to.x(), to.y())) return std::numeric_limits<double>::infinity();
    cost += map.step_cost(from.x(), from.y(), to.x(), to.y());
  }
  return cost;
}

// The first and last waypoints stay at their cells' centres (the robot's cell, the goal's).
void PathPlanner::centre_in_gaps(const NavigationMap& map, Plan& plan, std::size_t first) const {
  if (gap_centring_reach_m_ <= 0.0) return;  // off: the cells' centres, as set
  const std::size_t count = plan.cells.size();
  for (std::size_t k = first; k + 1 < count; ++k) {
    const Eigen::Vector2i along = plan.cells[k + 1] - plan.cells[k - 1];
    plan.waypoints[k] = map.centred_in_gap(plan.cells[k], along.cast<double>(), gap_centring_reach_m_);
  }
}

}  // namespace stereoscout::explore
