#include "kitti_front_end.hpp"

#include <chrono>

namespace stereoscout::cli::kitti {
namespace {

using Clock = std::chrono::steady_clock;

// Wall time only feeds the report's timings, never a result.
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

TimedFrontEnd::TimedFrontEnd(const core::VisionConfig& vision, const vision::StereoCalibration& calibration)
    : calibration_(calibration),
      noise_(vision::noise_from_config(vision)),
      max_keys_(static_cast<std::size_t>(vision.max_features)),
      left_sift_(vision::sift_params_from_config(vision)),
      right_sift_(vision::sift_params_from_config(vision)),
      left_keys_(max_keys_),
      right_keys_(max_keys_),
      matcher_(vision::match_params_from_config(vision), calibration.height_px, max_keys_),
      matches_(max_keys_),
      index_(vision::index_params_from_config(vision)) {}

void TimedFrontEnd::observe(const core::StereoFrame& frame, core::FixedVector<core::LandmarkObservation>& observations,
                            StageTimes& times) {
  observations.clear();
  stats_ = vision::FrontEndFrameStats{};
  Clock::time_point start = Clock::now();
  left_sift_.extract(frame.left, left_keys_);
  right_sift_.extract(frame.right, right_keys_);
  times.sift_s += seconds_since(start);

  start = Clock::now();
  matcher_.match(left_keys_, right_keys_, matches_);
  times.stereo_matching_s += seconds_since(start);

  start = Clock::now();
  const std::uint64_t frame_index = frame_counter_++;
  stats_.left_keys = left_keys_.size();
  stats_.right_keys = right_keys_.size();
  stats_.stereo_matches = matches_.size();
  for (const vision::StereoMatch& match : matches_) {
    const vision::Keypoint& key = right_keys_[match.right_index];
    const vision::IndexLookup lookup = index_.observe(key.descriptor, frame_index);
    switch (lookup.outcome) {
      case vision::IndexLookup::Outcome::candidate: ++stats_.candidate_sightings; continue;
      case vision::IndexLookup::Outcome::new_candidate: ++stats_.new_candidates; continue;
      case vision::IndexLookup::Outcome::refused: ++stats_.refused; continue;
      case vision::IndexLookup::Outcome::landmark: break;
    }
    const vision::StereoPoint point = vision::triangulate(calibration_, noise_, key.x_px, key.y_px, match.disparity_px);
    core::LandmarkObservation* observation = observations.emplace_back();
    if (observation == nullptr) {
      ++stats_.dropped;
      continue;
    }
    observation->landmark_id = lookup.landmark_id;
    observation->point_camera = point.point_camera;
    observation->covariance = point.covariance;
    ++stats_.landmark_observations;
  }
  times.index_lookup_s += seconds_since(start);
}

}  // namespace stereoscout::cli::kitti
