// The identity gate: one look in two places makes two landmarks, each found again where it
// is; a return after a long drive still finds its place (the drift widens the gate); full
// identities and a full pool drop keys, counted, keeping the others in order; no allocation.
#include <gtest/gtest.h>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/vision/identity_gate.hpp"

namespace stereoscout::vision {
namespace {

constexpr std::size_t kCapacity = 16;

IdentityGateParams small_gate(std::size_t instances = 64, std::size_t per_identity = 4) {
  IdentityGateParams params;
  params.identities = kCapacity;
  params.instances = instances;
  params.instances_per_identity = per_identity;
  return params;  // the filter's defaults: 99% gate, 0.05 m/m, 0.02 rad/m, ...
}

// A camera on the robot's centre, looking along the robot's x axis (optical z forward,
// optical x to the right, optical y down).
Eigen::Isometry3d camera_at(const core::Pose2& robot) {
  Eigen::Matrix3d optical_to_robot;
  optical_to_robot << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3d robot_from_camera = Eigen::Isometry3d::Identity();
  robot_from_camera.linear() = optical_to_robot;
  return robot.to_isometry3() * robot_from_camera;
}

// A sighting of the world point `world` (z up) from the robot at `robot`, as the index names it.
core::LandmarkObservation sighting(std::uint32_t identity, const core::Pose2& robot, const Eigen::Vector3d& world) {
  core::LandmarkObservation observation;
  observation.landmark_id = identity;
  observation.point_camera = camera_at(robot).inverse() * world;
  observation.covariance = Eigen::Matrix3d::Identity() * 0.0004;  // 2 cm
  return observation;
}

void observe(IdentityGate& gate, const core::Pose2& robot, core::FixedVector<core::LandmarkObservation>& frame) {
  gate.apply(robot, camera_at(robot), frame);
}

TEST(IdentityGate, OneLookInTwoPlacesIsTwoLandmarksEachFoundAgainWhereItIs) {
  IdentityGate gate(small_gate());
  core::FixedVector<core::LandmarkObservation> frame(8);
  const Eigen::Vector3d left(3.0, 1.0, 0.5);
  const Eigen::Vector3d right(3.0, -1.0, 0.5);  // the same look, 2 m away
  core::Pose2 robot{0.0, 0.0, 0.0};
  frame.push_back(sighting(5, robot, left));
  frame.push_back(sighting(5, robot, right));
  observe(gate, robot, frame);
  ASSERT_EQ(frame.size(), 2U);
  const std::uint32_t left_id = frame[0].landmark_id;
  const std::uint32_t right_id = frame[1].landmark_id;
  EXPECT_NE(left_id, right_id);
  EXPECT_EQ(gate.stats().instances_created, 2U);
  EXPECT_EQ(gate.stats().split, 1U);
  // 7 cm on, seen in the other order: each key finds its own place.
  robot = core::Pose2{0.07, 0.0, 0.0};
  frame.clear();
  frame.push_back(sighting(5, robot, right));
  frame.push_back(sighting(5, robot, left));
  observe(gate, robot, frame);
  EXPECT_EQ(frame[0].landmark_id, right_id);
  EXPECT_EQ(frame[1].landmark_id, left_id);
  // Half a metre beside the left place, right after: a third place, not the first.
  frame.clear();
  frame.push_back(sighting(5, robot, left + Eigen::Vector3d(0.0, 0.5, 0.0)));
  observe(gate, robot, frame);
  EXPECT_NE(frame[0].landmark_id, left_id);
  EXPECT_NE(frame[0].landmark_id, right_id);
  EXPECT_EQ(gate.stats().joined, 2U);
  EXPECT_EQ(gate.stats().instances_created, 3U);
}

TEST(IdentityGate, AReturnAfterALongDriveFindsItsPlaceThoughTheOdometryDrifted) {
  IdentityGate gate(small_gate());
  core::FixedVector<core::LandmarkObservation> frame(4);
  const Eigen::Vector3d post(2.0, 0.0, 0.5);
  frame.push_back(sighting(9, core::Pose2{0.0, 0.0, 0.0}, post));
  observe(gate, core::Pose2{0.0, 0.0, 0.0}, frame);
  const std::uint32_t id = frame[0].landmark_id;
  // A 20 m loop in 0.5 m steps; on return the odometry is 0.4 m off, so the post appears
  // 0.4 m from where it was put.
  for (int step = 1; step <= 40; ++step) {
    frame.clear();
    observe(gate, core::Pose2{0.5 * (step % 2), 0.0, 0.0}, frame);
  }
  const core::Pose2 robot{0.0, 0.0, 0.0};
  frame.clear();
  frame.push_back(sighting(9, robot, post + Eigen::Vector3d(0.0, 0.4, 0.0)));
  observe(gate, robot, frame);
  EXPECT_EQ(frame[0].landmark_id, id);
  // The same offset right after the last sighting is another place.
  frame.clear();
  frame.push_back(sighting(9, robot, post + Eigen::Vector3d(0.0, 0.8, 0.0)));
  observe(gate, robot, frame);
  EXPECT_NE(frame[0].landmark_id, id);
}

TEST(IdentityGate, FullIdentitiesAndAFullPoolDropKeysCountedAndKeepTheRestInOrder) {
  IdentityGate gate(small_gate(3, 2));
  core::FixedVector<core::LandmarkObservation> frame(8);
  const core::Pose2 robot{0.0, 0.0, 0.0};
  frame.push_back(sighting(1, robot, {2.0, 0.0, 0.5}));
  frame.push_back(sighting(1, robot, {2.0, 1.0, 0.5}));
  frame.push_back(sighting(1, robot, {2.0, -1.0, 0.5}));  // a third place of identity 1: full
  frame.push_back(sighting(0, robot, {2.0, 0.0, 0.5}));   // no identity
  frame.push_back(sighting(kCapacity + 1, robot, {2.0, 0.0, 0.5}));
  frame.push_back(sighting(2, robot, {3.0, 0.0, 0.5}));
  frame.push_back(sighting(3, robot, {4.0, 0.0, 0.5}));   // the pool (3) is full
  const core::AllocationScope scope;
  observe(gate, robot, frame);
  EXPECT_EQ(scope.allocations(), 0U);
  ASSERT_EQ(frame.size(), 3U);
  EXPECT_EQ(frame[0].landmark_id, 1U);
  EXPECT_EQ(frame[1].landmark_id, 2U);
  EXPECT_EQ(frame[2].landmark_id, 3U);
  EXPECT_DOUBLE_EQ(frame[2].point_camera.z(), 3.0);  // identity 2's key, moved up intact
  const IdentityGateStats& stats = gate.stats();
  EXPECT_EQ(stats.observations, 7U);
  EXPECT_EQ(stats.instances_created, 3U);
  EXPECT_EQ(stats.dropped_identity_full, 1U);
  EXPECT_EQ(stats.dropped_unknown_identity, 2U);
  EXPECT_EQ(stats.dropped_pool_full, 1U);
  EXPECT_EQ(gate.instances_used(), 3U);
}

}  // namespace
}  // namespace stereoscout::vision
