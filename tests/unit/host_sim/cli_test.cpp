#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <fstream>
#include <string>

#include "stereoscout/test/command.hpp"
#include "stereoscout/test/paths.hpp"

namespace {

std::string world_path(const char* name) { return stereoscout::test::source_path(std::string("config/worlds/") + name); }

int run(const std::string& arguments, std::string* output = nullptr) {
  const stereoscout::test::CommandResult result = stereoscout::test::run_stereoscout(arguments);
  if (output != nullptr) {
    *output = result.output;
  }
  return result.exit_code;
}

TEST(SimCommands, SimRenderWritesThePairAndDepthInMillimetres) {
  const std::string out = ::testing::TempDir() + "sim_render_test";
  std::string output;
  ASSERT_EQ(run("sim-render --world " + world_path("lab.yaml") + " --pose 2.5,2.5,30 --pan 0 --out " + out, &output), 0)
      << output;
  const cv::Mat left = cv::imread(out + "/left.png", cv::IMREAD_UNCHANGED);
  const cv::Mat right = cv::imread(out + "/right.png", cv::IMREAD_UNCHANGED);
  const cv::Mat depth = cv::imread(out + "/depth.png", cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(left.empty());
  ASSERT_FALSE(right.empty());
  ASSERT_FALSE(depth.empty());
  EXPECT_EQ(left.type(), CV_8UC1);
  EXPECT_EQ(right.size(), cv::Size(640, 480));
  EXPECT_EQ(depth.type(), CV_16UC1);
  // The bottom row sees the floor at Z = f h / (479 - cy) = 400 * 0.6 / 239.5 m.
  EXPECT_NEAR(depth.at<std::uint16_t>(479, 320), 1002, 1);
}

TEST(SimCommands, WorldMapWritesMapServerFiles) {
  const std::string out = ::testing::TempDir() + "world_map_test";
  std::string output;
  ASSERT_EQ(run("world-map --world " + world_path("lab.yaml") + " --resolution 0.1 --out " + out, &output), 0) << output;
  const cv::Mat map = cv::imread(out + "/map.pgm", cv::IMREAD_UNCHANGED);
  const cv::Mat reachable = cv::imread(out + "/reachable.pgm", cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(map.empty());
  ASSERT_EQ(reachable.size(), map.size());
  // 19 m + 2 x 0.5 m margin at 0.1 m.
  EXPECT_EQ(map.cols, 200);
  std::ifstream yaml(out + "/map.yaml");
  std::string first_line;
  std::getline(yaml, first_line);
  EXPECT_EQ(first_line, "image: map.pgm");
  EXPECT_NE(output.find("reachable"), std::string::npos);
}

// The integer after `"key": ` in a JSON text, or -1.
long long json_count(const std::string& text, const std::string& key) {
  const std::size_t at = text.find("\"" + key + "\": ");
  return at == std::string::npos ? -1 : std::stoll(text.substr(at + key.size() + 4));
}

// A few views of the office: the scan's columns placed against its walls. With the blank
// walls' bases and the textured posters nearly every obstacle column stands on a wall.
TEST(SimCommands, EvalScanPlacesTheScanAgainstTheWorld) {
  std::string output;
  ASSERT_EQ(run("eval-scan --world " + world_path("office.yaml") + " --grid 6 --headings 4", &output), 0) << output;
  EXPECT_EQ(json_count(output, "views"), 32) << output;
  const long long at = json_count(output, "within_0.1_m");
  const long long phantoms = json_count(output, "in_free_space");
  const long long all = at + json_count(output, "0.1_to_0.3_m") + json_count(output, "0.3_to_0.6_m") + phantoms;
  EXPECT_GE(at, all * 90 / 100) << output;
  EXPECT_LE(phantoms, all / 100) << output;
  const long long through = json_count(output, "free_through_obstacle");
  EXPECT_GE(through, 0) << output;
  const long long far_past = json_count(output, "free_past_obstacle_by_0.3_m");
  EXPECT_GE(far_past, 0) << output;
  EXPECT_LE(far_past, through) << output;
  EXPECT_EQ(run("eval-scan --world " + world_path("office.yaml") + " --headings 0", &output), 2);
}

TEST(SimCommands, BadWorldAndPoseAreReported) {
  const std::string bad = ::testing::TempDir() + "bad_world.yaml";
  std::ofstream(bad) << "start: [0, 0, 0]\nwalls:\n  - {points: [[0, 0], [1, 0]], colour: red}\n";
  std::string output;
  EXPECT_EQ(run("world-map --world " + bad + " --out " + ::testing::TempDir(), &output), 1);
  EXPECT_NE(output.find("bad_world.yaml: walls[0].colour: unknown key"), std::string::npos) << output;
  EXPECT_EQ(run("sim-render --world " + world_path("lab.yaml") + " --pose 1,2 --out " + ::testing::TempDir(), &output), 2);
  EXPECT_NE(output.find("--pose"), std::string::npos) << output;
}

}  // namespace
