#include "stereoscout/occupancy/scan_archive.hpp"

#include <algorithm>
#include <cmath>

#include "stereoscout/core/check.hpp"

namespace stereoscout::occupancy {

ScanArchive::ScanArchive(const GridGeometry& extent, double resolution_m, double tile_m, std::size_t tile_capacity,
                         const LogOddsModel& model, slam::TrajectoryTree& tree)
    : extent_(extent), resolution_m_(resolution_m), tree_(tree) {
  STEREOSCOUT_CHECK(resolution_m > 0.0 && tile_m >= resolution_m, "scan archive needs a tile of at least one cell");
  const int tile_cells = static_cast<int>(std::lround(tile_m / resolution_m));
  tile_m_ = tile_cells * resolution_m;
  tile_columns_ = static_cast<int>(std::ceil(extent.width_cells * extent.resolution_m / tile_m_));
  tile_rows_ = static_cast<int>(std::ceil(extent.height_cells * extent.resolution_m / tile_m_));
  tile_index_.assign(static_cast<std::size_t>(tile_columns_) * static_cast<std::size_t>(tile_rows_), kNoTile);
  GridGeometry tile;
  tile.width_cells = tile_cells;
  tile.height_cells = tile_cells;
  tile.resolution_m = resolution_m;
  tiles_.reserve(tile_capacity);
  for (std::size_t i = 0; i < tile_capacity; ++i) tiles_.push_back(std::make_unique<OccupancyGrid>(tile, model));
}

ScanArchive::~ScanArchive() { release(); }

void ScanArchive::release() {
  if (last_node_) tree_.release(last_node_);
  last_node_ = {};
}

bool ScanArchive::on_lineage(slam::TrajectoryNodeHandle node) const {
  return empty() || tree_.ancestor_at(node, last_update_index_) == last_node_;
}

void ScanArchive::keep_leaving_scan(const ScanHistory& scans, std::uint32_t next_update_index,
                                    slam::TrajectoryNodeHandle ml_node) {
  if (tiles_.empty() || next_update_index < scans.capacity()) return;
  const auto leaving = static_cast<std::uint32_t>(next_update_index - scans.capacity());
  ScanView scan;
  if (scans.find(leaving, scan) != ScanLookup::found) return;
  const slam::TrajectoryNodeHandle node = tree_.ancestor_at(ml_node, leaving);
  if (!node) {
    ++stats_.scans_off_lineage;
    return;
  }
  remember(node);
  insert(scan, tree_.get(node).pose);
  ++stats_.scans_archived;
}

void ScanArchive::remember(slam::TrajectoryNodeHandle node) {
  if (last_node_ && tree_.ancestor_at(node, last_update_index_) != last_node_) ++stats_.lineage_switches;
  tree_.retain(node);
  release();
  last_node_ = node;
  last_update_index_ = tree_.get(node).update_index;
}

void ScanArchive::grow_bounds(double x, double y) {
  if (!has_bounds_) {
    bounds_ = {x, y, x, y};
    has_bounds_ = true;
    return;
  }
  bounds_.min_x = std::min(bounds_.min_x, x);
  bounds_.min_y = std::min(bounds_.min_y, y);
  bounds_.max_x = std::max(bounds_.max_x, x);
  bounds_.max_y = std::max(bounds_.max_y, y);
}

void ScanArchive::insert(const ScanView& scan, const core::Pose2& pose) {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  // The robot and its camera centre, where the rays start, then every end point.
  const double camera_x = pose.x + c * scan.origin_x_robot_m - s * scan.origin_y_robot_m;
  const double camera_y = pose.y + s * scan.origin_x_robot_m + c * scan.origin_y_robot_m;
  double min_x = std::min(pose.x, camera_x);
  double max_x = std::max(pose.x, camera_x);
  double min_y = std::min(pose.y, camera_y);
  double max_y = std::max(pose.y, camera_y);
  for_each_plausible_end(scan, pose, [&](double x, double y) {
    min_x = std::min(min_x, x);
    max_x = std::max(max_x, x);
    min_y = std::min(min_y, y);
    max_y = std::max(max_y, y);
  });
  grow_bounds(min_x, min_y);
  grow_bounds(max_x, max_y);
  const auto lattice = [this](double offset_m) { return static_cast<int>(std::floor(offset_m / tile_m_)); };
  const int first_column = lattice(min_x - extent_.origin_x_m);
  const int last_column = lattice(max_x - extent_.origin_x_m);
  const int first_row = lattice(min_y - extent_.origin_y_m);
  const int last_row = lattice(max_y - extent_.origin_y_m);
  if (first_column < 0 || first_row < 0 || last_column >= tile_columns_ || last_row >= tile_rows_) ++stats_.scans_outside;
  bool refused = false;
  for (int row = std::max(0, first_row); row <= std::min(last_row, tile_rows_ - 1); ++row) {
    for (int column = std::max(0, first_column); column <= std::min(last_column, tile_columns_ - 1); ++column) {
      OccupancyGrid* tile = tile_at(column, row);
      if (tile == nullptr) {
        refused = true;
        continue;
      }
      tile->insert(scan, pose);
    }
  }
  if (refused) ++stats_.tile_refusals;
}

OccupancyGrid* ScanArchive::tile_at(int column, int row) {
  std::uint32_t& slot = tile_index_[static_cast<std::size_t>(row) * static_cast<std::size_t>(tile_columns_) +
                                    static_cast<std::size_t>(column)];
  if (slot == kNoTile) {
    if (stats_.tiles_used == tiles_.size()) return nullptr;
    slot = static_cast<std::uint32_t>(stats_.tiles_used++);
    tiles_[slot]->clear_at(extent_.origin_x_m + column * tile_m_, extent_.origin_y_m + row * tile_m_);
  }
  return tiles_[slot].get();
}

bool ScanArchive::bounds(ArchiveBounds& out) const {
  if (!has_bounds_) return false;
  out = bounds_;
  return true;
}

void ScanArchive::paste_into(OccupancyGrid& grid) const {
  for (std::size_t i = 0; i < stats_.tiles_used; ++i) grid.paste(*tiles_[i]);
}

}  // namespace stereoscout::occupancy
