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
}

}  // namespace
}  // namespace stereoscout::vision
