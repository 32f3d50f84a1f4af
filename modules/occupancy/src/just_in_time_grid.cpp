#include "stereoscout/occupancy/just_in_time_grid.hpp"

#include <algorithm>

#include "stereoscout/core/check.hpp"

namespace stereoscout::occupancy {

JustInTimeGrid::JustInTimeGrid(const core::GridConfig& config, const GridGeometry& geometry,
                               std::size_t max_scan_columns, slam::TrajectoryTree& tree)
    : geometry_(geometry),
      tree_(tree),
      capacity_(static_cast<std::size_t>(config.cache_capacity)),
      walk_limit_(static_cast<std::size_t>(config.scan_history)),
      scans_(static_cast<std::size_t>(config.scan_history), max_scan_columns),
      slot_node_(new slam::TrajectoryNodeHandle[capacity_]),
      slot_dependents_(new std::uint32_t[capacity_]()),
      free_slots_(new std::uint32_t[capacity_]),
      path_(new slam::TrajectoryNodeHandle[walk_limit_]) {
  STEREOSCOUT_CHECK(capacity_ >= 2, "the grid cache needs room for a source and a copy");
  const LogOddsModel model = LogOddsModel::from_config(config);
  grids_.reserve(capacity_);
  for (std::size_t i = 0; i < capacity_; ++i) {
    grids_.push_back(std::make_unique<OccupancyGrid>(geometry, model));
    free_slots_[i] = static_cast<std::uint32_t>(capacity_ - 1 - i);  // slot 0 handed out first
  }
  free_count_ = capacity_;
}

JustInTimeGrid::~JustInTimeGrid() { release_all(); }

const OccupancyGrid* JustInTimeGrid::ml_grid() const {
  return ml_slot_ == kNoSlot ? nullptr : grids_[ml_slot_].get();
}

void JustInTimeGrid::update(slam::TrajectoryNodeHandle ml_node, const slam::TrajectoryNodeHandle* live_nodes,
                            std::size_t live_count) {
  if (!ml_node || !tree_.is_live(ml_node)) {
    ++stats_.updates_skipped_no_ml_node;  // e.g. before the filter started: nothing to bring forward
    return;
  }
  ++stats_.updates;
  count_dependents(live_nodes, live_count);
  const std::uint32_t existing = tree_.get(ml_node).user_slot;
  if (existing != kNoSlot) {
    ml_slot_ = existing;
  } else {
    bring_forward(ml_node);
    count_dependents(live_nodes, live_count);  // the ML lineage now ends at its own grid
  }
  free_unneeded();
  record_holding_stats();
}

void JustInTimeGrid::count_dependents(const slam::TrajectoryNodeHandle* live_nodes, std::size_t live_count) {
  std::fill(slot_dependents_.get(), slot_dependents_.get() + capacity_, 0U);
  std::uint64_t steps = 0;
  for (std::size_t i = 0; i < live_count; ++i) {
    slam::TrajectoryNodeHandle node = live_nodes[i];
    std::size_t visited = 0;
    while (node && visited < walk_limit_) {
      const std::uint32_t slot = tree_.get(node).user_slot;
      if (slot != kNoSlot) {
        ++slot_dependents_[slot];
        break;
      }
      node = tree_.parent(node);
      ++visited;
    }
    if (!node || visited == walk_limit_) ++stats_.dependents_unresolved;
    steps += visited;
  }
  stats_.dependents_walk_steps += steps;
  stats_.dependents_walk_steps_max = std::max(stats_.dependents_walk_steps_max, steps);
}

void JustInTimeGrid::free_unneeded() {
  for (std::uint32_t slot = 0; slot < capacity_; ++slot) {
    if (slot_node_[slot] && slot_dependents_[slot] == 0 && slot != ml_slot_) free_slot(slot);
  }
}

void JustInTimeGrid::bring_forward(slam::TrajectoryNodeHandle ml_node) {
  bool complete = true;
  const std::uint32_t source = collect_rollup_path(ml_node, complete);
  std::uint32_t target = kNoSlot;
  if (source != kNoSlot && slot_dependents_[source] <= 1) {
    // Only the ML lineage needs the ancestor's grid: hand it down instead of copying.
    const slam::TrajectoryNodeHandle holder = slot_node_[source];
    tree_.set_user_slot(holder, kNoSlot);
    slot_node_[source] = {};
    tree_.release(holder);  // still alive: ml_node descends from it
    target = source;
    ++stats_.moves;
  } else {
    target = acquire_slot(source);
    if (source != kNoSlot) {
      grids_[target]->copy_from(*grids_[source]);
      ++stats_.copies;
    } else {
      grids_[target]->clear();
      ++stats_.built_from_empty;
    }
  }
  roll_up(target, complete);
  attach(target, ml_node);
  slot_dependents_[target] = 1;
  ml_slot_ = target;
  ++stats_.rollups;
  stats_.rollup_scans += path_count_;
  stats_.rollup_length_max = std::max<std::uint64_t>(stats_.rollup_length_max, path_count_);
  if (!complete) ++stats_.rollup_incomplete;
}

std::uint32_t JustInTimeGrid::collect_rollup_path(slam::TrajectoryNodeHandle ml_node, bool& complete) {
  path_count_ = 0;
  slam::TrajectoryNodeHandle node = ml_node;
  while (node) {
    const std::uint32_t slot = tree_.get(node).user_slot;
    if (slot != kNoSlot) return slot;
    if (path_count_ == walk_limit_) {
      complete = false;  // the scans further up have left the ring anyway
      return kNoSlot;
    }
    path_[path_count_++] = node;
    node = tree_.parent(node);
  }
  return kNoSlot;  // root reached: the whole trajectory is on the path
}

std::uint32_t JustInTimeGrid::acquire_slot(std::uint32_t keep_slot) {
  if (free_count_ == 0) {
    std::uint32_t victim = kNoSlot;
    for (std::uint32_t slot = 0; slot < capacity_; ++slot) {
      if (slot == keep_slot || !slot_node_[slot]) continue;
      if (victim == kNoSlot || slot_dependents_[slot] < slot_dependents_[victim] ||
          (slot_dependents_[slot] == slot_dependents_[victim] &&
           tree_.get(slot_node_[slot]).update_index < tree_.get(slot_node_[victim]).update_index)) {
        victim = slot;
      }
    }
    STEREOSCOUT_CHECK(victim != kNoSlot, "grid cache has no slot to evict");
    if (slot_dependents_[victim] > 0) ++stats_.evictions;
    free_slot(victim);
  }
  return free_slots_[--free_count_];
}

void JustInTimeGrid::roll_up(std::uint32_t slot, bool& complete) {
  OccupancyGrid& grid = *grids_[slot];
  for (std::size_t i = path_count_; i-- > 0;) {  // oldest first: insertion order matters (clamps)
    const slam::TrajectoryNode& node = tree_.get(path_[i]);
    ScanView scan;
    const ScanLookup lookup = scans_.find(node.update_index, scan);
    if (lookup == ScanLookup::found) {
      grid.insert(scan, node.pose);
    } else if (lookup == ScanLookup::overwritten) {
      ++stats_.scans_overwritten;
      complete = false;
    }
  }
}

void JustInTimeGrid::attach(std::uint32_t slot, slam::TrajectoryNodeHandle node) {
  tree_.retain(node);
  tree_.set_user_slot(node, slot);
  slot_node_[slot] = node;
}

void JustInTimeGrid::free_slot(std::uint32_t slot) {
  const slam::TrajectoryNodeHandle node = slot_node_[slot];
  tree_.set_user_slot(node, kNoSlot);
  slot_node_[slot] = {};
  slot_dependents_[slot] = 0;
  tree_.release(node);
  free_slots_[free_count_++] = slot;
  ++stats_.grids_freed;
  if (slot == ml_slot_) ml_slot_ = kNoSlot;
}

void JustInTimeGrid::release_all() {
  for (std::uint32_t slot = 0; slot < capacity_; ++slot) {
    if (slot_node_[slot]) free_slot(slot);
  }
  ml_slot_ = kNoSlot;
}

void JustInTimeGrid::record_holding_stats() {
  const std::uint64_t held = grids_held();
  stats_.grids_held_sum += held;
  stats_.grids_held_max = std::max(stats_.grids_held_max, held);
}

}  // namespace stereoscout::occupancy
