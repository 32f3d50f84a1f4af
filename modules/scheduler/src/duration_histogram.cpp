#include "stereoscout/scheduler/duration_histogram.hpp"

#include <cmath>

namespace stereoscout::scheduler {
namespace {
constexpr double kGrowth = 1.05;  // bucket width: 5%
}

std::size_t DurationHistogram::bucket_of(std::int64_t duration_us) {
  if (duration_us <= 1) {
    return 0;
  }
  const auto bucket = static_cast<std::size_t>(std::log(static_cast<double>(duration_us)) / std::log(kGrowth)) + 1;
  return bucket < kBuckets ? bucket : kBuckets - 1;
}

std::int64_t DurationHistogram::upper_edge_us(std::size_t bucket) {
  return static_cast<std::int64_t>(std::ceil(std::pow(kGrowth, static_cast<double>(bucket))));
}

void DurationHistogram::add(std::int64_t duration_us) {
  if (duration_us < 0) {
    duration_us = 0;
  }
  ++counts_[bucket_of(duration_us)];
  ++count_;
  if (duration_us > max_us_) {
    max_us_ = duration_us;
  }
}

std::int64_t DurationHistogram::quantile_us(double q) const {
  if (count_ == 0) {
    return 0;
  }
  const auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(count_)));
  std::uint64_t seen = 0;
  for (std::size_t bucket = 0; bucket < kBuckets; ++bucket) {
    seen += counts_[bucket];
    if (seen >= rank && seen > 0) {
      if (bucket == kBuckets - 1) {
        return max_us_;  // the open-ended last bucket has no upper edge
      }
      const std::int64_t edge = upper_edge_us(bucket);
      return edge < max_us_ ? edge : max_us_;
    }
  }
  return max_us_;
}

}  // namespace stereoscout::scheduler
