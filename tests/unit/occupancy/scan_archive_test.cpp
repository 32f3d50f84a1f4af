#include "stereoscout/occupancy/scan_archive.hpp"

#include <gtest/gtest.h>

#include <initializer_list>
#include <vector>

#include "ancestry_driver.hpp"
#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/occupancy/final_map.hpp"
#include "stereoscout/occupancy/just_in_time_grid.hpp"

namespace stereoscout::occupancy {
namespace {

using testing::AncestryDriver;
using testing::DriverSettings;

constexpr double kFinalResolutionM = 0.02;
constexpr double kTileM = 1.0;

GridGeometry geometry_of(int width_cells, int height_cells, double resolution_m, double origin_x_m, double origin_y_m) {
  GridGeometry geometry;
  geometry.width_cells = width_cells;
  geometry.height_cells = height_cells;
  geometry.resolution_m = resolution_m;
  geometry.origin_x_m = origin_x_m;
  geometry.origin_y_m = origin_y_m;
  return geometry;
}

core::GridConfig ring_config(int scan_history) {
  core::GridConfig config;
  config.width_cells = 120;  // the driver's circle and its 3 m scans stay inside
  config.height_cells = 120;
  config.resolution_m = 0.1;
  config.cache_capacity = 8;
  config.scan_history = scan_history;
  return config;
}

// A run of `updates` updates with a ring of `scan_history` scans, as the stack drives it: the
// archive takes each scan the ring is about to overwrite. Keeps its own copy of every scan.
struct LongRun {
  slam::TrajectoryTree tree{20000};
  core::GridConfig config;
  GridGeometry geometry;
  AncestryDriver driver;
  JustInTimeGrid cache;
  ScanArchive archive;
  std::vector<core::DepthScan> scans;

  LongRun(int scan_history, std::size_t tiles, const DriverSettings& settings)
      : config(ring_config(scan_history)),
        geometry(GridGeometry::centred_on(config, core::Pose2{})),
        driver(tree, settings),
        cache(config, geometry, 32, tree),
        archive(geometry, kFinalResolutionM, kTileM, tiles, LogOddsModel::from_config(config), tree) {}

  ~LongRun() {
    archive.release();
    driver.release_all();
    cache.release_all();
  }

  void run(std::uint32_t updates) {
    scans.resize(updates);
    driver.start(core::Pose2{});
    for (std::uint32_t u = 0; u < updates; ++u) {
      if (u > 0) driver.step();
      driver.make_scan(scans[u], 32);
      archive.keep_leaving_scan(cache.scans(), u, driver.ml_node());
      cache.record_scan(u, scans[u]);
      cache.update(driver.ml_node(), driver.nodes(), driver.count());
    }
  }

  // The whole lineage's scans, from the test's own copies, into a grid of `geometry`.
  std::unique_ptr<OccupancyGrid> reference(const GridGeometry& final_geometry) const {
    auto grid = std::make_unique<OccupancyGrid>(final_geometry, LogOddsModel::from_config(config));
    std::vector<slam::TrajectoryNodeHandle> lineage;
    for (slam::TrajectoryNodeHandle node = driver.ml_node(); node; node = tree.parent(node)) lineage.push_back(node);
    for (auto it = lineage.rbegin(); it != lineage.rend(); ++it) {
      grid->insert(scans[tree.get(*it).update_index], tree.get(*it).pose);
    }
    return grid;
  }
};

DriverSettings settings_with_seed(std::uint64_t seed) {
  DriverSettings settings;
  settings.seed = seed;
  settings.particles = 12;
  settings.likelihood_sigma_m = 0.05;  // good lineages stay good, as in a real filter
  return settings;
}

struct CellComparison {
  std::size_t known_in_reference = 0;
  std::size_t known_in_candidate = 0;
  std::size_t differing = 0;
};

CellComparison compare_cells(const OccupancyGrid& reference, const OccupancyGrid& candidate) {
  const CellThresholds thresholds;
  CellComparison result;
  const GridGeometry& geometry = reference.geometry();
  for (int y = 0; y < geometry.height_cells; ++y) {
    for (int x = 0; x < geometry.width_cells; ++x) {
      const CellState want = thresholds.classify(reference.log_odds(x, y));
      const CellState got = thresholds.classify(candidate.log_odds(x, y));
      if (want != CellState::unknown) ++result.known_in_reference;
      if (got != CellState::unknown) ++result.known_in_candidate;
      if (want != got) ++result.differing;
    }
  }
  return result;
}

struct ArchivedRun {
  TrajectoryScanCounts counts;
  ScanArchiveStats stats;
  CellComparison against_reference;    // the final map against every scan in one grid
  CellComparison ring_only_reference;  // the same for the map without the archive
  std::uint64_t ring_only_missing = 0;
};

// 140 updates, a ring of 40: the first 100 scans leave it.
ArchivedRun archived_run(std::uint64_t seed) {
  LongRun run(40, 144, settings_with_seed(seed));
  run.run(140);
  ArchivedRun result;
  const LogOddsModel model = LogOddsModel::from_config(run.config);
  const auto final_map = build_final_map(run.tree, run.driver.ml_node(), run.cache.scans(), &run.archive,
                                         kFinalResolutionM, 0.5, model, &result.counts);
  result.stats = run.archive.stats();
  result.against_reference = compare_cells(*run.reference(final_map->geometry()), *final_map);
  TrajectoryScanCounts ring_only;
  const auto without =
      build_final_map(run.tree, run.driver.ml_node(), run.cache.scans(), nullptr, kFinalResolutionM, 0.5, model, &ring_only);
  result.ring_only_reference = compare_cells(*run.reference(without->geometry()), *without);
  result.ring_only_missing = ring_only.scans_overwritten;
  return result;
}

TEST(ScanArchive, FinalMapOfARunLongerThanTheRingHoldsItsFirstScans) {
  for (const std::uint64_t seed : std::initializer_list<std::uint64_t>{1, 2, 4, 5}) {
    const ArchivedRun run = archived_run(seed);
    EXPECT_EQ(run.stats.scans_archived, 100u) << "seed " << seed;
    EXPECT_EQ(run.stats.scans_outside, 0u);
    EXPECT_EQ(run.stats.tile_refusals, 0u) << run.stats.tiles_used;
    EXPECT_EQ(run.counts.nodes, 140u);
    EXPECT_EQ(run.counts.nodes_archived, 100u);
    EXPECT_EQ(run.counts.scans_inserted, 40u);
    EXPECT_EQ(run.counts.scans_overwritten, 0u);
    EXPECT_TRUE(run.counts.archive_on_lineage) << "seed " << seed;
    EXPECT_EQ(run.stats.lineage_switches, 0u) << "seed " << seed;
    // The cells of every scan of the lineage inserted into one grid (measured: identical; a
    // ray end rounded differently on a tile's border could change a cell).
    EXPECT_GT(run.against_reference.known_in_reference, 30000u);
    EXPECT_LE(run.against_reference.differing, run.against_reference.known_in_reference / 10000) << "seed " << seed;
    // Without the archive the map lacks the first 100 scans.
    EXPECT_EQ(run.ring_only_missing, 100u);
    EXPECT_LT(run.ring_only_reference.known_in_candidate, run.against_reference.known_in_candidate / 2);
  }
}

// Seed 3: twice the ML lineage, when a scan left the ring, was not the one that won; those
// scans sit at the poses of a branch that later died. Counted, and the map is still nearly
// the whole trajectory's.
TEST(ScanArchive, CountsArchivedScansOfAnMlLineageThatLaterLost) {
  const ArchivedRun run = archived_run(3);
  EXPECT_EQ(run.stats.lineage_switches, 2u);
  EXPECT_EQ(run.stats.scans_archived, 100u);
  EXPECT_EQ(run.counts.scans_overwritten, 0u);
  EXPECT_GT(run.against_reference.differing, 0u);
  EXPECT_LT(run.against_reference.differing, run.against_reference.known_in_reference / 50);
}

TEST(ScanArchive, RunsWithinTheRingArchiveNothingAndGiveTheSameMapAsBefore) {
  LongRun run(200, 64, settings_with_seed(4));
  run.run(60);
  EXPECT_TRUE(run.archive.empty());
  EXPECT_EQ(run.archive.stats().tiles_used, 0u);
  const LogOddsModel model = LogOddsModel::from_config(run.config);
  const auto with = build_final_map(run.tree, run.driver.ml_node(), run.cache.scans(), &run.archive,
                                    kFinalResolutionM, 0.5, model);
  const auto ring_only = build_final_map(run.tree, run.driver.ml_node(), run.cache.scans(), kFinalResolutionM, 0.5, model);
  EXPECT_TRUE(with->same_cells_as(*ring_only));
}

TEST(ScanArchive, KeepsALeavingScanWithoutTheHeap) {
  LongRun run(5, 64, settings_with_seed(5));
  run.run(10);
  core::DepthScan scan;
  run.driver.step();
  run.driver.make_scan(scan, 32);
  const core::AllocationScope scope;
  run.archive.keep_leaving_scan(run.cache.scans(), 10, run.driver.ml_node());
  EXPECT_EQ(scope.allocations(), 0u);
  EXPECT_EQ(run.archive.stats().scans_archived, 6u);
}

TEST(ScanArchive, CountsTheScansThatFindNoTileLeft) {
  LongRun run(5, 2, settings_with_seed(6));
  run.run(40);
  EXPECT_EQ(run.archive.stats().tiles_used, 2u);
  EXPECT_GT(run.archive.stats().tile_refusals, 0u);
  EXPECT_EQ(run.archive.stats().scans_archived, 35u) << "a scan that lost a part is still archived where it could be";
}

TEST(ScanArchive, ZeroTilesArchivesNothing) {
  LongRun run(5, 0, settings_with_seed(7));
  run.run(20);
  EXPECT_TRUE(run.archive.empty());
  EXPECT_EQ(run.archive.stats().scans_archived, 0u);
}

// Root r (update 0) with two branches a and b; the ML lineage goes a, b, then a again.
TEST(ScanArchive, CountsAnMlLineageThatLeavesTheArchivedBranch) {
  slam::TrajectoryTree tree(64);
  ScanHistory scans(1, 8);
  const GridGeometry extent = geometry_of(100, 100, 0.1, -5.0, -5.0);
  ScanArchive archive(extent, 0.05, 2.0, 16, LogOddsModel{}, tree);
  const auto r = tree.add({}, core::Pose2{}, 0, 0);
  const auto a1 = tree.add(r, core::Pose2{0.1, 0.0, 0.0}, 1, 1);
  const auto b1 = tree.add(r, core::Pose2{0.1, 0.1, 0.0}, 1, 1);
  const auto a2 = tree.add(a1, core::Pose2{0.2, 0.0, 0.0}, 2, 2);
  const auto b2 = tree.add(b1, core::Pose2{0.2, 0.1, 0.0}, 2, 2);
  const auto a3 = tree.add(a2, core::Pose2{0.3, 0.0, 0.0}, 3, 3);
  core::DepthScan scan;
  scan.columns.resize(1);
  scan.columns[0].x_robot_m = 1.0F;
  scan.columns[0].kind = core::DepthScanColumn::Kind::obstacle;
  scans.record(0, scan);
  archive.keep_leaving_scan(scans, 1, a1);  // update 0 leaves: the root
  scans.record(1, scan);
  archive.keep_leaving_scan(scans, 2, b2);  // update 1 leaves, ML on branch b: b1
  scans.record(2, scan);
  EXPECT_EQ(archive.stats().lineage_switches, 0u);
  EXPECT_TRUE(archive.on_lineage(b2));
  EXPECT_FALSE(archive.on_lineage(a3));
  archive.keep_leaving_scan(scans, 3, a3);  // update 2 leaves, ML back on branch a: a2 is not below b1
  EXPECT_EQ(archive.stats().lineage_switches, 1u);
  EXPECT_EQ(archive.stats().scans_archived, 3u);
  EXPECT_TRUE(archive.on_lineage(a3));
  EXPECT_FALSE(archive.on_lineage(b2));
  archive.release();
  for (const auto node : {r, a1, b1, a2, b2, a3}) tree.release(node);
  EXPECT_EQ(tree.in_use(), 0u);
}

TEST(OccupancyGridPaste, CopiesTheCellsBothGridsCoverAndNothingElse) {
  const GridGeometry tile = geometry_of(10, 10, 0.1, 0.0, 0.0);
  OccupancyGrid part(tile, LogOddsModel{});
  part.clear_at(0.5, -0.3);
  core::DepthScan scan;
  scan.columns.resize(1);
  scan.columns[0].x_robot_m = 0.75F;
  scan.columns[0].y_robot_m = 0.05F;
  scan.columns[0].kind = core::DepthScanColumn::Kind::obstacle;
  part.insert(scan, core::Pose2{0.6, 0.0, 0.0});  // from (0.6, 0) to a hit at (1.35, 0.05): part cell (8, 3)
  const GridGeometry whole = geometry_of(16, 6, 0.1, 0.0, 0.0);
  OccupancyGrid grid(whole, LogOddsModel{});
  grid.paste(part);
  // part's cell (i, j) is grid's (i + 5, j - 3): grid columns 5..14 and rows 0..5 overlap it.
  for (int y = 0; y < whole.height_cells; ++y) {
    for (int x = 0; x < whole.width_cells; ++x) {
      const bool covered = x >= 5 && x - 5 < tile.width_cells && y + 3 < tile.height_cells;
      const float expected = covered ? part.log_odds(x - 5, y + 3) : 0.0F;
      EXPECT_EQ(grid.log_odds(x, y), expected) << x << "," << y;
    }
  }
  EXPECT_GT(grid.log_odds(13, 0), 0.0F) << "the hit came across";
  EXPECT_LT(grid.log_odds(9, 0), 0.0F) << "the ray's passed cells came across";
}

}  // namespace
}  // namespace stereoscout::occupancy
