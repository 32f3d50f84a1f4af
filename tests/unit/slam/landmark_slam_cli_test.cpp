// `stereoscout landmark-slam` as a user runs it: the files it writes, report.json's keys, the
// same bytes for the same seed, and clear errors.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "stereoscout/test/command.hpp"
#include "stereoscout/test/paths.hpp"

namespace {

using stereoscout::test::CommandResult;

CommandResult run(const std::string& arguments) {
  return stereoscout::test::run_stereoscout("landmark-slam " + arguments);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(LandmarkSlamCli, WritesTheRunFilesAndTheSameBytesForTheSameSeed) {
  const std::string folder = stereoscout::test::data_path("mrclam/Dataset1");
  if (folder.empty()) {
    GTEST_SKIP() << "MRCLAM Dataset1 not found under " << stereoscout::test::data_dir();
  }
  const std::string out_a = ::testing::TempDir() + "landmark_slam_a";
  const std::string out_b = ::testing::TempDir() + "landmark_slam_b";
  const std::string common = "--mrclam " + folder + " --robot 3 --particles 30 --duration 60 --seed 4 --out ";
  const CommandResult a = run(common + out_a);
  ASSERT_EQ(a.exit_code, 0) << a.output;
  ASSERT_EQ(run(common + out_b).exit_code, 0);
  const std::string report = read_file(out_a + "/report.json");
  for (const char* key : {"\"landmark_rmse_m\"", "\"landmarks_mapped\"", "\"deadreckoning_landmark_rmse_m\"",
                          "\"wall_time_s\"", "\"updates\""}) {
    EXPECT_NE(report.find(key), std::string::npos) << key << " missing in\n" << report;
  }
  EXPECT_EQ(report.find("ate_rmse_m"), std::string::npos);  // no RobotN_Groundtruth.dat here
  const std::string trajectory = read_file(out_a + "/trajectory.tum");
  EXPECT_GT(trajectory.size(), 100u);
  EXPECT_EQ(trajectory, read_file(out_b + "/trajectory.tum"));
  EXPECT_EQ(read_file(out_a + "/landmarks.ply"), read_file(out_b + "/landmarks.ply"));
  EXPECT_EQ(read_file(out_a + "/landmarks.ply").rfind("ply\nformat ascii 1.0\n", 0), 0u);
  EXPECT_FALSE(read_file(out_a + "/odometry.tum").empty());
}

TEST(LandmarkSlamCli, NamesAMissingFolderAndAMissingOption) {
  CommandResult result = run("--mrclam /nonexistent/mrclam --robot 1 --out " + ::testing::TempDir() + "unused");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("/nonexistent/mrclam/Barcodes.dat"), std::string::npos) << result.output;
  result = run("--robot 1");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.output.find("--mrclam is required"), std::string::npos) << result.output;
}

}  // namespace
