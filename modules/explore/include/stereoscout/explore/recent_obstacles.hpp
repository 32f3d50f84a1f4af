#pragma once
// What the recent scans saw standing at the camera's height, kept in the odometry frame: a
// local obstacle layer that does not move with the map (explore.recent_obstacle_s).
//
// The grid the explorer plans on is the estimate particle's, rolled up along that particle's
// trajectory; when the estimate moves to another lineage the grid near the robot is re-rolled
// from other poses, and a jamb or a stretch of wall the robot saw a moment ago can be shifted
// or erased in it (docs/results.md, office seed 6: a door held 0.3 m east of the truth, a 1 m
// gap in a wall). Wheel odometry drifts centimetres over a few metres, so obstacles kept in its
// frame stay where they were relative to the robot while it passes them, out of the camera's
// view beside it or nearer than the matcher measures in front of it. stamp() marks their cells
// occupied in the grid the explorer plans on and checks its moves against, placed from the
// robot's current pose.
//
// A point is forgotten when a later scan saw past it (the floor or a surface beyond it, in
// every column around its bearing, farther than the matcher's near limit): a person who walked
// on, a stray match. Otherwise after recent_obstacle_s, or once the odometry has driven
// recent_obstacle_travel_m since it was kept (its drift grows with distance, not time).
//
// With recent_obstacle_blank_walls the scan's blank-wall columns are kept too: the base of a
// wall stereo did not measure (a door's jambs in the office's blank corridor walls).
//
// With recent_obstacle_estimate_heading the points are kept in a layer frame instead: its
// heading is the estimate's, its translation the odometry's, each stretch driven between scans
// turned by the estimate's heading at the stretch's start. Odometry's heading drifts most in a
// turn in place (a look), where its translation hardly moves; the filter's heading is held by
// the landmarks.
// Buffers are allocated by the constructor; observe() and stamp() allocate nothing.

#include <cstddef>
#include <cstdint>
#include <memory>

#include <Eigen/Core>

#include "stereoscout/core/config/explore.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/explore/grid_view.hpp"
#include "stereoscout/explore/seen_obstacles.hpp"

namespace stereoscout::explore {

class RecentObstacles {
 public:
  // Points kept from one scan's obstacle columns are at least this far apart (adjacent columns
  // of a wall 1.5 m away are 4 mm apart; a tenth-metre grid cell needs a few, not forty).
  static constexpr double kPointSpacing_m = 0.03;
  // Bearings are compared in bins of this width (a 640-pixel image at 400 px focal length has
  // 0.14 degrees a column: seven columns a bin).
  static constexpr int kBearingBins = 360;
  // A later scan sees past a point when it measured the floor or a surface this much beyond it
  // (the scan's same-surface depth), plus twice a free column's end-range sigma.
  static constexpr double kSeenPastMargin_m = 0.15;
  // A blank-wall point is kept only when the scan before had one this near it (in the layer
  // frame): a wall's base is found again from 0.06 m further on (0.5 s at 0.12 m/s), a
  // brightness step on the floor seen through a door for one scan is not (office seed 1: such
  // a step 0.55 m inside S2's door, in one scan, closed the door for the plans).
  static constexpr double kBlankConfirm_m = 0.05;
  // Blank-wall points of one scan remembered for that (a scan has 640 columns).
  static constexpr std::size_t kMaxBlankPerScan = 1024;
  // gap_ahead()'s `support` at most.
  static constexpr int kMaxGapSupport = 8;

  // max_width x max_height: the largest grid stamp() must copy.
  RecentObstacles(const core::ExploreConfig& config, int max_width, int max_height);

  bool enabled() const { return keep_s_ > 0.0; }

  // A new scan (seen.scan, taken at seen.odometry and seen.pose; a scan already observed is
  // ignored):
  // forgets the kept points it saw past, then keeps its obstacle columns at the camera's
  // height within recent_obstacle_range_m of the camera.
  void observe(const SeenObstacles& seen);
  // Forgets points older than recent_obstacle_s or kept more than recent_obstacle_travel_m of
  // driving ago, then returns `grid` with the cells holding recent_obstacle_min_points kept
  // points occupied, the points placed from `pose` (the robot's map pose now) by the odometry
  // since (`odometry`: the odometry pose now; its heading not used with
  // recent_obstacle_estimate_heading): a copy in the memory's own buffer, or `grid`
  // itself when no cell changes (or it is larger than the buffer, counted). Valid until the
  // next call.
  GridView stamp(const GridView& grid, const core::Pose2& pose, const core::Pose2& odometry, double time_s);

  // The gap between kept points just ahead of the robot, in the robot's frame (x forward, y
  // left): of the points from `behind_m` behind the robot's centre to `ahead_m` ahead of it and
  // within `aside_m` of its centre line, the `support`-th nearest the line on either side (so
  // that a lone stray match does not make a side). False when either side has fewer.
  struct Gap {
    Eigen::Vector2d left = Eigen::Vector2d::Zero();
    Eigen::Vector2d right = Eigen::Vector2d::Zero();
  };
  bool gap_ahead(const core::Pose2& pose, const core::Pose2& odometry, double behind_m, double ahead_m, double aside_m,
                 int support, Gap& gap) const;

  std::size_t held() const { return size_; }
  std::uint64_t kept() const { return kept_; }
  std::uint64_t seen_past() const { return seen_past_; }
  std::uint64_t expired() const { return expired_; }  // by time or by distance driven
  double driven_m() const { return driven_m_; }      // odometry path length over the scans
  std::uint64_t dropped_full() const { return dropped_full_; }
  std::uint64_t blank_unconfirmed() const { return blank_unconfirmed_; }  // blank-wall points the scan before lacked
  std::uint64_t cells_stamped() const { return cells_stamped_; }  // over all stamp() calls
  std::uint64_t grid_too_large() const { return grid_too_large_; }

 private:
  struct Point {
    Eigen::Vector2d layer_xy = Eigen::Vector2d::Zero();  // in the layer frame (layer_pose())
    double time_s = 0.0;
    double driven_m = 0.0;  // the odometry path length when it was kept
  };
  // What one scan saw past, per bearing bin from its camera origin (robot frame).
  struct BearingBin {
    float seen_past_m = 0.0F;     // the nearest range the bin's columns measured anything at
    float measurable_m = 0.0F;    // the farthest of their near limits
    bool measured = false;
  };

  // The robot's pose in the frame the points are kept in: the odometry pose, or with
  // estimate_heading_ the layer pose at the last scan moved by the odometry's translation since,
  // with the estimate's heading (`pose`).
  core::Pose2 layer_pose(const core::Pose2& pose, const core::Pose2& odometry) const;
  void forget_seen_past(const core::DepthScan& scan, const core::Pose2& layer);
  void keep_columns(const core::DepthScan& scan, const core::Pose2& layer, double time_s);
  bool confirmed_blank(const Eigen::Vector2d& layer_xy);
  bool outlived(const Point& point, double time_s) const;  // past either limit
  void drop_oldest(std::size_t count);
  static int bin_of(double bearing_rad);

  double keep_s_ = 0.0;
  double travel_m_ = 0.0;  // 0: no distance limit
  double range_m_ = 0.0;
  int min_points_ = 1;
  bool estimate_heading_ = false;
  bool blank_walls_ = false;  // recent_obstacle_blank_walls
  std::size_t capacity_ = 0;
  std::unique_ptr<Point[]> points_;  // oldest first
  std::size_t size_ = 0;
  BearingBin bins_[kBearingBins];
  double last_scan_time_s_ = -1.0;
  core::Pose2 last_scan_odometry_;
  core::Pose2 last_scan_layer_;
  double driven_m_ = 0.0;
  // stamp(): per-cell counts, reset through the list of cells touched.
  std::size_t cell_capacity_ = 0;
  std::unique_ptr<std::uint8_t[]> counts_;
  std::unique_ptr<std::uint8_t[]> cells_;
  std::unique_ptr<std::size_t[]> touched_;
  // recent_obstacle_blank_walls: the previous scan's blank-wall points and this scan's (layer frame).
  std::unique_ptr<Eigen::Vector2d[]> blank_previous_;
  std::unique_ptr<Eigen::Vector2d[]> blank_current_;
  std::size_t blank_previous_size_ = 0;
  std::size_t blank_current_size_ = 0;
  std::uint64_t blank_unconfirmed_ = 0;
  std::uint64_t kept_ = 0;
  std::uint64_t seen_past_ = 0;
  std::uint64_t expired_ = 0;
  std::uint64_t dropped_full_ = 0;
  std::uint64_t cells_stamped_ = 0;
  std::uint64_t grid_too_large_ = 0;
};

}  // namespace stereoscout::explore
