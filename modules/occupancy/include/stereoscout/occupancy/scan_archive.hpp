#pragma once
// Where the final map keeps the scans that leave the ring (paper V: the final map is the ML
// trajectory's scans, all of them, at grid.final_map_resolution_m).
//
// The ring (ScanHistory) holds the last grid.scan_history updates' scans, enough for every
// roll-up; a longer run overwrites its first scans. Before a scan is overwritten it is inserted
// here, at the pose of the maximum-likelihood lineage's node for its update, into square tiles
// at the final map's resolution. Tiles come from a pool allocated at start-up
// (grid.final_map_archive_tiles of grid.final_map_tile_m) and lie on a lattice over the
// navigation grid's extent; a scan goes into every tile its bounding box touches.
//
// Exact while the particles' lineages have merged within the ring's length (with hundreds of
// particles they merge within tens of updates): the ML lineage at the time a scan leaves is
// then the final one, and the final map (archive first, then the ring's scans, in update
// order) is the whole trajectory's grid. The archive keeps a reference to the last node it
// archived and counts every archived node that does not descend from the one before
// (lineage_switches); on_lineage() tells whether the final ML node descends from the archive.
//
// keep_leaving_scan() does not touch the heap. Destroy (or release()) before the tree.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "stereoscout/occupancy/occupancy_grid.hpp"
#include "stereoscout/occupancy/scan_history.hpp"
#include "stereoscout/slam/trajectory_tree.hpp"

namespace stereoscout::occupancy {

struct ScanArchiveStats {
  std::uint64_t scans_archived = 0;
  std::uint64_t lineage_switches = 0;   // archived node not a descendant of the previous one
  std::uint64_t scans_off_lineage = 0;  // the ML lineage has no node for the leaving scan's update
  std::uint64_t tile_refusals = 0;      // a scan needed a tile while the pool was empty: that part is lost
  std::uint64_t scans_outside = 0;      // a scan reaching beyond the navigation extent: that part is lost
  std::size_t tiles_used = 0;
};

// A map-frame rectangle: the extent of what has been archived.
struct ArchiveBounds {
  double min_x = 0.0;
  double min_y = 0.0;
  double max_x = 0.0;
  double max_y = 0.0;
};

class ScanArchive {
 public:
  // extent: the navigation grid (its origin anchors the tile lattice, its size bounds it);
  // resolution_m: the final map's cell size; tile_m: a tile's side; tile_capacity: tiles
  // allocated now (0: nothing is archived).
  ScanArchive(const GridGeometry& extent, double resolution_m, double tile_m, std::size_t tile_capacity,
              const LogOddsModel& model, slam::TrajectoryTree& tree);
  ~ScanArchive();

  ScanArchive(const ScanArchive&) = delete;
  ScanArchive& operator=(const ScanArchive&) = delete;

  // Call before scans.record(next_update_index): archives the scan that record will overwrite,
  // at the pose of ml_node's ancestor for that scan's update.
  void keep_leaving_scan(const ScanHistory& scans, std::uint32_t next_update_index, slam::TrajectoryNodeHandle ml_node);
  // Drops the node reference (before the tree goes).
  void release();

  bool empty() const { return !last_node_; }
  // The update index of the newest archived scan (meaningful when not empty).
  std::uint32_t last_update_index() const { return last_update_index_; }
  // True when the archive is empty or `node` descends from the last archived node.
  bool on_lineage(slam::TrajectoryNodeHandle node) const;
  // The extent of the archived scans and poses; false when empty.
  bool bounds(ArchiveBounds& out) const;
  // The map-frame corner the tiles' cells are aligned to.
  double lattice_origin_x() const { return extent_.origin_x_m; }
  double lattice_origin_y() const { return extent_.origin_y_m; }
  double resolution_m() const { return resolution_m_; }
  // Copies every used tile into `grid` (final-map resolution, origin on the lattice).
  void paste_into(OccupancyGrid& grid) const;

  std::size_t tile_capacity() const { return tiles_.size(); }
  const ScanArchiveStats& stats() const { return stats_; }

 private:
  static constexpr std::uint32_t kNoTile = 0xFFFFFFFFU;

  void remember(slam::TrajectoryNodeHandle node);
  void insert(const ScanView& scan, const core::Pose2& pose);
  // The tile at lattice (column, row), taken from the pool if new; null when the pool is empty.
  OccupancyGrid* tile_at(int column, int row);
  void grow_bounds(double x, double y);

  GridGeometry extent_;
  double resolution_m_;
  double tile_m_;
  int tile_columns_;
  int tile_rows_;
  slam::TrajectoryTree& tree_;
  std::vector<std::unique_ptr<OccupancyGrid>> tiles_;  // built once, never resized
  std::vector<std::uint32_t> tile_index_;              // lattice cell -> tile, kNoTile if none
  slam::TrajectoryNodeHandle last_node_{};
  std::uint32_t last_update_index_ = 0;
  bool has_bounds_ = false;
  ArchiveBounds bounds_;
  ScanArchiveStats stats_;
};

}  // namespace stereoscout::occupancy
