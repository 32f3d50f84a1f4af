#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "stereoscout/core/allocation_counter.hpp"

namespace stereoscout::core {
namespace {

TEST(AllocationCounter, CountsEveryKindOfNew) {
  AllocationScope scope;
  auto single = std::make_unique<int>(5);
  auto array = std::make_unique<double[]>(16);
  struct alignas(64) Aligned {
    double values[8];
  };
  auto aligned = std::make_unique<Aligned>();
  std::vector<int> vector(100);
  EXPECT_EQ(scope.allocations(), 4u);
  EXPECT_GE(scope.bytes(), sizeof(int) + 16 * sizeof(double) + sizeof(Aligned) + 100 * sizeof(int));
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(aligned.get()) % 64, 0u);
  single.reset();
  array.reset();
  EXPECT_EQ(scope.deallocations(), 2u);
}

TEST(AllocationCounter, ScopeSeesNothingWhenNothingAllocates) {
  std::vector<int> vector;
  vector.reserve(64);
  AllocationScope scope;
  for (int i = 0; i < 64; ++i) {
    vector.push_back(i);
  }
  EXPECT_EQ(scope.allocations(), 0u);
  vector.push_back(64);  // grows: this one is seen
  EXPECT_EQ(scope.allocations(), 1u);
}

}  // namespace
}  // namespace stereoscout::core
