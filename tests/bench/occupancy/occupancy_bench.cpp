// Costs of the just-in-time grid at the paper's size (700 x 700 cells at 0.10 m, 640-column
// scans): one scan insertion, one grid copy, a roll-up of L scans, the dependents walk for
// 1000 particles, and a whole synthetic run with 1000 particles reporting grids held,
// roll-up lengths, copies, moves and evictions.
#include <benchmark/benchmark.h>

#include <vector>

#include "ancestry_driver.hpp"
#include "stereoscout/occupancy/just_in_time_grid.hpp"

namespace stereoscout::occupancy {
namespace {

constexpr std::size_t kColumns = 640;

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

void report(benchmark::State& state, const JustInTimeGrid& cache, const testing::AncestryDriver& driver) {
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
  state.counters["resamplings"] = static_cast<double>(driver.resamplings());
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
  report(state, cache, driver);
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
    report(state, cache, driver);
    driver.release_all();
  }
}
BENCHMARK(BM_Run1000Particles)->Args({300, 0})->Args({300, 1})->Args({300, 3})->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace stereoscout::occupancy

BENCHMARK_MAIN();
