#pragma once
// Counts heap allocations, to prove that a block of code (a tick, an update) does not
// touch the heap. The functions below live in the library stereoscout::allocation_counter,
// which also replaces the global operator new/delete; only executables that want counting
// (the tests, the stereoscout command for report.json) link it.
//
//   AllocationScope scope;
//   run_one_tick();
//   EXPECT_EQ(scope.allocations(), 0u);

#include <cstdint>

namespace stereoscout::core {

struct AllocationCounts {
  std::uint64_t allocations = 0;
  std::uint64_t deallocations = 0;
  std::uint64_t bytes = 0;
};

// Totals since the program started, over all threads.
AllocationCounts allocation_totals();

class AllocationScope {
 public:
  AllocationScope() : start_(allocation_totals()) {}
  std::uint64_t allocations() const { return allocation_totals().allocations - start_.allocations; }
  std::uint64_t deallocations() const { return allocation_totals().deallocations - start_.deallocations; }
  std::uint64_t bytes() const { return allocation_totals().bytes - start_.bytes; }

 private:
  AllocationCounts start_;
};

}  // namespace stereoscout::core
