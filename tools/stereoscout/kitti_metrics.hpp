#pragma once
// Scores of a run on a KITTI sequence against its ground truth (host tool code).

#include <cstdint>
#include <map>
#include <vector>

#include <Eigen/Geometry>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"

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

// The identity check on real images: does a landmark the index re-identifies land where it
// was before? Every identity keeps its stereo points fused in the world frame by the true
// camera poses (the estimate a filter would store with a perfect trajectory); a re-observation
// is consistent when that stored estimate, moved into the current camera by the true motion,
// agrees with the new stereo point within the sum of both covariances (chi-square gate).
class ReobservationCheck {
 public:
  explicit ReobservationCheck(double gate_chi2) : gate_chi2_(gate_chi2) {}

  // All observations of one frame, in the optical frame of the camera at `world_from_camera`.
  void observe(const Eigen::Isometry3d& world_from_camera, const core::LandmarkObservation* observations,
               std::size_t count);

  std::uint64_t reobservations() const { return reobservations_; }
  std::uint64_t consistent() const { return consistent_; }
  double consistency() const {
    return reobservations_ == 0 ? 0.0 : static_cast<double>(consistent_) / static_cast<double>(reobservations_);
  }

 private:
  struct Stored {
    Eigen::Vector3d mean_world;
    Eigen::Matrix3d covariance_world;
  };
  double gate_chi2_;
  std::map<std::uint32_t, Stored> stored_;  // ordered by identity: no hash order anywhere
  std::uint64_t reobservations_ = 0;
  std::uint64_t consistent_ = 0;
};

}  // namespace stereoscout::cli::kitti
