#include <gtest/gtest.h>

#include <limits>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/core/random.hpp"
#include "stereoscout/vision/stereo_matcher.hpp"

namespace stereoscout::vision {
namespace {

Descriptor random_descriptor(core::RandomStream& random) {
  Descriptor descriptor{};
  for (auto& value : descriptor) {
    value = static_cast<std::uint8_t>(random.uniform_index(64));
  }
  return descriptor;
}

// Keys of a synthetic pair: each right key has a left partner at a known disparity with a
// slightly perturbed descriptor, among unrelated clutter on nearby rows.
void make_pair(core::FixedVector<Keypoint>& left, core::FixedVector<Keypoint>& right, int count, std::uint32_t seed) {
  core::RandomStream random(seed, core::StreamId{0, 0, 0});
  for (int i = 0; i < count; ++i) {
    Keypoint key;
    key.x_px = static_cast<float>(random.uniform(0.0, 560.0));
    key.y_px = static_cast<float>(random.uniform(0.0, 479.0));
    key.descriptor = random_descriptor(random);
    right.push_back(key);
    Keypoint partner = key;
    partner.x_px += static_cast<float>(random.uniform(1.0, 70.0));
    partner.y_px += static_cast<float>(random.uniform(-1.0, 1.0));
    for (auto& value : partner.descriptor) {
      value = static_cast<std::uint8_t>(value + random.uniform_index(3));
    }
    left.push_back(partner);
    Keypoint clutter;
    clutter.x_px = static_cast<float>(random.uniform(0.0, 639.0));
    clutter.y_px = key.y_px + static_cast<float>(random.uniform(-3.0, 3.0));
    clutter.descriptor = random_descriptor(random);
    left.push_back(clutter);
  }
}

// The reference: every key of the other image, no bucketing.
struct BruteBest {
  std::uint32_t index = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t distance = 0;
  std::uint32_t second = 0;
  bool has_second = false;
};

BruteBest brute_best(const StereoMatchParams& params, const Keypoint& key, bool key_is_right,
                     const core::FixedVector<Keypoint>& others) {
  BruteBest best;
  for (std::uint32_t o = 0; o < others.size(); ++o) {
    const bool candidate = key_is_right ? is_stereo_candidate(params, others[o], key) : is_stereo_candidate(params, key, others[o]);
    if (!candidate) continue;
    const std::uint32_t distance = descriptor_distance_squared(others[o].descriptor, key.descriptor);
    if (best.index == std::numeric_limits<std::uint32_t>::max() || distance < best.distance) {
      if (best.index != std::numeric_limits<std::uint32_t>::max()) {
        best.second = best.distance;
        best.has_second = true;
      }
      best.index = o;
      best.distance = distance;
    } else if (!best.has_second || distance < best.second) {
      best.second = distance;
      best.has_second = true;
    }
  }
  return best;
}

void brute_force(const StereoMatchParams& params, const core::FixedVector<Keypoint>& left,
                 const core::FixedVector<Keypoint>& right, core::FixedVector<StereoMatch>& matches) {
  matches.clear();
  for (std::uint32_t r = 0; r < right.size(); ++r) {
    const BruteBest best = brute_best(params, right[r], true, left);
    if (best.index == std::numeric_limits<std::uint32_t>::max() ||
        !passes_ratio_test(params.ratio, best.distance, best.second, best.has_second)) {
      continue;
    }
    if (params.cross_check && brute_best(params, left[best.index], false, right).index != r) continue;
    matches.push_back({r, best.index, left[best.index].x_px - right[r].x_px, best.distance});
  }
}

TEST(StereoMatcher, SameResultAsBruteForceAndNoAllocation) {
  for (const bool cross_check : {true, false}) {
  StereoMatchParams params;
  params.cross_check = cross_check;
  core::FixedVector<Keypoint> left(2000);
  core::FixedVector<Keypoint> right(1000);
  make_pair(left, right, 800, 3);
  StereoMatcher matcher(params, 480, 2000);
  core::FixedVector<StereoMatch> matches(1000);
  core::FixedVector<StereoMatch> expected(1000);
  brute_force(params, left, right, expected);
  const core::AllocationScope scope;
  matcher.match(left, right, matches);
  EXPECT_EQ(scope.allocations(), 0U);
  ASSERT_EQ(matches.size(), expected.size());
  for (std::size_t i = 0; i < matches.size(); ++i) {
    EXPECT_EQ(matches[i].right_index, expected[i].right_index);
    EXPECT_EQ(matches[i].left_index, expected[i].left_index);
    EXPECT_EQ(matches[i].distance_squared, expected[i].distance_squared);
  }
  // Almost every right key finds its true partner (left index 2 * r).
  std::size_t correct = 0;
  for (const StereoMatch& match : matches) {
    correct += match.left_index == 2 * match.right_index ? 1U : 0U;
  }
  EXPECT_GT(correct, 780U);
  EXPECT_EQ(correct, matches.size());
  }
}

// A right key whose best left key prefers another right key is dropped by the cross-check.
TEST(StereoMatcher, CrossCheckKeepsOnlyMutualBestMatches) {
  core::FixedVector<Keypoint> left(4);
  core::FixedVector<Keypoint> right(4);
  Keypoint shared;
  shared.x_px = 300.0F;
  shared.y_px = 10.0F;
  left.push_back(shared);
  Keypoint exact = shared;  // the true partner, distance 0
  exact.x_px = 280.0F;
  Keypoint near = shared;   // also best for nothing else, distance 3
  near.x_px = 270.0F;
  near.descriptor[5] = 3;
  right.push_back(near);
  right.push_back(exact);
  StereoMatchParams params;
  params.ratio = 1.0;
  StereoMatcher with_check(params, 480, 4);
  core::FixedVector<StereoMatch> matches(4);
  with_check.match(left, right, matches);
  ASSERT_EQ(matches.size(), 1U);
  EXPECT_EQ(matches[0].right_index, 1U);
  EXPECT_EQ(with_check.rejected_by_cross_check(), 1U);
  params.cross_check = false;
  StereoMatcher without_check(params, 480, 4);
  without_check.match(left, right, matches);
  EXPECT_EQ(matches.size(), 2U);
}

TEST(StereoMatcher, RespectsEpipolarBandAndDisparityLimits) {
  StereoMatchParams params;
  params.epipolar_tolerance_px = 1.0;
  params.min_disparity_px = 2.0;
  params.max_disparity_px = 50.0;
  core::FixedVector<Keypoint> left(8);
  core::FixedVector<Keypoint> right(8);
  Keypoint key;
  key.x_px = 100.0F;
  key.y_px = 100.0F;
  right.push_back(key);
  Keypoint off_row = key;  // identical descriptor but 1.5 rows away
  off_row.x_px = 110.0F;
  off_row.y_px = 101.5F;
  left.push_back(off_row);
  Keypoint too_far = key;  // disparity 60 > 50
  too_far.x_px = 160.0F;
  left.push_back(too_far);
  Keypoint negative = key;  // left key left of the right key: negative disparity
  negative.x_px = 90.0F;
  left.push_back(negative);
  StereoMatcher matcher(params, 480, 8);
  core::FixedVector<StereoMatch> matches(8);
  matcher.match(left, right, matches);
  EXPECT_TRUE(matches.empty());
  Keypoint good = key;
  good.x_px = 120.0F;
  good.y_px = 100.9F;
  good.descriptor[0] = 5;
  left.push_back(good);
  matcher.match(left, right, matches);
  ASSERT_EQ(matches.size(), 1U);
  EXPECT_EQ(matches[0].left_index, 3U);
  EXPECT_FLOAT_EQ(matches[0].disparity_px, 20.0F);
}

TEST(StereoMatcher, RatioTestRejectsAmbiguousKeys) {
  const StereoMatchParams params;  // ratio 0.8
  core::FixedVector<Keypoint> left(4);
  core::FixedVector<Keypoint> right(4);
  Keypoint key;
  key.x_px = 200.0F;
  key.y_px = 50.0F;
  right.push_back(key);
  Keypoint a = key;
  a.x_px = 210.0F;
  a.descriptor[0] = 10;  // distance 10
  Keypoint b = key;
  b.x_px = 220.0F;
  b.descriptor[1] = 11;  // distance 11: not distinctive (10 > 0.8 * 11)
  left.push_back(a);
  left.push_back(b);
  StereoMatcher matcher(params, 480, 4);
  core::FixedVector<StereoMatch> matches(4);
  matcher.match(left, right, matches);
  EXPECT_TRUE(matches.empty());
  EXPECT_EQ(matcher.rejected_by_ratio(), 1U);
  left[1].descriptor[1] = 20;  // now 10 < 0.8 * 20
  matcher.match(left, right, matches);
  ASSERT_EQ(matches.size(), 1U);
  EXPECT_EQ(matches[0].left_index, 0U);
}

}  // namespace
}  // namespace stereoscout::vision
