#include "stereoscout/occupancy/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "stereoscout/occupancy/scan_history.hpp"

namespace stereoscout::occupancy {
namespace {

using Kind = core::DepthScanColumn::Kind;

GridGeometry small_geometry() {
  GridGeometry geometry;
  geometry.width_cells = 20;
  geometry.height_cells = 20;
  geometry.resolution_m = 0.1;
  geometry.origin_x_m = -1.0;
  geometry.origin_y_m = -1.0;
  return geometry;
}

core::DepthScan one_column(float x, float y, Kind kind) {
  core::DepthScan scan;
  scan.columns.push_back({x, y, kind});
  return scan;
}

TEST(OccupancyGrid, ObstacleRayMissesAlongTheWayAndHitsAtTheEnd) {
  OccupancyGrid grid(small_geometry(), LogOddsModel{});
  grid.insert(one_column(0.55F, 0.05F, Kind::obstacle), core::Pose2{0.05, 0.0, 0.0});
  // Origin (0.05, 0) is cell (10, 10); the end (0.60, 0.05) is cell (16, 10).
  for (int x = 10; x < 16; ++x) EXPECT_FLOAT_EQ(grid.log_odds(x, 10), -0.4F) << x;
  EXPECT_FLOAT_EQ(grid.log_odds(16, 10), 0.85F);
  EXPECT_FLOAT_EQ(grid.log_odds(17, 10), 0.0F);
  EXPECT_FLOAT_EQ(grid.log_odds(12, 11), 0.0F);
  EXPECT_EQ(grid.insert_counts().rays, 1u);
}

TEST(OccupancyGrid, FreeColumnStopsOneCellShortOfItsEndAndInvalidDoesNothing) {
  OccupancyGrid grid(small_geometry(), LogOddsModel{});
  // Origin (0.05, 0.05) is cell (10, 10); the end (0.43, 0.05) is cell (14, 10), but the free
  // ray stops 0.1 m short, in cell (13, 10): the farthest floor point may be a wall's base.
  grid.insert(one_column(0.38F, 0.0F, Kind::free), core::Pose2{0.05, 0.05, 0.0});
  for (int x = 10; x <= 13; ++x) EXPECT_FLOAT_EQ(grid.log_odds(x, 10), -0.4F) << x;
  EXPECT_FLOAT_EQ(grid.log_odds(14, 10), 0.0F);
  OccupancyGrid untouched(small_geometry(), LogOddsModel{});
  untouched.insert(one_column(0.35F, 0.0F, Kind::invalid), core::Pose2{});
  OccupancyGrid empty(small_geometry(), LogOddsModel{});
  EXPECT_TRUE(untouched.same_cells_as(empty));
}

// On a 5 cm grid a cell short is 5 cm, less than the farthest floor point's range error at a
// few metres: floor seen a few centimetres beyond a wall's face clears the wall's cell. With
// free_end_short_m the ray stops as short in metres as on the 10 cm grid.
TEST(OccupancyGrid, AFreeColumnStopsFreeEndShortMShortOfItsEndOnAFinerGrid) {
  GridGeometry fine = small_geometry();  // the same 2 m square, at half the cell size
  fine.width_cells = 40;
  fine.height_cells = 40;
  fine.resolution_m = 0.05;
  // Origin (0.025, 0.025) is cell (20, 20); the end (0.625, 0.025) is cell (32, 20).
  const core::DepthScan scan = one_column(0.6F, 0.0F, Kind::free);
  const core::Pose2 pose{0.025, 0.025, 0.0};
  OccupancyGrid a_cell_short(fine, LogOddsModel{});
  a_cell_short.insert(scan, pose);
  for (int x = 20; x <= 31; ++x) EXPECT_FLOAT_EQ(a_cell_short.log_odds(x, 20), -0.4F) << x;  // to 0.575 m
  EXPECT_FLOAT_EQ(a_cell_short.log_odds(32, 20), 0.0F);
  LogOddsModel metric;
  metric.free_end_short_m = 0.1F;
  OccupancyGrid tenth_short(fine, metric);
  tenth_short.insert(scan, pose);
  for (int x = 20; x <= 30; ++x) EXPECT_FLOAT_EQ(tenth_short.log_odds(x, 20), -0.4F) << x;  // to 0.525 m
  EXPECT_FLOAT_EQ(tenth_short.log_odds(31, 20), 0.0F);
  EXPECT_FLOAT_EQ(tenth_short.log_odds(32, 20), 0.0F);
  // Less than a cell changes nothing: the 10 cm grid stops a cell short whatever it says.
  metric.free_end_short_m = 0.05F;
  OccupancyGrid coarse(small_geometry(), metric);
  OccupancyGrid coarse_default(small_geometry(), LogOddsModel{});
  coarse.insert(one_column(0.38F, 0.0F, Kind::free), core::Pose2{0.05, 0.05, 0.0});
  coarse_default.insert(one_column(0.38F, 0.0F, Kind::free), core::Pose2{0.05, 0.05, 0.0});
  EXPECT_TRUE(coarse.same_cells_as(coarse_default));
}

// Stereo's range error grows with the square of the range: with hit_full_weight_range_m at
// 0.5 m, an obstacle 0.8 m away adds (0.5 / 0.8)^2 = 0.39 of log_odds_hit, one 0.4 m away all
// of it. One far hit alone leaves its cell short of occupied; four agreeing scans make it so.
TEST(OccupancyGrid, AnObstacleBeyondTheFullWeightRangeAddsLessByTheSquareOfItsRange) {
  LogOddsModel model;
  model.hit_full_weight_range_m = 0.5F;
  const CellThresholds thresholds;
  const core::Pose2 pose{0.05, 0.05, 0.0};  // the origin, cell (10, 10)
  OccupancyGrid grid(small_geometry(), model);
  core::DepthScan near_and_far = one_column(0.4F, 0.0F, Kind::obstacle);  // cell (14, 10), 0.4 m
  near_and_far.columns.push_back({0.0F, 0.8F, Kind::obstacle});           // cell (10, 18), 0.8 m
  grid.insert(near_and_far, pose);
  EXPECT_FLOAT_EQ(grid.log_odds(14, 10), 0.85F);
  EXPECT_FLOAT_EQ(grid.log_odds(10, 18), 0.85F * 0.25F / 0.64F);
  EXPECT_NE(thresholds.classify(grid.log_odds(10, 18)), CellState::occupied);
  const core::DepthScan far = one_column(0.0F, 0.8F, Kind::obstacle);
  for (int scan = 0; scan < 3; ++scan) grid.insert(far, pose);
  EXPECT_EQ(thresholds.classify(grid.log_odds(10, 18)), CellState::occupied);
  OccupancyGrid full_weight(small_geometry(), LogOddsModel{});
  full_weight.insert(far, pose);
  EXPECT_FLOAT_EQ(full_weight.log_odds(10, 18), 0.85F);
}

// A wall at x = 0.6 m (cell 16) seen once; then floor seen up to 0.25 m beyond it from the
// other side, as a far view's farthest floor point overshoots by its range error (0.2 m).
TEST(OccupancyGrid, AFreeColumnsUncertainEndDoesNotEraseAWallButClearsUnknownCells) {
  LogOddsModel model;
  model.free_end_sigmas = 2.0F;
  for (const bool guarded : {true, false}) {
    OccupancyGrid grid(small_geometry(), guarded ? model : LogOddsModel{});
    grid.insert(one_column(0.55F, 0.0F, Kind::obstacle), core::Pose2{0.05, 0.05, 0.0});  // the wall, cell (16, 10)
    core::DepthScan overshoot = one_column(0.8F, 0.0F, Kind::free);  // end (0.85, 0.05): cell (18, 10)
    overshoot.columns[0].end_range_sigma_m = 0.2F;
    for (int view = 0; view < 5; ++view) grid.insert(overshoot, core::Pose2{0.05, 0.05, 0.0});
    if (guarded) {
      EXPECT_FLOAT_EQ(grid.log_odds(16, 10), 0.85F);  // within 0.4 m of the end: kept
      EXPECT_FLOAT_EQ(grid.log_odds(17, 10), 5 * -0.4F);  // unknown there: cleared as before
      EXPECT_FLOAT_EQ(grid.log_odds(12, 10), 6 * -0.4F);  // before the uncertain end: every miss
    } else {
      EXPECT_LT(grid.log_odds(16, 10), 0.0F);  // erased by the floor seen beyond it
    }
    EXPECT_FLOAT_EQ(grid.log_odds(18, 10), 0.0F);  // the end cell itself: one cell short, as ever
  }
}

// With near_hit_hold_range_m at 0.6 m, from a camera at A (cell 10) and one 0.5 m behind it at
// B (cell 5): a blank wall's base hit from A at 0.5 m (cell 15) holds its cell against five
// views of floor beyond it from B, whose misses pass it 1.0 m from their camera, while a
// phantom hit from B at 0.8 m (cell 13) and a person hit at the camera's height (cell 12) are
// lowered by them, as are free and unknown cells. Misses from A, within 0.6 m, lower the wall;
// once they bring it to log-odds 0 or below, a far hit there no longer holds against far misses.
TEST(OccupancyGrid, ANearHitHoldsItsCellAgainstFarMissesButNotNearOnes) {
  LogOddsModel model;
  model.near_hit_hold_range_m = 0.6F;
  const core::Pose2 near_pose{0.05, 0.05, 0.0};
  const core::Pose2 far_pose{-0.45, 0.05, 0.0};
  const core::DepthScan far_floor = one_column(1.3F, 0.0F, Kind::free);  // from B: misses cells 5-17
  for (const bool holding : {true, false}) {
    OccupancyGrid grid(small_geometry(), holding ? model : LogOddsModel{});
    grid.insert(one_column(0.5F, 0.0F, Kind::obstacle), near_pose);  // the wall: cell 15
    grid.insert(one_column(0.8F, 0.0F, Kind::obstacle), far_pose);   // a phantom: cell 13
    core::DepthScan person = one_column(0.2F, 0.0F, Kind::obstacle);  // cell 12
    person.columns[0].obstacle_at_camera_height = true;
    grid.insert(person, near_pose);
    for (int view = 0; view < 5; ++view) grid.insert(far_floor, far_pose);
    EXPECT_FLOAT_EQ(grid.log_odds(12, 10), 2 * -0.4F + 0.85F + 5 * -0.4F);  // the person: lowered
    EXPECT_FLOAT_EQ(grid.log_odds(13, 10), -0.4F + 0.85F + 5 * -0.4F);      // the phantom: lowered
    EXPECT_FLOAT_EQ(grid.log_odds(17, 10), 5 * -0.4F);                      // unknown: cleared
    if (!holding) {
      EXPECT_FLOAT_EQ(grid.log_odds(15, 10), 0.85F + 5 * -0.4F);
      continue;
    }
    EXPECT_FLOAT_EQ(grid.log_odds(15, 10), 0.85F);  // the wall: held
    const core::DepthScan near_floor = one_column(0.8F, 0.0F, Kind::free);  // from A: misses cells 10-17
    for (int view = 0; view < 3; ++view) grid.insert(near_floor, near_pose);
    EXPECT_FLOAT_EQ(grid.log_odds(15, 10), 0.85F + 3 * -0.4F);
    grid.insert(one_column(1.0F, 0.0F, Kind::obstacle), far_pose);  // a far hit on cell 15
    grid.insert(far_floor, far_pose);
    EXPECT_FLOAT_EQ(grid.log_odds(15, 10), 0.85F + 3 * -0.4F + 0.85F - 0.4F);  // not held: lowered
  }
}

// A far miss passes a held cell by only near its ray's end (near_hit_hold_end_m): the far
// floor's ray ends 0.2 m beyond the wall's cell 15 (its reach a cell short of 1.3 m). Within
// 0.3 m of the end the cell stays held; with 0.1 m the ray ran on beyond it, saw through it,
// and lowers it as any miss does.
TEST(OccupancyGrid, AFarMissThatRunsOnBeyondAHeldCellLowersIt) {
  const core::Pose2 near_pose{0.05, 0.05, 0.0};
  const core::Pose2 far_pose{-0.45, 0.05, 0.0};
  for (const float end_m : {0.3F, 0.1F}) {
    LogOddsModel model;
    model.near_hit_hold_range_m = 0.6F;
    model.near_hit_hold_end_m = end_m;
    OccupancyGrid grid(small_geometry(), model);
    grid.insert(one_column(0.5F, 0.0F, Kind::obstacle), near_pose);  // cell 15
    for (int view = 0; view < 3; ++view) grid.insert(one_column(1.3F, 0.0F, Kind::free), far_pose);
    EXPECT_FLOAT_EQ(grid.log_odds(15, 10), end_m > 0.2F ? 0.85F : 0.85F + 3 * -0.4F) << end_m;
  }
}

// A near hit does not hold a cell that near views saw free: a door's jamb drawn into the
// doorway by a pose a little off lands on floor seen free before. Floor seen four times out to
// 0.8 m from A makes cell 14 free; three near hits there then make it occupied, but one far
// view's miss lowers it, where it passes by cell 13, which was never free (the floor shows
// from cell 14).
TEST(OccupancyGrid, ANearHitDoesNotHoldACellThatNearViewsSawFree) {
  LogOddsModel model;
  model.near_hit_hold_range_m = 0.6F;
  const core::Pose2 near_pose{0.05, 0.05, 0.0};
  OccupancyGrid grid(small_geometry(), model);
  core::DepthScan floor = one_column(0.8F, 0.0F, Kind::free);
  floor.columns[0].floor_visible_from_m = 0.4F;  // from cell 14 on: cell 13 is never missed
  for (int view = 0; view < 4; ++view) grid.insert(floor, near_pose);
  EXPECT_FLOAT_EQ(grid.log_odds(14, 10), 4 * -0.4F);
  core::DepthScan jamb_and_wall = one_column(0.4F, 0.0F, Kind::obstacle);  // cell 14
  jamb_and_wall.columns.push_back({0.3F, 0.0F, Kind::obstacle});            // cell 13
  for (int view = 0; view < 3; ++view) grid.insert(jamb_and_wall, near_pose);
  grid.insert(one_column(1.3F, 0.0F, Kind::free), core::Pose2{-0.45, 0.05, 0.0});  // passes both
  EXPECT_FLOAT_EQ(grid.log_odds(14, 10), 4 * -0.4F + 3 * 0.85F - 0.4F);
  EXPECT_FLOAT_EQ(grid.log_odds(13, 10), 3 * 0.85F);
  // A row up: far views leave cell (16, 11) free, as grazing rays wear a blank wall away. Two near
  // hits there then hold it: far misses do not count as the cell seen free.
  const core::Pose2 far_row{-0.45, 0.15, 0.0};
  for (int view = 0; view < 4; ++view) grid.insert(one_column(1.3F, 0.0F, Kind::free), far_row);
  const core::DepthScan wall = one_column(0.56F, 0.0F, Kind::obstacle);  // cell (16, 11), 0.56 m
  for (int view = 0; view < 2; ++view) grid.insert(wall, core::Pose2{0.05, 0.15, 0.0});
  grid.insert(one_column(1.3F, 0.0F, Kind::free), far_row);
  EXPECT_FLOAT_EQ(grid.log_odds(16, 11), 4 * -0.4F + 2 * 0.85F);
}

// A wall at x = 0.6 m (cell 16) seen head on; then a scan whose 12 columns graze along it (all
// through cell (16, 10), ending beyond it), as a view along a corridor wall from a pose a little
// off puts them. With once_per_scan that scan lowers the wall's cell once, not twelve times;
// unknown cells take every column's miss, so one scan still clears the floor it sees, and so
// does an obstacle seen at the camera's height (a person), which every ray past it would see.
TEST(OccupancyGrid, OncePerScanLowersACellHoldingAnObstacleOnceAScan) {
  core::DepthScan grazing;
  for (int i = 0; i < 12; ++i) grazing.columns.push_back({0.75F + 0.002F * static_cast<float>(i), 0.0F, Kind::obstacle});
  for (const bool once : {true, false}) {
    LogOddsModel model;
    model.once_per_scan = once;
    OccupancyGrid grid(small_geometry(), model);
    core::DepthScan wall = one_column(0.55F, 0.0F, Kind::obstacle);
    wall.columns.push_back({0.56F, 0.01F, Kind::obstacle});  // two columns end in the wall's cell
    grid.insert(wall, core::Pose2{0.05, 0.05, 0.0});
    EXPECT_FLOAT_EQ(grid.log_odds(16, 10), 2 * 0.85F);  // every column's hit
    EXPECT_FLOAT_EQ(grid.log_odds(12, 10), 2 * -0.4F);  // unknown: every column's miss
    grid.insert(grazing, core::Pose2{0.05, 0.05, 0.0});
    EXPECT_NEAR(grid.log_odds(16, 10), once ? 2 * 0.85F - 0.4F : 2 * 0.85F - 12 * 0.4F, 1e-5);
    EXPECT_FLOAT_EQ(grid.log_odds(12, 10), -4.0F);  // free: every miss, down to the clamp
    EXPECT_FLOAT_EQ(grid.log_odds(18, 10), 4.0F);
    core::DepthScan person = one_column(0.36F, 0.0F, Kind::obstacle);  // cell (14, 10), at the camera's height
    person.columns[0].obstacle_at_camera_height = true;
    for (int scan = 0; scan < 6; ++scan) grid.insert(person, core::Pose2{0.05, 0.05, 0.0});
    EXPECT_NEAR(grid.log_odds(14, 10), -4.0F + 6 * 0.85F, 1e-5);  // free before, an obstacle now
    grid.insert(grazing, core::Pose2{0.05, 0.05, 0.0});
    EXPECT_NEAR(grid.log_odds(14, 10), -4.0F + 6 * 0.85F - 12 * 0.4F, 1e-5);  // walked on: every column's miss
  }
}

// Past the wrap of the scan numbers (after 255 inserts) consecutive scans still count once
// each: the numbers go on changing from scan to scan.
TEST(OccupancyGrid, OncePerScanCountsEveryScanPastTheNumbersWrap) {
  LogOddsModel model;
  model.once_per_scan = true;
  model.max = 1000.0F;
  OccupancyGrid grid(small_geometry(), model);
  core::DepthScan wall;
  core::DepthScan fan;
  for (int i = 0; i < 3; ++i) {
    wall.columns.push_back({0.55F, 0.001F * static_cast<float>(i), Kind::obstacle});  // cell (16, 10)
    fan.columns.push_back({0.75F, 0.001F * static_cast<float>(i), Kind::free});      // through it
  }
  for (int scan = 0; scan < 300; ++scan) grid.insert(wall, core::Pose2{0.05, 0.05, 0.0});
  for (int scan = 0; scan < 600; ++scan) grid.insert(fan, core::Pose2{0.05, 0.05, 0.0});
  EXPECT_NEAR(grid.log_odds(16, 10), 300.0F * 3.0F * 0.85F - 600.0F * 0.4F, 0.05);
}

// A cell lowered once and then left alone for a whole round of scan numbers (255; every stamp
// is reset when they restart) is lowered again by the next scan through it, wherever in the
// round that scan falls: a stale stamp equal to the new number would skip it.
TEST(OccupancyGrid, OncePerScanLowersACellAgainAfterAWholeRoundOfScanNumbers) {
  LogOddsModel model;
  model.once_per_scan = true;
  core::DepthScan wall;
  core::DepthScan through;
  for (int i = 0; i < 3; ++i) {
    wall.columns.push_back({0.55F, 0.001F * static_cast<float>(i), Kind::obstacle});  // cell (16, 10)
    through.columns.push_back({0.75F, 0.001F * static_cast<float>(i), Kind::free});  // passes it
  }
  const core::DepthScan elsewhere = one_column(0.0F, -0.5F, Kind::free);  // away from it
  const core::Pose2 pose{0.05, 0.05, 0.0};
  for (int scans_between = 250; scans_between <= 260; ++scans_between) {
    OccupancyGrid grid(small_geometry(), model);
    grid.insert(wall, pose);
    grid.insert(through, pose);
    for (int scan = 0; scan < scans_between; ++scan) grid.insert(elsewhere, pose);
    grid.insert(through, pose);
    EXPECT_NEAR(grid.log_odds(16, 10), 3 * 0.85F - 2 * 0.4F, 1e-5) << scans_between;
  }
}

core::DepthScan one_column_visible_from(float x, Kind kind, float floor_visible_from_m) {
  core::DepthScan scan = one_column(x, 0.0F, kind);
  scan.columns[0].floor_visible_from_m = floor_visible_from_m;
  return scan;
}

TEST(OccupancyGrid, RayStartsWhereTheColumnsFloorBecomesVisible) {
  OccupancyGrid grid(small_geometry(), LogOddsModel{});
  // Origin cell (10, 10); floor visible from 0.3 m (cell 13); obstacle at 0.75 m (cell 17).
  grid.insert(one_column_visible_from(0.7F, Kind::obstacle, 0.3F), core::Pose2{0.05, 0.05, 0.0});
  for (int x = 10; x < 13; ++x) EXPECT_FLOAT_EQ(grid.log_odds(x, 10), 0.0F) << x;
  for (int x = 13; x < 17; ++x) EXPECT_FLOAT_EQ(grid.log_odds(x, 10), -0.4F) << x;
  EXPECT_FLOAT_EQ(grid.log_odds(17, 10), 0.85F);
}

TEST(OccupancyGrid, ObstacleInsideTheBlindZoneMarksOnlyItsOwnCell) {
  OccupancyGrid grid(small_geometry(), LogOddsModel{});
  grid.insert(one_column_visible_from(0.4F, Kind::obstacle, 1.0F), core::Pose2{0.05, 0.05, 0.0});
  EXPECT_FLOAT_EQ(grid.log_odds(14, 10), 0.85F);
  for (int x = 0; x < 20; ++x) {
    if (x != 14) {
      EXPECT_FLOAT_EQ(grid.log_odds(x, 10), 0.0F) << x;
    }
  }
  // A free column whose visible floor ends within a cell of the blind zone clears nothing.
  OccupancyGrid untouched(small_geometry(), LogOddsModel{});
  untouched.insert(one_column_visible_from(0.4F, Kind::free, 0.35F), core::Pose2{0.05, 0.05, 0.0});
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 20; ++x) EXPECT_FLOAT_EQ(untouched.log_odds(x, y), 0.0F) << x << ", " << y;
  }
}

// What a column had in view: from where its floor becomes visible up to in_view_range_m (a
// free column: beyond its floor's end too, where a blank wall would stand), or to its obstacle.
// The cells nearer (the blind zone) were never in view; no log-odds change beyond the ray.
TEST(OccupancyGrid, ColumnsMarkWhatTheyHadInView) {
  LogOddsModel model;
  model.in_view_range_m = 0.8F;
  OccupancyGrid grid(small_geometry(), model);
  // Origin (0.05, 0.05) is cell (10, 10); floor visible from 0.2 m, seen up to 0.45 m.
  grid.insert(one_column_visible_from(0.45F, Kind::free, 0.2F), core::Pose2{0.05, 0.05, 0.0});
  for (int x = 10; x <= 11; ++x) EXPECT_FALSE(grid.in_view(x, 10)) << x;
  for (int x = 12; x <= 18; ++x) EXPECT_TRUE(grid.in_view(x, 10)) << x;  // to 0.85 m
  EXPECT_FALSE(grid.in_view(19, 10));
  EXPECT_FALSE(grid.in_view(14, 11));
  EXPECT_FLOAT_EQ(grid.log_odds(15, 10), 0.0F);  // beyond the floor: unknown, but in view
  // An obstacle 0.3 m ahead hides what is behind it.
  OccupancyGrid blocked(small_geometry(), model);
  blocked.insert(one_column_visible_from(0.3F, Kind::obstacle, 0.2F), core::Pose2{0.05, 0.05, 0.0});
  EXPECT_TRUE(blocked.in_view(13, 10));
  EXPECT_FALSE(blocked.in_view(14, 10));
  // classify_cells hands the marks on.
  std::vector<CellState> cells(small_geometry().cell_count());
  std::vector<std::uint8_t> in_view(small_geometry().cell_count(), 7);
  classify_cells(grid, CellThresholds{}, cells.data(), in_view.data());
  EXPECT_EQ(in_view[10 * 20 + 15], 1U);
  EXPECT_EQ(in_view[10 * 20 + 10], 0U);
  EXPECT_EQ(cells[10 * 20 + 15], CellState::unknown);
}

// What a column's ray passed over: from the camera, the blind zone included, up to
// looked_over_range_m or to its end. No log-odds change; nothing marked with the range at 0.
TEST(OccupancyGrid, ColumnsMarkTheCellsTheirRaysPassedOverBlindZoneIncluded) {
  LogOddsModel model;
  model.looked_over_range_m = 0.3F;
  OccupancyGrid grid(small_geometry(), model);
  // Origin (0.05, 0.05) is cell (10, 10); the floor visible from 0.2 m, an obstacle 0.4 m ahead (cell 14).
  grid.insert(one_column_visible_from(0.4F, Kind::obstacle, 0.2F), core::Pose2{0.05, 0.05, 0.0});
  for (int x = 10; x <= 13; ++x) EXPECT_TRUE(grid.looked_over(x, 10)) << x;  // to 0.35 m
  EXPECT_FALSE(grid.looked_over(14, 10));
  EXPECT_FALSE(grid.looked_over(12, 11));
  EXPECT_FALSE(grid.in_view(12, 10));
  EXPECT_FLOAT_EQ(grid.log_odds(11, 10), 0.0F);  // the blind zone: looked over, not measured
  EXPECT_FLOAT_EQ(grid.log_odds(14, 10), 0.85F);  // a hit keeps the mark it had
  // The range beyond the column's end: up to its end only.
  model.looked_over_range_m = 2.0F;
  OccupancyGrid far(small_geometry(), model);
  far.insert(one_column_visible_from(0.4F, Kind::obstacle, 0.2F), core::Pose2{0.05, 0.05, 0.0});
  EXPECT_TRUE(far.looked_over(14, 10));
  EXPECT_FALSE(far.looked_over(15, 10));
  std::vector<CellState> cells(small_geometry().cell_count());
  std::vector<std::uint8_t> looked_over(small_geometry().cell_count(), 7);
  classify_cells(far, CellThresholds{}, cells.data(), nullptr, looked_over.data());
  EXPECT_EQ(looked_over[10 * 20 + 14], 1U);
  EXPECT_EQ(looked_over[10 * 20 + 15], 0U);
  // Off: nothing marked.
  OccupancyGrid off(small_geometry(), LogOddsModel{});
  off.insert(one_column_visible_from(0.4F, Kind::obstacle, 0.2F), core::Pose2{0.05, 0.05, 0.0});
  for (int x = 0; x < 20; ++x) EXPECT_FALSE(off.looked_over(x, 10)) << x;
}

// A 0.1 m box 3 m ahead, approached in 7 cm steps (the update trigger) to 0.55 m, where the
// robot stays for 15 more scans (a look around). The camera (floor visible from 1 m) sees the
// box's top until it is 1 m x (1 - 0.1 / 0.6) = 0.83 m away; nearer, the box is below the
// image and the column reports the floor behind it, free up to 5 m.
float approach_low_box(float floor_visible_from_m) {
  GridGeometry geometry = small_geometry();
  geometry.width_cells = 80;
  OccupancyGrid grid(geometry, LogOddsModel{});
  constexpr double kBoxFaceX = 3.0;
  for (int step = 0; step < 50; ++step) {
    const double robot_x = std::min(0.07 * step, kBoxFaceX - 0.55);
    const bool box_visible = kBoxFaceX - robot_x > 0.85;
    const float end = box_visible ? static_cast<float>(kBoxFaceX - robot_x + 0.05) : 5.0F;
    grid.insert(one_column_visible_from(end, box_visible ? Kind::obstacle : Kind::free, floor_visible_from_m),
                core::Pose2{robot_x, 0.05, 0.0});
  }
  int box_x = 0;
  int box_y = 0;
  EXPECT_TRUE(grid.cell_of(kBoxFaceX + 0.05, 0.05, box_x, box_y));
  return grid.log_odds(box_x, box_y);
}

TEST(OccupancyGrid, LowBoxSeenFromFarIsNotClearedWhenApproached) {
  const float blind_aware = approach_low_box(1.0F);
  EXPECT_EQ(CellThresholds{}.classify(blind_aware), CellState::occupied);
  EXPECT_FLOAT_EQ(blind_aware, 4.0F);  // 31 hits, clamped; never missed
  // Rays from the camera (the old insert) erase it: this is the bug the test guards against.
  EXPECT_EQ(CellThresholds{}.classify(approach_low_box(0.0F)), CellState::free);
}

// A low box stands 0.6 m ahead, inside the blind zone (seen while it was still in view); a
// person (an obstacle at the camera's height) steps in front of it at 0.5 m and walks on.
// The views see the floor from 1 m on.
TEST(OccupancyGrid, LaterViewsClearAPersonInTheBlindZoneButNotALowBox) {
  OccupancyGrid grid(small_geometry(), LogOddsModel{});
  const core::Pose2 pose{0.05, 0.05, 0.0};
  core::DepthScan person = one_column_visible_from(0.5F, Kind::obstacle, 1.0F);
  person.columns[0].obstacle_at_camera_height = true;
  core::DepthScan box = one_column_visible_from(0.6F, Kind::obstacle, 1.0F);
  for (int i = 0; i < 3; ++i) grid.insert(box, pose);
  for (int i = 0; i < 3; ++i) grid.insert(person, pose);  // then the person stepped in front
  EXPECT_FLOAT_EQ(grid.log_odds(15, 10), 2.55F);
  EXPECT_FLOAT_EQ(grid.log_odds(16, 10), 2.55F);
  // The view through both cells to a wall at 1.5 m: the person's cell gets a miss per view,
  // the box's cell (out of view) none; the cells in front of them none (they held nothing).
  const core::DepthScan wall = one_column_visible_from(1.5F, Kind::obstacle, 1.0F);
  for (int i = 0; i < 7; ++i) grid.insert(wall, pose);
  EXPECT_NEAR(grid.log_odds(15, 10), 2.55F - 7 * 0.4F, 1e-5);
  EXPECT_EQ(CellThresholds{}.classify(grid.log_odds(15, 10)), CellState::unknown);
  EXPECT_FLOAT_EQ(grid.log_odds(16, 10), 2.55F);
  for (int x = 10; x < 15; ++x) EXPECT_FLOAT_EQ(grid.log_odds(x, 10), 0.0F) << x;
  // A later low hit in the person's cell makes it a low obstacle: no longer cleared there.
  grid.insert(one_column_visible_from(0.5F, Kind::obstacle, 1.0F), pose);
  grid.insert(wall, pose);
  EXPECT_NEAR(grid.log_odds(15, 10), 2.55F - 7 * 0.4F + 0.85F, 1e-5);
}

// A column that cannot measure nearer than 0.8 m (the image's edge, where the other camera
// does not look) saw floor far behind a person standing 0.5 m away: it must not clear the
// person's cell, nor any cell nearer than 0.8 m; beyond that it clears as usual.
TEST(OccupancyGrid, NothingNearerThanAColumnCanMeasureIsCleared) {
  OccupancyGrid grid(small_geometry(), LogOddsModel{});
  const core::Pose2 pose{0.05, 0.05, 0.0};
  core::DepthScan person = one_column_visible_from(0.5F, Kind::obstacle, 0.3F);
  person.columns[0].obstacle_at_camera_height = true;
  grid.insert(person, pose);
  float before[20] = {};
  for (int x = 0; x < 20; ++x) before[x] = grid.log_odds(x, 10);
  core::DepthScan edge = one_column_visible_from(1.6F, Kind::free, 0.3F);
  edge.columns[0].measurable_from_m = 0.8F;
  grid.insert(edge, pose);
  EXPECT_FLOAT_EQ(grid.log_odds(15, 10), 0.85F);  // the person's cell (0.55 m)
  for (int x = 10; x < 18; ++x) EXPECT_FLOAT_EQ(grid.log_odds(x, 10), before[x]) << x;  // up to 0.8 m: untouched
  for (int x = 18; x < 20; ++x) EXPECT_FLOAT_EQ(grid.log_odds(x, 10), -0.4F) << x;  // 0.85 m on: floor seen
  // The same column measuring from the origin clears the person's cell.
  edge.columns[0].measurable_from_m = 0.0F;
  grid.insert(edge, pose);
  EXPECT_FLOAT_EQ(grid.log_odds(15, 10), 0.45F);
}

TEST(OccupancyGrid, PoseRotatesAndTranslatesTheScan) {
  OccupancyGrid grid(small_geometry(), LogOddsModel{});
  // Robot at (0.05, 0.05) facing +y: a point 0.4 m ahead lands at (0.05, 0.45), cell (10, 14).
  grid.insert(one_column(0.4F, 0.0F, Kind::obstacle), core::Pose2{0.05, 0.05, M_PI / 2.0});
  EXPECT_FLOAT_EQ(grid.log_odds(10, 14), 0.85F);
  for (int y = 10; y < 14; ++y) EXPECT_FLOAT_EQ(grid.log_odds(10, y), -0.4F) << y;
}

TEST(OccupancyGrid, LogOddsAreClamped) {
  OccupancyGrid grid(small_geometry(), LogOddsModel{});
  const core::DepthScan scan = one_column(0.5F, 0.0F, Kind::obstacle);
  for (int i = 0; i < 20; ++i) grid.insert(scan, core::Pose2{0.05, 0.05, 0.0});
  EXPECT_FLOAT_EQ(grid.log_odds(15, 10), 4.0F);
  EXPECT_FLOAT_EQ(grid.log_odds(12, 10), -4.0F);
}

TEST(OccupancyGrid, RaysLeavingTheGridAndBrokenPointsAreSafe) {
  OccupancyGrid grid(small_geometry(), LogOddsModel{});
  grid.insert(one_column(5.0F, 0.0F, Kind::obstacle), core::Pose2{0.05, 0.05, 0.0});
  EXPECT_FLOAT_EQ(grid.log_odds(19, 10), -0.4F);  // passes the edge; the hit lies outside
  grid.insert(one_column(std::numeric_limits<float>::quiet_NaN(), 0.0F, Kind::obstacle), core::Pose2{});
  grid.insert(one_column(1e9F, 0.0F, Kind::obstacle), core::Pose2{});
  EXPECT_EQ(grid.insert_counts().rays, 1u);
  EXPECT_EQ(grid.insert_counts().rays_rejected, 2u);
}

// The cells a segment passes through, by dense sampling: the reference for the traversal.
std::set<std::pair<int, int>> sampled_cells(const GridGeometry& geometry, double x0, double y0, double x1, double y1) {
  std::set<std::pair<int, int>> cells;
  constexpr int kSamples = 100000;
  for (int i = 0; i <= kSamples; ++i) {
    const double t = static_cast<double>(i) / kSamples;
    cells.insert({static_cast<int>(std::floor((x0 + t * (x1 - x0) - geometry.origin_x_m) / geometry.resolution_m)),
                  static_cast<int>(std::floor((y0 + t * (y1 - y0) - geometry.origin_y_m) / geometry.resolution_m))});
  }
  return cells;
}

TEST(OccupancyGrid, RayMissesExactlyTheCellsItCrosses) {
  const GridGeometry geometry = small_geometry();
  // Shallow, steep and near-diagonal rays from a point off the cell centre.
  const double ends[][2] = {{0.53, 0.31}, {0.12, 0.77}, {-0.61, 0.58}, {-0.44, -0.47}, {0.71, -0.09}};
  for (const auto& end : ends) {
    OccupancyGrid grid(geometry, LogOddsModel{});
    const core::Pose2 pose{0.037, 0.062, 0.0};
    grid.insert(one_column(static_cast<float>(end[0]), static_cast<float>(end[1]), Kind::obstacle), pose);
    const float end_x = static_cast<float>(end[0]);  // the column stores floats
    const float end_y = static_cast<float>(end[1]);
    const auto crossed = sampled_cells(geometry, pose.x, pose.y, pose.x + end_x, pose.y + end_y);
    std::set<std::pair<int, int>> touched;
    for (int y = 0; y < geometry.height_cells; ++y) {
      for (int x = 0; x < geometry.width_cells; ++x) {
        if (grid.log_odds(x, y) != 0.0F) touched.insert({x, y});
      }
    }
    EXPECT_EQ(touched, crossed) << end[0] << ", " << end[1];
  }
}

TEST(OccupancyGrid, AHitWinsOverTheMissesOfTheSameScan) {
  OccupancyGrid grid(small_geometry(), LogOddsModel{});
  // One column ends on an obstacle in cell (15, 10); a second ray of the same scan crosses that
  // cell on its way further out.
  core::DepthScan scan;
  scan.columns.push_back({0.52F, 0.02F, Kind::obstacle});
  scan.columns.push_back({0.85F, 0.04F, Kind::obstacle});
  grid.insert(scan, core::Pose2{0.0, 0.0, 0.0});
  EXPECT_FLOAT_EQ(grid.log_odds(15, 10), 0.85F);
  EXPECT_FLOAT_EQ(grid.log_odds(18, 10), 0.85F);
  EXPECT_FLOAT_EQ(grid.log_odds(14, 10), -0.8F);  // both rays missed it
  // In a later scan without the first column the cell is crossed and missed as usual.
  grid.insert(one_column(0.85F, 0.04F, Kind::obstacle), core::Pose2{0.0, 0.0, 0.0});
  EXPECT_FLOAT_EQ(grid.log_odds(15, 10), 0.45F);
}

// A 2 cm board hangs across half of a 0.9 m door in a wall; views from the corridor, through
// the door and at the board, must not clear the board's end cell. Rays are cast against the
// true geometry (wall line y = 1.0 with a door x in [0, 0.9); the board covers x in [0, 0.45)),
// 640 columns over the camera's 77 deg facing north, the robot passing the door diagonally.
// The integer line walk between rounded end cells (before 6d39498) cleared the board's end
// cell on this path.
TEST(OccupancyGrid, RaysThroughADoorDoNotClearTheThinBoardBesideIt) {
  GridGeometry geometry;
  geometry.width_cells = 60;
  geometry.height_cells = 60;
  geometry.resolution_m = 0.1;
  geometry.origin_x_m = -3.0;
  geometry.origin_y_m = -2.0;
  OccupancyGrid grid(geometry, LogOddsModel{});
  constexpr double kWallY = 0.98;  // the board's face, in the cell row y in [0.9, 1.0)
  constexpr double kRoomDepth = 2.5;
  for (int view = 0; view < 40; ++view) {
    const core::Pose2 pose{-1.2 + 0.06 * view, -0.2 + 0.01 * view, 0.0};
    core::DepthScan scan;
    constexpr int kColumns = 640;
    constexpr double kFieldOfView = 1.35;
    for (int column = 0; column < kColumns; ++column) {
      const double bearing = 0.5 * (core::kPi - kFieldOfView) + kFieldOfView * column / kColumns;
      const double cx = std::cos(bearing);
      const double sy = std::sin(bearing);
      const double t_wall = (kWallY - pose.y) / sy;
      const double x_at_wall = pose.x + t_wall * cx;
      const bool through_door = x_at_wall >= 0.45 && x_at_wall < 0.9;
      const double t_end = through_door ? (kWallY + kRoomDepth - pose.y) / sy : t_wall;
      const auto kind = through_door ? Kind::free : Kind::obstacle;
      scan.columns.push_back(
          {static_cast<float>(t_end * cx), static_cast<float>(t_end * sy), kind});  // heading 0: robot = map axes
    }
    grid.insert(scan, pose);
  }
  int board_x = 0;
  int board_y = 0;
  ASSERT_TRUE(grid.cell_of(0.44, kWallY, board_x, board_y));
  EXPECT_EQ(CellThresholds{}.classify(grid.log_odds(board_x, board_y)), CellState::occupied);
  int door_x = 0;
  int door_y = 0;
  ASSERT_TRUE(grid.cell_of(0.65, kWallY, door_x, door_y));
  EXPECT_EQ(CellThresholds{}.classify(grid.log_odds(door_x, door_y)), CellState::free);
}

TEST(CellThresholds, ClassifiesByProbability) {
  const CellThresholds thresholds;
  EXPECT_EQ(thresholds.classify(0.0F), CellState::unknown);
  EXPECT_EQ(thresholds.classify(0.85F), CellState::occupied);  // p = 0.70
  EXPECT_EQ(thresholds.classify(-0.4F), CellState::unknown);   // p = 0.40
  EXPECT_EQ(thresholds.classify(-1.6F), CellState::free);      // p = 0.17
}

TEST(ScanHistory, KeepsOnlyValidColumnsAndInsertsLikeTheFullScan) {
  ScanHistory history(4, 8);
  core::DepthScan scan;
  scan.origin_robot = {0.1, 0.02};
  scan.columns = {{0.5F, 0.1F, Kind::obstacle, 0.3F, true},
                  {0.4F, 0.0F, Kind::invalid, 0.0F, false},
                  {0.6F, -0.2F, Kind::free, 0.2F, false}};
  history.record(7, scan);
  ScanView view;
  ASSERT_EQ(history.find(7, view), ScanLookup::found);
  ASSERT_EQ(view.count, 2u);
  EXPECT_EQ(view.points[1].kind, Kind::free);
  EXPECT_EQ(view.points[1].floor_visible_from_mm, 200);
  EXPECT_TRUE(view.points[0].obstacle_at_camera_height);
  OccupancyGrid from_view(small_geometry(), LogOddsModel{});
  OccupancyGrid from_scan(small_geometry(), LogOddsModel{});
  const core::Pose2 pose{0.13, -0.21, 0.7};
  from_view.insert(view, pose);
  from_scan.insert(scan, pose);
  EXPECT_TRUE(from_view.same_cells_as(from_scan));
}

TEST(ScanHistory, TellsOverwrittenFromNeverRecorded) {
  ScanHistory history(3, 4);
  const core::DepthScan scan = one_column(0.5F, 0.0F, Kind::obstacle);
  ScanView view;
  EXPECT_EQ(history.find(0, view), ScanLookup::never_recorded);
  history.record(1, scan);
  history.record(2, scan);
  history.record(4, scan);  // 3 skipped
  history.record(5, scan);
  EXPECT_EQ(history.find(1, view), ScanLookup::overwritten);
  EXPECT_EQ(history.find(2, view), ScanLookup::overwritten);
  EXPECT_EQ(history.find(3, view), ScanLookup::never_recorded);
  EXPECT_EQ(history.find(4, view), ScanLookup::found);
  EXPECT_EQ(history.find(6, view), ScanLookup::never_recorded);
  history.record(5, scan);
  EXPECT_EQ(history.counts().out_of_order, 1u);
}

TEST(ScanHistory, CountsColumnsBeyondCapacity) {
  ScanHistory history(2, 2);
  core::DepthScan scan;
  scan.columns.assign(5, {0.5F, 0.0F, Kind::obstacle});
  history.record(0, scan);
  ScanView view;
  ASSERT_EQ(history.find(0, view), ScanLookup::found);
  EXPECT_EQ(view.count, 2u);
  EXPECT_EQ(history.counts().columns_truncated, 3u);
}

}  // namespace
}  // namespace stereoscout::occupancy
