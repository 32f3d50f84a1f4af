#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/vision/dense_disparity.hpp"
#include "stereoscout/vision/speckle_filter.hpp"

namespace stereoscout::vision {
namespace {

// A slanted plane (disparity rising 0.2 px per row, like a floor) with a 3x3 island of a wrong
// disparity, a 2-pixel island, a 12x12 block of another surface and an invalid hole.
cv::Mat scene() {
  cv::Mat disparity(40, 50, CV_32FC1);
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 50; ++x) {
      disparity.at<float>(y, x) = 10.0F + 0.2F * static_cast<float>(y);
    }
  }
  disparity(cv::Rect(5, 5, 3, 3)).setTo(30.0F);
  disparity(cv::Rect(20, 30, 2, 1)).setTo(2.0F);
  disparity(cv::Rect(30, 10, 12, 12)).setTo(25.0F);
  disparity(cv::Rect(10, 20, 4, 4)).setTo(kInvalidDisparity);
  return disparity;
}

TEST(SpeckleFilter, RemovesSmallIslandsKeepsSurfacesWithoutAllocating) {
  cv::Mat disparity = scene();
  SpeckleFilter filter({20, 1.0}, 50, 40);
  const core::AllocationScope scope;
  const std::size_t removed = filter.apply(disparity, kInvalidDisparity);
  EXPECT_EQ(scope.allocations(), 0U);
  EXPECT_EQ(removed, 9U + 2U);
  EXPECT_EQ(disparity.at<float>(6, 6), kInvalidDisparity);
  EXPECT_EQ(disparity.at<float>(30, 21), kInvalidDisparity);
  EXPECT_EQ(disparity.at<float>(15, 35), 25.0F);           // 144 pixels: a surface
  EXPECT_FLOAT_EQ(disparity.at<float>(39, 0), 10.0F + 0.2F * 39.0F);  // the slant is one region
  EXPECT_EQ(disparity.at<float>(21, 11), kInvalidDisparity);  // holes stay holes
}

TEST(SpeckleFilter, StepDecidesWhatIsOneRegionAndZeroSwitchesItOff) {
  cv::Mat disparity = scene();
  // A step below the plane's 0.2 px per row cuts it into 1-row strips of 50 pixels.
  SpeckleFilter strict({60, 0.1}, 50, 40);
  strict.apply(disparity, kInvalidDisparity);
  EXPECT_EQ(disparity.at<float>(39, 0), kInvalidDisparity);
  cv::Mat untouched = scene();
  SpeckleFilter off({0, 1.0}, 50, 40);
  EXPECT_EQ(off.apply(untouched, kInvalidDisparity), 0U);
  EXPECT_EQ(cv::countNonZero(untouched != scene()), 0);
}

// Two 20 x 20 blocks of 400 pixels each, more than the pixel limit: at disparity 60 with a
// 0.1 m baseline each pixel spans 1/600 m, so the near block is a surface of 11 cm^2, at
// disparity 10 one of 400 cm^2. A region at disparity 0 (infinity) is larger than any limit.
TEST(SpeckleFilter, AnAreaRuleRemovesASmallSurfaceNearTheCameraWhateverItsPixels) {
  const auto blocks = [] {
    cv::Mat disparity(50, 60, CV_32FC1, cv::Scalar(kInvalidDisparity));
    disparity(cv::Rect(2, 2, 20, 20)).setTo(60.0F);
    disparity(cv::Rect(30, 2, 20, 20)).setTo(10.0F);
    disparity(cv::Rect(2, 28, 20, 20)).setTo(0.0F);
    return disparity;
  };
  cv::Mat disparity = blocks();
  SpeckleFilter filter({100, 1.0, 0.0025, 0.1}, 60, 50);
  const core::AllocationScope scope;
  EXPECT_EQ(filter.apply(disparity, kInvalidDisparity), 400U);
  EXPECT_EQ(scope.allocations(), 0U);
  EXPECT_EQ(disparity.at<float>(10, 10), kInvalidDisparity);
  EXPECT_EQ(disparity.at<float>(10, 40), 10.0F);
  EXPECT_EQ(disparity.at<float>(40, 10), 0.0F);
  // A 10 cm^2 limit keeps the near block; without a baseline, or a limit, no area rule.
  for (const SpeckleFilterParams params : {SpeckleFilterParams{100, 1.0, 0.001, 0.1}, SpeckleFilterParams{100, 1.0, 0.0025, 0.0},
                                           SpeckleFilterParams{100, 1.0, 0.0, 0.1}}) {
    cv::Mat kept = blocks();
    SpeckleFilter other(params, 60, 50);
    EXPECT_EQ(other.apply(kept, kInvalidDisparity), 0U) << params.min_area_m2 << " m^2, baseline " << params.baseline_m;
  }
  // With no pixel limit the area rule alone still runs.
  cv::Mat area_only = blocks();
  SpeckleFilter only({0, 1.0, 0.0025, 0.1}, 60, 50);
  EXPECT_EQ(only.apply(area_only, kInvalidDisparity), 400U);
}

// A near surface cut into pieces by holes (a brick wall's repeated courses) keeps its pieces:
// each has another beside it at about its disparity. A piece with only farther surfaces around
// it goes.
TEST(SpeckleFilter, TheAreaRuleKeepsPiecesOfOneSurfaceAndRemovesAPieceInFrontOfItsSurroundings) {
  cv::Mat disparity(50, 100, CV_32FC1, cv::Scalar(kInvalidDisparity));
  disparity(cv::Rect(2, 2, 20, 20)).setTo(60.0F);
  disparity(cv::Rect(26, 2, 20, 20)).setTo(58.5F);  // 4 px of hole between, 1.5 px farther
  disparity(cv::Rect(70, 24, 20, 20)).setTo(60.0F);
  disparity(cv::Rect(70, 45, 28, 5)).setTo(20.0F);  // a far surface below it: 350 cm^2
  SpeckleFilter filter({100, 1.0, 0.0025, 0.1, 3.0}, 100, 50);
  EXPECT_EQ(filter.apply(disparity, kInvalidDisparity), 400U);
  EXPECT_EQ(disparity.at<float>(10, 10), 60.0F);
  EXPECT_EQ(disparity.at<float>(10, 30), 58.5F);
  EXPECT_EQ(disparity.at<float>(30, 80), kInvalidDisparity);
  EXPECT_EQ(disparity.at<float>(47, 80), 20.0F);
}

TEST(SpeckleFilter, ResultDoesNotDependOnThePixelOrder) {
  // The regions are connected components, so a transposed map gives the transposed result.
  cv::Mat disparity = scene();
  cv::Mat transposed = scene().t();
  SpeckleFilter filter({20, 1.0}, 50, 40);
  SpeckleFilter transposed_filter({20, 1.0}, 40, 50);
  filter.apply(disparity, kInvalidDisparity);
  transposed_filter.apply(transposed, kInvalidDisparity);
  const cv::Mat back = transposed.t();
  EXPECT_EQ(cv::countNonZero(disparity != back), 0);
  // With the area rule too: the 12 x 12 block at disparity 25 is 23 cm^2 in front of the plane.
  cv::Mat with_area = scene();
  cv::Mat with_area_transposed = scene().t();
  SpeckleFilter area_filter({20, 1.0, 0.0025, 0.1}, 50, 40);
  SpeckleFilter area_transposed_filter({20, 1.0, 0.0025, 0.1}, 40, 50);
  EXPECT_EQ(area_filter.apply(with_area, kInvalidDisparity), 9U + 2U + 144U);
  area_transposed_filter.apply(with_area_transposed, kInvalidDisparity);
  const cv::Mat area_back = with_area_transposed.t();
  EXPECT_EQ(cv::countNonZero(with_area != area_back), 0);
}

}  // namespace
}  // namespace stereoscout::vision
