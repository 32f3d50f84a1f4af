#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "stereoscout/host_sim/ground_truth.hpp"
#include "test_worlds.hpp"

namespace stereoscout::host_sim {
namespace {

using testing::load_or_fail;
using testing::room_yaml;
using testing::source_path;

constexpr double kFloorTolerance = 0.02;
constexpr double kRobotHeight = 1.2;
constexpr double kRobotRadius = 0.35;

std::uint8_t cell_at(const GroundTruthGrid& grid, double x, double y) {
  const Eigen::Vector2i cell = grid.cell_of({x, y});
  return grid.at(cell.x(), cell.y());
}

TEST(GroundTruth, LinesOfSightAndNearestObstaclePointFollowTheBand) {
  // The room is 10 x 6; a low box at (2, 2) is in the robot's band and below a camera at 0.6 m,
  // a pillar at (5, 4) reaches above it.
  const World world = load_or_fail(room_yaml("brick") + "boxes:\n  - {center: [2, 2], size: [0.4, 0.4], z: [0, 0.1]}\n"
                                                        "cylinders:\n  - {center: [5, 4], radius: 0.2, z: [0, 0.9]}\n");
  const ObstacleBand robot_band(world, kFloorTolerance, kRobotHeight);
  const ObstacleBand camera_height(world, 0.6, 0.6);
  EXPECT_TRUE(robot_band.blocks_line({1.0, 2.0}, {3.0, 2.0}));   // through the low box
  EXPECT_FALSE(camera_height.blocks_line({1.0, 2.0}, {3.0, 2.0}));  // over it
  EXPECT_TRUE(camera_height.blocks_line({4.0, 4.1}, {6.0, 4.1}));   // through the pillar
  EXPECT_FALSE(camera_height.blocks_line({4.0, 4.5}, {6.0, 4.5}));  // beside it
  EXPECT_TRUE(camera_height.blocks_line({5.0, 5.0}, {5.0, 7.0}));   // out through the north wall
  EXPECT_FALSE(camera_height.blocks_line({1.0, 1.0}, {9.0, 5.0}));  // across the room
  EXPECT_NEAR((robot_band.nearest_point({2.0, 1.5}) - Eigen::Vector2d(2.0, 1.8)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((robot_band.nearest_point({5.0, 4.5}) - Eigen::Vector2d(5.0, 4.2)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((robot_band.nearest_point({9.7, 3.0}) - Eigen::Vector2d(10.0, 3.0)).norm(), 0.0, 1e-9);
}

TEST(GroundTruth, HeightBandDecidesWhatIsAnObstacle) {
  const World world = load_or_fail(room_yaml("brick") +
                                   "boxes:\n  - {center: [2, 2], size: [0.4, 0.4], z: [0, 0.1]}\n"   // low box: blocks
                                   "  - {center: [4, 2], size: [0.4, 0.4], z: [0.72, 0.76]}\n"        // table top: blocks
                                   "  - {center: [6, 2], size: [0.4, 0.4], z: [1.5, 2.0]}\n"          // above the robot
                                   "  - {center: [8, 2], size: [0.4, 0.4], z: [0, 0.01]}\n"           // flat mat
                                   "cylinders:\n  - {center: [5, 4], radius: 0.2, z: [0, 0.9]}\n");
  const GroundTruthGrid grid = rasterize_world(world, 0.05, kFloorTolerance, kRobotHeight);
  EXPECT_EQ(cell_at(grid, 2.0, 2.0), GroundTruthGrid::occupied);
  EXPECT_EQ(cell_at(grid, 4.0, 2.0), GroundTruthGrid::occupied);
  EXPECT_EQ(cell_at(grid, 6.0, 2.0), GroundTruthGrid::free);
  EXPECT_EQ(cell_at(grid, 8.0, 2.0), GroundTruthGrid::free);
  EXPECT_EQ(cell_at(grid, 5.0, 4.0), GroundTruthGrid::occupied);
  EXPECT_EQ(cell_at(grid, 5.0, 3.0), GroundTruthGrid::free);
  // Walls are thin lines of cells at any resolution.
  EXPECT_EQ(cell_at(grid, 10.0, 3.0), GroundTruthGrid::occupied);
  EXPECT_EQ(cell_at(grid, 9.9, 3.0), GroundTruthGrid::free);
  const GroundTruthGrid coarse = rasterize_world(world, 0.2, kFloorTolerance, kRobotHeight);
  EXPECT_EQ(cell_at(coarse, 10.0, 3.0), GroundTruthGrid::occupied);
  EXPECT_EQ(cell_at(coarse, 2.0, 2.0), GroundTruthGrid::occupied);
}

// Two rooms joined by one door of `door_width`.
World two_rooms(double door_width) {
  return load_or_fail("start: [2, 2, 0]\nwalls:\n  - {points: [[0, 0], [10, 0], [10, 4], [0, 4], [0, 0]]}\n"
                      "  - {points: [[5, 0], [5, 4]], openings: [{at: 2, width: " + std::to_string(door_width) + "}]}\n");
}

TEST(GroundTruth, ReachableSpaceStopsAtADoorTooNarrowForTheRobot) {
  for (const auto& [width, passable] : {std::pair{1.0, true}, std::pair{0.6, false}}) {
    const World world = two_rooms(width);
    const GroundTruthGrid grid = rasterize_world(world, 0.05, kFloorTolerance, kRobotHeight);
    const GroundTruthGrid reachable = reachable_free_space(grid, world.start.translation(), kRobotRadius);
    EXPECT_EQ(cell_at(reachable, 2.0, 2.0), GroundTruthGrid::free) << width;
    EXPECT_EQ(cell_at(reachable, 8.0, 2.0), passable ? GroundTruthGrid::free : GroundTruthGrid::unknown) << width;
    // Not within a radius of a wall.
    EXPECT_EQ(cell_at(reachable, 2.0, 0.2), GroundTruthGrid::unknown);
    EXPECT_EQ(cell_at(reachable, 5.0, 0.2), GroundTruthGrid::occupied);
  }
}

TEST(GroundTruth, LabRoomsAreJoinedByTheWideDoorOnly) {
  const WorldLoad load = load_world(source_path("config/worlds/lab.yaml"));
  ASSERT_TRUE(load.ok()) << load.error_text();
  const GroundTruthGrid grid = rasterize_world(load.world, 0.1, kFloorTolerance, kRobotHeight);
  const GroundTruthGrid reachable = reachable_free_space(grid, load.world.start.translation(), kRobotRadius);
  EXPECT_EQ(cell_at(reachable, 9.5, 4.0), GroundTruthGrid::free);      // the 1.1 m door
  EXPECT_NE(cell_at(reachable, 9.5, 12.0), GroundTruthGrid::free);     // the 0.6 m door
  EXPECT_EQ(cell_at(reachable, 15.0, 12.0), GroundTruthGrid::free);    // the east room, through the wide door
  const double reachable_m2 = static_cast<double>(reachable.count(GroundTruthGrid::free)) * 0.01;
  EXPECT_GT(reachable_m2, 200.0);
  EXPECT_LT(reachable_m2, 19.0 * 16.5);
}

TEST(GroundTruth, ShippedWorldsStartTheRobotInReachableFreeSpace) {
  for (const char* name : {"lab", "office", "clutter"}) {
    const WorldLoad load = load_world(source_path(std::string("config/worlds/") + name + ".yaml"));
    ASSERT_TRUE(load.ok()) << load.error_text();
    const GroundTruthGrid grid = rasterize_world(load.world, 0.1, kFloorTolerance, kRobotHeight);
    const GroundTruthGrid reachable = reachable_free_space(grid, load.world.start.translation(), kRobotRadius);
    EXPECT_GT(reachable.count(GroundTruthGrid::free), 1000U) << name;
    for (std::size_t i = 0; i < load.world.people.size(); ++i) {
      const double clearance = (load.world.person_position(i, 0.0) - load.world.start.translation()).norm();
      EXPECT_GT(clearance, kRobotRadius + load.world.people[i].radius) << name << " person " << i;
    }
  }
}

TEST(GroundTruth, MapServerFiles) {
  const World world = two_rooms(1.0);
  const GroundTruthGrid grid = rasterize_world(world, 0.1, kFloorTolerance, kRobotHeight);
  const std::string pgm = ::testing::TempDir() + "host_sim_map.pgm";
  const std::string yaml = ::testing::TempDir() + "host_sim_map.yaml";
  ASSERT_EQ(write_map_pgm(grid, pgm), "");
  ASSERT_EQ(write_map_yaml(grid, yaml, "map.pgm"), "");
  std::ifstream image(pgm, std::ios::binary);
  std::string magic;
  std::string comment;
  int width = 0;
  int height = 0;
  int max_value = 0;
  image >> magic;
  image.ignore();
  std::getline(image, comment);
  image >> width >> height >> max_value;
  image.ignore();
  EXPECT_EQ(magic, "P5");
  EXPECT_EQ(width, grid.width);
  EXPECT_EQ(height, grid.height);
  EXPECT_EQ(max_value, 255);
  std::vector<char> pixels(static_cast<std::size_t>(width * height));
  image.read(pixels.data(), static_cast<std::streamsize>(pixels.size()));
  ASSERT_TRUE(image.good());
  // Top-left pixel: highest y, lowest x, in the margin (free); cell (iy = 0) is the last row.
  const auto pixel = [&](int ix, int iy) { return static_cast<unsigned char>(pixels[static_cast<std::size_t>((height - 1 - iy) * width + ix)]); };
  const Eigen::Vector2i wall = grid.cell_of({5.0, 1.0});
  EXPECT_EQ(pixel(wall.x(), wall.y()), 0);
  const Eigen::Vector2i room = grid.cell_of({2.0, 2.0});
  EXPECT_EQ(pixel(room.x(), room.y()), 254);
  std::ifstream yaml_stream(yaml);
  std::stringstream text;
  text << yaml_stream.rdbuf();
  char expected[256];
  std::snprintf(expected, sizeof expected,
                "image: map.pgm\nresolution: 0.100000\norigin: [%.6f, %.6f, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
                grid.origin.x(), grid.origin.y());
  EXPECT_EQ(text.str(), expected);
  EXPECT_NEAR(grid.origin.x(), -0.5, 1e-12);
}

}  // namespace
}  // namespace stereoscout::host_sim
