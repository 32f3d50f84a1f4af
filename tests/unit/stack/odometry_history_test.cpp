#include "stereoscout/stack/odometry_history.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace stereoscout::stack {
namespace {

core::OdometryReading reading(std::int64_t t_ns, double x, double y, double theta) {
  core::OdometryReading r;
  r.timestamp_ns = t_ns;
  r.pose = core::Pose2{x, y, theta};
  return r;
}

TEST(OdometryHistory, InterpolatesBetweenTheReadingsAroundATime) {
  OdometryHistory history(4);
  ASSERT_TRUE(history.add(reading(100, 0.0, 0.0, 0.0)));
  ASSERT_TRUE(history.add(reading(200, 1.0, 2.0, 0.4)));
  core::Pose2 pose;
  ASSERT_TRUE(history.pose_at(125, pose));
  EXPECT_DOUBLE_EQ(pose.x, 0.25);
  EXPECT_DOUBLE_EQ(pose.y, 0.5);
  EXPECT_DOUBLE_EQ(pose.theta, 0.1);
  ASSERT_TRUE(history.pose_at(200, pose));
  EXPECT_DOUBLE_EQ(pose.x, 1.0);
  EXPECT_FALSE(history.pose_at(99, pose));   // before the history
  EXPECT_FALSE(history.pose_at(201, pose));  // after the newest reading: wait for the next
}

TEST(OdometryHistory, HeadingTakesTheShorterArcAcrossPi) {
  OdometryHistory history(4);
  history.add(reading(0, 0.0, 0.0, 3.0));
  history.add(reading(10, 0.0, 0.0, -3.0));  // 0.28 rad further, across +-pi
  core::Pose2 pose;
  ASSERT_TRUE(history.pose_at(5, pose));
  EXPECT_NEAR(std::abs(pose.theta), M_PI, 1e-12);
}

TEST(OdometryHistory, RefusesOldOrRepeatedReadingsAndForgetsTheOldest) {
  OdometryHistory history(2);
  EXPECT_TRUE(history.add(reading(10, 0.0, 0.0, 0.0)));
  EXPECT_FALSE(history.add(reading(10, 1.0, 0.0, 0.0)));
  EXPECT_FALSE(history.add(reading(5, 1.0, 0.0, 0.0)));
  EXPECT_TRUE(history.add(reading(20, 1.0, 0.0, 0.0)));
  EXPECT_TRUE(history.add(reading(30, 2.0, 0.0, 0.0)));
  core::Pose2 pose;
  EXPECT_FALSE(history.pose_at(15, pose));  // the reading at 10 left the history
  ASSERT_TRUE(history.pose_at(25, pose));
  EXPECT_DOUBLE_EQ(pose.x, 1.5);
}

}  // namespace
}  // namespace stereoscout::stack
