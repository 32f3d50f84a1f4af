// The front end on real outdoor stereo (KITTI odometry 06, frames 0-4): a feature that keeps
// its identity from one frame to the next must land on the same world point, given the
// ground-truth camera poses. Skips when the data folder is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "stereoscout/test/paths.hpp"
#include "stereoscout/vision/front_end.hpp"

namespace stereoscout::vision {
namespace {

// P0 and P1 of calib.txt give f, the principal point and the baseline (-P1[0,3] / f).
bool read_kitti_calibration(const std::string& path, int width, int height, StereoCalibration& calibration) {
  std::ifstream file(path);
  std::string line;
  std::vector<double> p0;
  std::vector<double> p1;
  while (std::getline(file, line)) {
    std::istringstream fields(line);
    std::string name;
    fields >> name;
    std::vector<double>& target = name == "P0:" ? p0 : p1;
    if (name != "P0:" && name != "P1:") continue;
    double value = 0.0;
    while (fields >> value) target.push_back(value);
  }
  if (p0.size() != 12 || p1.size() != 12) return false;
  calibration.focal_px = p0[0];
  calibration.principal_x_px = p0[2];
  calibration.principal_y_px = p0[6];
  calibration.baseline_m = -p1[3] / p1[0];
  calibration.width_px = width;
  calibration.height_px = height;
  return true;
}

std::vector<Eigen::Isometry3d> read_kitti_poses(const std::string& path) {
  std::vector<Eigen::Isometry3d> poses;
  std::ifstream file(path);
  std::string line;
  while (std::getline(file, line)) {
    std::istringstream fields(line);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 4; ++col) fields >> pose.matrix()(row, col);
    }
    poses.push_back(pose);
  }
  return poses;
}

TEST(KittiFrontEnd, IdentitiesLandOnTheSameWorldPoint) {
  const std::string folder = test::data_path("kitti-odometry/06-first51");
  if (folder.empty()) {
    GTEST_SKIP() << "KITTI excerpt not found under " << test::data_dir() << "/kitti-odometry/06-first51";
  }
  const std::vector<Eigen::Isometry3d> poses = read_kitti_poses(folder + "/poses.txt");
  ASSERT_GE(poses.size(), 10U);
  char name[32];
  std::snprintf(name, sizeof name, "/%06d.png", 0);
  const cv::Mat first = cv::imread(folder + "/image_0" + name, cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(first.empty());
  StereoCalibration calibration;
  ASSERT_TRUE(read_kitti_calibration(folder + "/calib.txt", first.cols, first.rows, calibration));
  core::VisionConfig config;
  config.candidate_min_frames = 1;
  config.max_disparity_px = 200.0;
  VisionFrontEnd front_end(config, core::RobotConfig{}, calibration, core::CameraMount{});
  core::FixedVector<core::LandmarkObservation> observations(front_end.max_observations());
  std::map<std::uint32_t, std::pair<Eigen::Vector3d, Eigen::Matrix3d>> previous;
  std::size_t shared = 0;
  std::size_t consistent = 0;
  std::vector<double> distances;
  std::size_t matches = 0;
  for (int frame = 0; frame < 5; ++frame) {
    std::snprintf(name, sizeof name, "/%06d.png", frame);
    core::StereoFrame pair;
    pair.left = cv::imread(folder + "/image_0" + name, cv::IMREAD_GRAYSCALE);
    pair.right = cv::imread(folder + "/image_1" + name, cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(pair.left.empty() || pair.right.empty());
    ASSERT_TRUE(front_end.observe_landmarks(pair, observations).ok());
    matches += front_end.last_frame_stats().stereo_matches;
    // Our points are in the right camera (cam1); KITTI poses are of cam0, a baseline left.
    Eigen::Isometry3d world_from_right = poses[static_cast<std::size_t>(frame)];
    world_from_right.translation() = poses[static_cast<std::size_t>(frame)] * Eigen::Vector3d(calibration.baseline_m, 0.0, 0.0);
    std::map<std::uint32_t, std::pair<Eigen::Vector3d, Eigen::Matrix3d>> current;
    for (const auto& observation : observations) {
      const Eigen::Vector3d world = world_from_right * observation.point_camera;
      const Eigen::Matrix3d covariance = core::rotate_covariance(world_from_right.linear(), observation.covariance);
      const auto before = previous.find(observation.landmark_id);
      if (before != previous.end()) {
        ++shared;
        const Eigen::Vector3d delta = world - before->second.first;
        consistent += core::mahalanobis_squared(delta, covariance + before->second.second) < 16.27 ? 1U : 0U;
        distances.push_back(delta.norm());
      }
      current[observation.landmark_id] = {world, covariance};
    }
    previous = current;
  }
  ASSERT_GT(shared, 100U);
  std::sort(distances.begin(), distances.end());
  std::printf("kitti 06 frames 0-4: %.0f stereo matches per frame, %zu re-identifications between consecutive frames, "
              "%.1f %% consistent with the ground-truth motion (chi-square 99.9 %%), median 3D distance %.3f m\n",
              static_cast<double>(matches) / 5.0, shared, 100.0 * static_cast<double>(consistent) / static_cast<double>(shared),
              distances[distances.size() / 2]);
  EXPECT_GT(static_cast<double>(consistent), 0.9 * static_cast<double>(shared));
}

}  // namespace
}  // namespace stereoscout::vision
