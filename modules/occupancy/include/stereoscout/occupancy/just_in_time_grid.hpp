#pragma once
// The just-in-time maximum-likelihood occupancy grid (paper V).
//
// Only the grid of the current maximum-likelihood (ML) particle is kept up to date. Grids
// hang off nodes of the particles' ancestry tree (slam::TrajectoryTree, user_slot = cache
// slot; the cache retains every node it tags). After each filter update:
//
//   1. The new ML node walks up to its nearest ancestor holding a grid. If that grid has no
//      other dependent it is MOVED down to the ML node, otherwise COPIED into a free slot;
//      then the stored scans of the nodes below the ancestor are rolled up, oldest first,
//      each at its node's pose. No grid within scan_history steps (or the root reached):
//      start from an empty grid.
//   2. Lifetime: every live particle's node walks up (at most scan_history steps) to its
//      nearest grid; that grid gains a dependent. Grids with no dependent are freed, except
//      the ML grid: no descendant can need them any more.
//   3. Cache full when a copy needs a slot: the grid with the fewest dependents, then the
//      oldest node, then the lowest slot, is evicted (counted). Its dependents later roll up
//      from a grid further up, which stays exact while the scans are still in the ring.
//
// Scan ring too short: a roll-up that needs a scan that has left the ring skips it and is
// counted in rollup_incomplete (and scans_overwritten); so is a roll-up that finds neither a
// grid nor the root within scan_history steps (it starts from an empty grid). Never a crash.
//
// Everything is allocated in the constructor; record_scan() and update() do not touch the
// heap. Destroy this object before the TrajectoryTree it tags (it releases its nodes).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "stereoscout/core/config/grid.hpp"
#include "stereoscout/occupancy/occupancy_grid.hpp"
#include "stereoscout/occupancy/scan_history.hpp"
#include "stereoscout/slam/trajectory_tree.hpp"

namespace stereoscout::occupancy {

struct JustInTimeGridStats {
  std::uint64_t updates = 0;
  std::uint64_t rollups = 0;             // ML grid brought down to a new ML node
  std::uint64_t rollup_scans = 0;        // nodes rolled over, summed over roll-ups
  std::uint64_t rollup_length_max = 0;
  std::uint64_t copies = 0;              // source grid still needed by another particle
  std::uint64_t moves = 0;               // source grid needed by nobody else: no copy
  std::uint64_t built_from_empty = 0;    // no grid-holding ancestor (start of a run, or bound)
  std::uint64_t evictions = 0;           // cache full: a grid with dependents was dropped
  std::uint64_t grids_freed = 0;
  std::uint64_t rollup_incomplete = 0;   // roll-ups missing a scan or hitting the walk bound
  std::uint64_t scans_overwritten = 0;   // scans a roll-up needed that had left the ring
  std::uint64_t grids_held_sum = 0;      // grids held after each update, summed
  std::uint64_t grids_held_max = 0;
  std::uint64_t dependents_walk_steps = 0;      // parent links followed, summed
  std::uint64_t dependents_walk_steps_max = 0;  // in one update
  std::uint64_t dependents_unresolved = 0;      // live nodes with no grid within the bound
  std::uint64_t updates_skipped_no_ml_node = 0;  // update() with a null or dead ML node

  double mean_grids_held() const {
    return updates == 0 ? 0.0 : static_cast<double>(grids_held_sum) / static_cast<double>(updates);
  }
  double mean_rollup_length() const {
    return rollups == 0 ? 0.0 : static_cast<double>(rollup_scans) / static_cast<double>(rollups);
  }
};

class JustInTimeGrid {
 public:
  // geometry: the navigation grid (GridGeometry::centred_on the start pose); max_scan_columns:
  // columns per scan (camera.width_px). Cache and ring sizes come from config.
  JustInTimeGrid(const core::GridConfig& config, const GridGeometry& geometry, std::size_t max_scan_columns,
                 slam::TrajectoryTree& tree);
  ~JustInTimeGrid();

  JustInTimeGrid(const JustInTimeGrid&) = delete;
  JustInTimeGrid& operator=(const JustInTimeGrid&) = delete;

  // The scan of filter update `update_index` (the update_index of that update's nodes), before
  // update() for that update. Indices must increase; a repeated or older one is refused and
  // counted (scans().counts().out_of_order).
  void record_scan(std::uint32_t update_index, const core::DepthScan& scan) { scans_.record(update_index, scan); }

  // Brings the grid of `ml_node` up to date and frees grids nobody can need. `live_nodes`
  // holds the current node of every particle (it must include ml_node; null handles skipped).
  void update(slam::TrajectoryNodeHandle ml_node, const slam::TrajectoryNodeHandle* live_nodes,
              std::size_t live_count);

  // The ML grid after the last update; null before the first.
  const OccupancyGrid* ml_grid() const;
  // Frees every grid and releases every node the cache retains.
  void release_all();

  std::size_t grids_held() const { return capacity_ - free_count_; }
  std::size_t cache_capacity() const { return capacity_; }
  const JustInTimeGridStats& stats() const { return stats_; }
  const ScanHistory& scans() const { return scans_; }
  const GridGeometry& geometry() const { return geometry_; }

 private:
  static constexpr std::uint32_t kNoSlot = slam::kNoUserSlot;

  void count_dependents(const slam::TrajectoryNodeHandle* live_nodes, std::size_t live_count);
  void free_unneeded();
  void bring_forward(slam::TrajectoryNodeHandle ml_node);
  // Nodes from ml_node up to (not including) its nearest grid holder, newest first.
  std::uint32_t collect_rollup_path(slam::TrajectoryNodeHandle ml_node, bool& complete);
  std::uint32_t acquire_slot(std::uint32_t keep_slot);
  void roll_up(std::uint32_t slot, bool& complete);
  void attach(std::uint32_t slot, slam::TrajectoryNodeHandle node);
  void free_slot(std::uint32_t slot);
  void record_holding_stats();

  GridGeometry geometry_;
  slam::TrajectoryTree& tree_;
  std::size_t capacity_;
  std::size_t walk_limit_;
  ScanHistory scans_;
  std::vector<std::unique_ptr<OccupancyGrid>> grids_;  // built once, never resized
  std::unique_ptr<slam::TrajectoryNodeHandle[]> slot_node_;
  std::unique_ptr<std::uint32_t[]> slot_dependents_;
  std::unique_ptr<std::uint32_t[]> free_slots_;
  std::size_t free_count_ = 0;
  std::unique_ptr<slam::TrajectoryNodeHandle[]> path_;
  std::size_t path_count_ = 0;
  std::uint32_t ml_slot_ = kNoSlot;
  JustInTimeGridStats stats_;
};

}  // namespace stereoscout::occupancy
