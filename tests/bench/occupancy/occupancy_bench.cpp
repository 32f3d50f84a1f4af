// Costs of the just-in-time grid at the paper's size (700 x 700 cells at 0.10 m, 640-column
// scans): one scan insertion (also at the final map's 1 cm, and into the scan archive's
// tiles), one grid copy, a roll-up of L scans, the dependents walk for
// 1000 particles, and a whole synthetic run with 1000 particles reporting grids held,
// roll-up lengths, copies, moves and evictions.
#include <benchmark/benchmark.h>

#include <time.h>  // clock_gettime (POSIX)

#include <algorithm>
#include <cmath>
#include <vector>

#include "ancestry_driver.hpp"
#include "stereoscout/occupancy/just_in_time_grid.hpp"
#include "stereoscout/occupancy/scan_archive.hpp"
#include "stereoscout/slam/particle_filter.hpp"

namespace stereoscout::occupancy {
namespace {

constexpr std::size_t kColumns = 640;

// CPU time of this thread: the machine is shared, wall time would count other people's work.
double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// A 640-column scan, one column per image column over a 60-degree field of view, ranges up to
// 4 m (the depth the paper's stereo head resolves indoors), 80 % obstacles.
core::DepthScan paper_scan(std::uint32_t seed) {
  core::RandomStream random(seed, {core::stream_purpose::test, seed, 7});
  core::DepthScan scan;
  scan.origin_robot = {0.1, 0.0};
  scan.columns.resize(kColumns);
  for (std::size_t c = 0; c < kColumns; ++c) {
    const double bearing = -0.52 + 1.04 * (static_cast<double>(c) + 0.5) / kColumns;
    const double range = random.uniform(0.5, 4.0);
    scan.columns[c] = {static_cast<float>(0.1 + range * std::cos(bearing)),
                       static_cast<float>(range * std::sin(bearing)),
                       random.uniform() < 0.8 ? core::DepthScanColumn::Kind::obstacle
                                              : core::DepthScanColumn::Kind::free};
  }
  return scan;
}

core::GridConfig paper_config() { return core::GridConfig{}; }

void BM_InsertScan(benchmark::State& state) {
  const core::GridConfig config = paper_config();
  OccupancyGrid grid(GridGeometry::centred_on(config, {}), LogOddsModel::from_config(config));
  const core::DepthScan scan = paper_scan(1);
  for (auto _ : state) {
    grid.insert(scan, core::Pose2{0.3, -0.2, 0.4});
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_InsertScan)->Unit(benchmark::kMicrosecond);

// The same scan into a grid at the final map's 1 cm (an office-sized 40 x 16 m): what the end
// of a run pays per scan.
void BM_InsertScanFinalResolution(benchmark::State& state) {
  const core::GridConfig config = paper_config();
  GridGeometry geometry;
  geometry.width_cells = 4000;
  geometry.height_cells = 1600;
  geometry.resolution_m = config.final_map_resolution_m;
  geometry.origin_x_m = -20.0;
  geometry.origin_y_m = -8.0;
  OccupancyGrid grid(geometry, LogOddsModel::from_config(config));
  const core::DepthScan scan = paper_scan(1);
  for (auto _ : state) {
    grid.insert(scan, core::Pose2{0.3, -0.2, 0.4});
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_InsertScanFinalResolution)->Unit(benchmark::kMicrosecond);

// A scan leaving the ring into the archive's 4 m tiles at 1 cm (the default config): what the
// observation update pays per update once the ring is full. The ring holds grid.scan_history
// scans, so finding the leaving scan's node walks that many parent links; the scan spans four
// tiles.
void BM_ArchiveLeavingScan(benchmark::State& state) {
  const core::GridConfig config = paper_config();
  slam::TrajectoryTree tree(1000000);
  ScanHistory ring(static_cast<std::size_t>(config.scan_history), kColumns);
  ScanArchive archive(GridGeometry::centred_on(config, {}), config.final_map_resolution_m, config.final_map_tile_m,
                      static_cast<std::size_t>(config.final_map_archive_tiles), LogOddsModel::from_config(config), tree);
  const core::DepthScan scan = paper_scan(1);
  const core::Pose2 pose{0.3, -0.2, 0.4};
  slam::TrajectoryNodeHandle node{};
  std::uint32_t update = 0;
  // One update: a new ML node, and its scan recorded (the archive first, as the stack does).
  const auto step = [&] {
    const slam::TrajectoryNodeHandle child = tree.add(node, pose, 0, update);
    if (node) tree.release(node);
    node = child;
    archive.keep_leaving_scan(ring, update, node);
    ring.record(update, scan);
    ++update;
  };
  while (update < ring.capacity()) step();  // the ring full: every step from now on archives
  for (auto _ : state) {
    step();
    benchmark::ClobberMemory();
  }
  state.counters["tiles"] = static_cast<double>(archive.stats().tiles_used);
  archive.release();
  tree.release(node);
}
BENCHMARK(BM_ArchiveLeavingScan)->Unit(benchmark::kMicrosecond);

void BM_GridCopy(benchmark::State& state) {
  const core::GridConfig config = paper_config();
  const GridGeometry geometry = GridGeometry::centred_on(config, {});
  OccupancyGrid source(geometry, LogOddsModel::from_config(config));
  OccupancyGrid target(geometry, LogOddsModel::from_config(config));
  for (auto _ : state) {
    target.copy_from(source);
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(geometry.cell_count() * sizeof(float)));
}
BENCHMARK(BM_GridCopy)->Unit(benchmark::kMicrosecond);

// A roll-up of L scans: copy the ancestor's grid, then insert L stored scans at their poses.
void BM_RollUp(benchmark::State& state) {
  const auto length = static_cast<std::uint32_t>(state.range(0));
  const core::GridConfig config = paper_config();
  const GridGeometry geometry = GridGeometry::centred_on(config, {});
  OccupancyGrid source(geometry, LogOddsModel::from_config(config));
  OccupancyGrid target(geometry, LogOddsModel::from_config(config));
  ScanHistory history(length, kColumns);
  std::vector<core::Pose2> poses;
  for (std::uint32_t u = 0; u < length; ++u) {
    history.record(u, paper_scan(u));
    poses.push_back({0.07 * u, 0.0, 0.02 * u});
  }
  for (auto _ : state) {
    target.copy_from(source);
    for (std::uint32_t u = 0; u < length; ++u) {
      ScanView view;
      history.find(u, view);
      target.insert(view, poses[u]);
    }
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_RollUp)->Arg(1)->Arg(2)->Arg(5)->Arg(10)->Arg(20)->Arg(50)->Arg(100)->Unit(benchmark::kMicrosecond);

void report(benchmark::State& state, const JustInTimeGrid& cache, std::uint64_t resamplings) {
  const JustInTimeGridStats& stats = cache.stats();
  state.counters["grids_mean"] = stats.mean_grids_held();
  state.counters["grids_max"] = static_cast<double>(stats.grids_held_max);
  state.counters["rollup_mean"] = stats.mean_rollup_length();
  state.counters["rollup_max"] = static_cast<double>(stats.rollup_length_max);
  state.counters["copies"] = static_cast<double>(stats.copies);
  state.counters["moves"] = static_cast<double>(stats.moves);
  state.counters["evictions"] = static_cast<double>(stats.evictions);
  state.counters["incomplete"] = static_cast<double>(stats.rollup_incomplete);
  state.counters["walk_steps_per_update"] =
      static_cast<double>(stats.dependents_walk_steps) / static_cast<double>(stats.updates);
  state.counters["walk_steps_max"] = static_cast<double>(stats.dependents_walk_steps_max);
  state.counters["resamplings"] = static_cast<double>(resamplings);
}

// The dependents walk alone: 1000 particles on a 10 x 10 grid with one-column scans, so the
// update's cost is the walk and the bookkeeping (after 200 updates of burn-in).
void BM_DependentsWalk1000(benchmark::State& state) {
  core::GridConfig config = paper_config();
  config.width_cells = 10;
  config.height_cells = 10;
  slam::TrajectoryTree tree(400000);
  testing::DriverSettings settings;
  settings.particles = 1000;
  testing::AncestryDriver driver(tree, settings);
  JustInTimeGrid cache(config, GridGeometry::centred_on(config, {}), 1, tree);
  core::DepthScan scan;
  scan.columns = {{0.2F, 0.0F, core::DepthScanColumn::Kind::obstacle}};
  driver.start({});
  for (std::uint32_t u = 0; u < 200; ++u) {
    if (u > 0) driver.step();
    cache.record_scan(u, scan);
    cache.update(driver.ml_node(), driver.nodes(), driver.count());
  }
  for (auto _ : state) {
    cache.update(driver.ml_node(), driver.nodes(), driver.count());  // ML unchanged: walk + free pass
  }
  report(state, cache, driver.resamplings());
}
BENCHMARK(BM_DependentsWalk1000)->Unit(benchmark::kMicrosecond);

// A synthetic run: 1000 particles, the paper's grid and scans, `updates` updates. Time is per
// whole run; the counters are the run's grid statistics.
void BM_Run1000Particles(benchmark::State& state) {
  const auto updates = static_cast<std::uint32_t>(state.range(0));
  const core::GridConfig config = paper_config();
  for (auto _ : state) {
    slam::TrajectoryTree tree(1000 * (updates + 2));
    testing::DriverSettings settings;
    settings.particles = 1000;
    // range(1) = 0: i.i.d. log-likelihoods of spread 1 (no lineage is better than another,
    // the worst case); else the likelihood of the distance to the true path, sigma in cm.
    settings.weight_noise = state.range(1) == 0 ? 1.0 : 0.1;
    settings.likelihood_sigma_m = static_cast<double>(state.range(1)) / 100.0;
    testing::AncestryDriver driver(tree, settings);
    JustInTimeGrid cache(config, GridGeometry::centred_on(config, {}), kColumns, tree);
    driver.start({});
    for (std::uint32_t u = 0; u <= updates; ++u) {
      if (u > 0) driver.step();
      cache.record_scan(u, paper_scan(u));
      cache.update(driver.ml_node(), driver.nodes(), driver.count());
    }
    report(state, cache, driver.resamplings());
    driver.release_all();
  }
}
BENCHMARK(BM_Run1000Particles)->Args({300, 0})->Args({300, 1})->Args({300, 3})->Iterations(1)->Unit(benchmark::kMillisecond);

// The real slam::ParticleFilter on a synthetic world: 400 landmarks in a 12 m x 12 m room,
// the robot drives circles of 2.3 m radius (7 cm, 1.7 degrees per update), odometry with 2 %
// scale error and noise, landmarks seen within 5 m and +-35 degrees with 3 cm noise. The
// genealogy (resampling, ML switches) is the filter's own; the counters are the grid cache's.
void BM_FilterRun(benchmark::State& state) {
  const auto particles = static_cast<int>(state.range(0));
  const auto updates = static_cast<std::uint32_t>(state.range(1));
  core::FilterConfig filter_config;
  filter_config.particles = particles;
  filter_config.particle_capacity = particles;
  filter_config.trajectory_node_capacity = particles * static_cast<int>(updates + 4);
  const core::GridConfig grid_config = paper_config();
  std::vector<Eigen::Vector3d> landmarks;
  core::RandomStream world(11, {core::stream_purpose::test, 0, 99});
  for (int i = 0; i < 400; ++i) {
    landmarks.emplace_back(world.uniform(-6.0, 6.0), world.uniform(-6.0, 6.0), world.uniform(0.0, 2.0));
  }
  std::vector<core::LandmarkObservation> observations;
  std::vector<slam::TrajectoryNodeHandle> live(static_cast<std::size_t>(particles));
  const core::Pose2 step{0.07, 0.0, 0.03};
  for (auto _ : state) {
    slam::ParticleFilter filter(filter_config, core::CameraMount{}, 7);
    core::Pose2 truth{0.0, -2.3, 0.0};
    core::OdometryReading odometry{0, 0, {}};
    filter.start(odometry, truth);
    JustInTimeGrid cache(grid_config, GridGeometry::centred_on(grid_config, truth), kColumns, filter.trajectory());
    // The root gets its (empty) grid at once, so every lineage has a grid-holding ancestor.
    for (std::size_t i = 0; i < live.size(); ++i) live[i] = filter.particle(i).trajectory;
    cache.update(filter.ml_trajectory_node(), live.data(), live.size());
    double grid_seconds = 0.0;
    double grid_seconds_max = 0.0;
    for (std::uint32_t u = 1; u <= updates; ++u) {
      core::RandomStream noise(11, {core::stream_purpose::test, u, 98});
      truth = truth.compose(step);
      odometry.pose = odometry.pose.compose(core::Pose2{step.x * 1.02 + noise.gaussian(0.0, 0.005),
                                                        noise.gaussian(0.0, 0.003),
                                                        step.theta + noise.gaussian(0.0, 0.004)});
      odometry.timestamp_ns += 200000000;
      ++odometry.sequence;
      observations.clear();
      const core::Pose2 robot_from_map = truth.inverse();
      for (std::uint32_t id = 0; id < landmarks.size(); ++id) {
        const Eigen::Vector2d local = robot_from_map.transform_point(landmarks[id].head<2>());
        if (local.norm() > 5.0 || local.x() < 0.1 || std::abs(std::atan2(local.y(), local.x())) > 0.6) continue;
        core::LandmarkObservation o;
        o.landmark_id = id;
        o.point_camera = Eigen::Vector3d(local.x() + noise.gaussian(0.0, 0.03), local.y() + noise.gaussian(0.0, 0.03),
                                         landmarks[id].z() + noise.gaussian(0.0, 0.03));
        o.covariance = Eigen::Matrix3d::Identity() * (0.03 * 0.03);
        observations.push_back(o);
      }
      filter.update(odometry, slam::ObservationList{observations.data(), observations.size()},
                    Eigen::Isometry3d::Identity());
      const slam::TrajectoryNodeHandle ml = filter.ml_trajectory_node();
      const core::DepthScan scan = paper_scan(u);
      for (std::size_t i = 0; i < live.size(); ++i) live[i] = filter.particle(i).trajectory;
      const double start = thread_cpu_seconds();
      cache.record_scan(filter.trajectory().get(ml).update_index, scan);
      cache.update(ml, live.data(), live.size());
      const double spent = thread_cpu_seconds() - start;
      grid_seconds += spent;
      grid_seconds_max = std::max(grid_seconds_max, spent);
    }
    report(state, cache, filter.counters().resamplings);
    const JustInTimeGridStats& stats = cache.stats();
    state.counters["rollups"] = static_cast<double>(stats.rollups);
    state.counters["from_empty"] = static_cast<double>(stats.built_from_empty);
    state.counters["refused_updates"] = static_cast<double>(filter.counters().updates_refused_trajectory_full);
    state.counters["scans_refused"] = static_cast<double>(cache.scans().counts().out_of_order);
    state.counters["grid_cpu_ms_mean"] = 1e3 * grid_seconds / updates;
    state.counters["grid_cpu_ms_max"] = 1e3 * grid_seconds_max;
  }
}
BENCHMARK(BM_FilterRun)->Args({1000, 300})->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace stereoscout::occupancy

BENCHMARK_MAIN();
