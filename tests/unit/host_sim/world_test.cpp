#include <gtest/gtest.h>

#include "stereoscout/host_sim/world.hpp"
#include "test_worlds.hpp"

namespace stereoscout::host_sim {
namespace {

using testing::load_or_fail;
using testing::room_yaml;
using testing::source_path;

std::string first_error(const std::string& yaml) {
  const WorldLoad load = load_world_text(yaml, "bad.yaml");
  return load.errors.empty() ? std::string() : load.errors.front();
}

TEST(World, ShippedWorldsLoad) {
  for (const char* name : {"lab", "office", "clutter"}) {
    const WorldLoad load = load_world(source_path(std::string("config/worlds/") + name + ".yaml"));
    EXPECT_TRUE(load.ok()) << name << ":\n" << load.error_text();
    EXPECT_EQ(load.world.name, name);
    EXPECT_FALSE(load.world.walls.empty());
  }
}

TEST(World, LabHasThePapersFeatures) {
  const WorldLoad load = load_world(source_path("config/worlds/lab.yaml"));
  ASSERT_TRUE(load.ok()) << load.error_text();
  const World& lab = load.world;
  // About 19 m x 16.5 m in all.
  EXPECT_NEAR(lab.bounds_max().x() - lab.bounds_min().x(), 19.0, 0.01);
  EXPECT_NEAR(lab.bounds_max().y() - lab.bounds_min().y(), 16.5, 0.01);
  EXPECT_EQ(lab.people.size(), 2U);
  EXPECT_EQ(lab.floor_type_at({3.0, 3.0}), FloorType::tile);
  EXPECT_EQ(lab.floor_type_at({15.0, 8.0}), FloorType::carpet);
  EXPECT_GT(lab.light_gain_at({14.0, 1.0}), 1.0);
  EXPECT_EQ(lab.light_gain_at({3.0, 3.0}), 1.0);
}

TEST(World, DoorsSplitWallsAndKeepTheLintel) {
  const World world = load_or_fail(
      "start: [1, 1, 0]\nceiling_height: 2.5\n"
      "walls:\n  - {points: [[0, 0], [10, 0]], openings: [{at: 5, width: 1, top: 2}]}\n");
  // Left of the door, right of the door, and the lintel above it.
  ASSERT_EQ(world.walls.size(), 3U);
  EXPECT_DOUBLE_EQ(world.walls[0].b.x(), 4.5);
  EXPECT_DOUBLE_EQ(world.walls[1].a.x(), 4.5);
  EXPECT_DOUBLE_EQ(world.walls[1].z_min, 2.0);
  EXPECT_DOUBLE_EQ(world.walls[2].a.x(), 5.5);
  EXPECT_DOUBLE_EQ(world.walls[2].z_max, 2.5);
  // The gap between the jambs is its doorway.
  ASSERT_EQ(world.doorways.size(), 1U);
  EXPECT_DOUBLE_EQ(world.doorways[0].jamb_a.x(), 4.5);
  EXPECT_DOUBLE_EQ(world.doorways[0].jamb_b.x(), 5.5);
  EXPECT_DOUBLE_EQ(world.doorways[0].jamb_b.y(), 0.0);
}

TEST(World, OnlyOpeningsDownToTheFloorAreDoorways) {
  const World world = load_or_fail(
      "start: [1, 1, 0]\nwalls:\n  - {points: [[0, 0], [10, 0], [10, 10]], openings: [{at: 2, width: 2, bottom: 1, top: 2, kind: window},"
      " {at: 5, width: 1, bottom: 0.3, top: 2}, {at: 14, width: 0.9, top: 2}]}\n");
  // The window and the hatch 0.3 m up are no ways through; the door on the second segment is.
  ASSERT_EQ(world.doorways.size(), 1U);
  EXPECT_DOUBLE_EQ(world.doorways[0].jamb_a.x(), 10.0);
  EXPECT_NEAR(world.doorways[0].jamb_a.y(), 3.55, 1e-12);
  EXPECT_NEAR(world.doorways[0].jamb_b.y(), 4.45, 1e-12);
}

TEST(World, WindowsAreBrightPanes) {
  const World world = load_or_fail(
      "start: [1, 1, 0]\nwalls:\n  - {points: [[0, 0], [10, 0]], openings: [{at: 5, width: 2, bottom: 1, top: 2, kind: window, brightness: 3.5}]}\n");
  // Left, below, above, the pane, right.
  ASSERT_EQ(world.walls.size(), 5U);
  EXPECT_FLOAT_EQ(world.walls[3].surface.brightness, 3.5F);
  EXPECT_DOUBLE_EQ(world.walls[3].z_min, 1.0);
}

TEST(World, PeopleWalkTheirLoop) {
  const World world = load_or_fail(
      "start: [1, 1, 0]\nwalls:\n  - {points: [[0, 0], [10, 0]]}\n"
      "people:\n  - {waypoints: [[0, 0], [4, 0], [4, 3]], speed: 1.0}\n");
  EXPECT_TRUE(world.person_position(0, 2.0).isApprox(Eigen::Vector2d(2.0, 0.0)));
  EXPECT_TRUE(world.person_position(0, 5.0).isApprox(Eigen::Vector2d(4.0, 1.0)));
  // The loop is 12 m long (back along the diagonal of 5 m): at 12 s it is home again.
  EXPECT_LT((world.person_position(0, 12.0) - Eigen::Vector2d(0.0, 0.0)).norm(), 1e-9);
}

TEST(World, UnknownKeyIsRejectedWithFileAndKey) {
  const std::string error = first_error(room_yaml("brick") + "cylinders:\n  - {center: [1, 1], radius: 0.2, z: [0, 1], colour: red}\n");
  EXPECT_EQ(error, "bad.yaml: cylinders[0].colour: unknown key");
  EXPECT_EQ(first_error(room_yaml("brick") + "gravity: 9.81\n"), "bad.yaml: gravity: unknown key");
  EXPECT_EQ(first_error(room_yaml("brick") + "ceiling_height: 3.0\n"), "bad.yaml: ceiling_height: key given more than once");
  EXPECT_EQ(first_error("start: [1, 1, 0]\nwalls:\n  - {points: [[0, 0], [4, 0]], openings: [{at: 1, width: 1, hinge: left}]}\n"),
            "bad.yaml: walls[0].openings[0].hinge: unknown key");
}

TEST(World, OpenPolygonIsRejected) {
  const std::string error = first_error(room_yaml("brick") + "prisms:\n  - {polygon: [[1, 1], [2, 1], [2, 2], [1, 2]], z: [0, 1]}\n");
  EXPECT_EQ(error, "bad.yaml: prisms[0].polygon: open polygon: the last point must repeat the first");
}

TEST(World, WrongTypesAndRangesAreRejected) {
  EXPECT_EQ(first_error(room_yaml("brick") + "cylinders:\n  - {center: [1, 1], radius: big, z: [0, 1]}\n"),
            "bad.yaml: cylinders[0].radius: expected a number, got text 'big'");
  EXPECT_EQ(first_error(room_yaml("brick") + "boxes:\n  - {center: [1, 1], size: [1, 1], z: [1, 0.5]}\n"),
            "bad.yaml: boxes[0].z: needs 0 <= z_min < z_max");
  EXPECT_EQ(first_error(room_yaml("marble")), "bad.yaml: walls[0].texture: unknown texture 'marble' (blank, low, noise, brick, wood, poster, books, tile, carpet)");
  EXPECT_EQ(first_error("walls: []\n"), "bad.yaml: start: missing (the robot's start pose [x, y, theta_deg] is required)");
  EXPECT_EQ(first_error(room_yaml("brick") + "floor_regions:\n  - {polygon: [[0, 0], [1, 0], [1, 1], [0, 0]], type: grass}\n"),
            "bad.yaml: floor_regions[0].type: unknown floor type 'grass' (tile, carpet)");
  EXPECT_EQ(first_error("texture_variants: 2.5\n" + room_yaml("brick")),
            "bad.yaml: texture_variants: expected a whole number of tiles, got 2.5");
  EXPECT_EQ(first_error("texture_variants: 0\n" + room_yaml("brick")).rfind("bad.yaml: texture_variants: ", 0), 0U);
  EXPECT_EQ(first_error("texture_variants: 33\n" + room_yaml("brick")).rfind("bad.yaml: texture_variants: ", 0), 0U);
}

TEST(World, MissingFileIsAnError) {
  const WorldLoad load = load_world("/nonexistent/world.yaml");
  ASSERT_FALSE(load.ok());
  EXPECT_EQ(load.errors.front(), "/nonexistent/world.yaml: cannot open the world file");
}

TEST(World, PolygonContainment) {
  const std::vector<Eigen::Vector2d> square = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  EXPECT_TRUE(polygon_contains(square, {1, 1}));
  EXPECT_FALSE(polygon_contains(square, {3, 1}));
}

}  // namespace
}  // namespace stereoscout::host_sim
