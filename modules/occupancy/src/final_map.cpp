#include "stereoscout/occupancy/final_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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

// A scan point this far from its camera is a broken measurement; it must not blow up the map.
constexpr double kMaxPlausibleRangeM = 100.0;

}  // namespace

TrajectoryScanCounts insert_trajectory_scans(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                                             const ScanHistory& scans, OccupancyGrid& grid) {
  TrajectoryScanCounts counts;
  for (const slam::TrajectoryNodeHandle handle : lineage(tree, node)) {
    const slam::TrajectoryNode& entry = tree.get(handle);
    ++counts.nodes;
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

GridGeometry fit_trajectory_geometry(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                                     const ScanHistory& scans, double resolution_m, double margin_m) {
  Bounds bounds;
  for (const slam::TrajectoryNodeHandle handle : lineage(tree, node)) {
    const slam::TrajectoryNode& entry = tree.get(handle);
    bounds.add(entry.pose.x, entry.pose.y);
    ScanView scan;
    if (scans.find(entry.update_index, scan) != ScanLookup::found) continue;
    const double c = std::cos(entry.pose.theta);
    const double s = std::sin(entry.pose.theta);
    for (std::size_t i = 0; i < scan.count; ++i) {
      const double px = scan.points[i].x_robot_m;
      const double py = scan.points[i].y_robot_m;
      if (!(std::hypot(px, py) < kMaxPlausibleRangeM)) continue;
      bounds.add(entry.pose.x + c * px - s * py, entry.pose.y + s * px + c * py);
    }
  }
  if (!std::isfinite(bounds.min_x)) bounds.add(0.0, 0.0);
  GridGeometry geometry;
  geometry.resolution_m = resolution_m;
  geometry.origin_x_m = std::floor((bounds.min_x - margin_m) / resolution_m) * resolution_m;
  geometry.origin_y_m = std::floor((bounds.min_y - margin_m) / resolution_m) * resolution_m;
  geometry.width_cells = static_cast<int>(std::ceil((bounds.max_x + margin_m - geometry.origin_x_m) / resolution_m)) + 1;
  geometry.height_cells = static_cast<int>(std::ceil((bounds.max_y + margin_m - geometry.origin_y_m) / resolution_m)) + 1;
  return geometry;
}

std::unique_ptr<OccupancyGrid> build_final_map(const slam::TrajectoryTree& tree, slam::TrajectoryNodeHandle node,
                                               const ScanHistory& scans, double resolution_m, double margin_m,
                                               const LogOddsModel& model, TrajectoryScanCounts* counts) {
  const GridGeometry geometry = fit_trajectory_geometry(tree, node, scans, resolution_m, margin_m);
  auto grid = std::make_unique<OccupancyGrid>(geometry, model);
  const TrajectoryScanCounts inserted = insert_trajectory_scans(tree, node, scans, *grid);
  if (counts != nullptr) *counts = inserted;
  return grid;
}

}  // namespace stereoscout::occupancy
