#pragma once
// The straightest wall of an obstacle scan, for a heading observation (ManhattanFrame).
//
// The scan's columns run in bearing order, so a wall is a run of neighbouring obstacle
// columns whose points lie close together. Each run (points within max_range_m of the
// camera, no two neighbours more than max_gap_m apart) is split at its point farthest from
// its chord while that lies more than three times max_rms_m off (a corner, a jamb before a
// wall), and each piece is fitted with a total-least-squares line. The longest piece with at
// least min_points points, at least min_length_m long and no more than max_rms_m off its
// line is the wall. No allocation.

#include "stereoscout/core/config/filter.hpp"
#include "stereoscout/core/messages.hpp"

namespace stereoscout::slam {

struct WallLineParams {
  double min_length_m = 1.0;
  double max_range_m = 3.0;
  double max_rms_m = 0.03;
  double max_gap_m = 0.15;
  int min_points = 20;  // enough for the rms to say whether the points lie on a line
};

WallLineParams wall_line_params_from_config(const core::FilterConfig& config);

struct WallLine {
  double direction_rad = 0.0;  // of the line in the robot frame, in [0, pi)
  double length_m = 0.0;       // extent of its points along the line
  double rms_m = 0.0;          // of its points' distances from the line
  int points = 0;
};

// False when the scan holds no run that passes.
bool fit_wall_line(const core::DepthScan& scan, const WallLineParams& params, WallLine& line);

}  // namespace stereoscout::slam
