#include "stereoscout/slam/landmark_map.hpp"

#include "stereoscout/core/check.hpp"

namespace stereoscout::slam {

unsigned bits_for_id(std::uint32_t id) {
  return id == 0 ? 0U : 32U - static_cast<unsigned>(__builtin_clz(id));  // every lookup needs it
}

unsigned levels_for_id(std::uint32_t id) { return (bits_for_id(id) + kTrieDigitBits - 1) / kTrieDigitBits; }

LandmarkStore::LandmarkStore(std::size_t node_capacity, std::size_t estimate_capacity)
    : nodes_(node_capacity), estimates_(estimate_capacity) {}

void LandmarkStore::retain(const LandmarkMap& map) {
  if (map.root) {
    nodes_.retain(map.root);
  }
}

void LandmarkStore::release(LandmarkMap& map) {
  if (map.root) {
    release_node(map.root);
  }
  map = LandmarkMap{};
}

void LandmarkStore::release_node(MapNodeHandle handle) {
  // The last reference frees the node, which drops its own references to what it held.
  nodes_.release(handle, [this](MapNode& dying) {
    // Children held only by the dying node die next and are read then; they were written an
    // update ago and are rarely in cache, so their fetches are started together first.
    for (const MapNodeHandle child : dying.child) {
      if (child && !nodes_.is_shared(child)) {
        __builtin_prefetch(&nodes_.get(child));
      }
    }
    for (const MapNodeHandle child : dying.child) {
      if (child) {
        release_node(child);
      }
    }
    for (const EstimateHandle e : dying.estimates) {
      estimates_.release(e);
    }
  });
}

const MapNode* LandmarkStore::find_leaf(const LandmarkMap& map, std::uint32_t id) const {
  if (!map.root || levels_for_id(id) > map.depth) {
    return nullptr;
  }
  MapNodeHandle at = map.root;
  for (unsigned level = map.depth; level > 0; --level) {
    at = nodes_.get(at).child[trie_digit(id, level)];
    if (!at) {
      return nullptr;
    }
  }
  return &nodes_.get(at);
}

// A copy of `source` that holds its own references to everything except the child on the
// path (`path_digit`), which the caller replaces by that child's copy straight away.
MapNodeHandle LandmarkStore::copy_for_path(MapNodeHandle source, unsigned level, unsigned path_digit) {
  // The references are taken from the source, which the walk down has just read: the copy
  // sits in a slot that is usually not in cache yet, and reading it back would wait for it.
  const MapNode& copied = nodes_.get(source);
  const MapNodeHandle copy = nodes_.acquire(copied);
  STEREOSCOUT_CHECK(copy, "landmark node pool ran out after its room was checked");
  if (level > 0) {
    for (unsigned digit = 0; digit < kTrieFanout; ++digit) {
      if (digit != path_digit && copied.child[digit]) {
        nodes_.retain(copied.child[digit]);
      }
    }
  } else {
    for (const EstimateHandle e : copied.estimates) {
      estimates_.retain(e);
    }
  }
  ++counters_.path_nodes_copied;
  return copy;
}

MapNode* LandmarkStore::mutable_leaf(LandmarkMap& map, std::uint32_t id, std::size_t estimates_needed) {
  const unsigned needed_depth = levels_for_id(id);
  const unsigned depth = needed_depth > map.depth ? needed_depth : map.depth;
  // Worst case: every node on the path copied or created, plus one new root per new level.
  const std::size_t worst_nodes = depth + 1U + (depth - map.depth);
  if (nodes_.capacity() - nodes_.in_use() < worst_nodes ||
      estimates_.capacity() - estimates_.in_use() < estimates_needed) {
    ++counters_.refused_pool_full;
    return nullptr;
  }
  if (!map.root) {
    map.depth = static_cast<std::uint8_t>(depth);
  }
  while (map.root && map.depth < depth) {
    // Grow one level: the old tree becomes the first (high digit 0) child of a new root.
    MapNode grown;
    grown.child[0] = map.root;  // the map's reference moves to the new root
    map.root = nodes_.acquire(grown);
    ++map.depth;
  }
  // Path copying. Everything below a shared node is reachable from several maps, so from the
  // first shared node down every node on the path is copied without asking; only that first
  // one gives back the reference its (exclusive) parent held.
  MapNodeHandle* link = &map.root;
  bool below_shared = false;
  for (unsigned level = map.depth;; --level) {
    const unsigned path_digit = trie_digit(id, level);
    MapNodeHandle current = *link;
    if (!current) {
      current = nodes_.acquire();
      below_shared = false;
    } else if (below_shared) {
      current = copy_for_path(current, level, path_digit);
    } else if (nodes_.is_shared(current)) {
      const MapNodeHandle copy = copy_for_path(current, level, path_digit);
      release_node(current);  // shared, so this only drops the reference we held
      current = copy;
      below_shared = true;
    }
    *link = current;
    if (level == 0) {
      return &nodes_.get(current);
    }
    link = &nodes_.get(current).child[path_digit];
  }
}

LandmarkEstimate& LandmarkStore::mutable_estimate(MapNode& leaf, std::size_t index) {
  EstimateHandle& handle = leaf.estimates[index];
  if (estimates_.is_shared(handle)) {
    const EstimateHandle copy = estimates_.acquire(estimates_.get(handle));
    STEREOSCOUT_CHECK(copy, "landmark estimate pool ran out after its room was checked");
    estimates_.release(handle);
    handle = copy;
    ++counters_.estimates_copied;
  }
  return estimates_.get(handle);
}

LandmarkEstimate& LandmarkStore::add_estimate(MapNode& leaf, const LandmarkEstimate& estimate) {
  const EstimateHandle handle = estimates_.acquire(estimate);
  STEREOSCOUT_CHECK(handle, "landmark estimate pool ran out after its room was checked");
  STEREOSCOUT_CHECK(leaf.estimates.push_back(handle), "add_estimate on a full estimate list");
  return estimates_.get(handle);
}

}  // namespace stereoscout::slam
