#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/host_sim/simulator.hpp"
#include "test_worlds.hpp"

namespace stereoscout::host_sim {
namespace {

using testing::load_or_fail;
using testing::room_yaml;

// A large empty hall, tile everywhere, or carpet everywhere.
std::string hall_yaml(bool carpet) {
  std::string yaml =
      "start: [10, 10, 0]\nwalls:\n  - {points: [[0, 0], [20, 0], [20, 20], [0, 20], [0, 0]]}\n";
  if (carpet) yaml += "floor_regions:\n  - {polygon: [[0, 0], [20, 0], [20, 20], [0, 20], [0, 0]], type: carpet}\n";
  return yaml;
}

core::SimConfig noiseless() {
  core::SimConfig sim;
  sim.tile = core::OdometryNoiseConfig{};
  sim.carpet = core::OdometryNoiseConfig{};
  return sim;
}

// Drives at `speed` for `seconds` (or turns at `turn_rate`), then stops.
void drive(Simulator& simulator, double speed, double turn_rate, double seconds) {
  simulator.command({speed, turn_rate});
  simulator.step(seconds);
  simulator.command({});
}

// A square with sides of `side` m at full speed, turning left 90 degrees at each corner.
void drive_square(Simulator& simulator, double side, int sides) {
  const core::RobotConfig robot;
  const double turn_rate = core::degrees_to_radians(robot.max_turn_rate_deg_s);
  for (int i = 0; i < sides; ++i) {
    drive(simulator, robot.max_speed_mps, 0.0, side / robot.max_speed_mps);
    drive(simulator, 0.0, turn_rate, (core::kPi / 2.0) / turn_rate);
  }
}

// The newest odometry reading with its true pose (drains the queue).
OdometrySample last_sample(Simulator& simulator) {
  OdometrySample sample;
  OdometrySample newest;
  while (simulator.pop_odometry(sample)) newest = sample;
  return newest;
}

TEST(Simulator, CommandsAreClampedToTheRobotsLimits) {
  const World world = load_or_fail(hall_yaml(false));
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
  simulator.command({1.0, 1.0});
  EXPECT_DOUBLE_EQ(simulator.current_command().linear_mps, 0.12);
  EXPECT_NEAR(simulator.current_command().angular_rad_s, core::degrees_to_radians(8.0), 1e-12);
  simulator.step(10.0);
  EXPECT_NEAR(simulator.distance_travelled_m(), 1.2, 1e-9);
  EXPECT_NEAR(simulator.true_pose().theta, core::degrees_to_radians(80.0), 1e-9);
}

TEST(Simulator, OdometryArrivesAtItsRateAndIsExactWithoutNoise) {
  const World world = load_or_fail(hall_yaml(false));
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
  SimOdometry odometry(simulator);
  drive_square(simulator, 2.0, 4);
  int readings = 0;
  core::OdometryReading reading;
  std::int64_t last_timestamp = 0;
  while (odometry.read(reading).ok()) {
    ++readings;
    EXPECT_GT(reading.timestamp_ns, last_timestamp);
    last_timestamp = reading.timestamp_ns;
  }
  EXPECT_FALSE(odometry.read(reading).ok());
  // 5.4 Hz over the whole run (the queue holds 64 readings; older ones are dropped, counted).
  const double expected = simulator.time_s() * 5.4;
  EXPECT_NEAR(static_cast<double>(readings) + static_cast<double>(simulator.odometry_dropped()), expected, 1.0);
  EXPECT_NEAR(reading.pose.x, odometry.last_true_pose().x, 1e-9);
  EXPECT_NEAR(reading.pose.y, odometry.last_true_pose().y, 1e-9);
  EXPECT_NEAR(reading.pose.theta, odometry.last_true_pose().theta, 1e-9);
}

TEST(Simulator, SystematicOdometryErrorsAreThoseOfTheModel) {
  core::SimConfig sim = noiseless();
  sim.tile.scale_error = 0.05;
  sim.tile.drift_deg_per_m = 1.0;
  const World world = load_or_fail(hall_yaml(false));
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, sim, 1);
  drive(simulator, 0.12, 0.0, 2.0 / 0.12);  // 2 m, then wait for the last reading
  simulator.step(1.0);
  const OdometrySample sample = last_sample(simulator);
  const core::Pose2 start = world.start;
  const double true_distance = (sample.true_pose.translation() - start.translation()).norm();
  const double odometry_distance = (sample.reading.pose.translation() - start.translation()).norm();
  EXPECT_NEAR(true_distance, 2.0, 1e-9);
  // Each reading's heading drift bends the path slightly; the length is the model's.
  EXPECT_NEAR(odometry_distance, 2.0 * 1.05, 0.005);
  EXPECT_NEAR(sample.reading.pose.theta - sample.true_pose.theta, core::degrees_to_radians(2.0), 1e-9);
}

// Heading error after driving a square many times with different seeds: the random part of
// the model predicts its spread (variance sigma_rad^2 * turned + sigma_m^2 * driven).
std::vector<double> heading_errors(bool carpet, int runs, int sides, double* position_rms) {
  const World world = load_or_fail(hall_yaml(carpet));
  core::SimConfig sim;
  sim.tile.scale_error = 0.0;
  sim.tile.drift_deg_per_m = 0.0;
  sim.carpet.scale_error = 0.0;
  sim.carpet.drift_deg_per_m = 0.0;
  std::vector<double> errors;
  double squared = 0.0;
  for (int run = 0; run < runs; ++run) {
    Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, sim, static_cast<std::uint64_t>(100 + run));
    drive_square(simulator, 2.0, sides);
    simulator.step(0.5);
    const OdometrySample sample = last_sample(simulator);
    errors.push_back(core::wrap_angle(sample.reading.pose.theta - sample.true_pose.theta));
    squared += (sample.reading.pose.translation() - sample.true_pose.translation()).squaredNorm();
  }
  *position_rms = std::sqrt(squared / runs);
  return errors;
}

double rms(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v * v;
  return std::sqrt(sum / static_cast<double>(values.size()));
}

TEST(Simulator, RandomOdometryErrorGrowsAsTheNoiseModelSays) {
  const core::SimConfig sim;
  constexpr int kRuns = 40;
  double position_one_side = 0.0;
  double position_square = 0.0;
  double position_carpet = 0.0;
  const auto one_side = heading_errors(false, kRuns, 1, &position_one_side);
  const auto square = heading_errors(false, kRuns, 4, &position_square);
  const auto carpet = heading_errors(true, kRuns, 4, &position_carpet);
  auto predicted = [](const core::OdometryNoiseConfig& noise, double turned_rad, double driven_m) {
    return std::sqrt(noise.rotation_sigma_rad_per_sqrt_rad * noise.rotation_sigma_rad_per_sqrt_rad * turned_rad +
                     noise.rotation_sigma_rad_per_sqrt_m * noise.rotation_sigma_rad_per_sqrt_m * driven_m);
  };
  // One side and its corner: 2 m, pi/2 turned. The square: 8 m, 2 pi turned.
  EXPECT_NEAR(rms(one_side) / predicted(sim.tile, core::kPi / 2.0, 2.0), 1.0, 0.3);
  EXPECT_NEAR(rms(square) / predicted(sim.tile, 2.0 * core::kPi, 8.0), 1.0, 0.3);
  EXPECT_NEAR(rms(carpet) / predicted(sim.carpet, 2.0 * core::kPi, 8.0), 1.0, 0.3);
  EXPECT_GT(position_square, position_one_side);
  EXPECT_GT(position_carpet, position_square);
}

TEST(Simulator, OdometryIsIdenticalForTheSameSeed) {
  const World world = load_or_fail(hall_yaml(false));
  auto run = [&](std::uint64_t seed) {
    Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, core::SimConfig{}, seed);
    drive_square(simulator, 1.0, 2);
    return last_sample(simulator).reading.pose;
  };
  const core::Pose2 first = run(5);
  const core::Pose2 second = run(5);
  EXPECT_EQ(first.x, second.x);
  EXPECT_EQ(first.y, second.y);
  EXPECT_EQ(first.theta, second.theta);
  EXPECT_NE(first.x, run(6).x);
}

TEST(Simulator, DriveIntoAWallIsStoppedAndCounted) {
  // Start 2 m from the wall at x = 10, facing it; the robot's radius is 0.35 m.
  const World world = load_or_fail(room_yaml("brick"));
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
  simulator.teleport(core::Pose2{8.0, 3.0, 0.0});
  SimDrive drive_interface(simulator);
  ASSERT_TRUE(drive_interface.command({0.12, 0.0}).ok());
  simulator.step(30.0);
  EXPECT_EQ(simulator.collision_count(), 1U);
  EXPECT_EQ(simulator.collision_event_count(), 1U);
  ASSERT_EQ(simulator.collision_log_size(), 1U);
  EXPECT_EQ(simulator.collision_log(0).pose.x, simulator.true_pose().x);
  EXPECT_GT(simulator.collision_log(0).time_s, 13.0);  // 1.65 m at 0.12 m/s
  EXPECT_EQ(simulator.collision_log(0).person, Simulator::kStaticObstacle);
  EXPECT_EQ(simulator.person_collision_event_count(), 0U);
  EXPECT_GT(simulator.true_pose().x, 10.0 - 0.35 - 0.002);
  EXPECT_LE(simulator.true_pose().x, 10.0 - 0.35);
  EXPECT_EQ(simulator.current_command().linear_mps, 0.0);
  // Pushing again is stopped again; backing away works.
  ASSERT_TRUE(drive_interface.command({0.12, 0.0}).ok());
  simulator.step(1.0);
  EXPECT_EQ(simulator.collision_count(), 2U);
  EXPECT_EQ(simulator.collision_event_count(), 1U);  // the same contact: it has not moved clear
  ASSERT_TRUE(drive_interface.command({-0.12, 0.0}).ok());
  simulator.step(1.0);
  EXPECT_NEAR(simulator.true_pose().x, 10.0 - 0.35 - 0.12, 0.003);
  EXPECT_EQ(simulator.collision_count(), 2U);
  // Driving back into it is a new contact.
  ASSERT_TRUE(drive_interface.command({0.12, 0.0}).ok());
  simulator.step(3.0);
  EXPECT_EQ(simulator.collision_count(), 3U);
  EXPECT_EQ(simulator.collision_event_count(), 2U);
}

TEST(Simulator, ANearMissIsAnApproachThatTouchedNothingAndAContactIsNone) {
  // The room's south wall is y = 0; the radius 0.35 m; sim.near_miss_m 0.03 m.
  const World world = load_or_fail(room_yaml("brick"));
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
  ASSERT_DOUBLE_EQ(simulator.near_misses().threshold_m(), 0.03);
  // Along the wall 0.02 m clear, then away: one near miss, logged at its least clearance.
  simulator.teleport(core::Pose2{2.0, 0.37, 0.0});
  drive(simulator, 0.12, 0.0, 1.0);
  EXPECT_EQ(simulator.near_misses().count(), 1U);  // under way, untouched
  EXPECT_EQ(simulator.near_misses().log_size(), 0U);
  simulator.teleport(core::Pose2{3.0, 1.0, 0.0});
  drive(simulator, 0.12, 0.0, 1.0);
  ASSERT_EQ(simulator.near_misses().log_size(), 1U);
  EXPECT_NEAR(simulator.near_misses().log(0).clearance_m, 0.02, 1e-9);
  EXPECT_NEAR(simulator.near_misses().log(0).pose.y, 0.37, 1e-9);
  // 0.04 m clear is no near miss.
  simulator.teleport(core::Pose2{2.0, 0.39, 0.0});
  drive(simulator, 0.12, 0.0, 1.0);
  simulator.teleport(core::Pose2{3.0, 1.0, 0.0});
  drive(simulator, 0.12, 0.0, 1.0);
  EXPECT_EQ(simulator.near_misses().count(), 1U);
  // Into the wall and back out: a contact, not a near miss.
  simulator.teleport(core::Pose2{5.0, 0.6, -core::kPi / 2.0});
  drive(simulator, 0.12, 0.0, 3.0);
  EXPECT_EQ(simulator.collision_event_count(), 1U);
  drive(simulator, -0.12, 0.0, 3.0);
  EXPECT_GT(simulator.true_pose().y, 0.6);
  EXPECT_EQ(simulator.near_misses().count(), 1U);
  EXPECT_EQ(simulator.near_misses().log_size(), 1U);
}

// A wall along y = 4 with a 0.9 m door whose middle is x = 2 (as the office's), in a room.
std::string door_room_yaml() {
  return "start: [2, 2, 0]\nwalls:\n  - {points: [[0, 0], [6, 0], [6, 8], [0, 8], [0, 0]]}\n"
         "  - {points: [[0, 4], [6, 4]], openings: [{at: 2.0, width: 0.9, top: 2}]}\n";
}

TEST(Simulator, EachPassThroughADoorIsAVisitWithItsLeastClearance) {
  const World world = load_or_fail(door_room_yaml());
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
  const DoorVisits& visits = simulator.door_visits();
  ASSERT_TRUE(visits.active());
  ASSERT_DOUBLE_EQ(visits.zone_m(), 0.35 + 0.15);
  // North through the door 0.06 m east of its middle: the disc passes the east jamb (2.45, 4)
  // 0.45 - 0.06 - 0.35 = 0.04 m clear.
  simulator.teleport(core::Pose2{2.06, 3.0, core::kPi / 2.0});
  drive(simulator, 0.12, 0.0, 2.0 / 0.12);
  ASSERT_EQ(visits.log_size(), 1U);
  EXPECT_EQ(visits.log(0).door, 0U);
  EXPECT_NEAR(visits.log(0).clearance_m, 0.04, 1e-9);
  EXPECT_NEAR(visits.log(0).pose.y, 4.0, 0.002);
  EXPECT_TRUE(visits.log(0).crossed);
  EXPECT_FALSE(visits.log(0).touched);
  // Up to the door and back the way it came: a visit, not a crossing.
  simulator.teleport(core::Pose2{2.0, 5.0, -core::kPi / 2.0});
  drive(simulator, 0.12, 0.0, 0.8 / 0.12);
  drive(simulator, -0.12, 0.0, 0.8 / 0.12);
  EXPECT_EQ(visits.count(), 2U);
  EXPECT_EQ(visits.crossings(), 1U);
  EXPECT_FALSE(visits.log(1).crossed);
  EXPECT_NEAR(visits.log(1).clearance_m, std::hypot(0.45, 0.2) - 0.35, 1e-9);  // its nearest, at y 4.2
  // 0.12 m off the middle, into the east jamb: a touched visit, as many as the contacts.
  simulator.teleport(core::Pose2{2.12, 3.0, core::kPi / 2.0});
  drive(simulator, 0.12, 0.0, 2.0 / 0.12);
  EXPECT_EQ(simulator.collision_event_count(), 1U);
  EXPECT_EQ(visits.touched_count(), 1U);
  EXPECT_EQ(visits.count(), 3U);  // still in the doorway's zone, under way
  EXPECT_EQ(visits.log_size(), 2U);
  simulator.teleport(core::Pose2{2.0, 2.0, 0.0});
  drive(simulator, 0.12, 0.0, 0.1);
  ASSERT_EQ(visits.log_size(), 3U);
  EXPECT_TRUE(visits.log(2).touched);
  EXPECT_LT(visits.log(2).clearance_m, 0.002);
  // Along the wall 1 m from the door: no visit.
  simulator.teleport(core::Pose2{3.5, 3.55, 0.0});
  drive(simulator, 0.12, 0.0, 1.0 / 0.12);
  EXPECT_EQ(visits.count(), 3U);
}

TEST(Simulator, NoDoorVisitsAreCountedWithAReachOfNought) {
  const World world = load_or_fail(door_room_yaml());
  core::SimConfig sim = noiseless();
  sim.door_visit_reach_m = 0.0;
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, sim, 1);
  simulator.teleport(core::Pose2{2.0, 3.0, core::kPi / 2.0});
  drive(simulator, 0.12, 0.0, 2.0 / 0.12);
  EXPECT_FALSE(simulator.door_visits().active());
  EXPECT_EQ(simulator.door_visits().count(), 0U);
}

TEST(Simulator, NoNearMissesAreCountedWithAThresholdOfNought) {
  const World world = load_or_fail(room_yaml("brick"));
  core::SimConfig sim = noiseless();
  sim.near_miss_m = 0.0;
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, sim, 1);
  simulator.teleport(core::Pose2{2.0, 0.36, 0.0});
  drive(simulator, 0.12, 0.0, 1.0);
  simulator.teleport(core::Pose2{3.0, 1.0, 0.0});
  drive(simulator, 0.12, 0.0, 1.0);
  EXPECT_EQ(simulator.near_misses().count(), 0U);
}

TEST(Simulator, APersonWalkingIntoTheRobotIsTheirCollisionNotOurs) {
  // A person walks to and fro along y = 10 through the robot standing at (10, 10), 0.5 m/s.
  const World world =
      load_or_fail(hall_yaml(false) + "people:\n  - {waypoints: [[5, 10], [15, 10]], speed: 0.5}\n");
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
  simulator.step(20.0);  // stopped: the person passes through once
  EXPECT_EQ(simulator.collision_count(), 0U);
  EXPECT_EQ(simulator.person_collision_event_count(), 0U);
  EXPECT_EQ(simulator.person_contact_count(), 1U);
  simulator.command({0.0, 0.1});  // turning in place as the person comes back: still theirs
  simulator.step(15.0);
  EXPECT_EQ(simulator.collision_count(), 0U);
  EXPECT_EQ(simulator.person_contact_count(), 2U);
  EXPECT_GT(simulator.true_pose().theta, 1.0);  // the turn was not blocked
}

TEST(Simulator, APersonOvertakingTheRobotIsTheirCollision) {
  // The robot drives east along y = 10 at 0.12 m/s; a person walks east along y = 10.4 at
  // 0.5 m/s from behind, brushes its disc and walks on ahead.
  const World world =
      load_or_fail(hall_yaml(false) + "people:\n  - {waypoints: [[6, 10.4], [19, 10.4]], speed: 0.5}\n");
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
  simulator.command({0.12, 0.0});
  simulator.step(20.0);
  EXPECT_EQ(simulator.collision_count(), 0U);
  EXPECT_EQ(simulator.person_contact_count(), 1U);
  EXPECT_NEAR(simulator.true_pose().x, 10.0 + 0.12 * 20.0, 1e-9);
}

TEST(Simulator, APersonWalkingThroughTheRobotFromBehindIsNoCollisionOfOursAsTheyLeave) {
  // A person walks east along the robot's own line (y = 10) at 0.5 m/s, through the robot
  // driving east at 0.12 m/s, and on ahead. As they leave, the robot's next step used to
  // close the last millimetres to them before their own step did: one time in four, by the
  // phase of the integration steps. So ten start points, 0.7 mm apart.
  for (int k = 0; k < 10; ++k) {
    const double start_x = 6.0 + 0.0007 * k;
    const World world = load_or_fail(hall_yaml(false) + "people:\n  - {waypoints: [[" + std::to_string(start_x) +
                                     ", 10], [19, 10]], speed: 0.5}\n");
    Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
    simulator.command({0.12, 0.0});
    simulator.step(20.0);
    EXPECT_EQ(simulator.collision_count(), 0U) << "start x " << start_x;
    EXPECT_EQ(simulator.person_contact_count(), 1U) << "start x " << start_x;
    EXPECT_NEAR(simulator.true_pose().x, 10.0 + 0.12 * 20.0, 1e-9) << "start x " << start_x;
  }
}

TEST(Simulator, DrivingIntoAPersonIsOurCollision) {
  // A person stands at (12, 10); the robot drives at them from (10, 10).
  const World world =
      load_or_fail(hall_yaml(false) + "people:\n  - {waypoints: [[12, 10], [12, 10]], speed: 0.5}\n");
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
  simulator.command({0.12, 0.0});
  simulator.step(30.0);
  EXPECT_EQ(simulator.collision_count(), 1U);
  EXPECT_EQ(simulator.person_contact_count(), 0U);
  EXPECT_EQ(simulator.person_collision_event_count(), 1U);
  ASSERT_EQ(simulator.collision_log_size(), 1U);
  EXPECT_EQ(simulator.collision_log(0).person, 0);
  EXPECT_NEAR(simulator.true_pose().x, 12.0 - 0.25 - 0.35, 0.002);
}

TEST(Simulator, TheCollisionLogSaysWhereThePersonWasAndWhenTheyWereLastInView) {
  // The robot at (10, 10) faces east. Person 0 stands 2 m ahead, person 1 2 m to its left,
  // person 2 4 m to its left behind a wall from (9, 13) to (11, 13).
  const World world = load_or_fail(hall_yaml(false) + "  - {points: [[9, 13], [11, 13]]}\n"
                                   "people:\n  - {waypoints: [[12, 10], [12, 10]], speed: 0.5}\n"
                                   "  - {waypoints: [[10, 12], [10, 12]], speed: 0.5}\n"
                                   "  - {waypoints: [[10, 14], [10, 14]], speed: 0.5}\n");
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
  simulator.step(1.0);
  simulator.note_frame_captured();  // person 0 only
  simulator.command_pan(1.2);       // the camera turned 69 degrees to the left
  simulator.step(5.0);
  simulator.note_frame_captured();  // person 1 only: person 2 is behind the wall
  const double camera_forward = core::CameraConfig{}.mount_x_m;

  simulator.command({0.12, 0.0});
  simulator.step(30.0);
  ASSERT_EQ(simulator.collision_log_size(), 1U);
  EXPECT_EQ(simulator.collision_log(0).person, 0);
  EXPECT_NEAR(simulator.collision_log(0).bearing_rad, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(simulator.collision_log(0).last_in_view_s, 1.0);
  EXPECT_NEAR(simulator.collision_log(0).in_view_distance_m, 2.0 - camera_forward, 1e-9);

  simulator.teleport(core::Pose2{10.0, 10.0, core::kPi / 2.0});  // facing person 1
  simulator.command({0.12, 0.0});
  simulator.step(30.0);
  ASSERT_EQ(simulator.collision_log_size(), 2U);
  EXPECT_EQ(simulator.collision_log(1).person, 1);
  EXPECT_NEAR(simulator.collision_log(1).bearing_rad, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(simulator.collision_log(1).last_in_view_s, 6.0);
  EXPECT_NEAR(simulator.collision_log(1).in_view_distance_m, std::hypot(2.0, camera_forward), 1e-9);

  simulator.teleport(core::Pose2{12.0, 14.5, core::kPi});  // person 2 ahead and to the left
  simulator.command({0.12, 0.0});
  simulator.step(30.0);
  ASSERT_EQ(simulator.collision_log_size(), 3U);
  EXPECT_EQ(simulator.collision_log(2).person, 2);
  EXPECT_GT(simulator.collision_log(2).bearing_rad, 0.5);  // ahead to the left (south, facing west)
  EXPECT_EQ(simulator.collision_log(2).last_in_view_s, -1.0);
  EXPECT_EQ(simulator.collision_log(2).in_view_distance_m, -1.0);
  // A static obstacle's bearing is to its nearest point.
  simulator.teleport(core::Pose2{10.0, 19.0, core::kPi / 2.0 + 0.5});
  simulator.command({0.12, 0.0});
  simulator.step(30.0);
  ASSERT_EQ(simulator.collision_log_size(), 4U);
  EXPECT_EQ(simulator.collision_log(3).person, Simulator::kStaticObstacle);
  EXPECT_NEAR(simulator.collision_log(3).bearing_rad, -0.5, 1e-9);
  EXPECT_EQ(simulator.collision_log(3).last_in_view_s, -1.0);
}

TEST(Simulator, TurningAndPushingIntoTheSamePersonAgainIsOneContact) {
  // The robot runs into a person standing at (12, 10), turns a little in place (a free step:
  // it does not move clear of them) and pushes on: the same encounter. Backing 12 cm away and
  // driving in again is a new one.
  const World world =
      load_or_fail(hall_yaml(false) + "people:\n  - {waypoints: [[12, 10], [12, 10]], speed: 0.5}\n");
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
  simulator.command({0.12, 0.0});
  simulator.step(30.0);
  ASSERT_EQ(simulator.person_collision_event_count(), 1U);
  simulator.command({0.0, 0.1});
  simulator.step(0.5);
  simulator.command({0.12, 0.0});
  simulator.step(1.0);
  EXPECT_EQ(simulator.collision_count(), 2U);
  EXPECT_EQ(simulator.collision_event_count(), 1U);
  EXPECT_EQ(simulator.person_collision_event_count(), 1U);
  simulator.command({0.0, -0.1});
  simulator.step(0.5);
  simulator.command({-0.12, 0.0});
  simulator.step(1.0);
  simulator.command({0.12, 0.0});
  simulator.step(3.0);
  EXPECT_EQ(simulator.collision_count(), 3U);
  EXPECT_EQ(simulator.collision_event_count(), 2U);
  EXPECT_EQ(simulator.person_collision_event_count(), 2U);
}

TEST(Simulator, LowAndHighObstaclesFollowTheHeightBand) {
  // A 1 cm cable protector is driven over; a shelf at 1.5 m is passed under (robot 1.2 m);
  // a 10 cm box blocks.
  const World world = load_or_fail(room_yaml("brick") +
                                    "boxes:\n  - {center: [4, 3], size: [0.2, 4], z: [0, 0.01]}\n"
                                    "  - {center: [5, 3], size: [0.4, 4], z: [1.5, 1.8]}\n"
                                    "  - {center: [7, 3], size: [0.4, 4], z: [0, 0.1]}\n");
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
  simulator.command({0.12, 0.0});
  simulator.step(60.0);
  EXPECT_EQ(simulator.collision_count(), 1U);
  EXPECT_NEAR(simulator.true_pose().x, 7.0 - 0.2 - 0.35, 0.002);
}

TEST(Simulator, PanUnitTurnsAtItsRate) {
  const World world = load_or_fail(hall_yaml(false));
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, noiseless(), 1);
  simulator.command_pan(core::degrees_to_radians(90.0));
  simulator.step(1.0);
  EXPECT_NEAR(simulator.pan_rad(), core::degrees_to_radians(30.0), 1e-9);
  simulator.step(5.0);
  EXPECT_NEAR(simulator.pan_rad(), core::degrees_to_radians(90.0), 1e-9);
}

TEST(Simulator, CameraDeliversFramesAtItsRateOnSimulatedTime) {
  const World world = load_or_fail(room_yaml("poster"));
  const core::CameraConfig camera;
  Simulator simulator(world, core::RobotConfig{}, camera, core::SimConfig{}, 1);
  StereoRenderer renderer(world, camera, core::SimConfig{}, 1);
  SimCamera sim_camera(simulator, renderer);
  SimClock clock(simulator);
  core::StereoFrame frame;
  frame.allocate(camera.width_px, camera.height_px);
  EXPECT_TRUE(sim_camera.capture(frame).ok());
  EXPECT_EQ(sim_camera.capture(frame).code, core::StatusCode::not_available);
  clock.sleep_until(clock.now_ns() + 1'000'000'000 / 15 + 1);
  const core::AllocationScope scope;
  EXPECT_TRUE(sim_camera.capture(frame).ok());
  EXPECT_EQ(scope.allocations(), 0U);
  EXPECT_EQ(frame.sequence, 1U);
  EXPECT_EQ(frame.timestamp_ns, clock.now_ns());
  // A capture 3.5 periods late gets one pair, not a burst of the missed ones.
  clock.sleep_until(clock.now_ns() + std::int64_t{3'000'000'000} / 15 + 1'000'000'000 / 30);
  EXPECT_TRUE(sim_camera.capture(frame).ok());
  EXPECT_EQ(sim_camera.capture(frame).code, core::StatusCode::not_available);
  EXPECT_EQ(sim_camera.frames_grabbed(), 3U);
  EXPECT_EQ(sim_camera.frames_rendered(), 3U);
}

// The stack renders only the pairs it keeps: a pair grabbed, then rendered after the robot
// moved on (and after pairs grabbed but never rendered), must be the pair as it was when
// grabbed, pixel for pixel: the same as from a camera that rendered every pair at once.
TEST(Simulator, APairRenderedOnlyWhenRetrievedIsThePairAsGrabbed) {
  const WorldLoad load = load_world(testing::source_path("config/worlds/lab.yaml"));
  ASSERT_TRUE(load.ok()) << load.error_text();
  const core::CameraConfig camera;
  auto drive = [](Simulator& simulator, int step) {
    simulator.command({0.12, step % 2 == 0 ? 0.15 : -0.1});
    simulator.command_pan(0.2 * step);
    simulator.step(0.1);
  };
  Simulator every_sim(load.world, core::RobotConfig{}, camera, core::SimConfig{}, 5);
  StereoRenderer every_renderer(load.world, camera, core::SimConfig{}, 5);
  SimCamera every(every_sim, every_renderer);
  Simulator lazy_sim(load.world, core::RobotConfig{}, camera, core::SimConfig{}, 5);
  StereoRenderer lazy_renderer(load.world, camera, core::SimConfig{}, 5);
  SimCamera lazy(lazy_sim, lazy_renderer);
  core::StereoFrame whole;
  core::StereoFrame grabbed;
  whole.allocate(camera.width_px, camera.height_px);
  grabbed.allocate(camera.width_px, camera.height_px);
  int compared = 0;
  for (int step = 0; step < 12; ++step) {
    ASSERT_TRUE(every.capture(whole).ok());
    ASSERT_TRUE(lazy.grab(grabbed).ok());
    EXPECT_EQ(grabbed.sequence, whole.sequence);
    EXPECT_EQ(grabbed.timestamp_ns, whole.timestamp_ns);
    EXPECT_EQ(grabbed.pan_rad, whole.pan_rad);
    const bool keep = step % 4 == 3;
    drive(every_sim, step);
    drive(lazy_sim, step);
    if (!keep) continue;
    const core::AllocationScope scope;
    ASSERT_TRUE(lazy.retrieve(grabbed).ok());  // the robot has moved on since the grab
    EXPECT_EQ(scope.allocations(), 0U);
    EXPECT_EQ(cv::norm(grabbed.left, whole.left, cv::NORM_INF), 0.0) << "step " << step;
    EXPECT_EQ(cv::norm(grabbed.right, whole.right, cv::NORM_INF), 0.0) << "step " << step;
    ++compared;
  }
  EXPECT_EQ(compared, 3);
  EXPECT_EQ(lazy.frames_grabbed(), 12U);
  EXPECT_EQ(lazy.frames_rendered(), 3U);
  // Nothing grabbed since the last render: nothing to render.
  EXPECT_EQ(lazy.retrieve(grabbed).code, core::StatusCode::invalid_input);
}

TEST(Simulator, ClosedLoopRunIsByteIdenticalForTheSameSeedAndCommands) {
  const WorldLoad load = load_world(testing::source_path("config/worlds/lab.yaml"));
  ASSERT_TRUE(load.ok()) << load.error_text();
  const core::CameraConfig camera;
  struct Run {
    std::vector<cv::Mat> frames;
    std::vector<core::Pose2> odometry;
  };
  auto run = [&](std::uint64_t seed) {
    Simulator simulator(load.world, core::RobotConfig{}, camera, core::SimConfig{}, seed);
    StereoRenderer renderer(load.world, camera, core::SimConfig{}, seed);
    SimCamera sim_camera(simulator, renderer);
    SimOdometry odometry(simulator);
    core::StereoFrame frame;
    frame.allocate(camera.width_px, camera.height_px);
    Run result;
    core::OdometryReading reading;
    for (int i = 0; i < 4; ++i) {
      simulator.command({0.12, i % 2 == 0 ? 0.1 : -0.1});
      simulator.command_pan(0.3 * i);
      simulator.step(0.7);
      EXPECT_TRUE(sim_camera.capture(frame).ok());
      result.frames.push_back(frame.left.clone());
      result.frames.push_back(frame.right.clone());
      while (odometry.read(reading).ok()) result.odometry.push_back(reading.pose);
    }
    return result;
  };
  const Run first = run(11);
  const Run second = run(11);
  ASSERT_EQ(first.frames.size(), second.frames.size());
  for (std::size_t i = 0; i < first.frames.size(); ++i) {
    EXPECT_EQ(cv::norm(first.frames[i], second.frames[i], cv::NORM_L1), 0.0) << i;
  }
  ASSERT_EQ(first.odometry.size(), second.odometry.size());
  for (std::size_t i = 0; i < first.odometry.size(); ++i) {
    EXPECT_EQ(first.odometry[i].x, second.odometry[i].x);
    EXPECT_EQ(first.odometry[i].theta, second.odometry[i].theta);
  }
}

TEST(Simulator, StepAndOdometryDoNotAllocate) {
  const World world = load_or_fail(hall_yaml(true));
  Simulator simulator(world, core::RobotConfig{}, core::CameraConfig{}, core::SimConfig{}, 1);
  SimOdometry odometry(simulator);
  core::OdometryReading reading;
  const core::AllocationScope scope;
  simulator.command({0.1, 0.05});
  for (int i = 0; i < 100; ++i) {
    simulator.step(0.05);
    while (odometry.read(reading).ok()) {
    }
  }
  EXPECT_EQ(scope.allocations(), 0U);
}

}  // namespace
}  // namespace stereoscout::host_sim
