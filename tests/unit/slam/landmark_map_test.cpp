#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <vector>

#include "stereoscout/slam/landmark_map.hpp"

namespace stereoscout::slam {
namespace {

LandmarkEstimate estimate_at(double x) {
  LandmarkEstimate e;
  e.mean = Eigen::Vector3d(x, 0.0, 0.0);
  e.observations = 1;
  return e;
}

void insert(LandmarkStore& store, LandmarkMap& map, std::uint32_t id) {
  MapNode* leaf = store.mutable_leaf(map, id, 1);
  ASSERT_NE(leaf, nullptr);
  store.add_estimate(*leaf, estimate_at(static_cast<double>(id)));
}

// Every node index reachable from a map.
void collect(const LandmarkStore& store, MapNodeHandle at, std::set<std::uint32_t>& seen) {
  if (!at) {
    return;
  }
  seen.insert(at.index);
  for (const MapNodeHandle child : store.node(at).child) {
    collect(store, child, seen);
  }
}

TEST(LandmarkStore, BaseEightDigitsForIdAreTheTrieDepth) {
  EXPECT_EQ(bits_for_id(0), 0u);
  EXPECT_EQ(bits_for_id(1), 1u);
  EXPECT_EQ(bits_for_id(15), 4u);
  EXPECT_EQ(bits_for_id(16), 5u);
  EXPECT_EQ(bits_for_id(0xFFFFFFFFu), 32u);
  EXPECT_EQ(levels_for_id(0), 0u);
  EXPECT_EQ(levels_for_id(7), 1u);
  EXPECT_EQ(levels_for_id(8), 2u);
  EXPECT_EQ(levels_for_id(9999), 5u);  // 10,000 landmarks: 5 levels (14 in a binary trie)
  EXPECT_EQ(levels_for_id(0xFFFFFFFFu), 11u);
  EXPECT_EQ(trie_digit(0643, 3), 6u);  // octal: one digit per level, most significant first
  EXPECT_EQ(trie_digit(0643, 2), 4u);
  EXPECT_EQ(trie_digit(0643, 1), 3u);
}

TEST(LandmarkStore, SymmetricCovarianceKeepsTheUpperTriangleExactly) {
  Eigen::Matrix3d m;
  m << 4.0, 0.1, 0.2, 0.1, 5.0, 0.3, 0.2, 0.3, 6.0;
  const SymmetricMatrix3 s = m;
  EXPECT_EQ(s.full(), m);
  EXPECT_EQ(s(2, 1), 0.3);
  EXPECT_EQ(s(1, 2), 0.3);
  EXPECT_EQ(sizeof(LandmarkEstimate), 80u);
  EXPECT_EQ(sizeof(MapNode), 64u);  // one cache line per trie node
}

TEST(LandmarkStore, DenseIdsMakeABalancedTreeAndFindEveryLeaf) {
  LandmarkStore store(100, 100);
  LandmarkMap map;
  for (std::uint32_t id = 0; id < 16; ++id) {
    insert(store, map, id);
  }
  EXPECT_EQ(map.depth, 2);
  EXPECT_EQ(store.nodes_in_use(), 19u);  // 16 leaves under 2 interior nodes under the root
  EXPECT_EQ(store.estimates_in_use(), 16u);
  for (std::uint32_t id = 0; id < 16; ++id) {
    const MapNode* leaf = store.find_leaf(map, id);
    ASSERT_NE(leaf, nullptr);
    ASSERT_EQ(leaf->estimates.size(), 1u);
    EXPECT_EQ(store.estimate(leaf->estimates[0]).mean.x(), static_cast<double>(id));
  }
  EXPECT_EQ(store.find_leaf(map, 16), nullptr);
  std::vector<std::uint32_t> visited;
  store.for_each_estimate(map, [&](std::uint32_t id, const LandmarkEstimate&) { visited.push_back(id); });
  ASSERT_EQ(visited.size(), 16u);
  for (std::uint32_t id = 0; id < 16; ++id) {
    EXPECT_EQ(visited[id], id);  // increasing id order
  }
  store.release(map);
  EXPECT_EQ(store.nodes_in_use(), 0u);
  EXPECT_EQ(store.estimates_in_use(), 0u);
}

TEST(LandmarkStore, GrowsANewRootWhenAnIdNeedsMoreDigits) {
  LandmarkStore store(100, 100);
  LandmarkMap map;
  insert(store, map, 3);
  EXPECT_EQ(map.depth, 1);
  insert(store, map, 1000);
  EXPECT_EQ(map.depth, 4);
  ASSERT_NE(store.find_leaf(map, 3), nullptr);
  ASSERT_NE(store.find_leaf(map, 1000), nullptr);
  EXPECT_EQ(store.estimate(store.find_leaf(map, 3)->estimates[0]).mean.x(), 3.0);
  EXPECT_EQ(store.find_leaf(map, 2), nullptr);
  store.release(map);
  EXPECT_EQ(store.nodes_in_use(), 0u);
}

TEST(LandmarkStore, AnUpdateCopiesOnlyThePathAndReleaseRestoresExactCounts) {
  LandmarkStore store(200, 200);
  LandmarkMap a;
  for (std::uint32_t id = 0; id < 16; ++id) {
    insert(store, a, id);
  }
  const std::size_t nodes_before = store.nodes_in_use();
  const std::size_t estimates_before = store.estimates_in_use();
  LandmarkMap b = a;  // a resampled sibling
  store.retain(b);
  EXPECT_EQ(store.nodes_in_use(), nodes_before);

  MapNode* leaf = store.mutable_leaf(b, 5, 1);
  ASSERT_NE(leaf, nullptr);
  store.mutable_estimate(*leaf, 0).mean.x() = 42.0;
  // Root, one interior node and the leaf: depth + 1 copies, one estimate copy.
  EXPECT_EQ(store.counters().path_nodes_copied, 3u);
  EXPECT_EQ(store.counters().estimates_copied, 1u);
  EXPECT_EQ(store.nodes_in_use(), nodes_before + 3);
  EXPECT_EQ(store.estimates_in_use(), estimates_before + 1);
  EXPECT_EQ(store.estimate(store.find_leaf(a, 5)->estimates[0]).mean.x(), 5.0);  // a unchanged
  EXPECT_EQ(store.estimate(store.find_leaf(b, 5)->estimates[0]).mean.x(), 42.0);

  std::set<std::uint32_t> in_a;
  std::set<std::uint32_t> in_b;
  collect(store, a.root, in_a);
  collect(store, b.root, in_b);
  std::size_t shared = 0;
  for (const std::uint32_t index : in_b) {
    shared += in_a.count(index);
  }
  EXPECT_EQ(in_b.size(), 19u);
  EXPECT_EQ(shared, 16u);  // every node off the changed path is still shared

  // A second change of the same leaf copies nothing: b owns that path now.
  store.mutable_estimate(*store.mutable_leaf(b, 5, 1), 0).mean.x() = 43.0;
  EXPECT_EQ(store.counters().path_nodes_copied, 3u);
  EXPECT_EQ(store.counters().estimates_copied, 1u);

  store.release(b);
  EXPECT_EQ(store.nodes_in_use(), nodes_before);
  EXPECT_EQ(store.estimates_in_use(), estimates_before);
  store.release(a);
  EXPECT_EQ(store.nodes_in_use(), 0u);
  EXPECT_EQ(store.estimates_in_use(), 0u);
}

TEST(LandmarkStore, ManyParticlesShareAlmostEveryNodeAfterOneChangeEach) {
  constexpr std::uint32_t kLandmarks = 1024;
  constexpr std::size_t kParticles = 100;
  LandmarkStore store(10000, 2000);
  LandmarkMap base;
  for (std::uint32_t id = 0; id < kLandmarks; ++id) {
    insert(store, base, id);
  }
  const std::size_t base_nodes = store.nodes_in_use();
  EXPECT_EQ(base_nodes, 1171u);  // 1024 leaves + 128 + 16 + 2 interior nodes + the root
  std::vector<LandmarkMap> particles(kParticles, base);
  for (LandmarkMap& map : particles) {
    store.retain(map);
  }
  for (std::size_t i = 0; i < kParticles; ++i) {
    const auto id = static_cast<std::uint32_t>((i * 37) % kLandmarks);
    store.mutable_estimate(*store.mutable_leaf(particles[i], id, 1), 0).mean.y() = 1.0;
  }
  // O(N log K): each particle owns only its 5-node path; a copy of every map would be
  // 100 x 1171 nodes.
  EXPECT_EQ(store.nodes_in_use(), base_nodes + kParticles * 5);
  for (LandmarkMap& map : particles) {
    store.release(map);
  }
  EXPECT_EQ(store.nodes_in_use(), base_nodes);
  store.release(base);
  EXPECT_EQ(store.nodes_in_use(), 0u);
}

TEST(LandmarkStore, RefusesAChangeThePoolsCannotHoldAndLeavesTheMapUnchanged) {
  LandmarkStore store(5, 2);
  LandmarkMap map;
  insert(store, map, 2);  // depth 1: the root and a leaf
  EXPECT_EQ(store.nodes_in_use(), 2u);
  LandmarkMap sibling = map;
  store.retain(sibling);
  // Copying the 2-node path of the sibling fits (4 of 5 nodes); a new estimate too.
  ASSERT_NE(store.mutable_leaf(sibling, 2, 1), nullptr);
  // A further id of the original needs up to 2 more nodes: one left.
  EXPECT_EQ(store.mutable_leaf(map, 3, 1), nullptr);
  EXPECT_EQ(store.counters().refused_pool_full, 1u);
  EXPECT_EQ(store.find_leaf(map, 3), nullptr);
  ASSERT_NE(store.find_leaf(map, 2), nullptr);
  store.release(sibling);
  store.release(map);
  EXPECT_EQ(store.nodes_in_use(), 0u);
  EXPECT_EQ(store.estimates_in_use(), 0u);
}

}  // namespace
}  // namespace stereoscout::slam
