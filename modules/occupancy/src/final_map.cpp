#include "stereoscout/occupancy/final_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "stereoscout/core/check.hpp"

namespace stereoscout::occupancy {
namespace {

// Root first.
std::vector<slam::TrajectoryNodeHandle> lineage(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node) {
  std::vector<slam::TrajectoryNodeHandle> nodes;
  for (; node; node = tree.parent(node)) nodes.push_back(node);
  std::reverse(nodes.begin(), nodes.end());
  return nodes;
}

struct Bounds {
  double min_x = std::numeric_limits<double>::infinity();
  double min_y = std::numeric_limits<double>::infinity();
  double max_x = -std::numeric_limits<double>::infinity();
  double max_y = -std::numeric_limits<double>::infinity();
  void add(double x, double y) {
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    min_x = std::min(min_x, x);
    min_y = std::min(min_y, y);
    max_x = std::max(max_x, x);
    max_y = std::max(max_y, y);
  }
};

// Every pose of the trajectory and every stored scan point seen from it.
Bounds trajectory_bounds(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node, const ScanHistory& scans) {
  Bounds bounds;
  for (const slam::TrajectoryNodeHandle handle : lineage(tree, node)) {
    const slam::TrajectoryNode& entry = tree.get(handle);
    bounds.add(entry.pose.x, entry.pose.y);
    ScanView scan;
    if (scans.find(entry.update_index, scan) != ScanLookup::found) continue;
    for_each_plausible_end(scan, entry.pose, [&bounds](double x, double y) { bounds.add(x, y); });
  }
  if (!std::isfinite(bounds.min_x)) bounds.add(0.0, 0.0);
  return bounds;
}

// The bounds plus the margin, with the lower-left corner on the lattice through (anchor_x, anchor_y).
GridGeometry fit_geometry(const Bounds& bounds, double anchor_x, double anchor_y, double resolution_m, double margin_m) {
  GridGeometry geometry;
  geometry.resolution_m = resolution_m;
  geometry.origin_x_m = anchor_x + std::floor((bounds.min_x - margin_m - anchor_x) / resolution_m) * resolution_m;
  geometry.origin_y_m = anchor_y + std::floor((bounds.min_y - margin_m - anchor_y) / resolution_m) * resolution_m;
  geometry.width_cells = static_cast<int>(std::ceil((bounds.max_x + margin_m - geometry.origin_x_m) / resolution_m)) + 1;
  geometry.height_cells = static_cast<int>(std::ceil((bounds.max_y + margin_m - geometry.origin_y_m) / resolution_m)) + 1;
  return geometry;
}

// Inserts, oldest first, the ring's scans of the lineage's nodes newer than the archive's last.
TrajectoryScanCounts insert_scans_after(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                                        const ScanHistory& scans, const ScanArchive* archive, OccupancyGrid& grid) {
  TrajectoryScanCounts counts;
  counts.archive_on_lineage = archive == nullptr || archive->on_lineage(node);
  for (const slam::TrajectoryNodeHandle handle : lineage(tree, node)) {
    const slam::TrajectoryNode& entry = tree.get(handle);
    ++counts.nodes;
    if (archive != nullptr && entry.update_index <= archive->last_update_index()) {
      ++counts.nodes_archived;
      continue;
    }
    ScanView scan;
    const ScanLookup lookup = scans.find(entry.update_index, scan);
    if (lookup == ScanLookup::found) {
      grid.insert(scan, entry.pose);
      ++counts.scans_inserted;
    } else if (lookup == ScanLookup::overwritten) {
      ++counts.scans_overwritten;
    }
  }
  return counts;
}

}  // namespace

TrajectoryScanCounts insert_trajectory_scans(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                                             const ScanHistory& scans, OccupancyGrid& grid) {
  return insert_scans_after(tree, node, scans, nullptr, grid);
}

GridGeometry fit_trajectory_geometry(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                                     const ScanHistory& scans, double resolution_m, double margin_m) {
  return fit_geometry(trajectory_bounds(tree, node, scans), 0.0, 0.0, resolution_m, margin_m);
}

std::unique_ptr<OccupancyGrid> build_final_map(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                                               const ScanHistory& scans, double resolution_m, double margin_m,
                                               const LogOddsModel& model, TrajectoryScanCounts* counts) {
  return build_final_map(tree, node, scans, nullptr, resolution_m, margin_m, model, counts);
}

std::unique_ptr<OccupancyGrid> build_final_map(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                                               const ScanHistory& scans, const ScanArchive* archive,
                                               double resolution_m, double margin_m, const LogOddsModel& model,
                                               TrajectoryScanCounts* counts) {
  if (archive != nullptr && archive->empty()) archive = nullptr;
  STEREOSCOUT_CHECK(archive == nullptr || archive->resolution_m() == resolution_m,
                    "the scan archive must be kept at the final map's resolution");
  Bounds bounds = trajectory_bounds(tree, node, scans);
  ArchiveBounds archived;
  if (archive != nullptr && archive->bounds(archived)) {
    bounds.add(archived.min_x, archived.min_y);
    bounds.add(archived.max_x, archived.max_y);
  }
  // On the archive's lattice, so that its tiles paste cell for cell.
  const GridGeometry geometry =
      archive != nullptr
          ? fit_geometry(bounds, archive->lattice_origin_x(), archive->lattice_origin_y(), resolution_m, margin_m)
          : fit_geometry(bounds, 0.0, 0.0, resolution_m, margin_m);
  auto grid = std::make_unique<OccupancyGrid>(geometry, model);
  if (archive != nullptr) archive->paste_into(*grid);
  const TrajectoryScanCounts inserted = insert_scans_after(tree, node, scans, archive, *grid);
  if (counts != nullptr) *counts = inserted;
  return grid;
}

}  // namespace stereoscout::occupancy
