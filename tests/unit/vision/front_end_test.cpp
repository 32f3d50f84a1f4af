#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/vision/front_end.hpp"
#include "synthetic_stereo.hpp"

namespace stereoscout::vision {
namespace {

core::CameraMount paper_mount() { return {0.10, 0.0, 0.6, 0.0}; }

core::VisionConfig vision_config(int candidate_min_frames) {
  core::VisionConfig config;
  config.candidate_min_frames = candidate_min_frames;
  config.index_capacity = 20000;
  return config;
}

struct Observed {
  Eigen::Vector3d point_world;
  Eigen::Matrix3d covariance_world;
};

std::multimap<std::uint32_t, Observed> to_world(const core::FixedVector<core::LandmarkObservation>& observations,
                                                const Eigen::Isometry3d& world_from_camera) {
  std::multimap<std::uint32_t, Observed> result;
  for (const auto& observation : observations) {
    result.insert({observation.landmark_id,
                   {world_from_camera * observation.point_camera,
                    core::rotate_covariance(world_from_camera.linear(), observation.covariance)}});
  }
  return result;
}

// Paper IV: matched keys triangulate to the true surface within their covariance.
TEST(VisionFrontEnd, LandmarksTriangulateToGroundTruthWithinCovariance) {
  const StereoCalibration camera;
  const test::Rendering view = test::render(test::textured_room(), camera, paper_mount(), core::Pose2{0.0, 0.0, 0.1});
  VisionFrontEnd front_end(vision_config(1), core::RobotConfig{}, camera, paper_mount());
  core::FixedVector<core::LandmarkObservation> observations(front_end.max_observations());
  ASSERT_TRUE(front_end.observe_landmarks(view.frame, observations).ok());
  ASSERT_GT(observations.size(), 100U);
  std::vector<double> chi_square;
  for (const auto& observation : observations) {
    const Eigen::Vector3d& p = observation.point_camera;
    const int x = static_cast<int>(std::lround(camera.focal_px * p.x() / p.z() + camera.principal_x_px));
    const int y = static_cast<int>(std::lround(camera.focal_px * p.y() / p.z() + camera.principal_y_px));
    const double true_depth = view.right_depth.at<double>(y, x);
    ASSERT_GT(true_depth, 0.0);
    const Eigen::Vector3d truth = p * (true_depth / p.z());  // same ray, true depth
    chi_square.push_back(core::mahalanobis_squared(p - truth, observation.covariance));
  }
  std::sort(chi_square.begin(), chi_square.end());
  const double within_99 = static_cast<double>(std::count_if(chi_square.begin(), chi_square.end(),
                                                             [](double c) { return c < 11.34; })) /
                           static_cast<double>(chi_square.size());
  std::printf("%zu landmarks, median chi-square %.3f, %.1f %% below the 99 %% bound\n", chi_square.size(),
              chi_square[chi_square.size() / 2], 100.0 * within_99);
  EXPECT_GT(within_99, 0.95);
  EXPECT_LT(chi_square[chi_square.size() / 2], 3.0);
}

// The same physical feature seen from two poses gets the same identity.
TEST(VisionFrontEnd, SameFeatureFromTwoPosesKeepsItsIdentity) {
  const StereoCalibration camera;
  const test::Scene scene = test::textured_room();
  VisionFrontEnd front_end(vision_config(1), core::RobotConfig{}, camera, paper_mount());
  core::FixedVector<core::LandmarkObservation> observations(front_end.max_observations());
  const test::Rendering first = test::render(scene, camera, paper_mount(), core::Pose2{0.0, 0.0, 0.0});
  ASSERT_TRUE(front_end.observe_landmarks(first.frame, observations).ok());
  const auto first_world = to_world(observations, first.world_from_right_camera);
  const test::Rendering second = test::render(scene, camera, paper_mount(), core::Pose2{0.10, 0.03, 0.06});
  ASSERT_TRUE(front_end.observe_landmarks(second.frame, observations).ok());
  const auto second_world = to_world(observations, second.world_from_right_camera);
  std::size_t shared = 0;
  std::size_t consistent = 0;
  for (const auto& [id, seen] : second_world) {
    const auto range = first_world.equal_range(id);
    if (range.first == range.second) continue;
    ++shared;
    const Observed& before = range.first->second;
    const double distance = core::mahalanobis_squared(seen.point_world - before.point_world,
                                                      seen.covariance_world + before.covariance_world);
    consistent += distance < 16.27 ? 1U : 0U;  // chi-square 3 dof, 99.9 %
  }
  std::printf("%zu identities seen from both poses, %zu consistent\n", shared, consistent);
  EXPECT_GT(shared, 50U);
  EXPECT_GE(consistent, shared * 95 / 100);
}

TEST(VisionFrontEnd, FreshFeaturesWaitForEnoughFrames) {
  const StereoCalibration camera;
  const test::Scene scene = test::textured_room();
  VisionFrontEnd front_end(vision_config(3), core::RobotConfig{}, camera, paper_mount());
  core::FixedVector<core::LandmarkObservation> observations(front_end.max_observations());
  const core::Pose2 poses[] = {{0.0, 0.0, 0.0}, {0.03, 0.0, 0.01}, {0.06, 0.0, 0.02}};
  std::size_t handed_on[3] = {};
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(front_end.observe_landmarks(test::render(scene, camera, paper_mount(), poses[i]).frame, observations).ok());
    handed_on[i] = observations.size();
  }
  EXPECT_EQ(handed_on[0], 0U);
  EXPECT_EQ(handed_on[1], 0U);
  EXPECT_GT(handed_on[2], 50U);
  EXPECT_EQ(front_end.index().stats().promoted, front_end.index().stats().landmarks);
  EXPECT_GT(front_end.index().stats().candidates, 0U);  // keys seen fewer than 3 times wait
}

TEST(VisionFrontEnd, ParallelSiftGivesTheSequentialResult) {
  const StereoCalibration camera;
  const test::Rendering view = test::render(test::textured_room(), camera, paper_mount(), core::Pose2{0.2, -0.1, -0.05});
  core::VisionConfig parallel = vision_config(1);
  parallel.sift_parallel = true;
  VisionFrontEnd sequential_end(vision_config(1), core::RobotConfig{}, camera, paper_mount());
  VisionFrontEnd parallel_end(parallel, core::RobotConfig{}, camera, paper_mount());
  core::FixedVector<core::LandmarkObservation> a(sequential_end.max_observations());
  core::FixedVector<core::LandmarkObservation> b(parallel_end.max_observations());
  sequential_end.observe_landmarks(view.frame, a);
  parallel_end.observe_landmarks(view.frame, b);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 0U);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].landmark_id, b[i].landmark_id);
    EXPECT_EQ(a[i].point_camera, b[i].point_camera);  // bit for bit
    EXPECT_EQ(a[i].covariance, b[i].covariance);
  }
  const auto& left_a = sequential_end.last_left_keys();
  const auto& left_b = parallel_end.last_left_keys();
  ASSERT_EQ(left_a.size(), left_b.size());
  for (std::size_t i = 0; i < left_a.size(); ++i) {
    EXPECT_EQ(left_a[i].x_px, left_b[i].x_px);
    EXPECT_EQ(left_a[i].descriptor, left_b[i].descriptor);
  }
}

TEST(VisionFrontEnd, BadPairIsSkippedAndCounted) {
  const StereoCalibration camera;
  VisionFrontEnd front_end(vision_config(1), core::RobotConfig{}, camera, paper_mount());
  core::FixedVector<core::LandmarkObservation> observations(front_end.max_observations());
  core::DepthScan scan;
  front_end.allocate_scan(scan);
  core::StereoFrame wrong_size;
  wrong_size.allocate(320, 240);
  EXPECT_EQ(front_end.observe_landmarks(wrong_size, observations).code, core::StatusCode::invalid_input);
  core::StereoFrame empty;
  EXPECT_EQ(front_end.scan(empty, scan).code, core::StatusCode::invalid_input);
  EXPECT_EQ(front_end.rejected_frames(), 2U);
  EXPECT_TRUE(observations.empty());
}

// A low box whose face is 0.45 m from the camera, nearer than the dense matcher reaches
// (40 / 63 = 0.63 m): its columns hold it only from the SIFT matches (scan_near_min_matches),
// where the box is (its face and the near edge of its top; the test's smooth texture gives
// SIFT few keys that near, and few patches of it that match nowhere else within the dense
// matcher's range), and nothing appears where the view holds only the floor.
struct NearBoxColumns {
  int on_box = 0;     // obstacle columns on the box
  int elsewhere = 0;  // obstacle columns nearer than 1 m that are not on it
};

NearBoxColumns scan_near_box(int near_min_matches, std::uint64_t* allocations) {
  const StereoCalibration camera;
  test::Scene scene;
  scene.boxes.push_back({{0.55, 0.0, 0.0}, {0.9, 0.4, 0.5}});  // below the camera at 0.6 m
  const test::Rendering view = test::render(scene, camera, paper_mount(), core::Pose2{});
  core::VisionConfig config = vision_config(1);
  config.scan_near_min_matches = near_min_matches;
  VisionFrontEnd front_end(config, core::RobotConfig{}, camera, paper_mount());
  core::FixedVector<core::LandmarkObservation> observations(front_end.max_observations());
  core::DepthScan scan;
  front_end.allocate_scan(scan);
  EXPECT_TRUE(front_end.observe_landmarks(view.frame, observations).ok());
  {
    const core::AllocationScope scope;
    EXPECT_TRUE(front_end.scan(view.frame, scan).ok());
    if (allocations != nullptr) *allocations = scope.allocations();
  }
  NearBoxColumns columns;
  for (const core::DepthScanColumn& column : scan.columns) {
    if (column.kind != core::DepthScanColumn::Kind::obstacle) continue;
    const bool on_box = column.x_robot_m > 0.5 && column.x_robot_m < 0.95 && column.y_robot_m > -0.05 &&
                        column.y_robot_m < 0.45;  // its footprint and 5 cm around
    if (on_box) {
      ++columns.on_box;
    } else if (std::hypot(column.x_robot_m - scan.origin_robot.x(), column.y_robot_m - scan.origin_robot.y()) < 1.0) {
      ++columns.elsewhere;
    }
  }
  return columns;
}

TEST(VisionFrontEnd, SurfacesNearerThanTheDenseMatcherReachesComeFromTheStereoMatches) {
  const NearBoxColumns dense_only = scan_near_box(0, nullptr);
  std::uint64_t allocations = 1;
  const NearBoxColumns with_matches = scan_near_box(3, &allocations);
  std::printf("obstacle columns on the box: %d dense only, %d with the matches (%d, %d elsewhere within 1 m)\n",
              dense_only.on_box, with_matches.on_box, dense_only.elsewhere, with_matches.elsewhere);
  EXPECT_EQ(dense_only.on_box, 0);
  EXPECT_GE(with_matches.on_box, 2);
  EXPECT_EQ(with_matches.elsewhere, dense_only.elsewhere);
  EXPECT_EQ(allocations, 0U);
}

// The dense path (block matcher and scan) does not allocate once built; SIFT does, inside
// OpenCV, and the count is printed so the figure in docs/results.md can be checked.
TEST(VisionFrontEnd, AllocationsPerFrame) {
  const StereoCalibration camera;
  const test::Rendering view = test::render(test::textured_room(), camera, paper_mount(), core::Pose2{});
  VisionFrontEnd front_end(vision_config(1), core::RobotConfig{}, camera, paper_mount());
  core::FixedVector<core::LandmarkObservation> observations(front_end.max_observations());
  core::DepthScan scan;
  front_end.allocate_scan(scan);
  front_end.observe_landmarks(view.frame, observations);  // warm-up: OpenCV's buffers grow
  {
    const core::AllocationScope scope;
    EXPECT_TRUE(front_end.scan(view.frame, scan).ok());
    EXPECT_EQ(scope.allocations(), 0U);
  }
  const core::AllocationScope scope;
  front_end.observe_landmarks(view.frame, observations);
  std::printf("observe_landmarks after warm-up: %llu heap allocations, %llu bytes (all inside cv::SIFT)\n",
              static_cast<unsigned long long>(scope.allocations()), static_cast<unsigned long long>(scope.bytes()));
}

}  // namespace
}  // namespace stereoscout::vision
