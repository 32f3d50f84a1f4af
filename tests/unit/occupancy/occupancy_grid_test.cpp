#include "stereoscout/occupancy/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

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

TEST(OccupancyGrid, FreeColumnMissesItsEndCellAndInvalidDoesNothing) {
  OccupancyGrid grid(small_geometry(), LogOddsModel{});
  grid.insert(one_column(0.35F, 0.0F, Kind::free), core::Pose2{0.05, 0.05, 0.0});
  for (int x = 10; x <= 13; ++x) EXPECT_FLOAT_EQ(grid.log_odds(x, 10), -0.4F) << x;
  OccupancyGrid untouched(small_geometry(), LogOddsModel{});
  untouched.insert(one_column(0.35F, 0.0F, Kind::invalid), core::Pose2{});
  OccupancyGrid empty(small_geometry(), LogOddsModel{});
  EXPECT_TRUE(untouched.same_cells_as(empty));
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

TEST(OccupancyGrid, DiagonalRayIsAConnectedLine) {
  OccupancyGrid grid(small_geometry(), LogOddsModel{});
  grid.insert(one_column(0.5F, 0.3F, Kind::obstacle), core::Pose2{0.05, 0.05, 0.0});
  EXPECT_FLOAT_EQ(grid.log_odds(15, 13), 0.85F);
  int missed = 0;
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 20; ++x) missed += grid.log_odds(x, y) < 0.0F ? 1 : 0;
  }
  EXPECT_EQ(missed, 5);  // Bresenham: max(|dx|, |dy|) cells before the end
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
  scan.columns = {{0.5F, 0.1F, Kind::obstacle}, {0.4F, 0.0F, Kind::invalid}, {0.3F, -0.2F, Kind::free}};
  history.record(7, scan);
  ScanView view;
  ASSERT_EQ(history.find(7, view), ScanLookup::found);
  ASSERT_EQ(view.count, 2u);
  EXPECT_EQ(view.points[1].kind, Kind::free);
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
