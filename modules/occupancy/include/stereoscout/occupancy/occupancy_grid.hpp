#pragma once
// A log-odds occupancy grid updated from 2.5D depth scans by ray casting (paper V).
//
// Cells hold float log-odds, clamped to [log_odds_min, log_odds_max]. A scan column is a ray
// on the floor from the camera centre towards its end point, but the camera cannot see the
// floor in its first metre or so (the column's floor_visible_from_m: a 0.6 m high camera
// with a 62 deg vertical field of view), where a low box or a table edge is invisible. So:
//   - the ray starts where the column's floor becomes visible; every cell it crosses from
//     there (exact traversal) gets log_odds_miss, except the cells where another column of
//     the same scan ends on an obstacle: the hit wins (a thin poster beside a door fills a
//     sliver of its cell, and the rays through the door cross the rest of it);
//   - an obstacle column's end cell gets log_odds_hit (an obstacle nearer than the visible
//     floor marks only its own cell); with hit_full_weight_range_m, an end farther than that
//     gets log_odds_hit x (that / range)^2, as its range error grows with the square of the
//     range, and one hit makes a cell occupied: a far wall seen at a slant may land its
//     hits along the wall, in a door beside it;
//   - a free column (floor seen up to its end) stops one cell (or free_end_short_m, if more)
//     short of its end point: the farthest floor point often lies in the cell of the wall
//     behind it, which must not be cleared (on a finer grid, in the cell after); nothing is
//     cleared when that leaves no visible floor. Within free_end_sigmas standard deviations
//     of its end's range (DepthScanColumn::end_range_sigma_m) it lowers no cell that holds
//     an obstacle (log-odds above 0): that end is the farthest of the column's floor
//     points, the one the disparity error put farthest out, so at a wall's base it lies
//     beyond the wall, and floor seen up to a wall from both sides erased it
//     (the office's corridor walls, where plans then ran). Unknown and free cells there are
//     cleared as before: ending the ray short instead left strips of unknown cells before
//     every wall and in every door seen from afar, which closed the doors. Off by default:
//     measured on the office it kept smeared jamb cells and a person's trace too, and
//     lowered coverage (docs/results.md);
//   - with near_hit_hold_range_m, a low obstacle's hit (not at the camera's height: a blank
//     wall seen by its base) from within that range of the camera holds its cell, unless
//     misses from within that range once left the cell free: misses from farther than that
//     pass it by, until a nearer miss lowers it to log-odds 0 or a hit at the camera's height
//     replaces it. A far ray's error across its way is the heading's error times its range,
//     and the rays that reach a corridor's blank walls are far ones at a slant. Far hits and
//     people stay for far misses to clear, and so do obstacles on cells that near views saw
//     free (a door's jamb drawn into it by a pose a little off: held, it shut a room that
//     the robot then stood too far from to see clear). Far misses that leave a cell free do
//     not count: they are how a blank wall is worn away. A far miss passes a held cell by
//     only within near_hit_hold_end_m of its ray's end: the rays that wear a wall away end
//     on it, and one that runs on beyond the cell saw through it (a doorway seen from
//     inside its room). Off by default;
//   - invalid columns change nothing, and no column changes a cell nearer than its
//     measurable_from_m (the part of the view the other camera does not share, or beyond
//     the matcher's largest disparity): it could not have seen an obstacle there.
// In view: every cell a column passes from where its floor becomes visible (and it can
// measure) up to in_view_range_m, or to its obstacle if nearer, was in view of the camera. An
// unknown cell in view is a surface the stereo could not measure (a blank wall just beyond
// the floor seen up to it), unlike an unknown cell of the camera's blind zone, which no view
// ever covered; the planner may cross the latter near the robot, never the former. The mark
// does not change the cell's log-odds and stays set.
// Looked over (grid.looked_over_range_m): every cell a valid column's ray passes from the
// camera up to that range, or to its end if nearer, the blind zone included. An unknown cell
// near the robot that no ray ever passed over lay beside its way, out of the field of view,
// where a low box's side may stand; the planner keeps clear of those. Also a mark only.
// People walk on. Each cell remembers whether its last hit came from an obstacle at the
// camera's height (DepthScanColumn::obstacle_at_camera_height). Such an obstacle is in view
// at every range, so a ray that passes through the cell without ending there means it has
// gone: in the blind zone too, such cells get log_odds_miss (other cells there are left alone:
// a low box may be there, out of view). Without this, a person who passed within a metre of
// the robot left occupied cells that no later view could clear. It is a rule of insertion,
// not a timer, so the grid stays a function of the scans along the trajectory (the
// just-in-time invariant).
// (Rays that started at the camera cleared a low box as the robot approached it: the floor
// seen beyond the box, once the box was below the image, erased the box's cells.)
// Once per scan (grid.once_per_scan): a scan lowers a cell that holds a low obstacle (log-odds
// above 0, its last hit not at the camera's height: a blank wall seen by its base, a low box)
// once, however many of its columns pass through it. Without it a cell counts a scan as often
// as columns cross it: a wall's cell along which the rays graze is passed by tens of columns of
// one scan, so a view along a wall from a pose a little off (a particle lineage's) erases it at
// once, and metre-long gaps open in a corridor wall. Unknown and free cells still take every
// column's miss (one scan clears the floor it sees), every column ending in a cell adds its
// hit, and so does every column through an obstacle at the camera's height: such an obstacle
// is in view at every range, so a ray past it is good evidence that it has gone (a person
// walking on clears in a scan, as before).
// Because of the clamps the result depends on the order of insertion, so "the grid of a
// trajectory" always means its scans inserted in update order.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
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

// What a scan says about the cells: log-odds, and how far a column's view counts.
struct LogOddsModel {
  float hit = 0.85F;
  float miss = -0.4F;
  float min = -4.0F;
  float max = 4.0F;
  float in_view_range_m = 0.0F;  // grid.in_view_range_m (0: nothing is marked)
  float looked_over_range_m = 0.0F;  // grid.looked_over_range_m (0: nothing is marked)
  float free_end_sigmas = 0.0F;  // grid.free_end_sigmas (0: a free column's misses are all alike)
  float free_end_short_m = 0.0F;  // grid.free_end_short_m (0: a cell short)
  float hit_full_weight_range_m = 0.0F;  // grid.hit_full_weight_range_m (0: every hit in full)
  float near_hit_hold_range_m = 0.0F;  // grid.near_hit_hold_range_m (0: misses lower obstacles at any range)
  float near_hit_hold_end_m = 1.5F;  // grid.near_hit_hold_end_m
  float free_below = -1.41F;  // grid.free_threshold's log-odds: a cell below it is free
  bool once_per_scan = false;    // grid.once_per_scan (see the header comment)
  static LogOddsModel from_config(const core::GridConfig& config);
};

enum class CellState : std::uint8_t { unknown, free, occupied };

// Probability thresholds of the ROS map_server convention, applied to p = 1 - 1/(1 + e^l).
// Compared in log-odds (l > logit(occupied), l < logit(free)): the same test without an exp
// per cell, and the one test every user of a grid (explorer, final map, scores) applies.
struct CellThresholds {
  double occupied = 0.65;
  double free = 0.196;
  static CellThresholds from_config(const core::GridConfig& config);
  CellState classify(float log_odds) const;
};

// A ray in cell units: (x_m - origin_x_m) / resolution_m, likewise y.
struct GridSegment {
  double x0 = 0.0;
  double y0 = 0.0;
  double x1 = 0.0;
  double y1 = 0.0;
};

class OccupancyGrid;
// Classifies every cell of `grid` into `cells` (grid.geometry().cell_count() entries, row-major
// like the grid), and, if `in_view` is given, writes 1 there for the cells that were in view
// (OccupancyGrid::in_view), else 0; likewise `looked_over` (OccupancyGrid::looked_over). No
// allocation: the tick loop calls it after each roll-up.
void classify_cells(const OccupancyGrid& grid, const CellThresholds& thresholds, CellState* cells,
                    std::uint8_t* in_view = nullptr, std::uint8_t* looked_over = nullptr);

// One valid column of a scan, compact (robot frame at capture time): 16 bytes, so the ring of
// 4096 scans x 640 columns stays at 42 MB.
struct ScanPoint {
  float x_robot_m = 0.0F;
  float y_robot_m = 0.0F;
  core::DepthScanColumn::Kind kind = core::DepthScanColumn::Kind::invalid;
  bool obstacle_at_camera_height = false;
  std::uint16_t floor_visible_from_mm = 0;  // DepthScanColumn::floor_visible_from_m, whole mm
  std::uint16_t measurable_from_mm = 0;     // DepthScanColumn::measurable_from_m, whole mm
  std::uint16_t end_range_sigma_mm = 0;     // DepthScanColumn::end_range_sigma_m, whole mm

  // The one conversion both insert() overloads use, so they give identical cells.
  static ScanPoint from_column(const core::DepthScanColumn& column);
  double floor_visible_from_m() const { return 0.001 * floor_visible_from_mm; }
  double measurable_from_m() const { return 0.001 * measurable_from_mm; }
  double end_range_sigma_m() const { return 0.001 * end_range_sigma_mm; }
};
static_assert(sizeof(ScanPoint) == 16, "the scan history's memory budget counts 16 bytes a column");

// A stored scan as seen by the grid: the camera centre and the valid columns in order.
struct ScanView {
  double origin_x_robot_m = 0.0;
  double origin_y_robot_m = 0.0;
  const ScanPoint* points = nullptr;
  std::size_t count = 0;
};

// A column end this far from the robot is a broken measurement: it must size no map.
inline constexpr double kMaxPlausibleScanRangeM = 100.0;

// Calls visit(x_m, y_m) with the map-frame end of every column of `scan` seen from `pose`,
// except broken measurements. For sizing maps and archives.
template <typename Visit>
void for_each_plausible_end(const ScanView& scan, const core::Pose2& pose, Visit&& visit) {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  for (std::size_t i = 0; i < scan.count; ++i) {
    const double px = scan.points[i].x_robot_m;
    const double py = scan.points[i].y_robot_m;
    if (!(std::hypot(px, py) < kMaxPlausibleScanRangeM)) continue;
    visit(pose.x + c * px - s * py, pose.y + s * px + c * py);
  }
}

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
  // Clears the grid and moves its lower-left corner (same size, no allocation): a tile of the
  // scan archive taking its place.
  void clear_at(double origin_x_m, double origin_y_m);
  // Same geometry required (checked); no allocation.
  void copy_from(const OccupancyGrid& other);
  // Copies the cells (log-odds and marks) of `part` that this grid also covers. Same
  // resolution, and origins a whole number of cells apart (checked).
  void paste(const OccupancyGrid& part);

  // Inserts a scan taken at `pose` (map frame). Both overloads give identical cells for the
  // same valid columns in the same order.
  void insert(const ScanView& scan, const core::Pose2& pose);
  void insert(const core::DepthScan& scan, const core::Pose2& pose);

  float log_odds(int cell_x, int cell_y) const { return cells_[index(cell_x, cell_y)]; }
  const float* data() const { return cells_.get(); }
  const GridGeometry& geometry() const { return geometry_; }
  const InsertCounts& insert_counts() const { return counts_; }
  bool same_cells_as(const OccupancyGrid& other) const;
  bool in_view(int cell_x, int cell_y) const { return (cell_flags_[index(cell_x, cell_y)] & kInView) != 0U; }
  bool looked_over(int cell_x, int cell_y) const { return (cell_flags_[index(cell_x, cell_y)] & kLookedOver) != 0U; }
  // in_view() and looked_over() of every cell as 1 or 0, row-major (either may be null).
  void copy_marks(std::uint8_t* in_view, std::uint8_t* looked_over) const;
  // Cell containing a map-frame point; false when outside the grid.
  bool cell_of(double x_m, double y_m, int& cell_x, int& cell_y) const;

 private:
  std::size_t index(int cell_x, int cell_y) const {
    return static_cast<std::size_t>(cell_y) * static_cast<std::size_t>(geometry_.width_cells) +
           static_cast<std::size_t>(cell_x);
  }
  struct ScanFrame;
  static constexpr std::uint8_t kLastHitAtCameraHeight = 1U;  // the cell's last hit was at the camera's height
  static constexpr std::uint8_t kHitThisScan = 2U;            // a column of the scan being inserted ends here
  static constexpr int kInViewBit = 2;
  static constexpr int kLookedOverBit = 3;
  static constexpr std::uint8_t kInView = 1U << kInViewBit;          // a column's view covered the cell
  static constexpr std::uint8_t kLookedOver = 1U << kLookedOverBit;  // a column's ray passed over it, blind zone too
  static constexpr std::uint8_t kHeldByNearHit = 16U;  // near_hit_hold_range_m: far misses pass the cell by
  static constexpr std::uint8_t kWasFree = 32U;  // near misses left it free once: a near hit does not hold it
  static constexpr double kNoLimit = std::numeric_limits<double>::infinity();
  // How a ray treats its cells (insert_column sets it from the model).
  struct RayRules {
    bool at_camera_height = false;  // the end's obstacle point
    float end_log_odds = 0.0F;      // an obstacle end adds this
    bool end_holds = false;         // an obstacle end holds its cell (near_hit_hold_range_m)
    double firm_m = kNoLimit;       // beyond this along the ray: miss_unless_occupied
    double held_beyond_m = kNoLimit;  // beyond this along the ray: cells held by a near hit are passed by ...
    double held_within_end_m = kNoLimit;  // ... where they lie within this of the ray's end
  };

  void add(int cell_x, int cell_y, float delta);
  void hit(int cell_x, int cell_y, bool at_camera_height, float log_odds, bool holds);
  // An obstacle end's log-odds at this range from the camera (hit_full_weight_range_m).
  float hit_log_odds(double range_m) const;
  // log_odds_miss, unless a column of the scan being inserted ends in the cell.
  void miss(int cell_x, int cell_y);
  // A miss from within near_hit_hold_range_m: it also marks the cell free once (kWasFree) if it
  // leaves it free.
  void near_miss(int cell_x, int cell_y);
  // The same, but not to a cell that holds an obstacle (log-odds above 0).
  void miss_unless_occupied(int cell_x, int cell_y);
  bool marked_hit_this_scan(int cell_x, int cell_y) const;
  // Holds an obstacle (log-odds above 0) that a near hit put there (near_hit_hold_range_m).
  bool held_by_near_hit(int cell_x, int cell_y) const;
  // once_per_scan: starts the numbering of a new scan's misses.
  void begin_scan();
  void set_hit_marks(const Eigen::Vector2d& end, bool marked);
  bool grid_coordinates(double start_x, double start_y, double end_x, double end_y, GridSegment& segment) const;
  // No cell of the segment (end cell included) lies in the grid: its walk can be skipped.
  bool misses_grid(const GridSegment& segment) const;
  template <typename EachPoint>
  void insert_points(const ScanFrame& frame, EachPoint&& each_point);
  // Every cell but the last is passed through (a miss, by `rules`); the last is where the
  // column ends.
  void cast_ray(double start_x, double start_y, double end_x, double end_y, bool end_is_obstacle,
                const RayRules& rules);
  // Misses, before the end cell, only the cells whose last hit was at the camera's height.
  void clear_camera_height_hits(double start_x, double start_y, double end_x, double end_y);
  // One column: origin and end point in the map frame.
  void insert_column(const Eigen::Vector2d& origin, const Eigen::Vector2d& end, const ScanPoint& point);
  // Sets `flag` in the cells from `from` to `to` (map frame), both cells included.
  void mark_cells(const Eigen::Vector2d& from, const Eigen::Vector2d& to, std::uint8_t flag);

  GridGeometry geometry_;
  LogOddsModel model_;
  std::unique_ptr<float[]> cells_;
  // kLastHitAtCameraHeight | kHitThisScan | kInView | kLookedOver | kHeldByNearHit | kWasFree
  std::unique_ptr<std::uint8_t[]> cell_flags_;
  // once_per_scan: the number of the scan that last missed each cell, against scan_number_
  // (counts inserts from 1, wraps to 1 after 255 with every stamp reset); empty otherwise.
  // Scratch of one insert: never copied, compared or pasted.
  std::unique_ptr<std::uint8_t[]> miss_stamps_;
  std::uint8_t scan_number_ = 0;
  InsertCounts counts_;
};

}  // namespace stereoscout::occupancy
