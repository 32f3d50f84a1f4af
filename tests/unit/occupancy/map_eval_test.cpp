#include "map_eval.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "map_png.hpp"

namespace stereoscout::cli {
namespace {

using occupancy::CellState;

occupancy::RosMap make_map(int width, int height, double resolution, double origin_x, CellState fill) {
  occupancy::RosMap map;
  map.geometry.width_cells = width;
  map.geometry.height_cells = height;
  map.geometry.resolution_m = resolution;
  map.geometry.origin_x_m = origin_x;
  map.cells.assign(map.geometry.cell_count(), fill);
  return map;
}

void set(occupancy::RosMap& map, int x, int y, CellState state) {
  map.cells[static_cast<std::size_t>(y * map.geometry.width_cells + x)] = state;
}

// Ground truth 4 x 4 at 5 cm: left half occupied, right half free. The map, at 10 cm with one
// extra unknown column on the left (origin -0.1), holds: (1,0) occupied, (1,1) unknown,
// (2,0) free, (2,1) occupied.
TEST(MapEval, ComparesAcrossResolutionsAndOrigins) {
  occupancy::RosMap truth = make_map(4, 4, 0.05, 0.0, CellState::free);
  for (int y = 0; y < 4; ++y) {
    set(truth, 0, y, CellState::occupied);
    set(truth, 1, y, CellState::occupied);
  }
  occupancy::RosMap map = make_map(3, 2, 0.1, -0.1, CellState::unknown);
  set(map, 1, 0, CellState::occupied);
  set(map, 2, 0, CellState::free);
  set(map, 2, 1, CellState::occupied);
  occupancy::RosMap reachable = make_map(4, 4, 0.05, 0.0, CellState::unknown);
  for (int y = 0; y < 4; ++y) {
    set(reachable, 2, y, CellState::free);
    set(reachable, 3, y, CellState::free);
  }
  const MapEvaluation result = evaluate_map(map, truth, &reachable);
  EXPECT_EQ(result.ground_truth_known, 16u);
  EXPECT_EQ(result.compared, 12u);
  EXPECT_EQ(result.correct, 8u);
  EXPECT_DOUBLE_EQ(result.accuracy(), 8.0 / 12.0);
  EXPECT_DOUBLE_EQ(result.occupied_precision(), 0.5);
  EXPECT_DOUBLE_EQ(result.occupied_recall(), 0.5);
  EXPECT_DOUBLE_EQ(result.coverage(), 0.5);
  EXPECT_NE(result.to_json().find("\"coverage\": 0.500000"), std::string::npos) << result.to_json();
  EXPECT_NE(evaluate_map(map, truth, nullptr).to_json().find("\"coverage\": null"), std::string::npos);
}

TEST(MapPng, DrawsThePathsInTheirColours) {
  occupancy::RosMap map = make_map(40, 30, 0.1, 0.0, CellState::free);
  MapOverlays overlays;
  overlays.estimated_trajectory = {{0.5, 1.05}, {3.5, 1.05}};
  overlays.raw_odometry = {{0.5, 2.05}, {3.5, 2.05}};
  overlays.plan = {{2.05, 0.2}, {2.05, 0.6}};
  const std::string path = ::testing::TempDir() + "/occupancy_map.png";
  ASSERT_EQ(write_map_png(map, overlays, path), "");
  const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  ASSERT_EQ(image.rows, 30);
  ASSERT_EQ(image.cols, 40);
  // y = 1.05 m is image row 30 - 10.5 = 19; blue dominates there.
  const cv::Vec3b trajectory = image.at<cv::Vec3b>(19, 20);
  EXPECT_GT(trajectory[0], trajectory[2]);
  const cv::Vec3b odometry = image.at<cv::Vec3b>(9, 20);
  EXPECT_GT(odometry[2], odometry[0]);
  const cv::Vec3b plan = image.at<cv::Vec3b>(26, 20);
  EXPECT_GT(plan[1], plan[0]);
  EXPECT_EQ(image.at<cv::Vec3b>(2, 2), cv::Vec3b(254, 254, 254));
}

}  // namespace
}  // namespace stereoscout::cli
