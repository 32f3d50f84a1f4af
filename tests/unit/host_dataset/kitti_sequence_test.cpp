// The KITTI parsers (calib.txt, times.txt, poses.txt), the folder loader and the conversion of
// KITTI camera poses to ground-plane robot poses.
#include <gtest/gtest.h>

#include <cmath>

#include "kitti_test_folder.hpp"
#include "stereoscout/host_dataset/kitti_sequence.hpp"

namespace stereoscout::host_dataset {
namespace {

TEST(KittiCalibration, FocalPrincipalPointAndBaselineFromP0AndP1) {
  KittiCalibration calibration;
  std::string error;
  ASSERT_TRUE(parse_kitti_calibration(test::kCalibration, "calib.txt", calibration, error)) << error;
  EXPECT_DOUBLE_EQ(calibration.focal_px, 700.0);
  EXPECT_DOUBLE_EQ(calibration.principal_x_px, 300.0);
  EXPECT_DOUBLE_EQ(calibration.principal_y_px, 100.0);
  EXPECT_DOUBLE_EQ(calibration.baseline_m, 0.5);  // -P1[0][3] / f = 350 / 700
}

TEST(KittiCalibration, BadLineIsNamedWithFileAndLine) {
  KittiCalibration calibration;
  std::string error;
  const std::string text = "P0: 700 0 300 0 0 700 100 0 0 0 1 0\nP1: 700 0 300 -350 0 seven 100 0 0 0 1 0\n";
  EXPECT_FALSE(parse_kitti_calibration(text, "dir/calib.txt", calibration, error));
  EXPECT_EQ(error, "dir/calib.txt:2: P1: needs 12 numbers (a 3x4 projection matrix, row-major)");
  EXPECT_FALSE(parse_kitti_calibration("P0: 700 0 300 0 0 700 100 0 0 0 1 0\n", "c.txt", calibration, error));
  EXPECT_EQ(error, "c.txt: no P1: line");
  // A left/right swap gives a negative baseline: refused rather than mirrored depth.
  const std::string swapped = "P0: 700 0 300 0 0 700 100 0 0 0 1 0\nP1: 700 0 300 350 0 700 100 0 0 0 1 0\n";
  EXPECT_FALSE(parse_kitti_calibration(swapped, "c.txt", calibration, error));
  EXPECT_NE(error.find("baseline"), std::string::npos);
}

TEST(KittiTimes, OneTimePerLineInOrder) {
  std::vector<double> times;
  std::string error;
  ASSERT_TRUE(parse_kitti_times("0.000000e+00\n1.036e-01\n\n2.07e-01\n", "times.txt", times, error)) << error;
  ASSERT_EQ(times.size(), 3U);
  EXPECT_DOUBLE_EQ(times[1], 0.1036);
  EXPECT_FALSE(parse_kitti_times("0\n0.1 0.2\n", "times.txt", times, error));
  EXPECT_EQ(error, "times.txt:2: expected one time in seconds");
  EXPECT_FALSE(parse_kitti_times("0\n0.2\n0.1\n", "times.txt", times, error));
  EXPECT_EQ(error, "times.txt:3: time does not increase");
  EXPECT_FALSE(parse_kitti_times("0\n0.2\n0.2\n", "times.txt", times, error));
  EXPECT_EQ(error, "times.txt:3: time does not increase");
  EXPECT_FALSE(parse_kitti_times("nan\n", "times.txt", times, error));
}

TEST(KittiPoses, TwelveNumbersRowMajor) {
  std::vector<Eigen::Isometry3d> poses;
  std::string error;
  ASSERT_TRUE(parse_kitti_poses("1 0 0 1 0 1 0 2 0 0 1 3\n", "poses.txt", poses, error)) << error;
  ASSERT_EQ(poses.size(), 1U);
  EXPECT_EQ(poses[0].translation(), Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_FALSE(parse_kitti_poses("1 0 0 1 0 1 0 2 0 0 1 3\n1 0 0\n", "poses.txt", poses, error));
  EXPECT_EQ(error, "poses.txt:2: expected 12 numbers (3x4 [R|t], row-major)");
}

TEST(KittiFrames, CameraPoseProjectsOntoTheGroundPlane) {
  // Forward along camera z is robot x; right along camera x is robot -y.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(2.0, -1.5, 10.0);  // y (down) is dropped
  core::Pose2 ground = ground_pose_from_camera(pose);
  EXPECT_DOUBLE_EQ(ground.x, 10.0);
  EXPECT_DOUBLE_EQ(ground.y, -2.0);
  EXPECT_DOUBLE_EQ(ground.theta, 0.0);
  // Turning left (counter-clockwise seen from above) is a rotation about the camera's -y axis.
  const double yaw = 0.3;
  pose.linear() = Eigen::AngleAxisd(yaw, -Eigen::Vector3d::UnitY()).toRotationMatrix();
  ground = ground_pose_from_camera(pose);
  EXPECT_NEAR(ground.theta, yaw, 1e-12);
  // The optical axis now points forward-left: camera x of the axis is negative.
  EXPECT_LT((pose.linear() * Eigen::Vector3d::UnitZ()).x(), 0.0);
}

TEST(KittiFrames, GroundTruthIsTheRightCameraFromTheOrigin) {
  KittiSequence sequence;
  sequence.calibration.baseline_m = 0.5;
  sequence.times_s = {0.0, 0.1};
  Eigen::Isometry3d turned = Eigen::Isometry3d::Identity();
  turned.linear() = Eigen::AngleAxisd(core::kPi / 2.0, -Eigen::Vector3d::UnitY()).toRotationMatrix();
  turned.translation() = Eigen::Vector3d(0.0, 0.0, 4.0);
  sequence.world_from_cam0 = {Eigen::Isometry3d::Identity(), turned};
  const std::vector<core::Pose2> poses = ground_truth_robot_poses(sequence);
  ASSERT_EQ(poses.size(), 2U);
  EXPECT_NEAR(poses[0].x, 0.0, 1e-12);
  EXPECT_NEAR(poses[0].y, 0.0, 1e-12);
  // cam0 at 4 m forward, turned 90 deg left: cam1 is half a metre further forward (its x axis
  // now points along the old z), and the origin is cam1 at frame 0, half a metre right of cam0.
  EXPECT_NEAR(poses[1].x, 4.5, 1e-12);
  EXPECT_NEAR(poses[1].y, 0.5, 1e-12);
  EXPECT_NEAR(poses[1].theta, core::kPi / 2.0, 1e-12);
}

TEST(KittiFolder, LoadsAFolderAndItsImageSize) {
  const test::KittiTestFolder folder(5, 64, 48);
  KittiSequence sequence;
  std::string error;
  ASSERT_TRUE(load_kitti_sequence(folder.path(), 0, sequence, error)) << error;
  EXPECT_EQ(sequence.frames(), 5U);
  EXPECT_EQ(sequence.calibration.width_px, 64);
  EXPECT_EQ(sequence.calibration.height_px, 48);
  ASSERT_TRUE(sequence.has_ground_truth());
  ASSERT_TRUE(load_kitti_sequence(folder.path(), 3, sequence, error)) << error;
  EXPECT_EQ(sequence.frames(), 3U);
  EXPECT_EQ(sequence.world_from_cam0.size(), 3U);
}

TEST(KittiFolder, MissingAndShortFilesAreNamed) {
  const test::KittiTestFolder folder(3);
  KittiSequence sequence;
  std::string error;
  folder.write("poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n");
  EXPECT_FALSE(load_kitti_sequence(folder.path(), 0, sequence, error));
  EXPECT_EQ(error, folder.path() + "/poses.txt: 1 poses for 3 frames of times.txt");
  folder.write("calib.txt", "P0: 1 2\n");
  EXPECT_FALSE(load_kitti_sequence(folder.path(), 0, sequence, error));
  EXPECT_EQ(error, folder.path() + "/calib.txt:1: P0: needs 12 numbers (a 3x4 projection matrix, row-major)");
  EXPECT_FALSE(load_kitti_sequence(folder.path() + "/nowhere", 0, sequence, error));
  EXPECT_EQ(error, folder.path() + "/nowhere/calib.txt: cannot open");
}

TEST(KittiFolder, MissingFirstImageIsNamed) {
  const test::KittiTestFolder folder(2);
  std::remove(kitti_image_path(folder.path(), 1, 0).c_str());
  KittiSequence sequence;
  std::string error;
  EXPECT_FALSE(load_kitti_sequence(folder.path(), 0, sequence, error));
  EXPECT_EQ(error, kitti_image_path(folder.path(), 1, 0) + ": missing or not an image");
}

}  // namespace
}  // namespace stereoscout::host_dataset
