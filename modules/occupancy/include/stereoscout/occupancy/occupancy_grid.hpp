#pragma once
// A log-odds occupancy grid updated from 2.5D depth scans by ray casting (paper V).
//
// Cells hold float log-odds, clamped to [log_odds_min, log_odds_max]. A scan column is a ray
// from the camera centre on the floor to its end point: every cell the integer line walk
// passes gets log_odds_miss; the end cell gets log_odds_hit for an obstacle, log_odds_miss
// for a free column (nothing seen up to the range limit); invalid columns change nothing.
// Because of the clamps the result depends on the order of insertion, so "the grid of a
// trajectory" always means its scans inserted in update order.

#include <cstddef>
#include <cstdint>
#include <memory>

#include "stereoscout/core/config/grid.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"

namespace stereoscout::occupancy {

struct GridGeometry {
  int width_cells = 0;
  int height_cells = 0;
  double resolution_m = 0.1;
  double origin_x_m = 0.0;  // map-frame position of the lower-left corner of cell (0, 0)
  double origin_y_m = 0.0;

  // The configured navigation grid, placed so that `centre` lies in its middle cell.
  static GridGeometry centred_on(const core::GridConfig& config, const core::Pose2& centre);
  std::size_t cell_count() const {
    return static_cast<std::size_t>(width_cells) * static_cast<std::size_t>(height_cells);
  }
  bool contains(int cell_x, int cell_y) const {
    return cell_x >= 0 && cell_y >= 0 && cell_x < width_cells && cell_y < height_cells;
  }
  bool same_as(const GridGeometry& other) const;
};

struct LogOddsModel {
  float hit = 0.85F;
  float miss = -0.4F;
  float min = -4.0F;
  float max = 4.0F;
  static LogOddsModel from_config(const core::GridConfig& config);
};

enum class CellState : std::uint8_t { unknown, free, occupied };

// Probability thresholds of the ROS map_server convention, applied to p = 1 - 1/(1 + e^l).
struct CellThresholds {
  double occupied = 0.65;
  double free = 0.196;
  static CellThresholds from_config(const core::GridConfig& config);
  CellState classify(float log_odds) const;
};

// One valid column of a scan, compact (robot frame at capture time).
struct ScanPoint {
  float x_robot_m = 0.0F;
  float y_robot_m = 0.0F;
  core::DepthScanColumn::Kind kind = core::DepthScanColumn::Kind::invalid;
};

// A stored scan as seen by the grid: the camera centre and the valid columns in order.
struct ScanView {
  double origin_x_robot_m = 0.0;
  double origin_y_robot_m = 0.0;
  const ScanPoint* points = nullptr;
  std::size_t count = 0;
};

struct InsertCounts {
  std::uint64_t rays = 0;
  std::uint64_t rays_rejected = 0;  // non-finite or absurdly far end points, skipped
};

class OccupancyGrid {
 public:
  // Allocates width x height cells (start-up only), all unknown (log-odds 0).
  OccupancyGrid(const GridGeometry& geometry, const LogOddsModel& model);

  OccupancyGrid(const OccupancyGrid&) = delete;
  OccupancyGrid& operator=(const OccupancyGrid&) = delete;

  void clear();
  // Same geometry required (checked); no allocation.
  void copy_from(const OccupancyGrid& other);

  // Inserts a scan taken at `pose` (map frame). Both overloads give identical cells for the
  // same valid columns in the same order.
  void insert(const ScanView& scan, const core::Pose2& pose);
  void insert(const core::DepthScan& scan, const core::Pose2& pose);

  float log_odds(int cell_x, int cell_y) const { return cells_[index(cell_x, cell_y)]; }
  const float* data() const { return cells_.get(); }
  const GridGeometry& geometry() const { return geometry_; }
  const InsertCounts& insert_counts() const { return counts_; }
  bool same_cells_as(const OccupancyGrid& other) const;
  // Cell containing a map-frame point; false when outside the grid.
  bool cell_of(double x_m, double y_m, int& cell_x, int& cell_y) const;

 private:
  std::size_t index(int cell_x, int cell_y) const {
    return static_cast<std::size_t>(cell_y) * static_cast<std::size_t>(geometry_.width_cells) +
           static_cast<std::size_t>(cell_x);
  }
  void add(int cell_x, int cell_y, float delta);
  void cast_ray(double start_x, double start_y, double end_x, double end_y, bool end_is_obstacle);

  GridGeometry geometry_;
  LogOddsModel model_;
  std::unique_ptr<float[]> cells_;
  InsertCounts counts_;
};

}  // namespace stereoscout::occupancy
