#pragma once
// RingBuffer<T>: a FIFO of fixed capacity (chosen at start-up) over storage allocated once.
// T must be default-constructible and assignable; slots are reused, never reallocated, so a
// T that owns a preallocated buffer (an image, a depth scan) keeps it across reuse.
//
// Two ways to add when full, chosen by the caller because the right degradation differs:
// try_push() refuses and counts a rejection (a log writer must not lose old records
// silently); push_overwrite() drops the oldest and counts it (a history of depth scans).

#include <cstddef>
#include <cstdint>
#include <memory>

#include "stereoscout/core/check.hpp"

namespace stereoscout::core {

template <class T>
class RingBuffer {
 public:
  explicit RingBuffer(std::size_t capacity) : capacity_(capacity), slots_(new T[capacity]()) {
    STEREOSCOUT_CHECK(capacity > 0, "RingBuffer needs a capacity of at least one");
  }

  bool try_push(const T& value) {
    if (full()) {
      ++rejected_;
      return false;
    }
    slot(size_) = value;
    ++size_;
    ++pushed_;
    return true;
  }

  void push_overwrite(const T& value) { next_slot_overwrite() = value; }

  // The slot the next element goes into, for filling in place without a copy. When full,
  // the oldest element is dropped (counted) to make room.
  T& next_slot_overwrite() {
    if (full()) {
      head_ = (head_ + 1) % capacity_;
      --size_;
      ++overwritten_;
    }
    T& target = slot(size_);
    ++size_;
    ++pushed_;
    return target;
  }

  void pop_front() {
    STEREOSCOUT_DEBUG_CHECK(size_ > 0, "RingBuffer::pop_front on an empty buffer");
    head_ = (head_ + 1) % capacity_;
    --size_;
  }
  void clear() {
    head_ = 0;
    size_ = 0;
  }

  // i = 0 is the oldest element.
  T& operator[](std::size_t i) {
    STEREOSCOUT_DEBUG_CHECK(i < size_, "RingBuffer index out of range");
    return slot(i);
  }
  const T& operator[](std::size_t i) const {
    STEREOSCOUT_DEBUG_CHECK(i < size_, "RingBuffer index out of range");
    return slots_[(head_ + i) % capacity_];
  }
  T& front() { return (*this)[0]; }
  T& back() { return (*this)[size_ - 1]; }
  const T& front() const { return (*this)[0]; }
  const T& back() const { return (*this)[size_ - 1]; }

  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == capacity_; }
  std::uint64_t pushed() const { return pushed_; }        // every element ever added
  std::uint64_t rejected() const { return rejected_; }    // try_push refusals
  std::uint64_t overwritten() const { return overwritten_; }  // oldest dropped by overwrite

 private:
  T& slot(std::size_t i) { return slots_[(head_ + i) % capacity_]; }

  std::size_t capacity_;
  std::unique_ptr<T[]> slots_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  std::uint64_t pushed_ = 0;
  std::uint64_t rejected_ = 0;
  std::uint64_t overwritten_ = 0;
};

}  // namespace stereoscout::core
