// `stereoscout slam --kitti` on the shared real excerpt (KITTI odometry 06, frames 0-50): the
// filter beats its noisy odometry, the identities hold on real images, and a seed gives one
// trajectory byte for byte. A prefix of the sequence and 100 particles keep it short. Skips
// when the data folder is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "kitti_test_folder.hpp"
#include "kitti_run.hpp"
#include "stereoscout/test/paths.hpp"

namespace stereoscout::cli::kitti {
namespace {

constexpr const char* kExcerpt = "kitti-odometry/06-first51";

bool load_excerpt(std::size_t frames, host_dataset::KittiSequence& sequence) {
  const std::string folder = test::data_path(kExcerpt);
  if (folder.empty()) return false;
  std::string error;
  EXPECT_TRUE(host_dataset::load_kitti_sequence(folder, frames, sequence, error)) << error;
  return true;
}

RunOptions test_options(std::uint64_t seed) {
  RunOptions options;
  options.filter.particles = 100;
  // KITTI's 1241 x 376 street views: the 1000 keys per image the excerpt's thresholds were
  // set with (the default of 500 is tuned for the simulated indoor robot).
  options.vision.max_features = 1000;
  options.filter.landmark_node_capacity = 400000;
  options.filter.landmark_estimate_capacity = 200000;
  options.filter.trajectory_node_capacity = 20000;
  // Odometry noticeably worse than the config's car-like default, so that over half the
  // excerpt the difference the filter makes is well above run-to-run spread.
  options.dataset.odometry = core::OdometryNoiseConfig{0.03, 0.02, 0.005, 0.02, 0.5};
  options.seed = seed;
  return options;
}

TEST(KittiSlam, FilterBeatsOdometryAndIdentitiesHold) {
  host_dataset::KittiSequence sequence;
  if (!load_excerpt(25, sequence)) {
    GTEST_SKIP() << "KITTI excerpt not found under " << test::data_dir() << "/" << kExcerpt;
  }
  const RunResult result = run_kitti_slam(sequence, test_options(1));
  ASSERT_TRUE(result.filter_score && result.odometry_score);
  std::printf("kitti 06 frames 0-24, 100 particles: ATE %.3f m (odometry %.3f m), RPE %.4f m/m (odometry %.4f), "
              "%zu landmarks, matched %.1f %%, reobservation consistency %.1f %% of %llu\n",
              result.filter_score->ate_rmse_m, result.odometry_score->ate_rmse_m, result.filter_score->rpe_per_m,
              result.odometry_score->rpe_per_m, result.landmarks, 100.0 * result.matched_share(),
              100.0 * result.reobservation_consistency(), static_cast<unsigned long long>(result.reobservations));
  EXPECT_EQ(result.frames, 25U);
  EXPECT_EQ(result.frames_skipped, 0U);
  EXPECT_EQ(result.frames_without_features, 0U);
  EXPECT_LT(result.filter_score->ate_rmse_m, 0.6 * result.odometry_score->ate_rmse_m);
  EXPECT_GT(result.reobservations, 1000U);
  EXPECT_GT(result.reobservation_consistency(), 0.75);
  EXPECT_GT(result.matched_share(), 0.5);
  EXPECT_GT(result.landmarks, 50U);
  EXPECT_EQ(result.changes_refused_pool_full, 0U);
}

TEST(KittiSlam, SameSeedSameTrajectoryBytes) {
  host_dataset::KittiSequence sequence;
  if (!load_excerpt(6, sequence)) {
    GTEST_SKIP() << "KITTI excerpt not found under " << test::data_dir() << "/" << kExcerpt;
  }
  const RunResult first = run_kitti_slam(sequence, test_options(5));
  const RunResult again = run_kitti_slam(sequence, test_options(5));
  ASSERT_FALSE(first.trajectory_tum.empty());
  EXPECT_EQ(first.trajectory_tum, again.trajectory_tum);
  EXPECT_EQ(first.odometry_tum, again.odometry_tum);
  EXPECT_EQ(first.landmarks_ply, again.landmarks_ply);
  EXPECT_EQ(std::count(first.trajectory_tum.begin(), first.trajectory_tum.end(), '\n'), 6);
}

// Any folder in the layout runs: here a tiny one of blank 80 x 30 images (no features at all)
// with one pair missing. Every frame is still an update (odometry only), nothing crashes.
TEST(KittiSlam, FeaturelessAndMissingFramesAreCountedNotFatal) {
  const host_dataset::test::KittiTestFolder folder(6, 80, 30);
  std::remove(host_dataset::kitti_image_path(folder.path(), 1, 3).c_str());
  host_dataset::KittiSequence sequence;
  std::string error;
  ASSERT_TRUE(host_dataset::load_kitti_sequence(folder.path(), 0, sequence, error)) << error;
  RunOptions options = test_options(1);
  options.dataset.odometry = core::OdometryNoiseConfig{};
  options.filter.motion_noise_translation_per_m = 0.0;
  options.filter.motion_noise_rotation_per_rad = 0.0;
  options.filter.motion_noise_rotation_per_m = 0.0;
  options.filter.motion_noise_translation_per_rad = 0.0;
  const RunResult result = run_kitti_slam(sequence, options);
  EXPECT_EQ(result.frames, 6U);
  EXPECT_EQ(result.frames_skipped, 1U);
  EXPECT_EQ(result.frames_without_features, 5U);
  ASSERT_EQ(result.warnings.size(), 1U);
  EXPECT_EQ(result.warnings[0].rfind(host_dataset::kitti_image_path(folder.path(), 1, 3), 0), 0U);
  EXPECT_EQ(result.observations, 0U);
  EXPECT_EQ(result.landmarks, 0U);
  // Exact odometry, no proposal noise, no observations: the particles follow the true line.
  ASSERT_TRUE(result.filter_score && result.odometry_score);
  EXPECT_NEAR(result.odometry_score->ate_rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(result.filter_score->ate_rmse_m, 0.0, 1e-9);
  EXPECT_EQ(std::count(result.groundtruth_tum.begin(), result.groundtruth_tum.end(), '\n'), 6);
}

}  // namespace
}  // namespace stereoscout::cli::kitti
