#pragma once
// The grid of one particle's whole trajectory, built from scratch (paper V: the final map is
// rebuilt at the end of a run, at grid.final_map_resolution_m, from the ML trajectory's
// scans; those that left the ring come from the ScanArchive). Also the reference the
// just-in-time grid is tested against. Allocates: for the end of a run and for tests, not for
// the tick loop.

#include <cstdint>
#include <memory>

#include "stereoscout/occupancy/occupancy_grid.hpp"
#include "stereoscout/occupancy/scan_archive.hpp"
#include "stereoscout/occupancy/scan_history.hpp"
#include "stereoscout/slam/trajectory_tree.hpp"

namespace stereoscout::occupancy {

struct TrajectoryScanCounts {
  std::uint64_t nodes = 0;              // root to node
  std::uint64_t nodes_archived = 0;     // up to the archive's last update: their scans came from the archive
  std::uint64_t scans_inserted = 0;     // from the ring
  std::uint64_t scans_overwritten = 0;  // had left the ring and are not archived: the map lacks them
  bool archive_on_lineage = true;       // node descends from the archive's last node (ScanArchive::on_lineage)
};

// Inserts, oldest first, the stored scans of every node from the root down to `node`.
TrajectoryScanCounts insert_trajectory_scans(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                                             const ScanHistory& scans, OccupancyGrid& grid);

// The smallest grid at `resolution_m` that holds every pose of the trajectory and every
// stored scan point seen from it, plus `margin_m` on each side.
GridGeometry fit_trajectory_geometry(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                                     const ScanHistory& scans, double resolution_m, double margin_m);

// fit_trajectory_geometry + insert_trajectory_scans (config: grid.final_map_resolution_m,
// grid.final_map_margin_m).
std::unique_ptr<OccupancyGrid> build_final_map(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                                               const ScanHistory& scans, double resolution_m, double margin_m,
                                               const LogOddsModel& model, TrajectoryScanCounts* counts = nullptr);

// The same, for a run whose first scans have left the ring: the archive's tiles first, then
// the ring's scans of the nodes after the archive's last update. The grid's corner lies on
// the archive's lattice and it holds the archive's extent too.
std::unique_ptr<OccupancyGrid> build_final_map(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                                               const ScanHistory& scans, const ScanArchive* archive,
                                               double resolution_m, double margin_m, const LogOddsModel& model,
                                               TrajectoryScanCounts* counts = nullptr);

}  // namespace stereoscout::occupancy
