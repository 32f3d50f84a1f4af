#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "stereoscout/core/random.hpp"

namespace stereoscout::core {
namespace {

// Known-answer vectors of Philox4x32-10 published with Random123 (kat_vectors).
TEST(Philox, MatchesPublishedKnownAnswers) {
  EXPECT_EQ(philox4x32_10({0, 0, 0, 0}, {0, 0}),
            (PhiloxCounter{0x6627e8d5U, 0xe169c58dU, 0xbc57ac4cU, 0x9b00dbd8U}));
  EXPECT_EQ(philox4x32_10({0xffffffffU, 0xffffffffU, 0xffffffffU, 0xffffffffU}, {0xffffffffU, 0xffffffffU}),
            (PhiloxCounter{0x408f276dU, 0x41c83b0eU, 0xa20bc7c6U, 0x6d5451fdU}));
  EXPECT_EQ(philox4x32_10({0x243f6a88U, 0x85a308d3U, 0x13198a2eU, 0x03707344U}, {0xa4093822U, 0x299f31d0U}),
            (PhiloxCounter{0xd16cfe09U, 0x94fdccebU, 0x5001e420U, 0x24126ea1U}));
}

// Pinned outputs of our streams: any change here changes every recorded run.
TEST(RandomStream, PinnedValues) {
  RandomStream stream(42, {stream_purpose::test, 7, 3});
  EXPECT_EQ(stream.next_u32(), 4233266298u);
  EXPECT_EQ(stream.next_u32(), 934472727u);
  RandomStream uniform_stream(42, {stream_purpose::test, 7, 3});
  EXPECT_EQ(uniform_stream.uniform(), 0x1.f8a508f46f65dp-1);
  RandomStream gaussian_stream(42, {stream_purpose::test, 7, 3});
  EXPECT_EQ(gaussian_stream.gaussian(), 0x1.b5380f63fa67cp-2);
  EXPECT_EQ(gaussian_stream.gaussian(), 0x1.7822fbcb943d5p-2);
}

TEST(RandomStream, SameKeySameSequence) {
  RandomStream a(1234, {stream_purpose::motion_noise, 10, 99});
  RandomStream b(1234, {stream_purpose::motion_noise, 10, 99});
  for (int i = 0; i < 1000; ++i) {
    ASSERT_EQ(a.gaussian(), b.gaussian());
  }
}

TEST(RandomStream, StreamsAreIndependentOfOtherStreamsDraws) {
  // Particle 5's draws at step 10 do not depend on how much particle 4 drew before.
  RandomStream alone(7, {stream_purpose::motion_noise, 10, 5});
  const double expected = alone.gaussian();
  RandomStream other(7, {stream_purpose::motion_noise, 10, 4});
  for (int i = 0; i < 123; ++i) {
    other.gaussian();
  }
  RandomStream again(7, {stream_purpose::motion_noise, 10, 5});
  EXPECT_EQ(again.gaussian(), expected);
}

TEST(RandomStream, DifferentKeysDiffer) {
  RandomStream base(7, {1, 2, 3});
  const std::uint64_t reference = base.next_u64();
  EXPECT_NE(RandomStream(8, {1, 2, 3}).next_u64(), reference);
  EXPECT_NE(RandomStream(7, {9, 2, 3}).next_u64(), reference);
  EXPECT_NE(RandomStream(7, {1, 9, 3}).next_u64(), reference);
  EXPECT_NE(RandomStream(7, {1, 2, 9}).next_u64(), reference);
}

TEST(RandomStream, UniformMomentsAndRange) {
  RandomStream stream(99, {stream_purpose::test, 0, 0});
  const int n = 200000;
  double sum = 0.0;
  double sum_squares = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = stream.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum_squares += u * u;
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 0.5, 0.005);
  EXPECT_NEAR(sum_squares / n - mean * mean, 1.0 / 12.0, 0.002);
}

TEST(RandomStream, GaussianMoments) {
  RandomStream stream(99, {stream_purpose::test, 1, 0});
  const int n = 200000;
  double sum = 0.0;
  double sum_squares = 0.0;
  double sum_fourth = 0.0;
  int beyond_two_sigma = 0;
  for (int i = 0; i < n; ++i) {
    const double z = stream.gaussian();
    sum += z;
    sum_squares += z * z;
    sum_fourth += z * z * z * z;
    beyond_two_sigma += std::abs(z) > 2.0 ? 1 : 0;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(sum_squares / n, 1.0, 0.015);
  EXPECT_NEAR(sum_fourth / n, 3.0, 0.1);  // a normal's kurtosis
  EXPECT_NEAR(static_cast<double>(beyond_two_sigma) / n, 0.0455, 0.003);
}

TEST(RandomStream, UniformIndexIsUnbiasedAndInRange) {
  RandomStream stream(5, {stream_purpose::test, 2, 0});
  std::vector<int> counts(7, 0);
  const int n = 70000;
  for (int i = 0; i < n; ++i) {
    const std::uint32_t k = stream.uniform_index(7);
    ASSERT_LT(k, 7u);
    ++counts[k];
  }
  for (int count : counts) {
    EXPECT_NEAR(count, n / 7, 300);
  }
}

TEST(PortableLog, AgreesWithLibmAndHandlesEdgeCases) {
  for (double x : {1e-300, 1e-10, 0.001, 0.3, 0.7071, 1.0, 1.5, 2.0, 10.0, 12345.678, 1e300}) {
    EXPECT_NEAR(portable_log(x), std::log(x), 2e-15 * std::max(1.0, std::abs(std::log(x)))) << x;
  }
  EXPECT_EQ(portable_log(1.0), 0.0);
  EXPECT_EQ(portable_log(0.0), -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(portable_log(-1.0)));
  EXPECT_TRUE(std::isnan(portable_log(std::numeric_limits<double>::quiet_NaN())));
}

}  // namespace
}  // namespace stereoscout::core
