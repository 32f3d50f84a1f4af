#include "stereoscout/explore/contact_memory.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace stereoscout::explore {
namespace {

bool any_within(const core::FixedVector<Eigen::Vector2d>& points, const Eigen::Vector2d& point, double radius_m) {
  for (const Eigen::Vector2d& other : points) {
    if ((other - point).norm() <= radius_m) return true;
  }
  return false;
}

}  // namespace

StallDetector::StallDetector(const core::ExploreConfig& config)
    : window_s_(config.stall_window_s),
      min_commanded_m_(config.stall_min_commanded_m),
      progress_fraction_(config.stall_progress_fraction) {}

void StallDetector::reset() {
  window_open_ = false;
  commanded_m_ = 0.0;
  last_linear_mps_ = 0.0;
}

bool StallDetector::stalled(double time_s, const Eigen::Vector2d& position) {
  if (!(last_linear_mps_ > 0.0)) {
    // No forward command since the last tick: the next forward command opens a new window.
    window_open_ = false;
    last_time_s_ = time_s;
    return false;
  }
  if (!window_open_) {
    window_open_ = true;
    window_start_s_ = last_time_s_;
    window_start_position_ = last_position_;
    commanded_m_ = 0.0;
  }
  commanded_m_ += last_linear_mps_ * std::max(0.0, time_s - last_time_s_);
  last_time_s_ = time_s;
  // A slow command (the follower's short lookahead in a doorway) stretches the window until it
  // has commanded enough to judge: pushing on a jamb at 0.035 m/s is a stall too.
  if (time_s - window_start_s_ < window_s_ || commanded_m_ < min_commanded_m_) return false;
  const double travelled = (position - window_start_position_).norm();
  const bool stall = travelled < progress_fraction_ * commanded_m_;
  window_open_ = false;
  return stall;
}

void StallDetector::commanded(double time_s, const Eigen::Vector2d& position, double linear_mps) {
  last_time_s_ = time_s;
  last_position_ = position;
  last_linear_mps_ = linear_mps;
}

ContactMemory::ContactMemory(const core::ExploreConfig& config, int max_width, int max_height)
    : arc_rad_(core::degrees_to_radians(config.contact_arc_deg)),
      hold_s_(config.contact_hold_s),
      repeat_radius_m_(config.contact_repeat_radius_m),
      trail_radius_m_(config.trail_contact_radius_m),
      explained_margin_m_(config.contact_explained_margin_m),
      toward_mapped_m_(config.contact_toward_mapped_m),
      contacts_(static_cast<std::size_t>(config.contact_memory)),
      cleared_points_(static_cast<std::size_t>(config.contact_memory)),
      mapped_stalls_at_(static_cast<std::size_t>(config.contact_memory)),
      cells_(new std::uint8_t[static_cast<std::size_t>(max_width) * static_cast<std::size_t>(max_height)]),
      cell_capacity_(static_cast<std::size_t>(max_width) * static_cast<std::size_t>(max_height)) {}

void ContactMemory::record(const GridView& grid, const core::Pose2& pose, double radius_m, double time_s,
                           const TrailMemory& trail) {
  // Just beyond the rim: the surface the robot pushes against lies in that cell.
  const double reach = radius_m + 0.5 * grid.resolution_m;
  const bool first_here = !mapped_stall_here_before(pose.translation());  // the mapped surface is trusted once a place
  Eigen::Vector2d to_surface;
  const bool explained = first_here && explained_margin_m_ > 0.0 &&
                         nearest_mapped_in_front(grid, pose, radius_m + explained_margin_m_, to_surface);
  // Straight ahead unless a mapped surface near the front half of the rim says where.
  const bool toward_mapped = !explained && first_here && toward_mapped_m_ > 0.0 &&
                             nearest_mapped_in_front(grid, pose, radius_m + toward_mapped_m_, to_surface);
  const double facing = toward_mapped ? std::atan2(to_surface.y(), to_surface.x()) : pose.theta;
  if (toward_mapped) ++toward_mapped_;
  if (explained || toward_mapped) mapped_stalls_at_.emplace_back(pose.translation());  // none when full
  for (const double offset : {0.0, -arc_rad_, arc_rad_}) {
    const double angle = facing + offset;
    const Eigen::Vector2d point = pose.translation() + reach * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    if (on_trail(point, trail)) {
      ++on_trail_;
      continue;
    }
    const Eigen::Vector2i cell = grid.cell_of(point);
    const bool free = grid.contains(cell.x(), cell.y()) && grid.at(cell.x(), cell.y()) == CellState::free;
    if (free && explained) {
      ++explained_;
      continue;
    }
    const bool repeated = near_a_cleared_contact(point);
    ++recorded_;
    if (repeated) ++repeated_;
    if (contacts_.emplace_back(Contact{point, time_s, free, repeated}) == nullptr) ++forgotten_full_;
  }
}

bool ContactMemory::on_trail(const Eigen::Vector2d& point, const TrailMemory& trail) const {
  if (trail_radius_m_ <= 0.0) return false;
  const double radius2 = trail_radius_m_ * trail_radius_m_;
  for (std::size_t i = 0; i < trail.size(); ++i) {
    if ((trail[i].position - point).squaredNorm() <= radius2) return true;
  }
  return false;
}

// The occupied cell nearest the robot's centre within reach_m, in front of its middle (behind
// it a surface cannot stop a forward push): true when there is one, its offset from the centre
// in `offset`.
bool ContactMemory::nearest_mapped_in_front(const GridView& grid, const core::Pose2& pose, double reach_m,
                                            Eigen::Vector2d& offset) const {
  const Eigen::Vector2d centre = pose.translation();
  const Eigen::Vector2d heading(std::cos(pose.theta), std::sin(pose.theta));
  const Eigen::Vector2i low = grid.cell_of(centre - Eigen::Vector2d::Constant(reach_m));
  const Eigen::Vector2i high = grid.cell_of(centre + Eigen::Vector2d::Constant(reach_m));
  bool found = false;
  double nearest_m = reach_m;
  for (int y = std::max(low.y(), 0); y <= std::min(high.y(), grid.height - 1); ++y) {
    for (int x = std::max(low.x(), 0); x <= std::min(high.x(), grid.width - 1); ++x) {
      if (grid.at(x, y) != CellState::occupied) continue;
      const Eigen::Vector2d to_cell = grid.center(x, y) - centre;
      const double distance_m = to_cell.norm();
      if (distance_m > nearest_m || to_cell.dot(heading) <= 0.0) continue;
      found = true;
      nearest_m = distance_m;
      offset = to_cell;
    }
  }
  return found;
}

bool ContactMemory::mapped_stall_here_before(const Eigen::Vector2d& position) const {
  return any_within(mapped_stalls_at_, position, repeat_radius_m_);
}

bool ContactMemory::near_a_cleared_contact(const Eigen::Vector2d& point) const {
  return repeat_radius_m_ > 0.0 && any_within(cleared_points_, point, repeat_radius_m_);
}

bool ContactMemory::keep(const Contact& contact, const GridView& grid, double time_s) {
  if (time_s - contact.time_s > hold_s_) {
    ++expired_;
    return false;
  }
  const Eigen::Vector2i cell = grid.cell_of(contact.point);
  if (!contact.free_at_contact && grid.contains(cell.x(), cell.y()) && grid.at(cell.x(), cell.y()) == CellState::free) {
    ++freed_;
    return false;
  }
  return true;
}

std::size_t ContactMemory::clear() {
  std::size_t forgotten = 0;
  for (std::size_t i = 0; i < contacts_.size();) {
    if (contacts_[i].repeated) {
      ++i;
      continue;
    }
    cleared_points_.emplace_back(contacts_[i].point);  // none when full: the oldest stay
    contacts_[i] = contacts_[contacts_.size() - 1];
    contacts_.pop_back();
    ++forgotten;
  }
  cleared_ += forgotten;
  return forgotten;
}

GridView ContactMemory::stamp(const GridView& grid, double time_s) {
  // Forget first (swap with the last; the order of contacts does not matter).
  for (std::size_t i = 0; i < contacts_.size();) {
    if (keep(contacts_[i], grid, time_s)) {
      ++i;
      continue;
    }
    contacts_[i] = contacts_[contacts_.size() - 1];
    contacts_.pop_back();
  }
  if (contacts_.size() == 0) return grid;
  const std::size_t count = static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height);
  if (count > cell_capacity_) {
    ++grid_too_large_;
    return grid;
  }
  std::memcpy(cells_.get(), grid.cells, count);
  for (const Contact& contact : contacts_) {
    const Eigen::Vector2i cell = grid.cell_of(contact.point);
    if (grid.contains(cell.x(), cell.y())) cells_[grid.index(cell.x(), cell.y())] = static_cast<std::uint8_t>(CellState::occupied);
  }
  GridView stamped = grid;
  stamped.cells = cells_.get();
  return stamped;
}

}  // namespace stereoscout::explore
