#pragma once
// Durations of one task's runs in fixed storage: log-spaced buckets 5% wide from 1 us to
// about 100 s, so median and p99 are known to within 5% without keeping samples; count and
// maximum are exact.

#include <array>
#include <cstdint>

namespace stereoscout::scheduler {

class DurationHistogram {
 public:
  static constexpr std::size_t kBuckets = 380;

  void add(std::int64_t duration_us);
  // The q-quantile (0 < q <= 1) in microseconds: the upper edge of the bucket holding it,
  // never above the largest sample. 0 when empty.
  std::int64_t quantile_us(double q) const;
  std::int64_t max_us() const { return max_us_; }
  std::uint64_t count() const { return count_; }

 private:
  static std::size_t bucket_of(std::int64_t duration_us);
  static std::int64_t upper_edge_us(std::size_t bucket);

  std::array<std::uint32_t, kBuckets> counts_{};
  std::uint64_t count_ = 0;
  std::int64_t max_us_ = 0;
};

}  // namespace stereoscout::scheduler
