#pragma once
// Where a blank wall stands on the floor, found in the left image. Stereo gives a wall
// without texture no disparity at all, and the strip of floor at its base is often not
// matched either (plain tile interiors), so the floor's matched part can end 0.3-0.6 m
// short of the wall, or, head-on within about 1.5 m, not be matched at all. The wall's
// foot is still plain to see: a step in brightness between the floor and the wall, with
// the wall blank from there up past the horizon. On a flat floor the row of that step gives
// the wall's range (the floor-plane ray of that row), as in appearance-based obstacle
// detection on mobile robots; the stereo's part is to say that the run above is blank.
//
// Down each column of the left image from the horizon row, the first row where the mean
// brightness of the kStepBandRows rows above and of those below differ by at least
// min_step_grey ends the run; its row is where that difference peaks. It is a wall's base
// only if at least untextured_fraction of the run's pixels (horizon to base) were rejected by
// the matcher for lack of texture (kUntexturedDisparity): anything the matcher could see
// (furniture, a person, a poster) is the scan's to measure. The first step ends the search
// whatever it is: a tile's edge or a grout line steps too, but on open floor the first one
// below the horizon mostly lies far away, beyond the scan's wall_base_within_m, and the
// scan keeps a base only where stereo saw nothing beyond it (sweeps of rendered views of
// the three worlds: docs/results.md).

#include <opencv2/core/mat.hpp>

namespace stereoscout::vision {

struct WallBaseParams {
  double min_step_grey = 12.0;         // 0: never a wall base
  double untextured_fraction = 0.5;    // of the run's pixels, horizon to base
};

// Rows averaged on either side of a candidate step: three rows cut the sensor's noise
// (2 grey levels in the simulator) to about a grey level per band.
inline constexpr int kStepBandRows = 3;

// The boundary between the wall's last row and the floor's first in column x_left (a
// half-integer row), or a negative value when the column has no blank wall base below
// horizon_row. left: 8-bit grey; disparity: the matcher's left-referenced map of the pair.
double find_wall_base_row(const cv::Mat& left, const cv::Mat& disparity, int x_left, int horizon_row,
                          const WallBaseParams& params);

}  // namespace stereoscout::vision
