// The identity check against the true camera poses: a re-observation agrees only where the
// true motion puts it, a wrong one does not move the stored point, and identities past the
// capacity are counted instead of checked.
#include <gtest/gtest.h>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/vision/identity_check.hpp"

namespace stereoscout::vision {
namespace {

constexpr double kGate99 = 11.345;  // chi-square, 3 degrees of freedom, 99%

core::LandmarkObservation sighting(std::uint32_t id, const Eigen::Vector3d& point_camera) {
  core::LandmarkObservation observation;
  observation.landmark_id = id;
  observation.point_camera = point_camera;
  observation.covariance = Eigen::Matrix3d::Identity() * 0.01;
  return observation;
}

Eigen::Isometry3d camera_forward(double metres) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.0, 0.0, metres);  // optical z is forward
  return pose;
}

TEST(IdentityCheck, ReobservationsAgreeOnlyWhereTheTrueMotionPutsThem) {
  IdentityCheck check(100, kGate99);
  const core::LandmarkObservation first = sighting(7, {1.0, 0.5, 10.0});
  check.observe(Eigen::Isometry3d::Identity(), &first, 1);
  EXPECT_EQ(check.first_sightings(), 1U);
  EXPECT_EQ(check.reobservations(), 0U);
  // The camera moved 2 m forward: the same world point is 2 m closer.
  const core::LandmarkObservation again = sighting(7, {1.0, 0.5, 8.05});
  const core::LandmarkObservation wrong = sighting(7, {2.0, 0.5, 8.0});  // 1 m to the side
  check.observe(camera_forward(2.0), &again, 1);
  check.observe(camera_forward(2.0), &wrong, 1);
  EXPECT_EQ(check.reobservations(), 2U);
  EXPECT_EQ(check.consistent(), 1U);
  EXPECT_DOUBLE_EQ(check.consistency(), 0.5);
}

TEST(IdentityCheck, AWrongSightingDoesNotMoveTheStoredPoint) {
  IdentityCheck check(100, kGate99);
  const core::LandmarkObservation first = sighting(3, {0.0, 0.0, 5.0});
  const core::LandmarkObservation wrong = sighting(3, {0.6, 0.0, 5.0});
  const core::LandmarkObservation right = sighting(3, {0.0, 0.0, 5.1});
  check.observe(Eigen::Isometry3d::Identity(), &first, 1);
  for (int k = 0; k < 5; ++k) check.observe(Eigen::Isometry3d::Identity(), &wrong, 1);
  check.observe(Eigen::Isometry3d::Identity(), &right, 1);
  EXPECT_EQ(check.reobservations(), 6U);
  EXPECT_EQ(check.consistent(), 1U);
}

TEST(IdentityCheck, IdentitiesPastTheCapacityAreCountedNotChecked) {
  IdentityCheck check(10, kGate99);
  const core::LandmarkObservation frame[] = {sighting(10, {0.0, 0.0, 4.0}), sighting(11, {0.0, 0.0, 4.0}),
                                             sighting(0, {0.0, 0.0, 4.0})};
  const core::AllocationScope scope;
  check.observe(Eigen::Isometry3d::Identity(), frame, 3);
  check.observe(Eigen::Isometry3d::Identity(), frame, 3);
  EXPECT_EQ(scope.allocations(), 0U);
  EXPECT_EQ(check.first_sightings(), 1U);
  EXPECT_EQ(check.reobservations(), 1U);
  EXPECT_EQ(check.consistent(), 1U);
  EXPECT_EQ(check.past_capacity(), 4U);
}

TEST(IdentityCheck, ReobservationsOfFloorIdentitiesAreCountedApart) {
  // The world's z is the height: the camera's optical axis points up here, 5 m below the floor,
  // so a point 5 m along it lies on the floor and one 6 m along it 1 m above.
  IdentityCheck check(10, kGate99, 0.05);
  const Eigen::Isometry3d below(Eigen::Translation3d(0.0, 0.0, -5.0));
  const core::LandmarkObservation first[] = {sighting(1, {0.0, 0.0, 5.0}), sighting(2, {0.0, 0.0, 6.0})};
  check.observe(below, first, 2);
  const core::LandmarkObservation again[] = {sighting(1, {0.0, 0.0, 5.0}), sighting(1, {1.0, 0.0, 5.0}),
                                             sighting(2, {0.0, 0.0, 6.0})};
  check.observe(below, again, 3);
  EXPECT_EQ(check.reobservations(), 3U);
  EXPECT_EQ(check.consistent(), 2U);
  EXPECT_EQ(check.floor_reobservations(), 2U);
  EXPECT_EQ(check.floor_consistent(), 1U);
  // Without a floor height nothing is the floor's.
  IdentityCheck no_floor(10, kGate99);
  no_floor.observe(below, first, 2);
  no_floor.observe(below, again, 3);
  EXPECT_EQ(no_floor.floor_reobservations(), 0U);
}

}  // namespace
}  // namespace stereoscout::vision
