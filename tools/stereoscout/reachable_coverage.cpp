#include "reachable_coverage.hpp"

#include "stereoscout/host_sim/ground_truth.hpp"

namespace stereoscout::cli {

ReachableCoverage::ReachableCoverage(const core::SystemConfig& config, const host_sim::World& world) {
  const host_sim::GroundTruthGrid truth = host_sim::rasterize_world(
      world, config.grid.resolution_m, config.sim.floor_tolerance_m, config.robot.height_m);
  const host_sim::GroundTruthGrid reachable =
      host_sim::reachable_free_space(truth, world.start.translation(), config.robot.radius_m);
  for (int y = 0; y < reachable.height; ++y) {
    for (int x = 0; x < reachable.width; ++x) {
      if (reachable.at(x, y) == host_sim::GroundTruthGrid::free) centres_.push_back(reachable.cell_center(x, y));
    }
  }
}

std::size_t ReachableCoverage::covered_cells(const explore::GridView& grid) const {
  std::size_t free = 0;
  for (const Eigen::Vector2d& centre : centres_) {
    const Eigen::Vector2i cell = grid.cell_of(centre);
    if (grid.contains(cell.x(), cell.y()) && grid.at(cell.x(), cell.y()) == explore::CellState::free) ++free;
  }
  return free;
}

double ReachableCoverage::coverage(const explore::GridView& grid) const {
  return centres_.empty() ? 0.0 : static_cast<double>(covered_cells(grid)) / static_cast<double>(centres_.size());
}

}  // namespace stereoscout::cli
