#include <gtest/gtest.h>

#include <vector>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/core/random.hpp"
#include "stereoscout/vision/descriptor_index.hpp"

namespace stereoscout::vision {
namespace {

using Outcome = IndexLookup::Outcome;

Descriptor random_descriptor(core::RandomStream& random) {
  Descriptor descriptor{};
  for (auto& value : descriptor) {
    value = static_cast<std::uint8_t>(random.uniform_index(64));
  }
  return descriptor;
}

Descriptor noisy_copy(const Descriptor& source, core::RandomStream& random, int amplitude) {
  Descriptor copy = source;
  for (auto& value : copy) {
    const int noisy = static_cast<int>(value) + static_cast<int>(random.uniform_index(static_cast<std::uint32_t>(2 * amplitude + 1))) - amplitude;
    value = static_cast<std::uint8_t>(std::clamp(noisy, 0, 255));
  }
  return copy;
}

std::vector<Descriptor> random_set(std::size_t count, std::uint32_t seed) {
  core::RandomStream random(seed, core::StreamId{0, 0, 0});
  std::vector<Descriptor> set(count);
  for (auto& descriptor : set) {
    descriptor = random_descriptor(random);
  }
  return set;
}

DescriptorIndexParams params(std::size_t capacity, int leaf_checks, int min_frames) {
  DescriptorIndexParams p;
  p.capacity = capacity;
  p.max_leaf_checks = leaf_checks;
  p.candidate_min_frames = min_frames;
  p.match_distance = 100.0;
  return p;
}

TEST(DescriptorIndex, EnoughLeafChecksGiveTheExactNearestNeighbour) {
  const std::vector<Descriptor> stored = random_set(3000, 1);
  DescriptorIndex index(params(4000, 100000, 1));
  for (std::size_t i = 0; i < stored.size(); ++i) {
    ASSERT_EQ(index.observe(stored[i], i).outcome, Outcome::landmark);
  }
  EXPECT_EQ(index.size(), stored.size());
  const std::vector<Descriptor> queries = random_set(100, 2);
  for (const Descriptor& query : queries) {
    std::uint32_t best = 0;
    std::uint32_t best_distance = std::numeric_limits<std::uint32_t>::max();
    for (std::uint32_t i = 0; i < stored.size(); ++i) {
      const std::uint32_t distance = descriptor_distance_squared(query, stored[i]);
      if (distance < best_distance) {
        best_distance = distance;
        best = i;
      }
    }
    const IndexNeighbour found = index.nearest(query);
    ASSERT_TRUE(found.found);
    EXPECT_EQ(found.distance_squared, best_distance);
    EXPECT_EQ(found.entry, best);  // entries fill slots in insertion order
  }
}

TEST(DescriptorIndex, BoundedBestBinFirstFindsNoisyCopies) {
  const std::vector<Descriptor> stored = random_set(20000, 3);
  DescriptorIndex index(params(20000, 64, 1));
  for (std::size_t i = 0; i < stored.size(); ++i) {
    index.observe(stored[i], 0);
  }
  core::RandomStream random(4, core::StreamId{0, 0, 0});
  int found = 0;
  const int queries = 500;
  for (int q = 0; q < queries; ++q) {
    const std::uint32_t target = random.uniform_index(static_cast<std::uint32_t>(stored.size()));
    const IndexLookup lookup = index.observe(noisy_copy(stored[target], random, 3), 1);
    found += lookup.outcome == Outcome::landmark && lookup.entry == target ? 1 : 0;
  }
  EXPECT_GE(found, queries * 95 / 100);
  // Bounded work: never more than 64 leaves per search.
  EXPECT_LE(index.stats().leaves_checked, index.stats().lookups * 64U);
}

DescriptorIndexParams box_params(std::size_t capacity, int leaf_checks) {
  DescriptorIndexParams p = params(capacity, leaf_checks, 1);
  p.box_distance = true;
  return p;
}

std::uint32_t brute_force_nearest(const std::vector<Descriptor>& stored, const Descriptor& query) {
  std::uint32_t best = 0;
  for (std::uint32_t i = 1; i < stored.size(); ++i) {
    if (descriptor_distance_squared(query, stored[i]) < descriptor_distance_squared(query, stored[best])) {
      best = i;
    }
  }
  return best;
}

TEST(DescriptorIndex, BoxDistanceGivesTheExactNearestNeighbour) {
  const std::vector<Descriptor> stored = random_set(3000, 1);
  DescriptorIndex index(box_params(4000, 100000));
  for (std::size_t i = 0; i < stored.size(); ++i) {
    index.observe(stored[i], i);
  }
  core::RandomStream random(5, core::StreamId{0, 0, 0});
  for (int q = 0; q < 100; ++q) {
    // Half the queries are noisy copies (a neighbour near), half random (none near).
    const Descriptor query = q % 2 == 0 ? noisy_copy(stored[random.uniform_index(3000)], random, 20)
                                        : random_descriptor(random);
    const std::uint32_t best = brute_force_nearest(stored, query);
    const IndexNeighbour found = index.nearest(query);
    ASSERT_TRUE(found.found);
    EXPECT_EQ(found.distance_squared, descriptor_distance_squared(query, stored[best]));
  }
}

TEST(DescriptorIndex, BoxDistanceIsExactWhereItsBoundsPrune) {
  // Descriptors spread over 4 dimensions only: the cells' bounds become tight, so a wrong
  // bound would cut off the nearest entry, and the search must end long before every leaf.
  core::RandomStream random(10, core::StreamId{0, 0, 0});
  std::vector<Descriptor> stored(3000);
  for (Descriptor& d : stored) {
    d.fill(0);
    for (std::size_t k = 0; k < 4; ++k) d[k] = static_cast<std::uint8_t>(random.uniform_index(256));
  }
  DescriptorIndexParams p = box_params(4000, 100000);
  p.match_distance = 1.0;  // near neighbours in 4 dimensions: every key must be stored
  DescriptorIndex index(p);
  for (std::size_t i = 0; i < stored.size(); ++i) {
    index.observe(stored[i], i);
  }
  ASSERT_EQ(index.size(), stored.size());
  const std::uint64_t leaves_before = index.stats().leaves_checked;
  for (int q = 0; q < 100; ++q) {
    Descriptor query{};
    for (std::size_t k = 0; k < 4; ++k) query[k] = static_cast<std::uint8_t>(random.uniform_index(256));
    const IndexNeighbour found = index.nearest(query);
    ASSERT_TRUE(found.found);
    EXPECT_EQ(found.distance_squared, descriptor_distance_squared(query, stored[brute_force_nearest(stored, query)]));
  }
  EXPECT_LT(index.stats().leaves_checked - leaves_before, 100U * 20U);  // of about 250 leaves
}

TEST(DescriptorIndex, BoxDistanceSearchStopsAtTheMatchDistance) {
  const std::vector<Descriptor> stored = random_set(3000, 1);
  DescriptorIndex by_gap(params(4000, 100000, 1));
  DescriptorIndex by_box(box_params(4000, 100000));
  for (std::size_t i = 0; i < stored.size(); ++i) {
    by_gap.observe(stored[i], i);
    by_box.observe(stored[i], i);
  }
  // Stored bytes lie in 0..63; keys of bytes 128..191 are at least 64 * sqrt(128) = 724 away,
  // far past the match distance (100 here): each becomes a new entry.
  core::RandomStream random(6, core::StreamId{0, 0, 0});
  const std::uint64_t gap_leaves_before = by_gap.stats().leaves_checked;
  const std::uint64_t box_leaves_before = by_box.stats().leaves_checked;
  for (int q = 0; q < 50; ++q) {
    Descriptor far = random_descriptor(random);
    for (auto& value : far) value = static_cast<std::uint8_t>(value + 128);
    const auto frame = 3000 + static_cast<std::uint64_t>(q);
    EXPECT_EQ(by_gap.observe(far, frame).outcome, Outcome::landmark);  // promoted at once
    EXPECT_EQ(by_box.observe(far, frame).outcome, Outcome::landmark);
  }
  EXPECT_EQ(by_box.stats().matched, 0U);
  // The largest gap never reaches the match distance's square, so that search runs through
  // every leaf; the box distance leaves out every cell past the match distance.
  const std::uint64_t gap_leaves = by_gap.stats().leaves_checked - gap_leaves_before;
  const std::uint64_t box_leaves = by_box.stats().leaves_checked - box_leaves_before;
  EXPECT_LT(box_leaves * 10, gap_leaves) << "box " << box_leaves << ", largest gap " << gap_leaves;
}

TEST(DescriptorIndex, BoxDistanceFindsKeysNearTheMatchDistanceAtLeastAsOften) {
  const std::vector<Descriptor> stored = random_set(20000, 3);
  DescriptorIndex by_gap(params(20000, 64, 1));
  DescriptorIndex by_box(box_params(20000, 64));
  for (std::size_t i = 0; i < stored.size(); ++i) {
    by_gap.observe(stored[i], 0);
    by_box.observe(stored[i], 0);
  }
  core::RandomStream random(4, core::StreamId{0, 0, 0});
  int found_by_gap = 0;
  int found_by_box = 0;
  for (int q = 0; q < 500; ++q) {
    const std::uint32_t target = random.uniform_index(static_cast<std::uint32_t>(stored.size()));
    // About 135 from the source (12 per byte), as a key seen from elsewhere, under the
    // front end's match distance of 180; other entries lie about 295 away.
    const Descriptor query = noisy_copy(stored[target], random, 20);
    found_by_gap += by_gap.nearest(query).entry == target ? 1 : 0;
    found_by_box += by_box.nearest(query, 180 * 180).entry == target ? 1 : 0;
  }
  EXPECT_GT(found_by_box, found_by_gap) << "box " << found_by_box << ", largest gap " << found_by_gap;
  EXPECT_GE(found_by_box, 500 * 80 / 100) << found_by_box;
  EXPECT_LE(by_box.stats().leaves_checked, by_box.stats().lookups * 64U);
}

TEST(DescriptorIndex, CandidateBecomesLandmarkAfterEnoughFrames) {
  const std::vector<Descriptor> keys = random_set(2, 5);
  DescriptorIndex index(params(100, 64, 3));
  EXPECT_EQ(index.observe(keys[0], 10).outcome, Outcome::new_candidate);
  // Seen again in the same frame: still one frame.
  EXPECT_EQ(index.observe(keys[0], 10).outcome, Outcome::candidate);
  EXPECT_EQ(index.observe(keys[0], 11).outcome, Outcome::candidate);
  EXPECT_EQ(index.observe(keys[1], 11).outcome, Outcome::new_candidate);
  const IndexLookup third = index.observe(keys[0], 12);
  EXPECT_EQ(third.outcome, Outcome::landmark);
  EXPECT_EQ(third.landmark_id, 1U);
  EXPECT_EQ(index.observe(keys[0], 13).landmark_id, 1U);
  index.observe(keys[1], 13);
  const IndexLookup other = index.observe(keys[1], 14);
  EXPECT_EQ(other.outcome, Outcome::landmark);
  EXPECT_EQ(other.landmark_id, 2U);
  EXPECT_EQ(index.stats().promoted, 2U);
  EXPECT_EQ(index.stats().landmarks, 2U);
  EXPECT_EQ(index.stats().candidates, 0U);
}

TEST(DescriptorIndex, FullIndexEvictsStaleCandidatesNeverLandmarks) {
  const std::vector<Descriptor> keys = random_set(40, 6);
  DescriptorIndex index(params(16, 64, 2));
  // Ten landmarks (each seen in frames 0 and 1).
  for (std::uint64_t frame = 0; frame < 2; ++frame) {
    for (std::size_t i = 0; i < 10; ++i) index.observe(keys[i], frame);
  }
  // Six candidates, one per frame 2..7, so keys[10] is the stalest.
  for (std::size_t i = 10; i < 16; ++i) {
    EXPECT_EQ(index.observe(keys[i], i - 8).outcome, Outcome::new_candidate);
  }
  EXPECT_EQ(index.size(), 16U);
  index.observe(keys[11], 8);  // keys[11] refreshed: keys[10] is now the stalest
  EXPECT_EQ(index.observe(keys[16], 9).outcome, Outcome::new_candidate);
  EXPECT_EQ(index.stats().evicted, 1U);
  EXPECT_EQ(index.observe(keys[10], 9).outcome, Outcome::new_candidate);  // it was gone
  EXPECT_EQ(index.observe(keys[11], 9).outcome, Outcome::landmark);        // still there
  // Fill frame 20 with new keys: candidates from older frames go first, then refusals.
  std::size_t refused = 0;
  for (std::size_t i = 17; i < 40; ++i) {
    refused += index.observe(keys[i], 20).outcome == Outcome::refused ? 1U : 0U;
  }
  EXPECT_GT(refused, 0U);
  EXPECT_EQ(index.stats().refused, refused);
  for (std::size_t i = 0; i < 10; ++i) {
    const IndexLookup lookup = index.observe(keys[i], 21);
    EXPECT_EQ(lookup.outcome, Outcome::landmark);
    EXPECT_EQ(lookup.landmark_id, static_cast<std::uint32_t>(i + 1));
  }
}

TEST(DescriptorIndex, ChurnRebuildsTreeWithoutAllocatingOrLosingEntries) {
  const std::vector<Descriptor> keys = random_set(6000, 7);
  for (const bool box_distance : {false, true}) {
    SCOPED_TRACE(box_distance ? "box distance" : "largest gap");
    DescriptorIndexParams p = params(256, 100000, 2);
    p.bucket_size = 4;
    p.box_distance = box_distance;  // its cells come from the parents, which rebuilds renew
    DescriptorIndex index(p);
    const core::AllocationScope scope;
    for (std::size_t i = 0; i < keys.size(); ++i) {
      index.observe(keys[i], i);  // every key a fresh candidate in its own frame: constant eviction
    }
    EXPECT_EQ(scope.allocations(), 0U);
    EXPECT_EQ(index.size(), 256U);
    EXPECT_EQ(index.stats().evicted, keys.size() - 256U);
    EXPECT_GT(index.stats().rebuilds, 0U);
    // The 256 newest keys are all still found exactly.
    for (std::size_t i = keys.size() - 256; i < keys.size(); ++i) {
      const IndexNeighbour neighbour = index.nearest(keys[i]);
      ASSERT_TRUE(neighbour.found);
      EXPECT_EQ(neighbour.distance_squared, 0U);
    }
    // Keys that match none exactly get the true nearest too: the box distance's cells, rebuilt
    // from the parent links, must still bound the entries after the rebuilds.
    const std::vector<Descriptor> live(keys.end() - 256, keys.end());
    for (const Descriptor& query : random_set(50, 9)) {
      const IndexNeighbour neighbour = index.nearest(query);
      ASSERT_TRUE(neighbour.found);
      EXPECT_EQ(neighbour.distance_squared, descriptor_distance_squared(query, live[brute_force_nearest(live, query)]));
    }
  }
}

TEST(DescriptorIndex, SameInputsGiveSameIdentities) {
  const std::vector<Descriptor> keys = random_set(500, 8);
  core::RandomStream random(9, core::StreamId{0, 0, 0});
  std::vector<std::pair<std::uint32_t, std::uint64_t>> sequence;
  for (int i = 0; i < 3000; ++i) {
    sequence.emplace_back(random.uniform_index(500), static_cast<std::uint64_t>(i / 50));
  }
  std::vector<std::uint32_t> first;
  std::vector<std::uint32_t> second;
  for (auto* out : {&first, &second}) {
    DescriptorIndex index(params(300, 32, 3));
    core::RandomStream noise(10, core::StreamId{0, 0, 0});
    for (const auto& [key, frame] : sequence) {
      const IndexLookup lookup = index.observe(noisy_copy(keys[key], noise, 2), frame);
      out->push_back(lookup.landmark_id * 4U + static_cast<std::uint32_t>(lookup.outcome));
    }
  }
  EXPECT_EQ(first, second);
}

}  // namespace
}  // namespace stereoscout::vision
