#pragma once
// Containers that never grow after they are built.
//
// FixedVector<T>: capacity chosen at start-up (from config), storage allocated once in the
//   constructor. push_back on a full vector refuses, returns false and counts an overflow.
// StaticVector<T, N>: capacity in the type, storage inline (no heap at all); for short
//   lists inside other objects, such as the few spatially distinct estimates of a landmark.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>

#include "stereoscout/core/check.hpp"

namespace stereoscout::core {

template <class T>
class FixedVector {
 public:
  explicit FixedVector(std::size_t capacity) : capacity_(capacity), storage_(new Storage[capacity]) {}
  ~FixedVector() { clear(); }
  FixedVector(const FixedVector&) = delete;
  FixedVector& operator=(const FixedVector&) = delete;

  bool push_back(const T& value) { return emplace_back(value) != nullptr; }

  // Returns the new element, or nullptr (counted) when the vector is full.
  template <class... Args>
  T* emplace_back(Args&&... args) {
    if (size_ == capacity_) {
      ++overflows_;
      return nullptr;
    }
    T* element = new (storage_[size_].bytes) T(std::forward<Args>(args)...);
    ++size_;
    return element;
  }

  void pop_back() {
    STEREOSCOUT_DEBUG_CHECK(size_ > 0, "FixedVector::pop_back on an empty vector");
    --size_;
    data()[size_].~T();
  }

  void clear() {
    while (size_ > 0) {
      pop_back();
    }
  }

  T& operator[](std::size_t i) {
    STEREOSCOUT_DEBUG_CHECK(i < size_, "FixedVector index out of range");
    return data()[i];
  }
  const T& operator[](std::size_t i) const {
    STEREOSCOUT_DEBUG_CHECK(i < size_, "FixedVector index out of range");
    return data()[i];
  }
  T& back() { return (*this)[size_ - 1]; }
  const T& back() const { return (*this)[size_ - 1]; }

  T* data() { return std::launder(reinterpret_cast<T*>(storage_.get())); }
  const T* data() const { return std::launder(reinterpret_cast<const T*>(storage_.get())); }
  T* begin() { return data(); }
  T* end() { return data() + size_; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size_; }

  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == capacity_; }
  std::uint64_t overflows() const { return overflows_; }

  // Exchanges the two vectors' storage: no element is copied and nothing is allocated.
  void swap(FixedVector& other) noexcept {
    std::swap(capacity_, other.capacity_);
    storage_.swap(other.storage_);
    std::swap(size_, other.size_);
    std::swap(overflows_, other.overflows_);
  }

 private:
  struct Storage {
    alignas(T) unsigned char bytes[sizeof(T)];
  };
  std::size_t capacity_;
  std::unique_ptr<Storage[]> storage_;
  std::size_t size_ = 0;
  std::uint64_t overflows_ = 0;
};

// Inline storage; T must be default-constructible and copyable (plain data).
template <class T, std::size_t N>
class StaticVector {
 public:
  bool push_back(const T& value) {
    if (size_ == N) {
      return false;
    }
    items_[size_++] = value;
    return true;
  }
  void pop_back() {
    STEREOSCOUT_DEBUG_CHECK(size_ > 0, "StaticVector::pop_back on an empty vector");
    --size_;
  }
  // Removes element i by moving the last element into its place (order not kept).
  void swap_remove(std::size_t i) {
    STEREOSCOUT_DEBUG_CHECK(i < size_, "StaticVector index out of range");
    items_[i] = items_[size_ - 1];
    --size_;
  }
  void clear() { size_ = 0; }

  T& operator[](std::size_t i) {
    STEREOSCOUT_DEBUG_CHECK(i < size_, "StaticVector index out of range");
    return items_[i];
  }
  const T& operator[](std::size_t i) const {
    STEREOSCOUT_DEBUG_CHECK(i < size_, "StaticVector index out of range");
    return items_[i];
  }
  T* begin() { return items_.data(); }
  T* end() { return items_.data() + size_; }
  const T* begin() const { return items_.data(); }
  const T* end() const { return items_.data() + size_; }

  std::size_t size() const { return size_; }
  static constexpr std::size_t capacity() { return N; }
  bool empty() const { return size_ == 0; }
  bool full() const { return size_ == N; }

 private:
  std::array<T, N> items_{};
  std::size_t size_ = 0;
};

}  // namespace stereoscout::core
