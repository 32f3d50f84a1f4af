#include <gtest/gtest.h>

#include <string>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/core/ring_buffer.hpp"

namespace stereoscout::core {
namespace {

TEST(FixedVector, RefusesWhenFullAndCountsOverflows) {
  FixedVector<int> vector(3);
  EXPECT_TRUE(vector.push_back(1));
  EXPECT_TRUE(vector.push_back(2));
  EXPECT_TRUE(vector.push_back(3));
  EXPECT_TRUE(vector.full());
  EXPECT_FALSE(vector.push_back(4));
  EXPECT_EQ(vector.emplace_back(5), nullptr);
  EXPECT_EQ(vector.overflows(), 2u);
  EXPECT_EQ(vector.size(), 3u);
  int sum = 0;
  for (int value : vector) {
    sum += value;
  }
  EXPECT_EQ(sum, 6);
}

TEST(FixedVector, HoldsNonTrivialTypesAndDestroysThem) {
  FixedVector<std::string> vector(2);
  vector.emplace_back(std::string(40, 'x'));
  vector.emplace_back("short");
  EXPECT_EQ(vector[0].size(), 40u);
  vector.pop_back();
  EXPECT_EQ(vector.size(), 1u);
  vector.clear();
  EXPECT_TRUE(vector.empty());
}

TEST(FixedVector, SwapExchangesContentsAndCapacitiesWithoutAllocating) {
  FixedVector<int> small(2);
  FixedVector<int> large(5);
  small.push_back(1);
  small.push_back(2);
  small.push_back(3);  // refused, counted
  large.push_back(7);
  {
    AllocationScope scope;
    small.swap(large);
    EXPECT_EQ(scope.allocations(), 0u);
  }
  ASSERT_EQ(small.size(), 1u);
  EXPECT_EQ(small[0], 7);
  EXPECT_EQ(small.capacity(), 5u);
  EXPECT_EQ(small.overflows(), 0u);
  ASSERT_EQ(large.size(), 2u);
  EXPECT_EQ(large[1], 2);
  EXPECT_EQ(large.capacity(), 2u);
  EXPECT_EQ(large.overflows(), 1u);
}

TEST(FixedVector, NoHeapAllocationAfterConstruction) {
  FixedVector<int> vector(100);
  AllocationScope scope;
  for (int round = 0; round < 3; ++round) {
    for (int i = 0; i < 150; ++i) {
      vector.push_back(i);
    }
    vector.clear();
  }
  EXPECT_EQ(scope.allocations(), 0u);
}

TEST(StaticVector, InlineCapacityAndSwapRemove) {
  StaticVector<int, 4> vector;
  for (int i = 0; i < 6; ++i) {
    vector.push_back(i);
  }
  EXPECT_EQ(vector.size(), 4u);
  vector.swap_remove(1);
  ASSERT_EQ(vector.size(), 3u);
  EXPECT_EQ(vector[0], 0);
  EXPECT_EQ(vector[1], 3);
  EXPECT_EQ(vector[2], 2);
  EXPECT_EQ((StaticVector<int, 4>::capacity()), 4u);
}

TEST(RingBuffer, TryPushRefusesWhenFull) {
  RingBuffer<int> ring(2);
  EXPECT_TRUE(ring.try_push(1));
  EXPECT_TRUE(ring.try_push(2));
  EXPECT_FALSE(ring.try_push(3));
  EXPECT_EQ(ring.rejected(), 1u);
  EXPECT_EQ(ring.front(), 1);
  EXPECT_EQ(ring.back(), 2);
}

TEST(RingBuffer, OverwriteDropsOldestAndKeepsOrder) {
  RingBuffer<int> ring(3);
  for (int i = 1; i <= 5; ++i) {
    ring.push_overwrite(i);
  }
  ASSERT_EQ(ring.size(), 3u);
  EXPECT_EQ(ring[0], 3);
  EXPECT_EQ(ring[1], 4);
  EXPECT_EQ(ring[2], 5);
  EXPECT_EQ(ring.overwritten(), 2u);
  EXPECT_EQ(ring.pushed(), 5u);
  ring.pop_front();
  EXPECT_EQ(ring.front(), 4);
  ring.push_overwrite(6);
  EXPECT_EQ(ring.back(), 6);
  EXPECT_EQ(ring.overwritten(), 2u);  // there was room again
}

TEST(RingBuffer, SlotsAreReusedWithoutAllocation) {
  RingBuffer<std::string> ring(4);
  for (std::size_t i = 0; i < 4; ++i) {
    ring.next_slot_overwrite().assign(64, 'a');  // each slot gets its buffer once
  }
  AllocationScope scope;
  for (int i = 0; i < 100; ++i) {
    ring.next_slot_overwrite().assign(64, 'b');
  }
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_EQ(ring.front(), std::string(64, 'b'));
}

}  // namespace
}  // namespace stereoscout::core
