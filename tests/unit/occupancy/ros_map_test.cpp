#include "stereoscout/occupancy/ros_map.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace stereoscout::occupancy {
namespace {

std::string temp_dir() {
  const std::string dir = ::testing::TempDir();
  return dir.empty() || dir.back() == '/' ? dir : dir + "/";
}

TEST(RosMap, WritesAndReadsBackTheClassification) {
  GridGeometry geometry;
  geometry.width_cells = 5;
  geometry.height_cells = 3;
  geometry.resolution_m = 0.1;
  geometry.origin_x_m = -0.25;
  geometry.origin_y_m = 1.5;
  OccupancyGrid grid(geometry, LogOddsModel{});
  core::DepthScan scan;
  scan.columns.push_back({0.4F, 0.0F, core::DepthScanColumn::Kind::obstacle});
  // Ray from (-0.2, 1.55) to (0.2, 1.55): cells (0..4, 0); four hits at (4, 0), four misses before.
  for (int i = 0; i < 4; ++i) grid.insert(scan, core::Pose2{-0.2, 1.55, 0.0});
  const RosMap map = classify_grid(grid, CellThresholds{});
  EXPECT_EQ(map.at(4, 0), CellState::occupied);
  EXPECT_EQ(map.at(0, 0), CellState::free);
  EXPECT_EQ(map.at(0, 1), CellState::unknown);

  const std::string pgm = temp_dir() + "occupancy_roundtrip.pgm";
  const std::string yaml = temp_dir() + "occupancy_roundtrip.yaml";
  ASSERT_EQ(write_ros_map(map, pgm, yaml), "");
  RosMap back;
  ASSERT_EQ(read_ros_map(yaml, back), "");
  EXPECT_EQ(back.geometry.width_cells, 5);
  EXPECT_EQ(back.geometry.height_cells, 3);
  EXPECT_DOUBLE_EQ(back.geometry.resolution_m, 0.1);
  EXPECT_DOUBLE_EQ(back.geometry.origin_x_m, -0.25);
  EXPECT_DOUBLE_EQ(back.geometry.origin_y_m, 1.5);
  EXPECT_DOUBLE_EQ(back.occupied_thresh, 0.65);
  EXPECT_DOUBLE_EQ(back.free_thresh, 0.196);
  EXPECT_EQ(back.cells, map.cells);

  // The PGM's first image row is the map's top (highest y) row: unknown here.
  std::ifstream in(pgm, std::ios::binary);
  std::string header((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GE(header.size(), 15u);
  EXPECT_EQ(static_cast<unsigned char>(header[header.size() - 15]), kPgmUnknown);
  EXPECT_EQ(static_cast<unsigned char>(header[header.size() - 1]), kPgmOccupied);
  EXPECT_EQ(static_cast<unsigned char>(header[header.size() - 5]), kPgmFree);
}

TEST(RosMap, ParseErrorsNameTheFileAndLine) {
  const std::string yaml = temp_dir() + "occupancy_bad.yaml";
  {
    std::ofstream out(yaml);
    out << "image: missing.pgm\nresolution: 0.05\norigin: [1.0, 2.0]\n";
  }
  RosMap map;
  EXPECT_EQ(read_ros_map(yaml, map), yaml + ":3: origin must be [x, y, yaw]");
  {
    std::ofstream out(yaml);
    out << "image: missing.pgm\nresolution: 0.05\norigin: [1.0, 2.0, 0.0]\n";
  }
  const std::string error = read_ros_map(yaml, map);
  EXPECT_NE(error.find("missing.pgm"), std::string::npos) << error;
  {
    std::ofstream out(yaml);
    out << "resolution: 0.05\norigin: [1.0, 2.0, 0.0]\n";
  }
  EXPECT_EQ(read_ros_map(yaml, map), yaml + ": missing key 'image'");
}

TEST(RosMap, ReadsTheSimulatorsHeaderWithAComment) {
  const std::string pgm = temp_dir() + "occupancy_comment.pgm";
  {
    std::ofstream out(pgm, std::ios::binary);
    out << "P5\n# a comment\n2 1\n255\n";
    out.put(static_cast<char>(0));
    out.put(static_cast<char>(254));
  }
  RosMap map;
  ASSERT_EQ(read_pgm_cells(pgm, map), "");
  EXPECT_EQ(map.at(0, 0), CellState::occupied);
  EXPECT_EQ(map.at(1, 0), CellState::free);
  {
    std::ofstream out(pgm, std::ios::binary);
    out << "P5\n2 2\n255\n";
    out.put(static_cast<char>(0));
  }
  EXPECT_EQ(read_pgm_cells(pgm, map), pgm + ": truncated pixel data");
}

}  // namespace
}  // namespace stereoscout::occupancy
