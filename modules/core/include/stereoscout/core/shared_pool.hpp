#pragma once
// SharedPool<T>: a FixedPool whose objects carry an intrusive reference count, for data
// that many owners share and nobody copies: nodes of the persistent landmark tree
// (FastSLAM), nodes of the particles' trajectory tree, grids in the occupancy cache.
//
// acquire() hands out the first reference. retain() adds one, release() drops one; when the
// last goes, the optional before_free callback sees the object first, so a tree node can
// release its children, and then the slot returns to the pool.

#include <cstdint>
#include <memory>

#include "stereoscout/core/fixed_pool.hpp"

namespace stereoscout::core {

template <class T>
class SharedPool {
 public:
  explicit SharedPool(std::size_t capacity)
      : pool_(capacity), reference_count_(new std::uint32_t[capacity]()) {}

  template <class... Args>
  Handle<T> acquire(Args&&... args) {
    Handle<T> handle = pool_.acquire(std::forward<Args>(args)...);
    if (handle) {
      reference_count_[handle.index] = 1;
    }
    return handle;
  }

  void retain(Handle<T> handle) {
    STEREOSCOUT_DEBUG_CHECK(pool_.is_live(handle), "SharedPool::retain of a handle that is not live");
    ++reference_count_[handle.index];
  }

  // Drops one reference. Returns true when that was the last one and the object is gone.
  template <class BeforeFree>
  bool release(Handle<T> handle, BeforeFree&& before_free) {
    STEREOSCOUT_DEBUG_CHECK(pool_.is_live(handle), "SharedPool::release of a handle that is not live");
    std::uint32_t& count = reference_count_[handle.index];
    if (--count > 0) {
      return false;
    }
    before_free(pool_.get(handle));
    pool_.release(handle);
    return true;
  }
  bool release(Handle<T> handle) {
    return release(handle, [](T&) {});
  }

  std::uint32_t use_count(Handle<T> handle) const {
    STEREOSCOUT_DEBUG_CHECK(pool_.is_live(handle), "SharedPool::use_count of a handle that is not live");
    return reference_count_[handle.index];
  }
  bool is_shared(Handle<T> handle) const { return use_count(handle) > 1; }

  T& get(Handle<T> handle) { return pool_.get(handle); }
  const T& get(Handle<T> handle) const { return pool_.get(handle); }
  bool is_live(Handle<T> handle) const { return pool_.is_live(handle); }

  std::size_t capacity() const { return pool_.capacity(); }
  std::size_t in_use() const { return pool_.in_use(); }
  PoolStats stats() const { return pool_.stats(); }

 private:
  FixedPool<T> pool_;
  std::unique_ptr<std::uint32_t[]> reference_count_;
};

}  // namespace stereoscout::core
