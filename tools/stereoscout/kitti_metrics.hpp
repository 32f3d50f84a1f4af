#pragma once
// Scores of a run on a KITTI sequence against its ground truth (host tool code).

#include <cstdint>
#include <vector>

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::cli::kitti {

// Absolute trajectory error: RMSE of the positions after the best 2D rigid alignment of
// `estimated` onto `truth` in the ground plane (paired by index; same length).
double planar_ate_rmse(const std::vector<core::Pose2>& estimated, const std::vector<core::Pose2>& truth);

// Relative pose error per metre: from every frame i, the first frame j at least `segment_m`
// further along the true path; the error of the estimated relative translation (in frame i)
// against the true one, divided by the true path length from i to j, averaged over all i
// that have such a j. A path shorter than `segment_m` is one segment from first to last
// frame. Returns 0 when the truth does not move.
double relative_error_per_metre(const std::vector<core::Pose2>& estimated, const std::vector<core::Pose2>& truth,
                                double segment_m);

}  // namespace stereoscout::cli::kitti
