#include <gtest/gtest.h>

#include <cstdint>

#include "stereoscout/slam/counted_pool.hpp"

namespace stereoscout::slam {
namespace {

struct Item {
  int value = 0;
};

TEST(CountedPool, HandsOutSlotsInAddressOrderAndReusesTheLastReleased) {
  CountedPool<Item> pool(4);
  const PoolIndex<Item> a = pool.acquire(Item{10});
  const PoolIndex<Item> b = pool.acquire(Item{20});
  EXPECT_EQ(a.index, 1u);  // 0 is the null index
  EXPECT_EQ(b.index, 2u);
  EXPECT_EQ(pool.get(a).value, 10);
  EXPECT_EQ(pool.get(b).value, 20);
  EXPECT_TRUE(pool.release(a));
  const PoolIndex<Item> c = pool.acquire(Item{30});
  EXPECT_EQ(c.index, a.index);  // the warm slot comes back first
  EXPECT_EQ(pool.get(c).value, 30);
  EXPECT_EQ(pool.in_use(), 2u);
}

TEST(CountedPool, TheLastReferenceFreesAndTheCallbackSeesTheObjectFirst) {
  CountedPool<Item> pool(2);
  const PoolIndex<Item> a = pool.acquire(Item{7});
  pool.retain(a);
  EXPECT_EQ(pool.use_count(a), 2u);
  EXPECT_TRUE(pool.is_shared(a));
  int seen = 0;
  EXPECT_FALSE(pool.release(a, [&](Item& item) { seen = item.value; }));
  EXPECT_EQ(seen, 0);
  EXPECT_FALSE(pool.is_shared(a));
  EXPECT_TRUE(pool.release(a, [&](Item& item) { seen = item.value; }));
  EXPECT_EQ(seen, 7);
  EXPECT_FALSE(pool.is_live(a));
  EXPECT_EQ(pool.in_use(), 0u);
}

TEST(CountedPool, AFullPoolReturnsNullAndCountsIt) {
  CountedPool<Item> pool(2);
  ASSERT_TRUE(pool.acquire());
  ASSERT_TRUE(pool.acquire());
  EXPECT_EQ(pool.available(), 0u);
  EXPECT_FALSE(pool.acquire());
  const core::PoolStats stats = pool.stats();
  EXPECT_EQ(stats.capacity, 2u);
  EXPECT_EQ(stats.in_use, 2u);
  EXPECT_EQ(stats.high_water, 2u);
  EXPECT_EQ(stats.acquired, 2u);
  EXPECT_EQ(stats.exhausted, 1u);
}

}  // namespace
}  // namespace stereoscout::slam
