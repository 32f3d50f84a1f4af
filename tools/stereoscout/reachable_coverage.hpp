#pragma once
// Coverage of a simulated world while it is explored: the share of the ground truth's
// reachable free space (host_sim::reachable_free_space at grid.resolution_m, the robot's
// radius) whose cell centres the explorer's grid holds as free. Used by `explore-gt` and by
// `explore`'s progress line and coverage curve.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "stereoscout/core/system_config.hpp"
#include "stereoscout/explore/grid_view.hpp"
#include "stereoscout/host_sim/world.hpp"

namespace stereoscout::cli {

class ReachableCoverage {
 public:
  ReachableCoverage(const core::SystemConfig& config, const host_sim::World& world);
  std::size_t reachable_cells() const { return centres_.size(); }
  std::size_t covered_cells(const explore::GridView& grid) const;
  // covered / reachable (0 when nothing is reachable).
  double coverage(const explore::GridView& grid) const;

 private:
  std::vector<Eigen::Vector2d> centres_;  // of the reachable free cells
};

}  // namespace stereoscout::cli
