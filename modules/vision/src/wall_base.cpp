#include "stereoscout/vision/wall_base.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "stereoscout/vision/dense_disparity.hpp"

namespace stereoscout::vision {
namespace {

// Difference of the mean brightness of the bands just above and just below `row`.
double step_at(const cv::Mat& left, int x, int row) {
  int above = 0;
  int below = 0;
  for (int k = 1; k <= kStepBandRows; ++k) {
    above += left.ptr<std::uint8_t>(row - k)[x];
    below += left.ptr<std::uint8_t>(row + k)[x];
  }
  return std::abs(above - below) / static_cast<double>(kStepBandRows);
}

}  // namespace

double find_wall_base_row(const cv::Mat& left, const cv::Mat& disparity, int x_left, int horizon_row,
                          const WallBaseParams& params) {
  if (params.min_step_grey <= 0.0) return -1.0;
  const int first = std::max(horizon_row, kStepBandRows);
  const int last = left.rows - 1 - kStepBandRows;
  int untextured = 0;
  for (int row = first; row <= last; ++row) {
    untextured += disparity.ptr<float>(row)[x_left] == kUntexturedDisparity ? 1 : 0;
    double step = step_at(left, x_left, row);
    if (step < params.min_step_grey) continue;
    // The first band pair to reach the threshold still overlaps the edge; it is sharpest
    // where the step peaks.
    while (row < last) {
      const double next = step_at(left, x_left, row + 1);
      if (next <= step) break;
      step = next;
      ++row;
      untextured += disparity.ptr<float>(row)[x_left] == kUntexturedDisparity ? 1 : 0;
    }
    const int run = row - first + 1;
    if (untextured < params.untextured_fraction * run) return -1.0;
    return row + 0.5;
  }
  return -1.0;
}

}  // namespace stereoscout::vision
