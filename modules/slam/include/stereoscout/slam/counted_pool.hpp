#pragma once
// CountedPool<T>: the landmark store's own fixed pool of reference-counted slots, named by a
// 32-bit index. It does what core::SharedPool does, in a layout made for the observation
// update, whose cost is memory traffic (docs/results.md, RBPF benchmark):
//   - a slot is named by its index alone (4 bytes, 0 is null), so a trie node's 8 children
//     fit in half a cache line; there is no generation to store or check on every get();
//   - reference counts sit in their own dense array, so retaining the 7 off-path siblings of
//     a copied node touches one or two cache lines, not seven nodes;
//   - free slots are kept on a stack, so a release followed by an acquire reuses the warm
//     slot, and the slot that comes a few acquisitions later is prefetched for writing.
// Like core::FixedPool, the storage is reserved at start-up but an object is built in a slot
// only when the slot is handed out, so untouched capacity costs no physical memory.
// A stale index is not caught as a generation check would catch it; debug checks still catch
// a retain or release of a slot whose count is already zero.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>

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
  // Slots are reused without running destructors in between.
  static_assert(std::is_trivially_destructible_v<T>, "CountedPool holds trivially destructible objects");

 public:
  explicit CountedPool(std::size_t capacity)
      : capacity_(capacity),
        storage_(new Storage[capacity + 1]),
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
      __builtin_prefetch(storage_[free_stack_[free_count_ - kPrefetchDistance]].bytes, 1);
    }
    new (storage_[index].bytes) T(value);
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
    before_free(*object_at(slot.index));
    free_stack_[free_count_++] = slot.index;
    --stats_.in_use;
    return true;
  }
  bool release(PoolIndex<T> slot) {
    return release(slot, [](T&) {});
  }

  T& get(PoolIndex<T> slot) {
    STEREOSCOUT_DEBUG_CHECK(slot.index != 0 && slot.index <= capacity_, "CountedPool::get out of range");
    return *object_at(slot.index);
  }
  const T& get(PoolIndex<T> slot) const {
    STEREOSCOUT_DEBUG_CHECK(slot.index != 0 && slot.index <= capacity_, "CountedPool::get out of range");
    return *object_at(slot.index);
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
  struct Storage {
    alignas(T) unsigned char bytes[sizeof(T)];
  };

  T* object_at(std::size_t index) { return std::launder(reinterpret_cast<T*>(storage_[index].bytes)); }
  const T* object_at(std::size_t index) const {
    return std::launder(reinterpret_cast<const T*>(storage_[index].bytes));
  }

  std::size_t capacity_;
  std::unique_ptr<Storage[]> storage_;  // slot 0 unused
  std::unique_ptr<std::uint32_t[]> references_;
  std::unique_ptr<std::uint32_t[]> free_stack_;
  std::size_t free_count_ = 0;
  core::PoolStats stats_;
};

}  // namespace stereoscout::slam
