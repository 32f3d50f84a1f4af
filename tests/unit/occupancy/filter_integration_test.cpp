// The just-in-time grid driven by the real slam::ParticleFilter: its own resampling and ML
// switches, on a synthetic landmark world. After every update the ML grid equals the grid
// built from scratch along the ML particle's whole ancestry; the cache update does not touch
// the heap; everything is freed when the cache and filter let go.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ancestry_driver.hpp"
#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/occupancy/final_map.hpp"
#include "stereoscout/occupancy/just_in_time_grid.hpp"
#include "stereoscout/slam/particle_filter.hpp"

namespace stereoscout::occupancy {
namespace {

struct LandmarkWorld {
  std::vector<Eigen::Vector3d> landmarks;
  explicit LandmarkWorld(std::uint64_t seed) {
    core::RandomStream random(seed, {core::stream_purpose::test, 0, 50});
    for (int i = 0; i < 150; ++i) {
      landmarks.emplace_back(random.uniform(-4.0, 4.0), random.uniform(-4.0, 4.0), random.uniform(0.0, 2.0));
    }
  }
  // Landmarks within 4 m and +-35 degrees ahead, 3 cm noise, in the robot frame.
  void observe(const core::Pose2& truth, std::uint32_t step, std::vector<core::LandmarkObservation>& out) const {
    core::RandomStream noise(3, {core::stream_purpose::test, step, 51});
    out.clear();
    const core::Pose2 robot_from_map = truth.inverse();
    for (std::uint32_t id = 0; id < landmarks.size(); ++id) {
      const Eigen::Vector2d local = robot_from_map.transform_point(landmarks[id].head<2>());
      if (local.norm() > 4.0 || local.x() < 0.1 || std::abs(std::atan2(local.y(), local.x())) > 0.6) continue;
      core::LandmarkObservation o;
      o.landmark_id = id;
      o.point_camera = Eigen::Vector3d(local.x() + noise.gaussian(0.0, 0.03), local.y() + noise.gaussian(0.0, 0.03),
                                       landmarks[id].z() + noise.gaussian(0.0, 0.03));
      o.covariance = Eigen::Matrix3d::Identity() * (0.03 * 0.03);
      out.push_back(o);
    }
  }
};

TEST(JustInTimeGridWithFilter, EqualsTheGridFromScratchAndDoesNotAllocate) {
  core::FilterConfig filter_config;
  filter_config.particles = 100;
  filter_config.particle_capacity = 100;
  filter_config.trajectory_node_capacity = 100 * 100;
  filter_config.landmark_node_capacity = 400000;
  filter_config.landmark_estimate_capacity = 200000;
  core::GridConfig grid_config;
  grid_config.width_cells = 100;
  grid_config.height_cells = 100;
  grid_config.cache_capacity = 32;
  grid_config.scan_history = 200;
  const LandmarkWorld world(4);
  std::vector<core::LandmarkObservation> observations;
  observations.reserve(world.landmarks.size());
  std::vector<slam::TrajectoryNodeHandle> live(100);
  std::vector<core::DepthScan> scans(81);
  std::vector<bool> recorded(81, false);
  testing::DriverSettings scan_settings;
  slam::TrajectoryTree scan_tree(1);
  testing::AncestryDriver scan_maker(scan_tree, scan_settings);  // only its scan generator is used
  std::uint64_t allocations = 0;
  std::uint64_t mismatches = 0;
  std::uint64_t resamplings = 0;
  {
    slam::ParticleFilter filter(filter_config, core::CameraMount{}, 21);
    core::Pose2 truth{0.0, -1.5, 0.0};
    core::OdometryReading odometry{0, 0, {}};
    filter.start(odometry, truth);
    const GridGeometry geometry = GridGeometry::centred_on(grid_config, core::Pose2{});
    JustInTimeGrid cache(grid_config, geometry, 32, filter.trajectory());
    OccupancyGrid reference(geometry, LogOddsModel::from_config(grid_config));
    for (std::uint32_t u = 0; u <= 80; ++u) {
      if (u > 0) {
        core::RandomStream noise(3, {core::stream_purpose::test, u, 52});
        truth = truth.compose(core::Pose2{0.07, 0.0, 0.045});
        odometry.pose = odometry.pose.compose(
            core::Pose2{0.07 * 1.03 + noise.gaussian(0.0, 0.005), noise.gaussian(0.0, 0.003), 0.045 + noise.gaussian(0.0, 0.005)});
        odometry.timestamp_ns += 200000000;
        world.observe(truth, u, observations);
        const slam::UpdateResult result = filter.update(
            odometry, slam::ObservationList{observations.data(), observations.size()}, Eigen::Isometry3d::Identity());
        ASSERT_TRUE(result.status.ok());
        resamplings += result.resampled ? 1U : 0U;
      }
      const slam::TrajectoryNodeHandle ml = filter.ml_trajectory_node();
      const std::uint32_t index = filter.trajectory().get(ml).update_index;
      ASSERT_EQ(index, u);
      scan_maker.make_scan(scans[u], 32);
      recorded[u] = true;
      for (std::size_t i = 0; i < live.size(); ++i) live[i] = filter.particle(i).trajectory;
      core::AllocationScope scope;
      cache.record_scan(index, scans[u]);
      cache.update(ml, live.data(), live.size());
      allocations += scope.allocations();

      reference.clear();
      std::vector<slam::TrajectoryNodeHandle> lineage;
      for (slam::TrajectoryNodeHandle n = ml; n; n = filter.trajectory().parent(n)) lineage.push_back(n);
      for (auto it = lineage.rbegin(); it != lineage.rend(); ++it) {
        const slam::TrajectoryNode& node = filter.trajectory().get(*it);
        reference.insert(scans[node.update_index], node.pose);
      }
      mismatches += reference.same_cells_as(*cache.ml_grid()) ? 0U : 1U;
    }
    EXPECT_GT(cache.stats().copies, 0u);
    EXPECT_GT(cache.stats().rollup_length_max, 1u) << "the filter's ML switches need real roll-ups";
    EXPECT_EQ(cache.stats().evictions, 0u);
    EXPECT_EQ(cache.stats().built_from_empty, 1u);
    cache.release_all();
    EXPECT_EQ(cache.grids_held(), 0u);
  }
  EXPECT_GT(resamplings, 0u);
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(allocations, 0u);
}

}  // namespace
}  // namespace stereoscout::occupancy
