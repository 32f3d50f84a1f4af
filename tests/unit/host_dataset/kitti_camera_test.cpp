// The KITTI folder through the Camera interface: pairs in order with their times, a missing or
// wrongly sized image skipped, counted and named, the end of the sequence reported.
#include <gtest/gtest.h>

#include <cstdio>

#include "kitti_test_folder.hpp"
#include "stereoscout/host_dataset/kitti_camera.hpp"

namespace stereoscout::host_dataset {
namespace {

TEST(KittiCamera, DeliversPairsInOrderAndSkipsBrokenOnes) {
  const test::KittiTestFolder folder(4, 64, 48);
  std::remove(kitti_image_path(folder.path(), 0, 1).c_str());
  cv::imwrite(kitti_image_path(folder.path(), 1, 2), cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)));
  KittiSequence sequence;
  std::string error;
  ASSERT_TRUE(load_kitti_sequence(folder.path(), 0, sequence, error)) << error;
  KittiCamera camera(sequence);
  core::StereoFrame frame;
  frame.allocate(64, 48);

  ASSERT_TRUE(camera.capture(frame).ok());
  EXPECT_EQ(frame.sequence, 0U);
  EXPECT_EQ(frame.timestamp_ns, 0);

  EXPECT_EQ(camera.capture(frame).code, core::StatusCode::io_error);
  EXPECT_EQ(camera.last_failed_path(), kitti_image_path(folder.path(), 0, 1));
  EXPECT_EQ(camera.capture(frame).code, core::StatusCode::invalid_input);
  EXPECT_EQ(camera.last_failed_path(), kitti_image_path(folder.path(), 1, 2));

  ASSERT_TRUE(camera.capture(frame).ok());
  EXPECT_EQ(frame.sequence, 3U);
  EXPECT_EQ(frame.timestamp_ns, 300000000);
  EXPECT_EQ(frame.left.at<std::uint8_t>(5, 5), 30);
  EXPECT_EQ(frame.right.cols, 64);

  EXPECT_EQ(camera.capture(frame).code, core::StatusCode::not_available);
  EXPECT_EQ(camera.pairs_delivered(), 2U);
  EXPECT_EQ(camera.pairs_skipped(), 2U);
}

}  // namespace
}  // namespace stereoscout::host_dataset
