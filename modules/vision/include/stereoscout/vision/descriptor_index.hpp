#pragma once
// The sensor's descriptor index (paper section IV): maps a SIFT descriptor to an integer
// landmark identity by approximate nearest-neighbour search.
//
// Structure: a KD-tree over byte descriptors with bucket leaves that split at the median of
// their widest dimension when full, so entries are inserted one at a time. Search is
// best-bin-first (Beis and Lowe): a bounded number of leaves is examined, nearest cell
// first, which makes a lookup cost logarithmic in the number of entries. A cell's distance is
// either the largest gap in one dimension (as first built) or, with `box_distance`, the exact
// distance to the cell's box, which orders the cells truly and lets the search stop early.
// Every array (entries, nodes, leaf buckets, the search heap) is sized at construction;
// nothing allocates later.
//
// Identity: a key whose nearest entry lies within `match_distance` takes that entry. A key
// with no such entry becomes a new *candidate*; a candidate is handed to the filter (gets a
// landmark id) only once it has been seen in `candidate_min_frames` different frames.
// Landmark ids count up from 1 in order of promotion and are never reused.
//
// Full index policy: the least recently seen candidate is evicted to make room (candidates
// not seen in the current frame only); landmarks are never evicted (the filter holds their
// ids). If every entry is a landmark or was seen this frame, the new key is refused. When
// the node pool runs out (leaves left empty by evictions), the tree is rebuilt in place from
// the live entries in entry order. Everything is counted in DescriptorIndexStats. Ties are
// broken by the smaller entry index, so results never depend on addresses.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "stereoscout/core/config/vision.hpp"
#include "stereoscout/vision/keypoints.hpp"

namespace stereoscout::vision {

struct DescriptorIndexParams {
  std::size_t capacity = 100000;
  int bucket_size = 16;
  int max_leaf_checks = 64;
  double match_distance = 180.0;
  int candidate_min_frames = 3;
  bool box_distance = false;  // vision.index_box_distance
};

DescriptorIndexParams index_params_from_config(const core::VisionConfig& vision);

struct IndexLookup {
  enum class Outcome : std::uint8_t {
    landmark,       // matched (or just promoted to) a landmark: landmark_id is valid
    candidate,      // matched a candidate that has not been seen in enough frames yet
    new_candidate,  // no entry near enough: inserted as a new candidate
    refused,        // no entry near enough and no room (counted)
  };
  Outcome outcome = Outcome::refused;
  std::uint32_t landmark_id = 0;  // 0 unless outcome == landmark
  std::uint32_t entry = 0;        // slot of the entry (not for refused)
};

struct IndexNeighbour {
  bool found = false;
  std::uint32_t entry = 0;
  std::uint32_t distance_squared = 0;
};

struct DescriptorIndexStats {
  std::size_t capacity = 0;
  std::size_t entries = 0;
  std::size_t landmarks = 0;
  std::size_t candidates = 0;
  std::size_t nodes_in_use = 0;
  std::size_t nodes_high_water = 0;
  std::uint64_t lookups = 0;
  std::uint64_t matched = 0;
  std::uint64_t inserted = 0;
  std::uint64_t promoted = 0;
  std::uint64_t evicted = 0;            // stale candidates dropped to make room
  std::uint64_t refused = 0;            // new keys refused: index full of landmarks/current keys
  std::uint64_t rebuilds = 0;           // in-place tree rebuilds (node pool ran out)
  std::uint64_t search_heap_overflows = 0;
  std::uint64_t leaves_checked = 0;     // summed over all searches
};

class DescriptorIndex {
 public:
  explicit DescriptorIndex(const DescriptorIndexParams& params);

  // One key seen in frame `frame` (frames must not decrease). See the class comment.
  IndexLookup observe(const Descriptor& descriptor, std::uint64_t frame);

  // Best-bin-first search without changing any entry (the stats count it). With
  // box_distance, cells farther than `radius_squared` are not searched.
  IndexNeighbour nearest(const Descriptor& descriptor, std::uint32_t radius_squared = kNoRadius);

  static constexpr std::uint32_t kNoRadius = 0xFFFFFFFFU;

  // Changes the search bound (benchmarks, tests); capped by the heap sized at construction.
  void set_max_leaf_checks(int leaf_checks);

  // The landmark id of an entry (0 while it is a candidate).
  std::uint32_t landmark_id_of(std::uint32_t entry) const { return entries_[entry].landmark_id; }
  const DescriptorIndexStats& stats() const { return stats_; }
  std::size_t size() const { return stats_.entries; }

 private:
  static constexpr std::uint32_t kNone = 0xFFFFFFFFU;
  struct Entry {
    std::uint32_t landmark_id = 0;
    std::uint32_t frames_seen = 0;
    std::uint64_t last_seen_frame = 0;
    std::uint32_t leaf = kNone;  // node holding this entry
    std::uint32_t older = kNone;  // candidate recency list (oldest first)
    std::uint32_t newer = kNone;
    bool live = false;
  };
  struct Node {
    std::uint32_t low = kNone;   // child for descriptor[dimension] < threshold; kNone: leaf
    std::uint32_t high = kNone;  // child for descriptor[dimension] >= threshold
    std::uint32_t parent = kNone;
    std::uint16_t count = 0;     // entries in the bucket (leaves only)
    std::uint8_t dimension = 0;
    std::uint8_t threshold = 0;
    bool is_leaf() const { return low == kNone; }
  };
  struct HeapItem {
    std::uint32_t bound = 0;  // lower bound on the squared distance to the cell
    std::uint32_t node = 0;
  };
  // A cell of the tree: the byte range of every dimension (inclusive).
  struct Cell {
    std::array<std::uint8_t, kDescriptorLength> low;
    std::array<std::uint8_t, kDescriptorLength> high;
  };

  std::uint32_t allocate_leaf();
  void reset_tree();
  void rebuild_tree();
  bool insert_into_tree(std::uint32_t entry);
  bool split_leaf(std::uint32_t leaf);
  void remove_from_tree(std::uint32_t entry);
  std::uint32_t descend_to_leaf(const Descriptor& descriptor) const;
  void record_sighting(std::uint32_t entry, std::uint64_t frame);
  bool make_room(std::uint64_t frame);
  std::uint32_t new_entry(const Descriptor& descriptor, std::uint64_t frame);
  void promote(std::uint32_t entry);
  void unlink_candidate(std::uint32_t entry);
  void append_candidate(std::uint32_t entry);
  void heap_push(HeapItem item);
  HeapItem heap_pop();
  IndexNeighbour nearest_by_largest_gap(const Descriptor& descriptor);
  IndexNeighbour nearest_by_box_distance(const Descriptor& descriptor, std::uint32_t radius_squared);
  void cell_of(std::uint32_t node, Cell& cell) const;
  void check_leaf(std::uint32_t leaf, const Descriptor& descriptor, IndexNeighbour& best) const;
  std::uint32_t* bucket(std::uint32_t node) { return &buckets_[static_cast<std::size_t>(node) * bucket_size_]; }
  const std::uint32_t* bucket(std::uint32_t node) const {
    return &buckets_[static_cast<std::size_t>(node) * bucket_size_];
  }

  DescriptorIndexParams params_;
  std::size_t bucket_size_;
  std::uint32_t match_distance_squared_;
  std::vector<Descriptor> descriptors_;   // sized once: capacity
  std::vector<Entry> entries_;            // sized once: capacity
  std::vector<std::uint32_t> free_entries_;  // stack of free slots (reserved once)
  std::vector<Node> nodes_;               // sized once
  std::vector<std::uint32_t> buckets_;    // bucket_size slots per node
  std::size_t nodes_used_ = 0;
  std::uint32_t root_ = 0;
  std::vector<HeapItem> heap_;            // sized once
  std::size_t heap_size_ = 0;
  Cell search_cell_{};                    // the box search's current cell
  std::vector<std::uint8_t> split_scratch_;  // bucket_size + 1 values (median search)
  std::uint32_t oldest_candidate_ = kNone;
  std::uint32_t newest_candidate_ = kNone;
  std::uint32_t next_landmark_id_ = 1;
  DescriptorIndexStats stats_;
};

}  // namespace stereoscout::vision
