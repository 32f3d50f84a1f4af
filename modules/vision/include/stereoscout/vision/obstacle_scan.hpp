#pragma once
// The 2.5D obstacle scan (paper section V): a planar-laser-like scan made from dense stereo
// that also sees obstacles a planar laser would miss (a low box, a table top).
//
// Every valid pixel of the (left-referenced) disparity map is triangulated (eq. 3), moved into
// the robot frame at capture time with core::robot_from_camera (mount and pan) and filed
// under its column in the RIGHT image (x_left - d), so every column is a ray from the right
// camera's centre, `origin_robot`, the origin the occupancy grid ray-casts from. Per column:
//   - a point higher than floor_tolerance_m above the floor and lower than the robot's height
//     is an obstacle point; the column's obstacle is the nearest such point, confirmed by
//     min_obstacle_pixels obstacle points no farther than it (a single mismatch cannot make
//     a phantom obstacle);
//   - a point within floor_tolerance_m of the floor is free floor; one measured below the
//     floor is moved up its pixel's ray to the floor plane (floor_onto_plane): on a flat floor
//     its disparity error alone put it lower and farther;
//   - points above the robot or below the floor are ignored.
// The column reports the obstacle (kind obstacle), else free space up to the farthest floor
// point (kind free), else nothing (kind invalid). A free column also reports the standard
// deviation of its end's range from a disparity error of sigma_d_px, range * sigma_d / d
// (0.11 m at 3 m, 0.2 m at 4 m for the paper's 0.5 px): the farthest of a column's floor
// points is the one whose error put it farthest out, at a wall's base beyond the wall (the
// grid's free_end_sigmas, occupancy_grid.hpp), unless floor_onto_plane has moved it back.
// Ranges are capped at max_range_m: farther obstacles are ignored and farther floor is
// reported as free up to the cap.
// A table top at 0.75 m is below a 1.2 m robot, so it is an obstacle even though the space
// under it is free floor: the robot cannot drive under it.
// Every column also carries floor_visible_from_m: where the ray of the image's bottom
// row in that column meets the floor, measured on the floor from `origin_robot` (about 1 m
// for the paper's head at 0.6 m). Nearer floor, and a low obstacle on it, is out of view, so
// the occupancy grid must not clear cells there. It does not depend on the pan angle (a turn
// about the vertical axis keeps floor distances), so it is computed once per column.
// And measurable_from_m: the nearest distance the column can measure at all. A point at
// right column c with disparity d is left pixel c + d, so the largest disparity the matcher
// gives there, min(max_disparity_px, last matched left column - c), bounds how near it can
// be. Towards the right image's right edge that is far (the left camera does not see the
// near part of the view), and a column there would otherwise report floor far behind an
// obstacle it cannot see: the grid must not clear cells nearer than that. A column that can
// measure nothing within max_range_m is invalid.
// A blank wall gives stereo no disparity, so a column facing one would see floor up to the
// wall and nothing else, and report free space with the wall's cell left unknown (the office
// corridor's walls: the robot drove into them). So a column with no obstacle whose floor
// ends nearer than blank_wall_within_m, with no point off the floor seen farther than
// same_surface_depth_m beyond that end (at any height: a far wall above the horizon, a
// ceiling), reports an obstacle where its floor ends, provided the view above that end is
// blank: at least blank_wall_untextured_fraction of the left image's pixels from the floor's
// end up to the horizon row were rejected by the matcher for lack of texture
// (kUntexturedDisparity). The floor also ends where the matcher is confused, beside the edge
// of a near object that the two cameras see differently, with open floor beyond; an obstacle
// there closes a free passage. Farther out the floor's texture fades (the office's tiles at
// about 2 m, below a blank ceiling): its end there is not a wall.
// Given the left image as well, a column with no obstacle looks first for the wall's base
// (wall_base.hpp): the brightness step where a blank wall meets the floor, within
// wall_base_within_m on the floor plane (farther than the floor's end is trusted: the row of
// a step gives its range by geometry, not by the floor's fading texture). It puts the wall
// where it stands, not where the matched floor happens to end, and it also finds walls
// faced head-on whose floor strip was not matched at all. It must agree with the stereo: no floor or other point seen more than
// same_surface_depth_m beyond it, and beyond blank_wall_within_m some floor matched in the
// column (facing something nearer than the matcher's largest disparity reaches, nothing is
// matched, and a step near the horizon would pass for a far base). Failing that, the
// floor's end as above. Both kinds of blank-wall obstacle are marked blank_wall.
// An obstacle column is also marked obstacle_at_camera_height when the column holds an
// obstacle point within floor_tolerance_m of the camera's height no more than
// same_surface_depth_m behind the obstacle: such an obstacle (a person, a wall) stays in view
// at any range, so the grid may clear it when a later view looks through its cell.
// The dense matcher sees nothing nearer than its largest disparity (0.63 m from the camera on
// the default head), and the robot's disc reaches 0.45 m ahead of it: a surface that comes into
// view nearer than that, beside the robot as it turns (a low box's corner), is in no column.
// add_near_matches() takes such surfaces from the sparse stereo matches, which reach twice as
// near: a match whose disparity exceeds the dense matcher's, above the floor and below the
// robot, becomes its column's obstacle unless the column already holds a nearer one it
// measured, if three things hold. The dense matcher found little around it: at most
// near_max_dense_valid of the disparities in the near_window_px square around it are valid (a surface
// nearer than its reach has no match in its range, so it leaves holes; where it found a
// surface, the sparse match is a repeated texture matched one period off, the simulated
// clutter hall's every frame). Its patch matches only that near: the sum of absolute
// differences of that square patch at its disparity (give or take a pixel)
// is below near_uniqueness times the smallest at any disparity the dense matcher covers (a
// repeated texture the dense matcher left holes in, for its ambiguity, matches a period
// nearer as well). And near_min_matches such matches (itself included) lie within
// same_surface_depth_m of it on the floor.

#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "stereoscout/core/config/robot.hpp"
#include "stereoscout/core/config/vision.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"
#include "stereoscout/vision/calibration.hpp"
#include "stereoscout/vision/wall_base.hpp"

namespace stereoscout::vision {

struct ObstacleScanParams {
  double floor_tolerance_m = 0.05;
  double robot_height_m = 1.2;
  double max_range_m = 6.0;
  int min_obstacle_pixels = 4;
  // How far behind a column's nearest obstacle point a point at the camera's height still
  // counts as the same obstacle (a person's legs and chest, a wall's face).
  double same_surface_depth_m = 0.15;
  // What the disparity map can hold, for each column's measurable_from_m: the largest
  // disparity (dense_num_disparities - 1), and the columns at the left image's right edge the
  // matcher leaves unmatched (its window and census radii).
  int max_disparity_px = 63;
  int unmatched_border_px = 6;
  // A column whose floor ends nearer than this with nothing seen beyond it reports an
  // obstacle where the floor ends (a blank wall); 0: never.
  double blank_wall_within_m = 1.5;
  // ... and at least this fraction of the pixels above the floor's end are untextured.
  double blank_wall_untextured_fraction = 0.5;
  // The brightness step at a blank wall's base (wall_base.hpp); 0: the floor's end only.
  double wall_base_min_step_grey = 12.0;
  // ... looked for this far out on the floor plane.
  double wall_base_within_m = 3.5;
  // The disparity error of a matched pixel, for a free column's end_range_sigma_m.
  double sigma_d_px = 0.5;
  // A floor point measured below the floor is moved up its ray onto the floor plane
  // (vision.scan_floor_onto_plane).
  bool floor_onto_plane = true;
  // add_near_matches(): the matches that must agree on a near surface (0: off), and the most
  // matches it looks at (the keypoints of an image).
  int near_min_matches = 0;
  int max_near_matches = 500;
  // ... and a match counts only where at most this fraction of the dense disparities around it
  // are valid (vision.scan_near_max_dense_valid),
  double near_max_dense_valid = 0.4;
  // ... and where its patch's difference at its disparity is below this fraction of the
  // smallest at any disparity the dense matcher covers (vision.scan_near_uniqueness).
  double near_uniqueness = 0.7;
  // ... both judged in this square window around the match, odd (vision.scan_near_window_px).
  int near_window_px = 11;
};

ObstacleScanParams scan_params_from_config(const core::VisionConfig& vision, const core::RobotConfig& robot);

class ObstacleScanner {
 public:
  ObstacleScanner(const ObstacleScanParams& params, const StereoCalibration& calibration,
                  const core::CameraMount& mount);

  // Sizes scan.columns to one entry per image column (start-up only).
  void allocate(core::DepthScan& scan) const;

  // disparity: CV_32FC1 referenced to the left image (DenseDisparityMatcher); left: the
  // 8-bit grey left image it was matched from, for the walls' bases (empty: none, as for a
  // disparity map that came from ground-truth depth). No allocation.
  void compute(const cv::Mat& disparity, const cv::Mat& left, double pan_rad, std::int64_t timestamp_ns,
               core::DepthScan& scan);
  void compute(const cv::Mat& disparity, double pan_rad, std::int64_t timestamp_ns, core::DepthScan& scan) {
    compute(disparity, cv::Mat(), pan_rad, timestamp_ns, scan);
  }

  // A sparse stereo match of the same pair: where it is in the left image, and its disparity.
  struct NearMatch {
    float x_left_px = 0.0F;
    float y_px = 0.0F;
    float disparity_px = 0.0F;
  };
  // After compute() on the same pair (same pan, same disparity map): the matches nearer than
  // the dense matcher reaches become obstacles of their columns (see above); the others are
  // ignored. Looks at the first max_near_matches. Nothing happens with near_min_matches 0. No
  // allocation. Returns how many columns took an obstacle from them. left and right: the
  // pair's rectified 8-bit grey images.
  std::size_t add_near_matches(const NearMatch* matches, std::size_t count, const cv::Mat& disparity,
                               const cv::Mat& left, const cv::Mat& right, double pan_rad, core::DepthScan& scan);
  bool near_matches_used() const { return params_.near_min_matches > 0; }

 private:
  struct Candidate {
    double range_m = 0.0;
    double x_m = 0.0;
    double y_m = 0.0;
  };
  struct NearPoint {
    int column = 0;
    double range_m = 0.0;
    double x_m = 0.0;
    double y_m = 0.0;
    bool at_camera_height = false;
  };
  bool dense_matcher_found_little(const cv::Mat& disparity, const NearMatch& match) const;
  bool matches_only_that_near(const cv::Mat& left, const cv::Mat& right, const NearMatch& match) const;
  std::size_t near_points_of(const NearMatch* matches, std::size_t count, const cv::Mat& disparity,
                             const cv::Mat& left, const cv::Mat& right, const Eigen::Isometry3d& robot_from_camera);
  bool near_point_supported(const NearPoint& point, std::size_t count) const;
  struct ColumnState {
    int obstacle_points = 0;  // entries used in this column's slice of nearest_
    bool has_floor = false;
    Candidate farthest_floor;
    int floor_end_x_left = 0;  // left-image pixel of farthest_floor
    int floor_end_row = 0;
    double nearest_at_camera_height_m = 1e9;  // range of the nearest obstacle point there
    double farthest_off_floor_m = 0.0;        // range of the farthest point not on the floor
    bool has_wall_base = false;
    Candidate wall_base;                      // the nearest wall base filed under this column
  };
  bool wall_base_agrees_with_stereo(const ColumnState& state) const;
  bool floor_ends_at_unseen_surface(const ColumnState& state) const;
  double free_end_range_sigma(const cv::Mat& disparity, const ColumnState& state) const;
  bool nothing_seen_beyond(const ColumnState& state, double range_m) const;
  void add_wall_bases(const cv::Mat& disparity, const cv::Mat& left, const Eigen::Isometry3d& robot_from_camera);
  bool blank_above_floor_end(const cv::Mat& disparity, const ColumnState& state) const;
  void reset_columns();
  void add_point(int column, int x_left, int row, const Eigen::Vector3d& point, const Eigen::Vector3d& origin);
  void keep_nearest(ColumnState& state, Candidate* nearest, const Candidate& candidate) const;

  ObstacleScanParams params_;
  StereoCalibration calibration_;
  core::CameraMount mount_;
  std::size_t per_column_;                 // min_obstacle_pixels
  std::vector<ColumnState> columns_;       // one per image column, sized at construction
  std::vector<Candidate> nearest_;         // per column: its nearest obstacle points, sorted
  std::vector<float> floor_visible_from_m_;  // per column, from the calibration and mount
  std::vector<float> measurable_from_m_;     // per column, from the calibration and mount
  std::vector<NearPoint> near_;              // add_near_matches' points, max_near_matches
  int horizon_row_;                          // image row of level rays (mount tilt; nose down is up)
};

}  // namespace stereoscout::vision
