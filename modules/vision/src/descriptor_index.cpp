#include "stereoscout/vision/descriptor_index.hpp"

#include <algorithm>
#include <cmath>

#include "stereoscout/core/check.hpp"

namespace stereoscout::vision {
namespace {

// Depth allowance of the search heap: each descent pushes at most one far cell per level.
constexpr std::size_t kHeapSlotsPerLeafCheck = 64;

bool heap_less(std::uint32_t bound_a, std::uint32_t node_a, std::uint32_t bound_b, std::uint32_t node_b) {
  return bound_a < bound_b || (bound_a == bound_b && node_a < node_b);
}

}  // namespace

DescriptorIndexParams index_params_from_config(const core::VisionConfig& vision) {
  DescriptorIndexParams params;
  params.capacity = static_cast<std::size_t>(vision.index_capacity);
  params.bucket_size = vision.index_bucket_size;
  params.max_leaf_checks = vision.index_max_leaf_checks;
  params.match_distance = vision.index_match_distance;
  params.candidate_min_frames = vision.candidate_min_frames;
  params.box_distance = vision.index_box_distance;
  return params;
}

DescriptorIndex::DescriptorIndex(const DescriptorIndexParams& params)
    : params_(params),
      bucket_size_(static_cast<std::size_t>(std::max(params.bucket_size, 2))),
      match_distance_squared_(static_cast<std::uint32_t>(std::floor(params.match_distance * params.match_distance))) {
  STEREOSCOUT_CHECK(params.capacity > 0 && params.capacity < kNone / 2, "DescriptorIndex: bad capacity");
  descriptors_.resize(params.capacity);
  entries_.resize(params.capacity);
  free_entries_.resize(params.capacity);
  for (std::size_t i = 0; i < params.capacity; ++i) {
    // Stack of free slots, lowest index on top, so slots fill in order.
    free_entries_[i] = static_cast<std::uint32_t>(params.capacity - 1 - i);
  }
  // Leaves average at least half full after median splits; allow four nodes per bucket of
  // entries, and rebuild in place if evictions leave too many empty leaves behind.
  const std::size_t node_capacity = 4 * (params.capacity / bucket_size_ + 1) + 8;
  nodes_.resize(node_capacity);
  buckets_.resize(node_capacity * bucket_size_);
  heap_.resize(static_cast<std::size_t>(std::max(params.max_leaf_checks, 1)) * kHeapSlotsPerLeafCheck);
  split_scratch_.resize(bucket_size_ + 1);
  stats_.capacity = params.capacity;
  reset_tree();
}

void DescriptorIndex::set_max_leaf_checks(int leaf_checks) {
  params_.max_leaf_checks = std::max(leaf_checks, 1);
}

void DescriptorIndex::reset_tree() {
  nodes_used_ = 0;
  root_ = allocate_leaf();
}

std::uint32_t DescriptorIndex::allocate_leaf() {
  if (nodes_used_ == nodes_.size()) {
    return kNone;
  }
  const auto node = static_cast<std::uint32_t>(nodes_used_++);
  nodes_[node] = Node{};
  stats_.nodes_in_use = nodes_used_;
  stats_.nodes_high_water = std::max(stats_.nodes_high_water, nodes_used_);
  return node;
}

std::uint32_t DescriptorIndex::descend_to_leaf(const Descriptor& descriptor) const {
  std::uint32_t node = root_;
  while (!nodes_[node].is_leaf()) {
    const Node& split = nodes_[node];
    node = descriptor[split.dimension] < split.threshold ? split.low : split.high;
  }
  return node;
}

// Splits a full leaf at the median of its widest dimension (lowest dimension on ties).
// Returns false when the bucket cannot be split: identical descriptors, or no free nodes.
bool DescriptorIndex::split_leaf(std::uint32_t leaf) {
  const std::size_t count = nodes_[leaf].count;
  const std::uint32_t* members = bucket(leaf);
  int best_dimension = -1;
  int best_spread = 0;
  for (int dimension = 0; dimension < kDescriptorLength; ++dimension) {
    int low = 255;
    int high = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const int value = descriptors_[members[i]][static_cast<std::size_t>(dimension)];
      low = std::min(low, value);
      high = std::max(high, value);
    }
    if (high - low > best_spread) {
      best_spread = high - low;
      best_dimension = dimension;
    }
  }
  if (best_dimension < 0 || nodes_used_ + 2 > nodes_.size()) {
    return false;
  }
  const auto dimension = static_cast<std::size_t>(best_dimension);
  for (std::size_t i = 0; i < count; ++i) {
    split_scratch_[i] = descriptors_[members[i]][dimension];
  }
  const auto scratch_end = split_scratch_.begin() + static_cast<std::ptrdiff_t>(count);
  std::sort(split_scratch_.begin(), scratch_end);
  std::uint8_t threshold = split_scratch_[count / 2];
  if (threshold == split_scratch_[0]) {
    // The median equals the minimum: split just above it so both sides are non-empty.
    threshold = *std::upper_bound(split_scratch_.begin(), scratch_end, split_scratch_[0]);
  }
  const std::uint32_t low = allocate_leaf();
  const std::uint32_t high = allocate_leaf();
  nodes_[low].parent = leaf;
  nodes_[high].parent = leaf;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t entry = bucket(leaf)[i];
    const std::uint32_t child = descriptors_[entry][dimension] < threshold ? low : high;
    bucket(child)[nodes_[child].count++] = entry;
    entries_[entry].leaf = child;
  }
  Node& parent = nodes_[leaf];
  parent.low = low;
  parent.high = high;
  parent.count = 0;
  parent.dimension = static_cast<std::uint8_t>(dimension);
  parent.threshold = threshold;
  return true;
}

bool DescriptorIndex::insert_into_tree(std::uint32_t entry) {
  std::uint32_t leaf = descend_to_leaf(descriptors_[entry]);
  while (nodes_[leaf].count == bucket_size_) {
    if (!split_leaf(leaf)) {
      return false;
    }
    leaf = descend_to_leaf(descriptors_[entry]);
  }
  bucket(leaf)[nodes_[leaf].count++] = entry;
  entries_[entry].leaf = leaf;
  return true;
}

void DescriptorIndex::remove_from_tree(std::uint32_t entry) {
  const std::uint32_t leaf = entries_[entry].leaf;
  std::uint32_t* members = bucket(leaf);
  const std::size_t count = nodes_[leaf].count;
  for (std::size_t i = 0; i < count; ++i) {
    if (members[i] == entry) {
      members[i] = members[count - 1];
      --nodes_[leaf].count;
      break;
    }
  }
  entries_[entry].leaf = kNone;
}

void DescriptorIndex::rebuild_tree() {
  ++stats_.rebuilds;
  reset_tree();
  for (std::uint32_t entry = 0; entry < entries_.size(); ++entry) {
    if (entries_[entry].live && entries_[entry].leaf != kNone) {
      entries_[entry].leaf = kNone;
      if (!insert_into_tree(entry)) {
        break;  // cannot happen with the node allowance; left out of the tree if it does
      }
    }
  }
}

void DescriptorIndex::heap_push(HeapItem item) {
  if (heap_size_ == heap_.size()) {
    ++stats_.search_heap_overflows;
    return;
  }
  std::size_t i = heap_size_++;
  while (i > 0) {
    const std::size_t parent = (i - 1) / 2;
    if (!heap_less(item.bound, item.node, heap_[parent].bound, heap_[parent].node)) {
      break;
    }
    heap_[i] = heap_[parent];
    i = parent;
  }
  heap_[i] = item;
}

DescriptorIndex::HeapItem DescriptorIndex::heap_pop() {
  const HeapItem top = heap_[0];
  const HeapItem last = heap_[--heap_size_];
  std::size_t i = 0;
  while (true) {
    std::size_t child = 2 * i + 1;
    if (child >= heap_size_) {
      break;
    }
    if (child + 1 < heap_size_ && heap_less(heap_[child + 1].bound, heap_[child + 1].node, heap_[child].bound, heap_[child].node)) {
      ++child;
    }
    if (!heap_less(heap_[child].bound, heap_[child].node, last.bound, last.node)) {
      break;
    }
    heap_[i] = heap_[child];
    i = child;
  }
  if (heap_size_ > 0) {
    heap_[i] = last;
  }
  return top;
}

IndexNeighbour DescriptorIndex::nearest(const Descriptor& descriptor, std::uint32_t radius_squared) {
  ++stats_.lookups;
  return params_.box_distance ? nearest_by_box_distance(descriptor, radius_squared) : nearest_by_largest_gap(descriptor);
}

void DescriptorIndex::check_leaf(std::uint32_t leaf, const Descriptor& descriptor, IndexNeighbour& best) const {
  const std::uint32_t* members = bucket(leaf);
  const std::size_t count = nodes_[leaf].count;
  // A leaf's descriptors lie scattered over the whole table: ask for all of them at once, so
  // that their cache misses overlap instead of following one another.
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint8_t* row = descriptors_[members[i]].data();
    __builtin_prefetch(row);
    __builtin_prefetch(row + 64);
  }
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t entry = members[i];
    const std::uint32_t distance = descriptor_distance_squared(descriptor, descriptors_[entry]);
    if (!best.found || distance < best.distance_squared || (distance == best.distance_squared && entry < best.entry)) {
      best = {true, entry, distance};
    }
  }
}

// The search as first built: a far cell's bound is the largest single-dimension gap on the
// path to it, which never exceeds the true distance but often falls far below it.
IndexNeighbour DescriptorIndex::nearest_by_largest_gap(const Descriptor& descriptor) {
  IndexNeighbour best;
  heap_size_ = 0;
  heap_push({0, root_});
  int leaves_checked = 0;
  while (heap_size_ > 0 && leaves_checked < params_.max_leaf_checks) {
    const HeapItem item = heap_pop();
    if (best.found && item.bound > best.distance_squared) {
      break;  // every remaining cell is farther than the best entry found
    }
    std::uint32_t node = item.node;
    while (!nodes_[node].is_leaf()) {
      const Node& split = nodes_[node];
      const int value = descriptor[split.dimension];
      // Cells hold integers: the low side has values <= threshold - 1.
      const bool go_low = value < split.threshold;
      const int gap = go_low ? split.threshold - value : value - (split.threshold - 1);
      const auto far_bound = std::max(item.bound, static_cast<std::uint32_t>(gap * gap));
      heap_push({far_bound, go_low ? split.high : split.low});
      node = go_low ? split.low : split.high;
    }
    ++leaves_checked;
    check_leaf(node, descriptor, best);
  }
  stats_.leaves_checked += static_cast<std::uint64_t>(leaves_checked);
  return best;
}

// The byte ranges of a node's cell, from the splits on the path up to the root.
void DescriptorIndex::cell_of(std::uint32_t node, Cell& cell) const {
  cell.low.fill(0);
  cell.high.fill(255);
  for (std::uint32_t child = node, parent = nodes_[node].parent; parent != kNone;
       child = parent, parent = nodes_[parent].parent) {
    const Node& split = nodes_[parent];
    const std::size_t d = split.dimension;
    if (child == split.low) {
      cell.high[d] = std::min<std::uint8_t>(cell.high[d], static_cast<std::uint8_t>(split.threshold - 1));
    } else {
      cell.low[d] = std::max(cell.low[d], split.threshold);
    }
  }
}

// Priority search on the exact distance from the key to each cell (Arya and Mount): going
// down, the far side of a split differs from the near side in one dimension only, so its
// squared distance is the near side's with that dimension's gap replaced. With exact bounds
// the search stops as soon as the nearest cell left is farther than the best entry or the
// radius (how soon depends on how few dimensions the descriptors really spread over).
IndexNeighbour DescriptorIndex::nearest_by_box_distance(const Descriptor& descriptor, std::uint32_t radius_squared) {
  IndexNeighbour best;
  heap_size_ = 0;
  heap_push({0, root_});
  int leaves_checked = 0;
  Cell& cell = search_cell_;
  while (heap_size_ > 0 && leaves_checked < params_.max_leaf_checks) {
    const HeapItem item = heap_pop();
    if (item.bound > radius_squared || (best.found && item.bound > best.distance_squared)) {
      break;  // every remaining cell is farther than the radius or the best entry found
    }
    std::uint32_t node = item.node;
    cell_of(node, cell);
    while (!nodes_[node].is_leaf()) {
      const Node& split = nodes_[node];
      const std::size_t d = split.dimension;
      const int value = descriptor[d];
      const int low = cell.low[d];
      const int high = cell.high[d];
      const int gap = value < low ? low - value : (value > high ? value - high : 0);
      // Cells hold integers: the low side has values <= threshold - 1.
      const bool go_low = value < split.threshold;
      const int far_gap = go_low ? split.threshold - value : value - (split.threshold - 1);
      const auto far_bound = item.bound - static_cast<std::uint32_t>(gap * gap) + static_cast<std::uint32_t>(far_gap * far_gap);
      if (far_bound <= radius_squared && (!best.found || far_bound <= best.distance_squared)) {
        heap_push({far_bound, go_low ? split.high : split.low});
      }
      if (go_low) {
        cell.high[d] = static_cast<std::uint8_t>(split.threshold - 1);
        node = split.low;
      } else {
        cell.low[d] = split.threshold;
        node = split.high;
      }
    }
    ++leaves_checked;
    check_leaf(node, descriptor, best);
  }
  stats_.leaves_checked += static_cast<std::uint64_t>(leaves_checked);
  return best;
}

void DescriptorIndex::append_candidate(std::uint32_t entry) {
  Entry& e = entries_[entry];
  e.older = newest_candidate_;
  e.newer = kNone;
  if (newest_candidate_ != kNone) {
    entries_[newest_candidate_].newer = entry;
  } else {
    oldest_candidate_ = entry;
  }
  newest_candidate_ = entry;
}

void DescriptorIndex::unlink_candidate(std::uint32_t entry) {
  Entry& e = entries_[entry];
  if (e.older != kNone) {
    entries_[e.older].newer = e.newer;
  } else {
    oldest_candidate_ = e.newer;
  }
  if (e.newer != kNone) {
    entries_[e.newer].older = e.older;
  } else {
    newest_candidate_ = e.older;
  }
  e.older = kNone;
  e.newer = kNone;
}

void DescriptorIndex::promote(std::uint32_t entry) {
  unlink_candidate(entry);
  entries_[entry].landmark_id = next_landmark_id_++;
  ++stats_.promoted;
  ++stats_.landmarks;
  --stats_.candidates;
}

void DescriptorIndex::record_sighting(std::uint32_t entry, std::uint64_t frame) {
  Entry& e = entries_[entry];
  if (e.last_seen_frame != frame) {
    e.last_seen_frame = frame;
    ++e.frames_seen;
  }
  if (e.landmark_id == 0) {
    unlink_candidate(entry);  // most recently seen goes to the back of the eviction queue
    append_candidate(entry);
    if (static_cast<int>(e.frames_seen) >= params_.candidate_min_frames) {
      promote(entry);
    }
  }
}

// Evicts the least recently seen candidate unless it was seen in this very frame.
bool DescriptorIndex::make_room(std::uint64_t frame) {
  const std::uint32_t victim = oldest_candidate_;
  if (victim == kNone || entries_[victim].last_seen_frame == frame) {
    return false;
  }
  unlink_candidate(victim);
  remove_from_tree(victim);
  entries_[victim].live = false;
  free_entries_[stats_.capacity - stats_.entries] = victim;
  --stats_.entries;
  --stats_.candidates;
  ++stats_.evicted;
  return true;
}

std::uint32_t DescriptorIndex::new_entry(const Descriptor& descriptor, std::uint64_t frame) {
  if (stats_.entries == stats_.capacity && !make_room(frame)) {
    return kNone;
  }
  const std::uint32_t entry = free_entries_[stats_.capacity - stats_.entries - 1];
  descriptors_[entry] = descriptor;
  entries_[entry] = Entry{};
  entries_[entry].live = true;
  entries_[entry].last_seen_frame = frame;
  entries_[entry].frames_seen = 1;
  if (!insert_into_tree(entry)) {
    rebuild_tree();
    if (!insert_into_tree(entry)) {
      entries_[entry].live = false;
      return kNone;  // identical descriptors filled a whole bucket
    }
  }
  ++stats_.entries;
  ++stats_.candidates;
  ++stats_.inserted;
  append_candidate(entry);
  if (params_.candidate_min_frames <= 1) {
    promote(entry);
  }
  return entry;
}

IndexLookup DescriptorIndex::observe(const Descriptor& descriptor, std::uint64_t frame) {
  IndexLookup lookup;
  const IndexNeighbour neighbour = nearest(descriptor, match_distance_squared_);
  if (neighbour.found && neighbour.distance_squared <= match_distance_squared_) {
    ++stats_.matched;
    record_sighting(neighbour.entry, frame);
    lookup.entry = neighbour.entry;
    lookup.landmark_id = entries_[neighbour.entry].landmark_id;
    lookup.outcome = lookup.landmark_id != 0 ? IndexLookup::Outcome::landmark : IndexLookup::Outcome::candidate;
    return lookup;
  }
  const std::uint32_t entry = new_entry(descriptor, frame);
  if (entry == kNone) {
    ++stats_.refused;
    return lookup;
  }
  lookup.entry = entry;
  lookup.landmark_id = entries_[entry].landmark_id;
  lookup.outcome = lookup.landmark_id != 0 ? IndexLookup::Outcome::landmark : IndexLookup::Outcome::new_candidate;
  return lookup;
}

}  // namespace stereoscout::vision
