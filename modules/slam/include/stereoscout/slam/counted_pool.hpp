#pragma once
// CountedPool<T>: the landmark store's own fixed pool of reference-counted slots, named by a
// 32-bit index. It does what core::SharedPool does, in a layout made for the observation
// update, whose cost is memory traffic (docs/results.md, RBPF benchmark):
//   - a slot is named by its index alone (4 bytes, 0 is null), so a trie node's 8 children
//     fit in half a cache line; there is no generation to store or check on every get();
//   - reference counts sit in their own dense array, so retaining the 7 off-path siblings of
//     a copied node touches one or two cache lines, not seven nodes;
//   - every slot is built at start-up (all pages mapped before the first update) and free
//     slots are kept on a stack, so a release followed by an acquire reuses the warm slot.
// A stale index is not caught as a generation check would catch it; debug checks still catch
// a retain or release of a slot whose count is already zero.

#include <cstddef>
#include <cstdint>
#include <memory>

#include "stereoscout/core/check.hpp"
#include "stereoscout/core/fixed_pool.hpp"

namespace stereoscout::slam {

template <class T>
struct PoolIndex {
  std::uint32_t index = 0;  // 0 is never handed out: the null index

  constexpr explicit operator bool() const { return index != 0; }
  friend constexpr bool operator==(PoolIndex a, PoolIndex b) { return a.index == b.index; }
  friend constexpr bool operator!=(PoolIndex a, PoolIndex b) { return a.index != b.index; }
};

template <class T>
class CountedPool {
 public:
  explicit CountedPool(std::size_t capacity)
      : capacity_(capacity),
        slots_(new T[capacity + 1]),
        references_(new std::uint32_t[capacity + 1]()),
        free_stack_(new std::uint32_t[capacity]) {
    STEREOSCOUT_CHECK(capacity < 0xFFFFFFFFU, "pool capacity exceeds the 32-bit index range");
    // Lowest index on top, so a fresh pool hands out slots in address order.
    for (std::size_t i = 0; i < capacity; ++i) {
      free_stack_[i] = static_cast<std::uint32_t>(capacity - i);
    }
    free_count_ = capacity;
  }

  CountedPool(const CountedPool&) = delete;
  CountedPool& operator=(const CountedPool&) = delete;

  // A slot holding `value` with one reference, or null (counted) when the pool is full.
  PoolIndex<T> acquire(const T& value = T{}) {
    if (free_count_ == 0) {
      ++stats_.exhausted;
      return {};
    }
    const std::uint32_t index = free_stack_[--free_count_];
    if (free_count_ > kPrefetchDistance) {
      // The slot handed out a few acquisitions from now is rarely in cache: start fetching
      // it for writing now, so the copy into it does not wait (a hint, never a result).
      __builtin_prefetch(&slots_[free_stack_[free_count_ - kPrefetchDistance]], 1);
    }
    slots_[index] = value;
    references_[index] = 1;
    ++stats_.acquired;
    ++stats_.in_use;
    stats_.high_water = stats_.in_use > stats_.high_water ? stats_.in_use : stats_.high_water;
    return {index};
  }

  void retain(PoolIndex<T> slot) {
    STEREOSCOUT_DEBUG_CHECK(is_live(slot), "CountedPool::retain of a free slot");
    ++references_[slot.index];
  }

  // Drops one reference; on the last one `before_free` sees the object, then the slot is free.
  // Returns true when the object is gone.
  template <class BeforeFree>
  bool release(PoolIndex<T> slot, BeforeFree&& before_free) {
    STEREOSCOUT_DEBUG_CHECK(is_live(slot), "CountedPool::release of a free slot");
    if (--references_[slot.index] > 0) {
      return false;
    }
    before_free(slots_[slot.index]);
    free_stack_[free_count_++] = slot.index;
    --stats_.in_use;
    return true;
  }
  bool release(PoolIndex<T> slot) {
    return release(slot, [](T&) {});
  }

  T& get(PoolIndex<T> slot) {
    STEREOSCOUT_DEBUG_CHECK(slot.index != 0 && slot.index <= capacity_, "CountedPool::get out of range");
    return slots_[slot.index];
  }
  const T& get(PoolIndex<T> slot) const {
    STEREOSCOUT_DEBUG_CHECK(slot.index != 0 && slot.index <= capacity_, "CountedPool::get out of range");
    return slots_[slot.index];
  }
  std::uint32_t use_count(PoolIndex<T> slot) const { return references_[slot.index]; }
  bool is_shared(PoolIndex<T> slot) const { return references_[slot.index] > 1; }
  bool is_live(PoolIndex<T> slot) const {
    return slot.index != 0 && slot.index <= capacity_ && references_[slot.index] > 0;
  }

  std::size_t capacity() const { return capacity_; }
  std::size_t in_use() const { return stats_.in_use; }
  std::size_t available() const { return free_count_; }
  core::PoolStats stats() const {
    core::PoolStats copy = stats_;
    copy.capacity = capacity_;
    return copy;
  }

 private:
  static constexpr std::size_t kPrefetchDistance = 4;

  std::size_t capacity_;
  std::unique_ptr<T[]> slots_;                 // slot 0 unused
  std::unique_ptr<std::uint32_t[]> references_;
  std::unique_ptr<std::uint32_t[]> free_stack_;
  std::size_t free_count_ = 0;
  core::PoolStats stats_;
};

}  // namespace stereoscout::slam
