// The landmark filter on real data: a prefix of one MRCLAM robot's log (kept short so the suite
// stays fast); the full five-robot table is in docs/results.md.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "mrclam.hpp"
#include "stereoscout/test/paths.hpp"

namespace stereoscout::cli::mrclam {
namespace {

TEST(Mrclam, FilterMapIsFarBetterThanDeadReckoningOnAPrefixOfRobot1) {
  const std::string folder = test::data_path("mrclam/Dataset1");
  if (folder.empty()) {
    GTEST_SKIP() << "MRCLAM Dataset1 not found under " << test::data_dir() << " (set STEREOSCOUT_DATA_DIR)";
  }
  Dataset dataset;
  std::string error;
  ASSERT_TRUE(load_dataset(folder, 1, dataset, error)) << error;
  RunOptions options;
  options.filter.particles = 100;
  options.filter.particle_capacity = 100;
  options.filter.landmark_node_capacity = 100000;
  options.filter.landmark_estimate_capacity = 50000;
  options.filter.trajectory_node_capacity = 400000;
  options.duration_s = 400.0;
  const RunResult result = run_landmark_slam(dataset, options);
  EXPECT_GE(result.filter_map.mapped, 8u);
  EXPECT_GT(result.robot_measurements_dropped, 0u);
  EXPECT_EQ(result.updates_refused, 0u);
  EXPECT_LT(result.filter_map.rmse_m, 0.5);
  EXPECT_LT(result.filter_map.rmse_m * 3.0, result.dead_reckoning_map.rmse_m)
      << "filter " << result.filter_map.rmse_m << " m, dead reckoning " << result.dead_reckoning_map.rmse_m << " m";
}

TEST(Mrclam, AMissingOrMalformedFileIsNamed) {
  Dataset dataset;
  std::string error;
  EXPECT_FALSE(load_dataset("/nonexistent/folder", 1, dataset, error));
  EXPECT_NE(error.find("/nonexistent/folder/Barcodes.dat"), std::string::npos) << error;

  const std::string folder = ::testing::TempDir() + "/mrclam_bad";
  ASSERT_EQ(std::system(("mkdir -p " + folder).c_str()), 0);
  const auto write = [&](const std::string& name, const std::string& text) {
    FILE* file = std::fopen((folder + "/" + name).c_str(), "w");
    ASSERT_NE(file, nullptr);
    std::fputs(text.c_str(), file);
    std::fclose(file);
  };
  write("Barcodes.dat", "# subject barcode\n1 5\n6 72\n");
  write("Landmark_Groundtruth.dat", "6 1.0 2.0 0.001 0.001\n");
  write("Robot1_Odometry.dat", "# t v w\n10.0 0.1 0.0\n10.5 0.1 oops\n");
  write("Robot1_Measurement.dat", "10.2 72 1.5 0.1\n");
  EXPECT_FALSE(load_dataset(folder, 1, dataset, error));
  EXPECT_NE(error.find("Robot1_Odometry.dat:3"), std::string::npos) << error;
  EXPECT_FALSE(load_dataset(folder, 2, dataset, error));
  EXPECT_NE(error.find("Robot2_Odometry.dat"), std::string::npos) << error;
}

TEST(Mrclam, RigidFitRemovesAPureRotationAndTranslation) {
  const std::vector<Eigen::Vector2d> truth = {{0.0, 0.0}, {2.0, 0.0}, {0.0, 3.0}, {1.0, 1.0}};
  std::vector<Eigen::Vector2d> moved;
  const Eigen::Rotation2Dd rotation(0.7);
  for (const auto& p : truth) {
    moved.push_back(rotation * p + Eigen::Vector2d(5.0, -1.0));
  }
  const MapScore score = score_landmarks(moved, truth);
  EXPECT_EQ(score.mapped, 4u);
  EXPECT_NEAR(score.rmse_m, 0.0, 1e-12);
}

}  // namespace
}  // namespace stereoscout::cli::mrclam
