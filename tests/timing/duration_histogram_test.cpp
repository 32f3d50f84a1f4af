#include <gtest/gtest.h>

#include "stereoscout/scheduler/duration_histogram.hpp"

namespace stereoscout::scheduler {
namespace {

TEST(DurationHistogram, QuantilesWithinFivePercentAndExactMax) {
  DurationHistogram histogram;
  for (std::int64_t us = 1; us <= 1000; ++us) {
    histogram.add(us);
  }
  EXPECT_EQ(histogram.count(), 1000u);
  EXPECT_EQ(histogram.max_us(), 1000);
  EXPECT_NEAR(static_cast<double>(histogram.quantile_us(0.5)), 500.0, 25.0);
  EXPECT_NEAR(static_cast<double>(histogram.quantile_us(0.99)), 990.0, 50.0);
  EXPECT_EQ(histogram.quantile_us(1.0), 1000);
}

TEST(DurationHistogram, EmptyAndExtremeValues) {
  DurationHistogram histogram;
  EXPECT_EQ(histogram.quantile_us(0.5), 0);
  histogram.add(-5);  // a clock step backwards counts as zero
  histogram.add(0);
  EXPECT_EQ(histogram.quantile_us(0.5), 0);
  histogram.add(500'000'000);  // beyond the last bucket: kept in it, max exact
  EXPECT_EQ(histogram.max_us(), 500'000'000);
  EXPECT_EQ(histogram.quantile_us(1.0), 500'000'000);
}

TEST(DurationHistogram, ConstantSamplesGiveThatValue) {
  DurationHistogram histogram;
  for (int i = 0; i < 100; ++i) {
    histogram.add(250);
  }
  EXPECT_EQ(histogram.quantile_us(0.5), 250);
  EXPECT_EQ(histogram.quantile_us(0.99), 250);
}

}  // namespace
}  // namespace stereoscout::scheduler
