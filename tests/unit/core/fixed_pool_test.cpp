#include <gtest/gtest.h>

#include <vector>

#include "stereoscout/core/fixed_pool.hpp"
#include "stereoscout/core/shared_pool.hpp"

namespace stereoscout::core {
namespace {

struct Tracked {
  explicit Tracked(int v, int* live) : value(v), live_count(live) { ++*live_count; }
  ~Tracked() { --*live_count; }
  Tracked(const Tracked&) = delete;
  Tracked& operator=(const Tracked&) = delete;
  int value;
  int* live_count;
};

TEST(FixedPool, AcquireReleaseReusesSlotsAndCounts) {
  FixedPool<int> pool(3);
  const Handle<int> a = pool.acquire(1);
  const Handle<int> b = pool.acquire(2);
  ASSERT_TRUE(a);
  ASSERT_TRUE(b);
  EXPECT_EQ(pool.get(a), 1);
  EXPECT_EQ(pool.get(b), 2);
  EXPECT_EQ(pool.in_use(), 2u);
  pool.release(a);
  EXPECT_FALSE(pool.is_live(a));
  const Handle<int> c = pool.acquire(3);
  EXPECT_EQ(c.index, a.index);            // the freed slot is reused first
  EXPECT_NE(c.generation, a.generation);  // ... under a new generation
  const PoolStats stats = pool.stats();
  EXPECT_EQ(stats.capacity, 3u);
  EXPECT_EQ(stats.in_use, 2u);
  EXPECT_EQ(stats.high_water, 2u);
  EXPECT_EQ(stats.acquired, 3u);
  EXPECT_EQ(stats.exhausted, 0u);
}

TEST(FixedPool, ExhaustionReturnsNullHandleAndIsCounted) {
  FixedPool<int> pool(2);
  ASSERT_TRUE(pool.acquire(1));
  ASSERT_TRUE(pool.acquire(2));
  const Handle<int> refused = pool.acquire(3);
  EXPECT_TRUE(refused.is_null());
  EXPECT_FALSE(pool.acquire(4));
  EXPECT_EQ(pool.stats().exhausted, 2u);
  EXPECT_EQ(pool.stats().high_water, 2u);
  EXPECT_EQ(pool.available(), 0u);
}

TEST(FixedPool, ZeroCapacityPoolRefusesEverything) {
  FixedPool<int> pool(0);
  EXPECT_FALSE(pool.acquire(1));
  EXPECT_EQ(pool.stats().exhausted, 1u);
}

TEST(FixedPool, ConstructsAndDestroysObjects) {
  int live = 0;
  {
    FixedPool<Tracked> pool(4);
    const Handle<Tracked> a = pool.acquire(7, &live);
    pool.acquire(8, &live);
    EXPECT_EQ(live, 2);
    EXPECT_EQ(pool.get(a).value, 7);
    pool.release(a);
    EXPECT_EQ(live, 1);
  }
  EXPECT_EQ(live, 0);  // the pool's destructor destroys what is still live
}

TEST(FixedPool, HighWaterMarkSurvivesReleases) {
  FixedPool<int> pool(10);
  std::vector<Handle<int>> handles;
  for (int i = 0; i < 7; ++i) {
    handles.push_back(pool.acquire(i));
  }
  for (const Handle<int>& handle : handles) {
    pool.release(handle);
  }
  EXPECT_EQ(pool.in_use(), 0u);
  EXPECT_EQ(pool.stats().high_water, 7u);
}

TEST(FixedPool, NullHandleIsNeverLive) {
  FixedPool<int> pool(2);
  EXPECT_FALSE(pool.is_live(Handle<int>{}));
  EXPECT_FALSE(pool.is_live(Handle<int>{5, 1}));  // index out of range
}

#ifndef NDEBUG
using FixedPoolDeathTest = ::testing::Test;

TEST_F(FixedPoolDeathTest, UseAfterReleaseIsCaught) {
  FixedPool<int> pool(2);
  const Handle<int> handle = pool.acquire(1);
  pool.release(handle);
  EXPECT_DEATH(pool.get(handle), "not live");
}

TEST_F(FixedPoolDeathTest, StaleHandleToReusedSlotIsCaught) {
  FixedPool<int> pool(1);
  const Handle<int> old_handle = pool.acquire(1);
  pool.release(old_handle);
  const Handle<int> new_handle = pool.acquire(2);
  ASSERT_EQ(new_handle.index, old_handle.index);
  EXPECT_DEATH(pool.get(old_handle), "not live");
}

TEST_F(FixedPoolDeathTest, DoubleReleaseIsCaught) {
  FixedPool<int> pool(2);
  const Handle<int> handle = pool.acquire(1);
  pool.release(handle);
  EXPECT_DEATH(pool.release(handle), "not live");
}
#endif

// A persistent list built on SharedPool: the shape the landmark tree and trajectory tree use.
struct ListNode {
  int value;
  Handle<ListNode> next;
};

void release_list(SharedPool<ListNode>& pool, Handle<ListNode> head) {
  while (head) {
    Handle<ListNode> next;
    if (!pool.release(head, [&next](ListNode& node) { next = node.next; })) {
      return;  // still held elsewhere, and so is everything behind it
    }
    head = next;
  }
}

TEST(SharedPool, LastReleaseFreesAndSharedNodesSurvive) {
  SharedPool<ListNode> pool(8);
  // tail <- middle, shared by two heads.
  const Handle<ListNode> tail = pool.acquire(ListNode{3, {}});
  const Handle<ListNode> middle = pool.acquire(ListNode{2, tail});
  const Handle<ListNode> head_a = pool.acquire(ListNode{1, middle});
  pool.retain(middle);
  const Handle<ListNode> head_b = pool.acquire(ListNode{10, middle});
  EXPECT_EQ(pool.in_use(), 4u);
  EXPECT_EQ(pool.use_count(middle), 2u);
  EXPECT_TRUE(pool.is_shared(middle));

  release_list(pool, head_a);
  EXPECT_FALSE(pool.is_live(head_a));
  EXPECT_TRUE(pool.is_live(middle));
  EXPECT_TRUE(pool.is_live(tail));
  EXPECT_EQ(pool.use_count(middle), 1u);
  EXPECT_EQ(pool.in_use(), 3u);

  release_list(pool, head_b);
  EXPECT_EQ(pool.in_use(), 0u);  // exactly what no one holds is gone
}

TEST(SharedPool, ReleaseReportsWhetherObjectWasFreed) {
  SharedPool<int> pool(2);
  const Handle<int> handle = pool.acquire(5);
  pool.retain(handle);
  EXPECT_FALSE(pool.release(handle));
  EXPECT_TRUE(pool.release(handle));
  EXPECT_FALSE(pool.is_live(handle));
}

TEST(SharedPool, ExhaustionIsCounted) {
  SharedPool<int> pool(1);
  ASSERT_TRUE(pool.acquire(1));
  EXPECT_FALSE(pool.acquire(2));
  EXPECT_EQ(pool.stats().exhausted, 1u);
}

}  // namespace
}  // namespace stereoscout::core
