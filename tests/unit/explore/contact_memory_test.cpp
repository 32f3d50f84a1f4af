// The stall detector and the contact memory: a robot that commands motion and does not move
// has touched something its camera did not see; the cells beyond its rim are kept as
// occupied for planning until the grid sees them free or they expire.
#include <gtest/gtest.h>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/explore/contact_memory.hpp"
#include "test_grid.hpp"

namespace stereoscout::explore {
namespace {

using testing::TestGrid;

constexpr double kTick_s = 0.05;
constexpr double kSpeed_mps = 0.12;

// Drives for `duration_s` at `speed_mps`, the pose advancing by `moved_fraction` of the
// command; returns how many windows ended stalled.
int drive(StallDetector& detector, double& time_s, Eigen::Vector2d& position, double duration_s, double moved_fraction,
          double speed_mps = kSpeed_mps) {
  int stalls = 0;
  for (const double end = time_s + duration_s; time_s < end - 1e-9;) {
    stalls += detector.stalled(time_s, position) ? 1 : 0;
    detector.commanded(time_s, position, speed_mps);
    time_s += kTick_s;
    position.x() += moved_fraction * speed_mps * kTick_s;
  }
  return stalls;
}

TEST(StallDetector, ARobotThatMovesAsCommandedNeverStalls) {
  StallDetector detector{core::ExploreConfig{}};
  double time_s = 0.0;
  Eigen::Vector2d position(1.0, 1.0);
  EXPECT_EQ(drive(detector, time_s, position, 30.0, 1.0), 0);
  // Slowed down (a carpet, wheel slip) but moving: still not a stall.
  EXPECT_EQ(drive(detector, time_s, position, 30.0, 0.5), 0);
}

TEST(StallDetector, ARobotThatDoesNotMoveStallsWithinAWindow) {
  const core::ExploreConfig config;
  StallDetector detector{config};
  double time_s = 0.0;
  Eigen::Vector2d position(1.0, 1.0);
  drive(detector, time_s, position, 5.0, 1.0);
  const double blocked_at = time_s;
  int stalls = 0;
  while (stalls == 0 && time_s < blocked_at + 10.0) stalls = drive(detector, time_s, position, kTick_s, 0.0);
  EXPECT_EQ(stalls, 1);
  // At most one window that started before the contact, then one whole window.
  EXPECT_LE(time_s - blocked_at, 2.0 * config.stall_window_s + 2.0 * kTick_s);
}

TEST(StallDetector, TurningInPlaceOrStandingIsNeverAStall) {
  StallDetector detector{core::ExploreConfig{}};
  const Eigen::Vector2d position(1.0, 1.0);
  for (double time_s = 0.0; time_s < 30.0; time_s += kTick_s) {
    EXPECT_FALSE(detector.stalled(time_s, position));
    detector.commanded(time_s, position, 0.0);
  }
  // A forward command too small to judge (creeping onto a pure-pursuit path).
  for (double time_s = 30.0; time_s < 60.0; time_s += kTick_s) {
    EXPECT_FALSE(detector.stalled(time_s, position));
    detector.commanded(time_s, position, 0.001);
  }
}

// The follower's short lookahead in a doorway can command less than stall_min_commanded_m a
// window: the window stretches until it has commanded that much, and then judges it.
TEST(StallDetector, ASlowCommandAgainstSomethingStallsOnceEnoughWasCommanded) {
  const core::ExploreConfig config;
  StallDetector moving{config};
  double time_s = 0.0;
  Eigen::Vector2d position(1.0, 1.0);
  EXPECT_EQ(drive(moving, time_s, position, 30.0, 1.0, 0.03), 0);
  StallDetector blocked{config};
  time_s = 0.0;
  int stalls = 0;
  while (stalls == 0 && time_s < 10.0) stalls = drive(blocked, time_s, position, kTick_s, 0.0, 0.03);
  EXPECT_EQ(stalls, 1);
  EXPECT_NEAR(time_s, config.stall_min_commanded_m / 0.03, 2.0 * kTick_s);
}

TEST(ContactMemory, MarksTheCellsBeyondTheRimAheadAndForgetsThemWhenSeenFree) {
  const TrailMemory no_trail{core::ExploreConfig{}};  // the robot has not driven anywhere
  TestGrid grid(60, 60, CellState::free);
  grid.fill(40, 0, 60, 60, CellState::unknown);  // a blank wall from x = 4 m: never seen
  const core::ExploreConfig config;
  ContactMemory memory(config, 60, 60);
  const double radius_m = 0.35;
  // Touching it head on: centre 0.36 m before the wall.
  memory.record(grid.view(), core::Pose2{3.64, 3.05, 0.0}, radius_m, 100.0, no_trail);
  EXPECT_EQ(memory.recorded(), 3U);
  EXPECT_EQ(memory.held(), 3U);
  const GridView stamped = memory.stamp(grid.view(), 101.0);
  ASSERT_NE(stamped.cells, grid.view().cells);
  EXPECT_EQ(stamped.at(40, 30), CellState::occupied);  // straight ahead
  int occupied = 0;
  for (int y = 0; y < 60; ++y) {
    for (int x = 0; x < 60; ++x) occupied += stamped.at(x, y) == CellState::occupied ? 1 : 0;
  }
  EXPECT_EQ(occupied, 3);
  // The grid itself is untouched.
  EXPECT_EQ(grid.view().at(40, 30), CellState::unknown);
  // Still held while the grid holds the cells unknown ...
  memory.stamp(grid.view(), 200.0);
  EXPECT_EQ(memory.held(), 3U);
  // ... forgotten once it sees them free (whatever stood there has gone).
  grid.fill(40, 0, 60, 60, CellState::free);
  const GridView freed = memory.stamp(grid.view(), 201.0);
  EXPECT_EQ(memory.held(), 0U);
  EXPECT_EQ(memory.freed(), 3U);
  EXPECT_EQ(freed.cells, grid.view().cells);  // nothing to stamp: the grid itself
}

TEST(ContactMemory, ACellTheGridHeldFreeAtTheContactIsKeptUntilItExpires) {
  const TrailMemory no_trail{core::ExploreConfig{}};  // the robot has not driven anywhere
  TestGrid grid(60, 60, CellState::free);  // the grid is wrong there: a surface it cannot see
  core::ExploreConfig config;
  config.contact_hold_s = 60.0;
  ContactMemory memory(config, 60, 60);
  memory.record(grid.view(), core::Pose2{3.64, 3.05, 0.0}, 0.35, 100.0, no_trail);
  EXPECT_EQ(memory.stamp(grid.view(), 150.0).at(40, 30), CellState::occupied);
  EXPECT_EQ(memory.held(), 3U);
  EXPECT_EQ(memory.stamp(grid.view(), 161.0).at(40, 30), CellState::free);
  EXPECT_EQ(memory.held(), 0U);
  EXPECT_EQ(memory.expired(), 3U);
}

TEST(ContactMemory, ClearForgetsEveryContactAndCountsThem) {
  const TrailMemory no_trail{core::ExploreConfig{}};  // the robot has not driven anywhere
  TestGrid grid(60, 60, CellState::unknown);
  ContactMemory memory(core::ExploreConfig{}, 60, 60);
  memory.record(grid.view(), core::Pose2{3.02, 3.05, 0.0}, 0.35, 1.0, no_trail);
  ASSERT_EQ(memory.stamp(grid.view(), 2.0).at(34, 30), CellState::occupied);
  EXPECT_EQ(memory.clear(), 3U);
  EXPECT_EQ(memory.held(), 0U);
  EXPECT_EQ(memory.cleared(), 3U);
  EXPECT_EQ(memory.stamp(grid.view(), 3.0).cells, grid.view().cells);  // nothing left to stamp
  EXPECT_EQ(memory.clear(), 0U);
  EXPECT_EQ(memory.cleared(), 3U);
}

// A plain pillar in a gap the grid holds open: the robot drives into it, the explorer finds
// nothing else to do and clears the contact, and drives into it again. That second contact is
// real and outlives the next clear; a contact elsewhere is cleared as before.
TEST(ContactMemory, AContactMadeAgainWhereOneWasClearedIsNotClearedAgain) {
  const TrailMemory no_trail{core::ExploreConfig{}};  // the robot has not driven anywhere
  TestGrid grid(60, 60, CellState::free);
  core::ExploreConfig config;
  config.contact_repeat_radius_m = 0.2;
  ContactMemory memory(config, 60, 60);
  memory.record(grid.view(), core::Pose2{3.02, 3.05, 0.0}, 0.35, 1.0, no_trail);
  EXPECT_EQ(memory.clear(), 3U);
  memory.record(grid.view(), core::Pose2{3.05, 3.1, 0.1}, 0.35, 20.0, no_trail);  // the same pillar
  memory.record(grid.view(), core::Pose2{1.0, 1.0, 3.0}, 0.35, 21.0, no_trail);   // elsewhere
  EXPECT_EQ(memory.repeated(), 3U);
  EXPECT_EQ(memory.clear(), 3U);
  EXPECT_EQ(memory.held(), 3U);
  EXPECT_EQ(memory.stamp(grid.view(), 22.0).at(34, 31), CellState::occupied);
  EXPECT_EQ(memory.clear(), 0U);
  EXPECT_EQ(memory.cleared(), 6U);
  // It is forgotten as any contact is.
  EXPECT_EQ(memory.stamp(grid.view(), 20.0 + config.contact_hold_s + 1.0).cells, grid.view().cells);

  config.contact_repeat_radius_m = 0.0;  // off: every clear forgets every contact
  ContactMemory off(config, 60, 60);
  off.record(grid.view(), core::Pose2{3.02, 3.05, 0.0}, 0.35, 1.0, no_trail);
  EXPECT_EQ(off.clear(), 3U);
  off.record(grid.view(), core::Pose2{3.05, 3.1, 0.1}, 0.35, 20.0, no_trail);
  EXPECT_EQ(off.clear(), 3U);
  EXPECT_EQ(off.repeated(), 0U);
}

// The robot came into a room through a 0.9 m door in a wall at y = 3 m, driving south down
// its middle (x = 3 m). Leaving by it, it touches the east jamb while heading north-east: the
// point straight ahead and the one to its left lie where its centre passed on the way in, and
// are not recorded, so the doorway stays open to plans; the one on the jamb's side is.
TEST(ContactMemory, ContactPointsWhereTheRobotHadDrivenAreNotRecorded) {
  TestGrid grid(60, 60, CellState::free);
  core::ExploreConfig config;
  config.trail_contact_radius_m = 0.25;
  TrailMemory trail(config);
  for (double y = 5.0; y >= 1.0; y -= 0.05) trail.record(Eigen::Vector2d(3.0, y));
  ContactMemory memory(config, 60, 60);
  const core::Pose2 touching{3.05, 2.7, 1.2};  // 0.4 m ahead: (3.19, 3.07); 25 degrees left: (3.02, 3.10)
  memory.record(grid.view(), touching, 0.35, 10.0, trail);
  EXPECT_EQ(memory.on_trail(), 2U);
  EXPECT_EQ(memory.held(), 1U);
  EXPECT_EQ(memory.recorded(), 1U);
  const GridView stamped = memory.stamp(grid.view(), 11.0);
  EXPECT_EQ(stamped.at(31, 30), CellState::free);      // the doorway, straight ahead
  EXPECT_EQ(stamped.at(33, 29), CellState::occupied);  // 25 degrees right: (3.34, 2.98), towards the jamb

  config.trail_contact_radius_m = 0.0;  // off: all three are recorded
  ContactMemory off(config, 60, 60);
  off.record(grid.view(), touching, 0.35, 10.0, trail);
  EXPECT_EQ(off.held(), 3U);
  EXPECT_EQ(off.on_trail(), 0U);
}

// Leaving a room by a 0.9 m door in a mapped wall at y = 3 m (cells 26-34 open), the pose
// 0.1 m east of the door's middle, the robot pushes north and stalls on the east jamb beside
// it. The jamb is in the grid, so the stall is explained: no contact cell is marked on the
// corridor floor ahead, which the grid holds free and only contact_hold_s would end (it would
// shut the door the robot stands in). Once: a second stall there is a contact as any.
// A mapped wall at y = 3 m with a 0.9 m door (cells 26-34 open), and a robot in it 0.1 m east of
// its middle, facing north: the east jamb's cell (35, 30) is 0.42 m from its centre, 72 degrees
// right of its heading.
struct RobotInADoor {
  TestGrid grid{60, 60, CellState::free};
  const core::Pose2 pose{3.15, 2.92, 0.5 * M_PI};
  const TrailMemory no_trail{core::ExploreConfig{}};
  RobotInADoor() {
    grid.fill(0, 30, 26, 31, CellState::occupied);
    grid.fill(35, 30, 60, 31, CellState::occupied);
  }
  void stall(ContactMemory& memory, const core::Pose2& at, double time_s) const {
    memory.record(grid.view(), at, 0.35, time_s, no_trail);
  }
};

TEST(ContactMemory, AStallBesideAMappedJambMarksNoFreeCellAheadOnce) {
  const RobotInADoor door;
  const TestGrid& grid = door.grid;
  core::ExploreConfig config;
  config.contact_explained_margin_m = 0.15;
  ContactMemory memory(config, 60, 60);
  door.stall(memory, door.pose, 10.0);
  EXPECT_EQ(memory.held(), 0U);
  EXPECT_EQ(memory.explained(), 3U);
  EXPECT_EQ(memory.stamp(grid.view(), 11.0).cells, grid.view().cells);
  // Stalled again where it stood (the pose is off and the plan leads into the same surface):
  // no longer explained, the cells ahead are marked and the next plan goes elsewhere.
  door.stall(memory, core::Pose2{3.17, 2.95, 0.5 * M_PI}, 30.0);
  EXPECT_EQ(memory.held(), 3U);
  EXPECT_EQ(memory.explained(), 3U);

  config.contact_explained_margin_m = 0.0;  // off: the three cells ahead close the doorway
  ContactMemory off(config, 60, 60);
  door.stall(off, door.pose, 10.0);
  EXPECT_EQ(off.held(), 3U);
  EXPECT_EQ(off.explained(), 0U);
  EXPECT_EQ(off.stamp(grid.view(), 11.0).at(31, 33), CellState::occupied);  // ahead: (3.15, 3.32)
}

// The same stall beside the mapped east jamb, with contact_toward_mapped_m: the contact points
// are marked towards the jamb, not on the corridor floor straight ahead, so the doorway stays
// open but for the jamb's side. Once: a second stall there is marked straight ahead. With
// nothing mapped near the front half of the rim (a blank wall) it is straight ahead as ever.
TEST(ContactMemory, AStallBesideAMappedJambIsMarkedTowardsItOnce) {
  const RobotInADoor door;
  const TestGrid& grid = door.grid;
  core::ExploreConfig config;
  config.contact_toward_mapped_m = 0.15;
  ContactMemory memory(config, 60, 60);
  door.stall(memory, door.pose, 10.0);
  EXPECT_EQ(memory.held(), 3U);
  EXPECT_EQ(memory.toward_mapped(), 1U);
  const GridView stamped = memory.stamp(grid.view(), 11.0);
  EXPECT_EQ(stamped.at(31, 33), CellState::free);      // straight ahead: (3.15, 3.32)
  EXPECT_EQ(stamped.at(34, 31), CellState::occupied);  // towards the jamb, 25 degrees left of it: (3.44, 3.19)
  EXPECT_EQ(stamped.at(35, 28), CellState::occupied);  // 25 degrees right of it: (3.55, 2.87)
  for (int x = 26; x <= 31; ++x) {
    for (int y = 29; y <= 34; ++y) EXPECT_EQ(stamped.at(x, y), CellState::free) << x << "," << y;  // the doorway's west part
  }
  door.stall(memory, core::Pose2{3.17, 2.95, 0.5 * M_PI}, 30.0);
  EXPECT_EQ(memory.toward_mapped(), 1U);
  EXPECT_EQ(memory.stamp(grid.view(), 31.0).at(31, 33), CellState::occupied);

  TestGrid blank_wall(60, 60, CellState::free);
  blank_wall.fill(40, 0, 60, 60, CellState::unknown);
  ContactMemory at_blank_wall(config, 60, 60);
  at_blank_wall.record(blank_wall.view(), core::Pose2{3.64, 3.05, 0.0}, 0.35, 10.0, door.no_trail);
  EXPECT_EQ(at_blank_wall.toward_mapped(), 0U);
  EXPECT_EQ(at_blank_wall.stamp(blank_wall.view(), 11.0).at(40, 30), CellState::occupied);  // ahead: (4.04, 3.05)
}

// What a mapped surface does not explain: a stall against a blank wall (unknown cells ahead)
// marks them even with a mapped corner beside the robot, and a surface behind the robot's
// middle cannot stop it going forward.
TEST(ContactMemory, UnknownCellsAheadAndSurfacesBehindAreStillContacts) {
  const TrailMemory no_trail{core::ExploreConfig{}};
  core::ExploreConfig config;
  config.contact_explained_margin_m = 0.15;

  TestGrid blank_wall(60, 60, CellState::free);
  blank_wall.fill(40, 0, 60, 60, CellState::unknown);  // never seen from x = 4 m
  blank_wall.set(38, 33, CellState::occupied);         // a mapped corner 0.37 m off, to the left
  ContactMemory at_blank_wall(config, 60, 60);
  at_blank_wall.record(blank_wall.view(), core::Pose2{3.64, 3.05, 0.0}, 0.35, 10.0, no_trail);
  EXPECT_EQ(at_blank_wall.held(), 3U);
  EXPECT_EQ(at_blank_wall.explained(), 0U);

  TestGrid behind(60, 60, CellState::free);
  behind.set(32, 30, CellState::occupied);  // 0.36 m behind a robot at (3.55, 3.05) facing east
  ContactMemory with_surface_behind(config, 60, 60);
  with_surface_behind.record(behind.view(), core::Pose2{3.55, 3.05, 0.0}, 0.35, 10.0, no_trail);
  EXPECT_EQ(with_surface_behind.held(), 3U);
  EXPECT_EQ(with_surface_behind.explained(), 0U);
}

TEST(ContactMemory, AFullListCountsWhatItForgetsAndNothingAllocates) {
  const TrailMemory no_trail{core::ExploreConfig{}};  // the robot has not driven anywhere
  TestGrid grid(60, 60, CellState::unknown);
  core::ExploreConfig config;
  config.contact_memory = 4;
  ContactMemory memory(config, 60, 60);
  const core::AllocationScope counter;
  memory.record(grid.view(), core::Pose2{3.02, 3.05, 0.0}, 0.35, 1.0, no_trail);
  memory.record(grid.view(), core::Pose2{3.02, 3.05, 1.0}, 0.35, 2.0, no_trail);
  const GridView stamped = memory.stamp(grid.view(), 3.0);
  EXPECT_EQ(counter.allocations(), 0U);
  EXPECT_EQ(memory.held(), 4U);
  EXPECT_EQ(memory.forgotten_full(), 2U);
  EXPECT_EQ(stamped.at(34, 30), CellState::occupied);  // 0.4 m straight ahead of the first
  // A grid larger than the buffer is used as it is (counted).
  TestGrid large(80, 80, CellState::unknown);
  EXPECT_EQ(memory.stamp(large.view(), 4.0).cells, large.view().cells);
  EXPECT_EQ(memory.grid_too_large(), 1U);
}

}  // namespace
}  // namespace stereoscout::explore
