// Door standoff (door_standoff.hpp) driving a kinematic robot at the drive task's 20 Hz. The
// explorer standing off for a door in a corridor's side wall, and the sighting that follows,
// are in door_sighting_test.cpp (Explorer.StandingOffBeforeASideDoorLetsTheSightingKeepTheRobotClear).
#include "stereoscout/explore/door_standoff.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "test_grid.hpp"

namespace stereoscout::explore {
namespace {

constexpr double kTick_s = 0.05;
// A door in a wall, the straight way to its point clear; the way shut; a gap beside no wall.
constexpr DoorStandoff::GridAnswers kClear{true, true};
constexpr DoorStandoff::GridAnswers kShut{true, false};
constexpr DoorStandoff::GridAnswers kNoWall{false, true};

ExploreParams standoff_params() {
  ExploreParams params = testing::test_params(100, 100);
  params.explore.door_standoff_m = 1.0;
  return params;
}

// A door in a corridor's south wall (y 3.05), passed southwards into the room.
DoorPassage side_door() {
  DoorPassage door;
  door.known = true;
  door.middle = {5.0, 3.05};
  door.along = {0.0, -1.0};
  door.width_m = 0.9;
  door.clear_after_m = 0.55;
  return door;
}

void move(core::Pose2& pose, const core::DriveCommand& command) {
  pose.x += command.linear_mps * kTick_s * std::cos(pose.theta);
  pose.y += command.linear_mps * kTick_s * std::sin(pose.theta);
  pose.theta = core::wrap_angle(pose.theta + command.angular_rad_s * kTick_s);
}

// Steers until the standoff lets go (or `seconds` pass); the time it took.
double stand_off(DoorStandoff& standoff, const DoorPassage& door, core::Pose2& pose, double seconds = 60.0,
                 const DoorStandoff::GridAnswers& grid = kClear) {
  double time_s = 0.0;
  core::DriveCommand command;
  while (time_s < seconds && standoff.steer(door, false, grid, pose, time_s, command)) {
    move(pose, command);
    time_s += kTick_s;
  }
  return time_s;
}

// From the corridor, driving along it past the door's side: to the point 1 m before the door
// on its axis, then a quarter turn to face the door.
TEST(DoorStandoff, DrivesToThePointOnTheAxisThenFacesTheDoor) {
  DoorStandoff standoff(standoff_params());
  const DoorPassage door = side_door();
  core::Pose2 pose{3.6, 4.2, 0.0};
  const double took_s = stand_off(standoff, door, pose);
  EXPECT_LT(took_s, DoorStandoff::kApproachLimit_s);
  EXPECT_NEAR(pose.x, 5.0, DoorStandoff::kReached_m + 0.01);
  EXPECT_NEAR(pose.y, 4.05, DoorStandoff::kReached_m + 0.01);
  EXPECT_NEAR(pose.theta, -core::kPi / 2.0, DoorStandoff::kFacing_rad);
  EXPECT_EQ(standoff.counters().doors, 1U);
  EXPECT_EQ(standoff.counters().stood_off, 1U);
  // Done with this door: the follower drives on.
  core::DriveCommand command;
  EXPECT_FALSE(standoff.steer(door, false, kClear, pose, took_s + kTick_s, command));
}

// Nearer than the point but with the camera far enough before the door's line: it only turns.
TEST(DoorStandoff, TurnsWhereItStandsWhenThatIsFarEnoughBeforeTheDoor) {
  DoorStandoff standoff(standoff_params());
  core::Pose2 pose{5.3, 3.95, 0.0};  // 0.9 m before the line; the camera, turned, 0.8 m
  stand_off(standoff, side_door(), pose);
  EXPECT_NEAR(pose.x, 5.3, 1e-9);
  EXPECT_NEAR(pose.y, 3.95, 1e-9);
  EXPECT_NEAR(pose.theta, -core::kPi / 2.0, DoorStandoff::kFacing_rad);
  EXPECT_EQ(standoff.counters().stood_off, 1U);
}

// A robot just past the door, facing away from it, with a new plan back through it: on to the
// point, then half a turn.
TEST(DoorStandoff, ARobotFacingAwayFromTheDoorDrivesOnToThePointBeforeTurning) {
  DoorStandoff standoff(standoff_params());
  core::Pose2 pose{5.0, 3.55, core::kPi / 2.0};
  stand_off(standoff, side_door(), pose);
  EXPECT_NEAR(pose.x, 5.0, DoorStandoff::kReached_m + 0.01);
  EXPECT_NEAR(pose.y, 4.05, DoorStandoff::kReached_m + 0.01);
  EXPECT_NEAR(pose.theta, -core::kPi / 2.0, DoorStandoff::kFacing_rad);
  EXPECT_EQ(standoff.counters().stood_off, 1U);
}

// A robot that has turned round just past the door, facing it with its camera nearer than
// 0.7 m to the line, is left to the follower.
TEST(DoorStandoff, LeavesADoorTheRobotIsTooNearToSee) {
  DoorStandoff standoff(standoff_params());
  core::Pose2 pose{5.0, 3.6, -core::kPi / 2.0};
  core::DriveCommand command;
  EXPECT_FALSE(standoff.steer(side_door(), false, kClear, pose, 0.0, command));
  EXPECT_EQ(standoff.counters().too_near, 1U);
  EXPECT_EQ(standoff.counters().stood_off, 0U);
}

// A sighting on the way (taken obliquely, and carried through the turns to come) does not end
// the standoff; one held when the robot faces along the axis is counted.
TEST(DoorStandoff, GoesOnToThePointWhenSightedOnTheWay) {
  DoorStandoff standoff(standoff_params());
  const DoorPassage door = side_door();
  core::Pose2 pose{3.6, 4.2, 0.0};
  stand_off(standoff, door, pose, 2.0);
  core::DriveCommand command;
  double time_s = 2.0;
  while (time_s < 60.0 && standoff.steer(door, true, kClear, pose, time_s, command)) {
    move(pose, command);
    time_s += kTick_s;
  }
  EXPECT_NEAR(pose.y, 4.05, DoorStandoff::kReached_m + 0.01);
  EXPECT_NEAR(pose.theta, -core::kPi / 2.0, DoorStandoff::kFacing_rad);
  EXPECT_EQ(standoff.counters().stood_off, 1U);
  EXPECT_EQ(standoff.counters().sighted, 1U);
}

TEST(DoorStandoff, GivesTheDoorUpWhenTheWayIsShutAndLeavesGapsBesideNoWall) {
  const DoorPassage door = side_door();
  {
    DoorStandoff standoff(standoff_params());
    core::Pose2 pose{3.6, 4.2, 0.0};
    core::DriveCommand command;
    EXPECT_FALSE(standoff.steer(door, false, kShut, pose, 0.0, command));
    EXPECT_EQ(standoff.counters().way_shut, 1U);
  }
  {
    DoorStandoff standoff(standoff_params());
    core::Pose2 pose{3.6, 4.2, 0.0};
    core::DriveCommand command;
    EXPECT_FALSE(standoff.steer(door, false, kNoWall, pose, 0.0, command));
    EXPECT_EQ(standoff.counters().not_in_a_wall, 1U);
    EXPECT_EQ(standoff.counters().doors, 0U);
  }
}

// Kept from the point by something the grid does not hold (the robot does not move here).
TEST(DoorStandoff, GivesTheDoorUpAfterItsTimeLimit) {
  DoorStandoff standoff(standoff_params());
  const core::Pose2 pose{3.6, 4.2, 0.0};
  core::DriveCommand command;
  double time_s = 0.0;
  while (time_s < 60.0 && standoff.steer(side_door(), false, kClear, pose, time_s, command)) time_s += kTick_s;
  EXPECT_NEAR(time_s, DoorStandoff::kApproachLimit_s, 2.0 * kTick_s);
  EXPECT_EQ(standoff.counters().timed_out, 1U);
}

// A plan that loses the door for a while brings no second standoff near it; far from it the
// door is forgotten, and a later approach stands off again.
TEST(DoorStandoff, StandsOffOncePerApproach) {
  DoorStandoff standoff(standoff_params());
  const DoorPassage door = side_door();
  core::Pose2 pose{3.6, 4.2, 0.0};
  const double took_s = stand_off(standoff, door, pose);
  core::DriveCommand command;
  EXPECT_FALSE(standoff.steer(DoorPassage(), false, kClear, pose, took_s, command));
  EXPECT_FALSE(standoff.steer(door, false, kClear, pose, took_s + kTick_s, command));
  EXPECT_EQ(standoff.counters().doors, 1U);
  const core::Pose2 far{9.0, 4.2, core::kPi};
  EXPECT_FALSE(standoff.steer(DoorPassage(), false, kClear, far, took_s + 40.0, command));
  core::Pose2 back{3.6, 4.2, 0.0};
  stand_off(standoff, door, back);
  EXPECT_EQ(standoff.counters().doors, 2U);
  EXPECT_EQ(standoff.counters().stood_off, 2U);
}

// Once a door is done with, its passage needs no grid answers, but the next door's does: a
// door met after another must not begin with no answers (no wall, the way shut).
TEST(DoorStandoff, WantsTheGridAgainForTheNextDoor) {
  DoorStandoff standoff(standoff_params());
  const DoorPassage door = side_door();
  EXPECT_TRUE(standoff.wants_grid(door));
  core::Pose2 pose{3.6, 4.2, 0.0};
  stand_off(standoff, door, pose);
  EXPECT_FALSE(standoff.wants_grid(door));
  DoorPassage next = side_door();
  next.middle.x() += 2.5;
  EXPECT_TRUE(standoff.wants_grid(next));
  core::Pose2 on{pose.x, pose.y, 0.0};
  stand_off(standoff, next, on);
  EXPECT_EQ(standoff.counters().doors, 2U);
  EXPECT_EQ(standoff.counters().stood_off, 2U);
  EXPECT_EQ(standoff.counters().not_in_a_wall, 0U);
}

TEST(DoorStandoff, OffByDefault) {
  DoorStandoff standoff(testing::test_params(100, 100));
  core::Pose2 pose{3.6, 4.2, 0.0};
  core::DriveCommand command;
  EXPECT_FALSE(standoff.enabled());
  EXPECT_FALSE(standoff.steer(side_door(), false, kClear, pose, 0.0, command));
  EXPECT_EQ(standoff.counters().doors, 0U);
}

}  // namespace
}  // namespace stereoscout::explore
