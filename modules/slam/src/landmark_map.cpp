#include "stereoscout/slam/landmark_map.hpp"

#include "stereoscout/core/check.hpp"

namespace stereoscout::slam {

unsigned bits_for_id(std::uint32_t id) {
  unsigned bits = 0;
  while (id != 0) {
    ++bits;
    id >>= 1;
  }
  return bits;
}

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
  if (!map.root || bits_for_id(id) > map.depth) {
    return nullptr;
  }
  MapNodeHandle at = map.root;
  for (unsigned level = map.depth; level > 0; --level) {
    at = nodes_.get(at).child[(id >> (level - 1)) & 1U];
    if (!at) {
      return nullptr;
    }
  }
  return &nodes_.get(at);
}

// Returns a node that only the caller's parent holds: `handle` itself when nobody else
// holds it, else a fresh copy that takes over the caller's reference (path copying).
MapNodeHandle LandmarkStore::exclusive_copy(MapNodeHandle handle) {
  if (!nodes_.is_shared(handle)) {
    return handle;
  }
  const MapNodeHandle copy = nodes_.acquire(nodes_.get(handle));
  STEREOSCOUT_CHECK(copy, "landmark node pool ran out after its room was checked");
  const MapNode& copied = nodes_.get(copy);
  for (const MapNodeHandle child : copied.child) {
    if (child) {
      nodes_.retain(child);
    }
  }
  for (const EstimateHandle e : copied.estimates) {
    estimates_.retain(e);
  }
  release_node(handle);  // shared, so this only drops our reference
  ++counters_.path_nodes_copied;
  return copy;
}

MapNode* LandmarkStore::mutable_leaf(LandmarkMap& map, std::uint32_t id, std::size_t estimates_needed) {
  const unsigned needed_depth = bits_for_id(id);
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
    // Grow one level: the old tree becomes the left (high bit 0) child of a new root.
    MapNode grown;
    grown.child[0] = map.root;  // the map's reference moves to the new root
    map.root = nodes_.acquire(grown);
    ++map.depth;
  }
  if (!map.root) {
    map.root = nodes_.acquire();
  } else {
    map.root = exclusive_copy(map.root);
  }
  MapNodeHandle at = map.root;
  for (unsigned level = map.depth; level > 0; --level) {
    MapNodeHandle& child = nodes_.get(at).child[(id >> (level - 1)) & 1U];
    child = child ? exclusive_copy(child) : nodes_.acquire();
    at = child;
  }
  return &nodes_.get(at);
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
