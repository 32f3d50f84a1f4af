#pragma once
// Door sighting (explore.door_sighting_range_m): the robot's offset across a door it is about
// to pass, measured in the latest scan, and the pose it navigates by corrected for it.
//
// A 0.7 m robot has 0.10 m to spare on either side in a 0.9 m door, and six of the office's
// eight contacts were door jambs, met with the robot's centre 0.10-0.13 m off the door's
// middle (docs/results.md). The scan sees the door itself: a run of
// columns that see past the door's line (through it, into the room or corridor beyond),
// bounded on either side by a jamb or the wall beside it, which the matcher does not measure
// past. The run's end columns give the jambs' bearings from the camera (the left end's from the
// left camera, see measure()); rendered in front of the office's doors, they put the gap's
// middle within 0.003-0.006 m of the truth on the mean from 1.0-1.6 m away, wherever both
// jambs stood inside the image (tests/integration/door_sighting_test.cpp).
//
// The door is the one the plan passes next (find_door(), any waypoint with obstacle cells on
// both sides within reach): its line runs through the grid's jamb cells. Each new
// scan taken with the camera within door_sighting_range_m of the door's middle, and at least
// kMinAhead_m before its line, is searched for the run of past columns around the middle's
// bearing. The jambs' rays, met with the door's line, give the gap the scan saw; its middle's
// offset across the door from the grid's middle is how far the pose of the scan was off across
// it (a gap much wider or narrower than the grid's, a jamb at the image's edge, or an offset
// beyond door_sighting_max_offset_m is no sighting, counted). From then on, until the robot
// has cleared the door or drove kHoldTravelFactor times the range since, the explorer navigates
// by the scan's pose moved by that offset and then by the odometry since: its plans, the
// follower and the safety check place the robot against the grid's door where the camera saw
// it. Each later sighting of the same door replaces the earlier.
//
// Off by default: in the office runs the corrections put the door within 0.019 m of where it
// was across the robot's way on the median (judged in the robot's frame), but the contacts did
// not fall: at three of five the robot knew it was 0.10-0.14 m off the door's middle, and the
// pose a sighting leaves is carried by the odometry through the last metre (docs/results.md,
// "The door sighting judged in the robot's frame").
//
// With explore.door_sighting_heading the scan's heading is corrected first: the wall beside
// the door, seen in the scan and held in the grid, is one line, and the angle between the two
// is how far the pose's heading was off against the map. The offset across the door is then
// measured from the corrected heading. From one scan the jambs' bearings alone cannot tell a
// heading error from an offset across the door: both shift the jambs' bearings alike, and
// driving straight at the door keeps them so (only where the robot's heading line meets the
// door's line is seen). At the office's traced jamb contacts the heading was 8-11 degrees off
// (docs/results.md), 0.14-0.19 m across the way over the last metre the odometry carries the
// pose.
//
// Fixed-size state; observe() and navigation_pose() allocate nothing.

#include <cstdint>

#include <Eigen/Core>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"
#include "stereoscout/explore/door_axis.hpp"
#include "stereoscout/explore/grid_view.hpp"
#include "stereoscout/explore/seen_obstacles.hpp"

namespace stereoscout::explore {

struct DoorSightingCounters {
  std::uint64_t scans_at_doors = 0;     // scans taken with a door on the plan in range
  std::uint64_t not_in_a_wall = 0;      // of them: no wall beside a jamb in the grid (nor, with door_wall_from_scan, in the scan)
  std::uint64_t sightings = 0;          // of them: the door's gap measured and the pose corrected
  std::uint64_t no_gap = 0;             // no run of past columns around the middle's bearing
  std::uint64_t jamb_at_image_edge = 0;
  std::uint64_t width_disagrees = 0;    // the gap's width far from the grid's
  std::uint64_t offset_too_large = 0;
  std::uint64_t doors_sighted = 0;      // sightings of a door no sighting was held for
  // With door_sighting_heading, of the sightings: heading corrected from the wall's line, taken
  // from a held sighting of the door whose heading was (carried by the odometry), or neither
  // (no line fitted in the scan or in the grid, or their angles too far apart).
  std::uint64_t headings_corrected = 0;
  std::uint64_t headings_carried = 0;
  std::uint64_t heading_unmeasured = 0;
  // Scans whose wall gave a heading more than kMaxHeadingJump_deg from the held sighting's
  // (the held one's is kept).
  std::uint64_t heading_jumps = 0;
};

// What one scan saw of a door: its jambs on the door's line, in the map frame of the scan's
// pose.
struct DoorGap {
  Eigen::Vector2d left = Eigen::Vector2d::Zero();   // the jamb to the left of the way through
  Eigen::Vector2d right = Eigen::Vector2d::Zero();
  int first_column = 0;  // the gap's run of columns in the scan (the left jamb's end first)
  int last_column = 0;
};

class DoorSighting {
 public:
  // A jamb's bearing is kept only this many columns or more inside the image: the matcher
  // measures the image's edge columns badly (the other camera does not see them).
  static constexpr int kEdgeColumns = 32;
  // A column sees past the door when its point lies this far beyond the door's line.
  static constexpr double kPastLine_m = 0.1;
  // A run of such columns bridges this many that do not: the seam between two floors on the
  // threshold, seen as a surface there (the office's carpet meets the corridor's tiles in each
  // door), cut the gap in two. About 5 degrees; the wall beside a door fills hundreds.
  static constexpr int kMaxSplitColumns = 40;
  // The camera must be this far before the door's line: nearer, the jambs near the image's
  // edges are measured badly (on the office's windows, a sighting with the camera 0.5 m
  // before the line was 0.10 m off across the door; those from 0.8 to 1.7 m were 0.01-0.02 m
  // off on the median, judged in the robot's frame) and soon leave the image.
  static constexpr double kMinAhead_m = 0.7;
  // A gap whose width differs from the grid's (between its jamb cells' centres) by more than
  // this is another opening, or the run was cut short by something in the door.
  static constexpr double kWidthTolerance_m = 0.3;
  // A held sighting is dropped once the odometry has driven this many times the range since.
  static constexpr double kHoldTravelFactor = 2.0;
  // A door is an opening in a wall: of the grid's cells on the door's line just beyond each
  // jamb cell (kWallCells of them outwards), at least kWallCellsOccupied are occupied. A gap
  // between a person's trace and a wall, seen along a corridor, is none.
  static constexpr int kWallCells = 3;
  static constexpr int kWallCellsOccupied = 2;
  // With explore.door_wall_from_scan, a door is also in a wall when the scan sees the wall
  // beside it: outward from one end of the gap (the scan's jamb), the measured columns see
  // points within kWallOnLine_m of the door's line up to kWallBeside_m beyond the jamb, and
  // outward from neither end do more than one in kWallOffLineShare of them see a point off
  // the line (the floor past two posts, or a corridor's far wall beside a person). The other
  // side may be out of the image or unmeasured: nearer than about 1.1 m the matcher measures
  // no wall in the image's outer band. Square on from 1.1 m, the office's corridor walls are
  // measured on the line to the centimetre along their whole length in the image.
  static constexpr double kWallOnLine_m = 0.15;
  static constexpr double kWallBeside_m = 0.2;
  static constexpr int kWallOffLineShare = 4;
  // The wall's line for the heading (door_sighting_heading). The grid's: its occupied cells
  // from the jamb outward to kHeadingWallReach_m across from the door's middle, within
  // kHeadingBand_m of the door's line (a heading 15 degrees off moves a point 1.5 m out by
  // 0.4 m), fitted by least squares, then twice again to those within
  // max(kHeadingFitTolerance_m, kHeadingCellTolerance cells) of the last fit (at least
  // kHeadingMinCells, spread kHeadingMinSpan_m along it). The scan's: of its points in the
  // same place, turned about the robot by each kHeadingSearchStep_deg up to
  // kMaxHeadingError_deg either way, the most that fall within a band two
  // kHeadingFitTolerance_m wide along the grid's line and within kHeadingLineGap_m of it (at
  // least kHeadingMinColumns, spread kHeadingMinSpan_m); the line through them, fitted by
  // least squares. Points seen through the door into the room beyond, or of a chair before
  // the wall, lie off that band: a plain fit through the scan's points took them in from
  // 1.0 m aslant, 0.2 m past the wall's line.
  static constexpr double kHeadingWallReach_m = 1.5;
  static constexpr double kHeadingBand_m = 0.5;
  static constexpr double kHeadingFitTolerance_m = 0.05;
  // The grid's cell centres stand up to half a cell off a wall's line that runs aslant.
  static constexpr double kHeadingCellTolerance = 0.6;
  static constexpr int kHeadingMinColumns = 30;
  static constexpr int kHeadingMinCells = 6;
  // From 1.3 m before the office's doors the rendered scans saw 0.46-0.78 m of wall beside them.
  static constexpr double kHeadingMinSpan_m = 0.4;
  static constexpr double kMaxHeadingError_deg = 20.0;
  static constexpr double kHeadingSearchStep_deg = 0.25;
  // A held sighting's heading, carried by the odometry, and a later scan's wall's of the same
  // door lie within this of each other; beyond it the wall's is not trusted. Successive
  // sightings of one door agreed to 0.5-2 degrees in the office, and one 12 degrees off them
  // (a line through points seen through the door, it seems) steered the robot into the jamb
  // (office seed 3 at N3, docs/results.md).
  static constexpr double kMaxHeadingJump_deg = 3.0;
  // The scan's wall may lie this far from the grid's along the door's axis (the pose's error
  // along it, and the grid's cells: their centres up to half a cell behind the wall's face).
  static constexpr double kHeadingLineGap_m = 0.15;
  static constexpr int kHeadingOffsetBins = static_cast<int>(2.0 * kHeadingLineGap_m / kHeadingFitTolerance_m + 0.5);

  explicit DoorSighting(const ExploreParams& params);

  bool enabled() const { return range_m_ > 0.0; }
  // A scan observe() has not seen yet.
  bool wants(const SeenObstacles& seen) const;
  // A new scan (wants(seen); others are ignored) with `door`, the door the plan passes next
  // (door.known false: none; its width_m the grid's gap) in `grid`. A door other than the held
  // sighting's drops it.
  void observe(const SeenObstacles& seen, const DoorPassage& door, const GridView& grid);
  // The pose to navigate by now: `pose` (the estimate), or while a sighting is held the
  // sighted pose moved by the odometry since (`odometry`: the odometry pose now). Drops a held
  // sighting once the door is passed or left.
  core::Pose2 navigation_pose(const core::Pose2& pose, const core::Pose2& odometry);

  bool holding() const { return held_; }
  // Whether `door` is an opening in a wall in `grid` (kWallCells, kWallCellsOccupied).
  static bool in_a_wall(const DoorPassage& door, const GridView& grid);
  // Whether `scan` (taken at `pose`) sees the wall on `door`'s line beside `gap`
  // (kWallOnLine_m, kWallBeside_m, kWallOffLineShare).
  static bool wall_in_scan(const core::DepthScan& scan, const core::Pose2& pose, const DoorPassage& door,
                           const DoorGap& gap);
  // The last sighting's offset across the door (map frame, added to the scan's pose), and its
  // door.
  Eigen::Vector2d last_offset() const { return offset_; }
  // The last sighting's heading correction (radians, added to the scan's heading: the wall's,
  // or the held sighting's carried; 0 without door_sighting_heading or with neither).
  double last_heading_correction() const { return heading_correction_rad_; }
  // The angle (radians, the map frame) by which the wall beside `door` in `scan` (taken at
  // `pose`) must turn to lie along the wall beside it in `grid`; false when either line is
  // not measured or they lie more than kMaxHeadingError_deg apart.
  static bool heading_error(const core::DepthScan& scan, const core::Pose2& pose, const DoorPassage& door,
                            const GridView& grid, double& correction_rad);
  const DoorPassage& door() const { return door_; }
  const DoorSightingCounters& counters() const { return counters_; }

 private:
  // The door's gap in `scan` taken at `pose` (map frame) with the pan unit at `pan_rad`; false,
  // with the reason counted, when there is none to trust.
  bool measure(const core::DepthScan& scan, const core::Pose2& pose, double pan_rad, const DoorPassage& door,
               DoorGap& gap);
  void release();
  // Where a sighting's heading comes from (door_sighting_heading).
  enum class HeadingSource { none, wall, held, unmeasured };
  // The scan's pose `pose` (seen.pose on entry) with its heading corrected, and from where.
  HeadingSource scan_heading(const SeenObstacles& seen, const DoorPassage& door, const GridView& grid,
                             core::Pose2& pose);
  void count_heading(HeadingSource heading);
  // The line through the grid's wall beside `door` (relative to its middle); false when
  // there is none to trust.
  static bool grid_wall_line(const DoorPassage& door, const GridView& grid, double& angle_rad,
                             Eigen::Vector2d& through);
  // `visit` for each of the scan's points beside `door` (relative to its middle).
  template <typename Visit>
  static void for_each_scan_point(const core::DepthScan& scan, const core::Pose2& pose, const DoorPassage& door,
                                  Visit visit);
  struct HeadingSearch {
    int on_line = 0;
    double turn_rad = 0.0;
    double offset_m = 0.0;  // the band's middle from the grid's line
  };
  static bool touches_image_edge(int first, int last, int columns);
  // Whether `column` of `scan` (taken at `pose`) saw past the door's line; its point in `point`.
  static bool sees_past(const core::DepthScan& scan, const core::Pose2& pose, const DoorPassage& door, int column,
                        Eigen::Vector2d& point);
  // `column`'s point in the map frame of `pose`; false for a column that measured nothing.
  static bool measured_point(const core::DepthScan& scan, const core::Pose2& pose, int column, Eigen::Vector2d& point);

  double range_m_ = 0.0;
  double max_offset_m_ = 0.0;
  bool wall_from_scan_ = false;
  bool correct_heading_ = false;
  double baseline_m_ = 0.0;
  double last_scan_time_s_ = -1.0;
  bool held_ = false;
  bool heading_held_ = false;    // the held sighting's heading was corrected (wall or held)
  DoorPassage door_;             // the door the held sighting is of
  core::Pose2 sighted_pose_;     // the scan's pose, corrected
  core::Pose2 sighted_odometry_; // the odometry at the scan
  Eigen::Vector2d offset_ = Eigen::Vector2d::Zero();
  double heading_correction_rad_ = 0.0;
  DoorSightingCounters counters_;
};

}  // namespace stereoscout::explore
