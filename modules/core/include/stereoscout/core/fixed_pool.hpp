#pragma once
// FixedPool<T>: a pool of T whose capacity is fixed when it is built (from config, at
// start-up); acquire and release are O(1) and never touch the heap.
//
// Objects are named by Handle<T> (slot index + generation). Every slot's generation is odd
// while the slot is live and even while it is free, so a handle kept after its object was
// released no longer matches and is caught by STEREOSCOUT_DEBUG_CHECK (use-after-release,
// double release). A full pool is an expected event: acquire() returns a null handle and
// the exhaustion counter grows; the caller degrades as the design says.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <utility>

#include "stereoscout/core/check.hpp"

namespace stereoscout::core {

template <class T>
struct Handle {
  std::uint32_t index = 0;
  std::uint32_t generation = 0;  // 0 is never live: the null handle

  constexpr bool is_null() const { return generation == 0; }
  constexpr explicit operator bool() const { return !is_null(); }
  friend constexpr bool operator==(Handle a, Handle b) {
    return a.index == b.index && a.generation == b.generation;
  }
  friend constexpr bool operator!=(Handle a, Handle b) { return !(a == b); }
};

struct PoolStats {
  std::size_t capacity = 0;
  std::size_t in_use = 0;
  std::size_t high_water = 0;    // most slots ever live at once
  std::uint64_t acquired = 0;    // successful acquisitions
  std::uint64_t exhausted = 0;   // acquisitions refused because the pool was full
};

template <class T>
class FixedPool {
 public:
  explicit FixedPool(std::size_t capacity)
      : capacity_(capacity),
        storage_(new Storage[capacity]),
        generation_(new std::uint32_t[capacity]()),
        next_free_(new std::uint32_t[capacity]) {
    STEREOSCOUT_CHECK(capacity < kEndOfList, "pool capacity exceeds the 32-bit handle range");
    for (std::size_t i = 0; i < capacity; ++i) {
      next_free_[i] = static_cast<std::uint32_t>(i + 1 < capacity ? i + 1 : kEndOfList);
    }
    free_head_ = capacity > 0 ? 0 : kEndOfList;
  }

  ~FixedPool() {
    for (std::size_t i = 0; i < capacity_; ++i) {
      if (is_live_slot(i)) {
        object_at(i)->~T();
      }
    }
  }

  FixedPool(const FixedPool&) = delete;
  FixedPool& operator=(const FixedPool&) = delete;

  // Builds a T in a free slot. Returns the null handle (and counts it) when the pool is full.
  template <class... Args>
  Handle<T> acquire(Args&&... args) {
    if (free_head_ == kEndOfList) {
      ++stats_.exhausted;
      return {};
    }
    const std::uint32_t index = free_head_;
    free_head_ = next_free_[index];
    new (object_at(index)) T(std::forward<Args>(args)...);
    std::uint32_t& generation = generation_[index];
    generation = generation + 1 == 0 ? 1 : generation + 1;  // odd: live
    ++stats_.acquired;
    ++stats_.in_use;
    if (stats_.in_use > stats_.high_water) {
      stats_.high_water = stats_.in_use;
    }
    return {index, generation};
  }

  void release(Handle<T> handle) {
    STEREOSCOUT_DEBUG_CHECK(is_live(handle), "FixedPool::release of a handle that is not live");
    object_at(handle.index)->~T();
    ++generation_[handle.index];  // even: free
    next_free_[handle.index] = free_head_;
    free_head_ = handle.index;
    --stats_.in_use;
  }

  T& get(Handle<T> handle) {
    STEREOSCOUT_DEBUG_CHECK(is_live(handle), "FixedPool::get of a handle that is not live");
    return *object_at(handle.index);
  }
  const T& get(Handle<T> handle) const {
    STEREOSCOUT_DEBUG_CHECK(is_live(handle), "FixedPool::get of a handle that is not live");
    return *object_at(handle.index);
  }

  bool is_live(Handle<T> handle) const {
    return !handle.is_null() && handle.index < capacity_ &&
           generation_[handle.index] == handle.generation && is_live_slot(handle.index);
  }

  std::size_t capacity() const { return capacity_; }
  std::size_t in_use() const { return stats_.in_use; }
  std::size_t available() const { return capacity_ - stats_.in_use; }
  PoolStats stats() const {
    PoolStats copy = stats_;
    copy.capacity = capacity_;
    return copy;
  }

 private:
  static constexpr std::uint32_t kEndOfList = std::numeric_limits<std::uint32_t>::max();
  struct Storage {
    alignas(T) unsigned char bytes[sizeof(T)];
  };

  bool is_live_slot(std::size_t index) const { return (generation_[index] & 1U) != 0; }
  T* object_at(std::size_t index) { return std::launder(reinterpret_cast<T*>(storage_[index].bytes)); }
  const T* object_at(std::size_t index) const {
    return std::launder(reinterpret_cast<const T*>(storage_[index].bytes));
  }

  std::size_t capacity_;
  std::unique_ptr<Storage[]> storage_;
  std::unique_ptr<std::uint32_t[]> generation_;
  std::unique_ptr<std::uint32_t[]> next_free_;
  std::uint32_t free_head_ = kEndOfList;
  PoolStats stats_;
};

}  // namespace stereoscout::core
