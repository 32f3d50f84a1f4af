#include "kitti_metrics.hpp"

#include <cmath>

#include "mrclam.hpp"

namespace stereoscout::cli::kitti {

double planar_ate_rmse(const std::vector<core::Pose2>& estimated, const std::vector<core::Pose2>& truth) {
  std::vector<Eigen::Vector2d> from;
  std::vector<Eigen::Vector2d> to;
  for (std::size_t i = 0; i < estimated.size() && i < truth.size(); ++i) {
    from.push_back(estimated[i].translation());
    to.push_back(truth[i].translation());
  }
  // The MRCLAM scoring's best 2D rigid fit of paired points, reused for trajectories.
  return mrclam::score_landmarks(from, to).rmse_m;
}

double relative_error_per_metre(const std::vector<core::Pose2>& estimated, const std::vector<core::Pose2>& truth,
                                double segment_m) {
  const std::size_t n = std::min(estimated.size(), truth.size());
  std::vector<double> path(n, 0.0);  // true distance travelled up to each frame
  for (std::size_t i = 1; i < n; ++i) {
    path[i] = path[i - 1] + (truth[i].translation() - truth[i - 1].translation()).norm();
  }
  double sum = 0.0;
  std::size_t segments = 0;
  const auto add_segment = [&](std::size_t i, std::size_t j) {
    const Eigen::Vector2d true_motion = truth[i].between(truth[j]).translation();
    const Eigen::Vector2d estimated_motion = estimated[i].between(estimated[j]).translation();
    sum += (estimated_motion - true_motion).norm() / (path[j] - path[i]);
    ++segments;
  };
  std::size_t j = 0;
  for (std::size_t i = 0; i < n; ++i) {
    while (j < n && path[j] - path[i] < segment_m) ++j;
    if (j == n) break;  // no full segment starts here or later
    add_segment(i, j);
  }
  // A sequence shorter than one segment: its whole path is the one segment.
  if (segments == 0 && n > 1 && path[n - 1] > 1e-6) add_segment(0, n - 1);
  return segments == 0 ? 0.0 : sum / static_cast<double>(segments);
}

}  // namespace stereoscout::cli::kitti
