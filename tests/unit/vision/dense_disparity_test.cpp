#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/core/random.hpp"
#include "stereoscout/test/paths.hpp"
#include "stereoscout/vision/dense_disparity.hpp"

namespace stereoscout::vision {
namespace {

// Smooth random texture (blurred white noise, stretched).
cv::Mat random_texture(int width, int height, std::uint32_t seed) {
  cv::Mat noise(height, width, CV_32FC1);
  core::RandomStream random(seed, core::StreamId{0, 0, 0});
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      noise.at<float>(y, x) = static_cast<float>(random.uniform());
    }
  }
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.2);
  cv::Mat image;
  cv::normalize(noise, noise, 0.0, 255.0, cv::NORM_MINMAX);
  noise.convertTo(image, CV_8UC1);
  return image;
}

// Left image of a fronto-parallel plane at constant disparity: left(x) = right(x - d).
cv::Mat shift_right_image(const cv::Mat& right, double disparity) {
  cv::Mat map_x(right.size(), CV_32FC1);
  cv::Mat map_y(right.size(), CV_32FC1);
  for (int y = 0; y < right.rows; ++y) {
    for (int x = 0; x < right.cols; ++x) {
      map_x.at<float>(y, x) = static_cast<float>(x - disparity);
      map_y.at<float>(y, x) = static_cast<float>(y);
    }
  }
  cv::Mat left;
  cv::remap(right, left, map_x, map_y, cv::INTER_CUBIC, cv::BORDER_REFLECT);
  return left;
}

TEST(DenseDisparity, RecoversAPlaneToSubpixelWithoutAllocating) {
  const cv::Mat right = random_texture(320, 240, 11);
  const double truth = 17.4;
  const cv::Mat left = shift_right_image(right, truth);
  DenseDisparityMatcher matcher(DenseDisparityParams{}, 320, 240);
  cv::Mat disparity;
  matcher.allocate_output(disparity);
  const core::AllocationScope scope;
  matcher.compute(left, right, disparity);
  EXPECT_EQ(scope.allocations(), 0U);
  std::size_t valid = 0;
  std::size_t within = 0;
  double sum_error = 0.0;
  // Pixels whose search range covers the true disparity.
  for (int y = 0; y < 240; ++y) {
    for (int x = 40; x < 320; ++x) {
      const float d = disparity.at<float>(y, x);
      if (d < 0.0F) continue;
      ++valid;
      within += std::fabs(d - truth) < 0.5 ? 1U : 0U;
      sum_error += std::fabs(d - truth);
    }
  }
  const double interior = static_cast<double>((240 - 12) * (320 - 40 - 6));
  EXPECT_GT(static_cast<double>(valid), 0.9 * interior);
  EXPECT_GT(static_cast<double>(within), 0.98 * static_cast<double>(valid));
  EXPECT_LT(sum_error / static_cast<double>(valid), 0.25);  // subpixel refinement works
  EXPECT_EQ(matcher.stats().valid + matcher.stats().rejected_texture + matcher.stats().rejected_uniqueness +
                matcher.stats().rejected_left_right + matcher.stats().rejected_speckle + matcher.stats().border,
            matcher.stats().pixels);
}

// The vector (AVX2 / popcount) build of the inner loops gives the portable build's output bit
// for bit: a scene with two planes, a blank band and noise exercises every check.
TEST(DenseDisparity, SimdAndPortableBuildsGiveTheSameDisparities) {
  const cv::Mat right = random_texture(320, 240, 5);
  cv::Mat left = shift_right_image(right, 9.3);
  shift_right_image(right, 23.6)(cv::Rect(120, 60, 120, 100)).copyTo(left(cv::Rect(120, 60, 120, 100)));
  left(cv::Rect(40, 180, 200, 30)).setTo(128);
  core::RandomStream random(9, core::StreamId{0, 0, 0});
  for (int y = 0; y < left.rows; ++y) {
    for (int x = 0; x < left.cols; ++x) {
      const double noisy = left.at<std::uint8_t>(y, x) + random.gaussian(0.0, 3.0);
      left.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(std::clamp(std::lround(noisy), 0L, 255L));
    }
  }
  DenseDisparityParams params;
  params.num_disparities = 48;
  DenseDisparityMatcher fastest(params, 320, 240);
  params.allow_simd = false;
  DenseDisparityMatcher portable(params, 320, 240);
  EXPECT_STREQ(portable.kernels_name(), "portable");
  std::printf("fastest build of the inner loops here: %s\n", fastest.kernels_name());
  cv::Mat fast_disparity;
  cv::Mat portable_disparity;
  fastest.allocate_output(fast_disparity);
  portable.allocate_output(portable_disparity);
  fastest.compute(left, right, fast_disparity);
  portable.compute(left, right, portable_disparity);
  ASSERT_GT(portable.stats().valid, 20000U);
  EXPECT_GT(portable.stats().rejected_texture + portable.stats().rejected_uniqueness, 1000U);
  EXPECT_EQ(std::memcmp(fast_disparity.data, portable_disparity.data, fast_disparity.total() * sizeof(float)), 0);
  EXPECT_EQ(fastest.stats().valid, portable.stats().valid);
  EXPECT_EQ(fastest.stats().rejected_uniqueness, portable.stats().rejected_uniqueness);
  EXPECT_EQ(fastest.stats().rejected_left_right, portable.stats().rejected_left_right);
  EXPECT_EQ(fastest.stats().rejected_speckle, portable.stats().rejected_speckle);
}

// The box sum by doubling equals the plain window sum for every window the config allows,
// in both builds.
TEST(DenseDisparity, BoxSumByDoublingIsTheWindowSum) {
  const int width = 97;
  const int disparities = 3;
  std::vector<std::uint16_t> columns(static_cast<std::size_t>(width * disparities));
  core::RandomStream random(4, core::StreamId{0, 0, 0});
  for (std::uint16_t& value : columns) {
    value = static_cast<std::uint16_t>(random.uniform_index(48U * 31U));
  }
  std::vector<std::uint16_t> scratch(static_cast<std::size_t>(detail::kMaxBoxLevels * width));
  for (const detail::DenseKernels& kernels : detail::supported_dense_kernels()) {
    for (int window = 1; window <= 31; window += 2) {
      const int radius = window / 2;
      std::vector<std::uint16_t> out(columns.size(), 0);
      kernels.box_sum(columns.data(), out.data(), scratch.data(), disparities, width, radius);
      for (int d = 0; d < disparities; ++d) {
        for (int x = radius; x < width - radius; ++x) {
          int sum = 0;
          for (int k = -radius; k <= radius; ++k) sum += columns[static_cast<std::size_t>(d * width + x + k)];
          ASSERT_EQ(out[static_cast<std::size_t>(d * width + x)], sum) << kernels.name << " window " << window << " x " << x;
        }
      }
    }
  }
}

// The census kernels give the definition's bits: bit 47 - k set when neighbour k (row-major
// over the 7x7 window, centre left out) is darker than the centre; borders 0.
TEST(DenseDisparity, CensusTransformMatchesTheDefinition) {
  const cv::Mat image = random_texture(83, 29, 6);
  for (const detail::DenseKernels& kernels : detail::supported_dense_kernels()) {
    std::vector<std::uint64_t> census(static_cast<std::size_t>(image.total()), 1);
    kernels.census(image.ptr<std::uint8_t>(0), image.step[0], image.cols, image.rows, census.data());
    for (int y = 0; y < image.rows; ++y) {
      for (int x = 0; x < image.cols; ++x) {
        std::uint64_t expected = 0;
        if (y >= 3 && y < image.rows - 3 && x >= 3 && x < image.cols - 3) {
          for (int dy = -3; dy <= 3; ++dy) {
            for (int dx = -3; dx <= 3; ++dx) {
              if (dx == 0 && dy == 0) continue;
              expected = (expected << 1U) |
                         static_cast<std::uint64_t>(image.at<std::uint8_t>(y + dy, x + dx) < image.at<std::uint8_t>(y, x));
            }
          }
        }
        ASSERT_EQ(census[static_cast<std::size_t>(y * image.cols + x)], expected) << kernels.name << " " << x << "," << y;
      }
    }
  }
}

// Every build of the cost and winner kernels that this CPU runs gives the portable build's
// numbers (widths that leave a tail after the vector loops, random censuses and costs).
TEST(DenseDisparity, EveryKernelBuildGivesThePortableCostsAndWinners) {
  const int width = 203;
  const int disparities = 21;
  core::RandomStream random(17, core::StreamId{0, 0, 0});
  std::vector<std::uint64_t> left(static_cast<std::size_t>(width));
  std::vector<std::uint64_t> right(static_cast<std::size_t>(width));
  for (std::size_t i = 0; i < left.size(); ++i) {
    // 48-bit censuses from two 24-bit draws.
    left[i] = (std::uint64_t{random.uniform_index(1U << 24U)} << 24U) | random.uniform_index(1U << 24U);
    right[i] = (std::uint64_t{random.uniform_index(1U << 24U)} << 24U) | random.uniform_index(1U << 24U);
  }
  std::vector<std::uint16_t> aggregated(static_cast<std::size_t>(width * disparities));
  for (std::uint16_t& cost : aggregated) cost = static_cast<std::uint16_t>(random.uniform_index(200U));
  const auto run = [&](const detail::DenseKernels& kernels, std::vector<std::uint8_t>& costs,
                       std::vector<std::vector<std::int32_t>>& winners) {
    costs.assign(static_cast<std::size_t>(width * disparities), 0);
    for (int d = 0; d < disparities; ++d) {
      kernels.census_costs(left.data(), right.data(), &costs[static_cast<std::size_t>(d * width)], d + 3, width, d);
    }
    std::vector<std::uint16_t> best(static_cast<std::size_t>(width));
    std::vector<std::uint16_t> second(best.size());
    std::vector<std::int16_t> best_d(best.size());
    std::vector<std::uint16_t> right_best(best.size());
    std::vector<std::int16_t> right_best_d(best.size());
    detail::WinnerBuffers buffers{aggregated.data(), width,         disparities,        6,
                                  width - 7,         best.data(),   second.data(),      best_d.data(),
                                  right_best.data(), right_best_d.data()};
    kernels.winners(buffers);
    winners = {{best.begin(), best.end()},
               {second.begin(), second.end()},
               {best_d.begin(), best_d.end()},
               {right_best.begin(), right_best.end()},
               {right_best_d.begin(), right_best_d.end()}};
  };
  std::vector<std::uint8_t> portable_costs;
  std::vector<std::vector<std::int32_t>> portable_winners;
  run(detail::portable_dense_kernels(), portable_costs, portable_winners);
  // The definition, by brute force: best = the least cost (smallest disparity on ties) over
  // d <= x - first_x, second = the least cost with |d - best| > 1.
  for (int x = 6; x <= width - 7; ++x) {
    int best = 0;
    for (int d = 1; d <= std::min(disparities - 1, x - 6); ++d) {
      if (aggregated[static_cast<std::size_t>(d * width + x)] < aggregated[static_cast<std::size_t>(best * width + x)]) best = d;
    }
    int second = 0xFFFF;
    for (int d = 0; d <= std::min(disparities - 1, x - 6); ++d) {
      if (std::abs(d - best) > 1) second = std::min<int>(second, aggregated[static_cast<std::size_t>(d * width + x)]);
    }
    const auto column = static_cast<std::size_t>(x);
    ASSERT_EQ(portable_winners[2][column], best) << x;
    ASSERT_EQ(portable_winners[0][column], aggregated[static_cast<std::size_t>(best * width + x)]) << x;
    ASSERT_EQ(portable_winners[1][column], second) << x;
  }
  for (const detail::DenseKernels& kernels : detail::supported_dense_kernels()) {
    std::vector<std::uint8_t> costs;
    std::vector<std::vector<std::int32_t>> winners;
    run(kernels, costs, winners);
    EXPECT_EQ(costs, portable_costs) << kernels.name;
    EXPECT_EQ(winners, portable_winners) << kernels.name;
  }
}

TEST(DenseDisparity, UntexturedAreaIsInvalidNotGuessed) {
  cv::Mat right = random_texture(200, 120, 12);
  right(cv::Rect(80, 30, 60, 60)).setTo(100);
  const cv::Mat left = shift_right_image(right, 10.0);
  DenseDisparityMatcher matcher(DenseDisparityParams{}, 200, 120);
  cv::Mat disparity;
  matcher.allocate_output(disparity);
  matcher.compute(left, right, disparity);
  // The flat patch (seen in the left image at x + 10) well inside its border: all invalid,
  // and marked as lacking texture (the scan's blank-wall rule asks for that mark).
  for (int y = 40; y < 80; ++y) {
    for (int x = 100; x < 140; ++x) {
      EXPECT_EQ(disparity.at<float>(y, x), kUntexturedDisparity) << "at " << x << "," << y;
    }
  }
  EXPECT_GT(matcher.stats().rejected_texture, 1000U);
  // Textured pixels that fail a check are holes of the other kind: the left image's border
  // columns, whose search range leaves the image.
  EXPECT_EQ(disparity.at<float>(60, 2), kInvalidDisparity);
}

TEST(DenseDisparity, ScoreCountsBadPixelsAndDensity) {
  cv::Mat disparity(1, 4, CV_32FC1);
  disparity.at<float>(0, 0) = 10.0F;   // exact
  disparity.at<float>(0, 1) = 11.5F;   // off by 1.5: bad-1 only
  disparity.at<float>(0, 2) = 13.0F;   // off by 3: bad-1 and bad-2
  disparity.at<float>(0, 3) = kInvalidDisparity;
  cv::Mat truth(1, 4, CV_8UC1, cv::Scalar(40));  // scale 4: disparity 10
  const DisparityScore score = score_disparity(disparity, truth, 4.0);
  EXPECT_EQ(score.known, 4U);
  EXPECT_EQ(score.valid, 3U);
  EXPECT_DOUBLE_EQ(score.bad_1, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(score.bad_2, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(score.density, 0.75);
  EXPECT_DOUBLE_EQ(score.bad_2_all, 0.5);
}

// Real pairs: the figures go to docs/results.md; the bounds only catch a broken matcher.
TEST(DenseDisparity, MiddleburyPairs) {
  struct Pair {
    const char* scene;
    const char* left;
    const char* right;
    const char* truth;
    double scale;
    int disparities;
  };
  const Pair pairs[] = {{"tsukuba", "im3.png", "im4.png", "disp3.pgm", 16.0, 16},
                        {"venus", "im2.png", "im6.png", "disp2.pgm", 8.0, 20},
                        {"teddy", "im2.png", "im6.png", "disp2.png", 4.0, 60},
                        {"cones", "im2.png", "im6.png", "disp2.png", 4.0, 60}};
  const std::string folder = test::data_path("middlebury");
  if (folder.empty()) {
    GTEST_SKIP() << "Middlebury pairs not found under " << test::data_dir() << "/middlebury";
  }
  for (const Pair& pair : pairs) {
    const std::string base = folder + "/" + pair.scene + "/";
    const cv::Mat left = cv::imread(base + pair.left, cv::IMREAD_GRAYSCALE);
    const cv::Mat right = cv::imread(base + pair.right, cv::IMREAD_GRAYSCALE);
    const cv::Mat truth = cv::imread(base + pair.truth, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(left.empty() || right.empty() || truth.empty()) << "cannot read " << base;
    DenseDisparityParams params;
    params.num_disparities = pair.disparities;
    // The default texture threshold sits above the robot camera's noise (sigma 2 grey
    // levels); Middlebury's images are nearly noise-free and weak texture there matches.
    params.min_texture = 1.0;
    DenseDisparityMatcher matcher(params, left.cols, left.rows);
    cv::Mat disparity;
    matcher.allocate_output(disparity);
    matcher.compute(left, right, disparity);
    const DisparityScore score = score_disparity(disparity, truth, pair.scale);
    std::printf("middlebury %-8s bad-1.0 %.3f bad-2.0 %.3f density %.3f (texture %zu uniqueness %zu left-right %zu "
                "speckle %zu border %zu of %zu)\n",
                pair.scene, score.bad_1, score.bad_2, score.density, matcher.stats().rejected_texture,
                matcher.stats().rejected_uniqueness, matcher.stats().rejected_left_right, matcher.stats().rejected_speckle,
                matcher.stats().border, matcher.stats().pixels);
    EXPECT_LT(score.bad_2, 0.08) << pair.scene;
    EXPECT_GT(score.density, 0.7) << pair.scene;
  }
}

}  // namespace
}  // namespace stereoscout::vision
