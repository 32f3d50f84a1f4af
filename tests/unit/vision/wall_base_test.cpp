#include "stereoscout/vision/wall_base.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "stereoscout/vision/dense_disparity.hpp"

namespace stereoscout::vision {
namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 480;
constexpr int kHorizon = 240;

// A column picture: a blank wall (grey 190, untextured to the matcher) down to `base_row`,
// then tiled floor (grey 120-140 in 8-row bands, matched), both with the simulator's sensor
// noise (sigma 2 grey levels, fixed seed).
struct View {
  cv::Mat left = cv::Mat(kHeight, kWidth, CV_8UC1);
  cv::Mat disparity = cv::Mat(kHeight, kWidth, CV_32FC1);

  explicit View(int base_row) {
    cv::Mat noise(kHeight, kWidth, CV_32FC1);
    cv::RNG random(7);
    random.fill(noise, cv::RNG::NORMAL, 0.0, 2.0);
    for (int y = 0; y < kHeight; ++y) {
      const bool wall = y < base_row;
      const float grey = wall ? 190.0F : ((y / 8) % 2 == 0 ? 120.0F : 140.0F);
      for (int x = 0; x < kWidth; ++x) {
        left.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(grey + noise.at<float>(y, x));
        disparity.at<float>(y, x) = wall ? kUntexturedDisparity : 30.0F;
      }
    }
  }
};

// The boundary lies between rows 399 and 400; where the two band pairs that straddle it
// tie, the sensor noise may pick the row below.
constexpr double kRowTolerance = 1.0;

TEST(WallBase, TheBaseIsWhereTheBlankWallMeetsTheFloor) {
  const View view(400);
  for (int x = 0; x < kWidth; x += 9) {
    EXPECT_NEAR(find_wall_base_row(view.left, view.disparity, x, kHorizon, WallBaseParams{}), 399.5, kRowTolerance) << x;
  }
}

// Stereo measured the run above the step (a poster, furniture): the scan's points say where
// it is, not the step.
TEST(WallBase, AStepUnderATexturedRunIsNoWallBase) {
  View view(400);
  view.disparity.rowRange(kHorizon, 400).setTo(12.0F);
  EXPECT_LT(find_wall_base_row(view.left, view.disparity, 5, kHorizon, WallBaseParams{}), 0.0);
  // Half the run unmatched for lack of texture is still a blank wall (the default fraction).
  view.disparity.rowRange(kHorizon, 320).setTo(kUntexturedDisparity);
  EXPECT_NEAR(find_wall_base_row(view.left, view.disparity, 5, kHorizon, WallBaseParams{}), 399.5, kRowTolerance);
}

// The first step below the horizon ends the search: a far step (here the far floor's first
// band at row 300) is returned, and the scan finds it out of range, so the nearer floor's
// bands are never taken for a wall's base.
TEST(WallBase, TheFirstStepBelowTheHorizonEndsTheSearch) {
  View view(300);
  view.disparity.rowRange(300, kHeight).setTo(kUntexturedDisparity);  // floor texture faded
  EXPECT_NEAR(find_wall_base_row(view.left, view.disparity, 5, kHorizon, WallBaseParams{}), 299.5, kRowTolerance);
}

TEST(WallBase, StepsAboveTheHorizonAreNotSearched) {
  const View view(200);  // the "wall" ends above the horizon: floor from row 200 down
  // Below the horizon there are only the floor's bands, under a run that stereo matched.
  EXPECT_LT(find_wall_base_row(view.left, view.disparity, 5, kHorizon, WallBaseParams{}), 0.0);
}

TEST(WallBase, NoStepNoBase) {
  View view(kHeight);  // wall to the image's bottom (faced from nearer than the floor's view)
  EXPECT_LT(find_wall_base_row(view.left, view.disparity, 5, kHorizon, WallBaseParams{}), 0.0);
  WallBaseParams off;
  off.min_step_grey = 0.0;
  const View wall(400);
  EXPECT_LT(find_wall_base_row(wall.left, wall.disparity, 5, kHorizon, off), 0.0);
}

}  // namespace
}  // namespace stereoscout::vision
