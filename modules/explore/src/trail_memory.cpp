#include "stereoscout/explore/trail_memory.hpp"

#include <cmath>

namespace stereoscout::explore {
namespace {

std::size_t trail_capacity(double length_m) {
  if (length_m <= 0.0) return 1;
  return static_cast<std::size_t>(std::ceil(length_m / TrailMemory::kTrailSpacing_m)) + 1;
}

}  // namespace

TrailMemory::TrailMemory(const core::ExploreConfig& config)
    : enabled_(config.trail_length_m > 0.0), points_(trail_capacity(config.trail_length_m)) {}

void TrailMemory::record(const Eigen::Vector2d& position) {
  if (!enabled_) return;
  TrailPoint point;
  point.position = position;
  if (points_.size() > 0) {
    const double step = (position - points_[points_.size() - 1].position).norm();
    if (step < kTrailSpacing_m) return;
    point.joined = step <= kTrailJump_m;
  }
  points_.push_overwrite(point);
}

}  // namespace stereoscout::explore
