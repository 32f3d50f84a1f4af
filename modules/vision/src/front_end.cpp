#include "stereoscout/vision/front_end.hpp"

#include <thread>

#include "stereoscout/core/check.hpp"

namespace stereoscout::vision {

VisionFrontEnd::VisionFrontEnd(const core::VisionConfig& vision, const core::RobotConfig& robot,
                               const StereoCalibration& calibration, const core::CameraMount& mount)
    : calibration_(calibration),
      noise_(noise_from_config(vision)),
      parallel_sift_(vision.sift_parallel),
      max_keys_(static_cast<std::size_t>(vision.max_features)),
      left_sift_(sift_params_from_config(vision)),
      right_sift_(sift_params_from_config(vision)),
      left_keys_(max_keys_),
      right_keys_(max_keys_),
      matcher_(match_params_from_config(vision), calibration.height_px, max_keys_),
      matches_(max_keys_),
      near_matches_(max_keys_),
      index_(index_params_from_config(vision)),
      dense_(dense_params_from_config(vision, calibration.baseline_m), calibration.width_px, calibration.height_px),
      scanner_(scan_params_from_config(vision, robot), calibration, mount) {
  dense_.allocate_output(disparity_);
}

void VisionFrontEnd::extract_keys(const core::StereoFrame& frame) {
  if (parallel_sift_) {
    // Each image has its own extractor and output, so the result equals the sequential run.
    std::thread left_worker([&] { left_sift_.extract(frame.left, left_keys_); });
    right_sift_.extract(frame.right, right_keys_);
    left_worker.join();
  } else {
    left_sift_.extract(frame.left, left_keys_);
    right_sift_.extract(frame.right, right_keys_);
  }
}

bool VisionFrontEnd::frame_is_usable(const core::StereoFrame& frame) const {
  const auto usable = [&](const cv::Mat& image) {
    return image.type() == CV_8UC1 && image.cols == calibration_.width_px && image.rows == calibration_.height_px;
  };
  return usable(frame.left) && usable(frame.right);
}

core::Status VisionFrontEnd::observe_landmarks(const core::StereoFrame& frame,
                                               core::FixedVector<core::LandmarkObservation>& observations) {
  observations.clear();
  frame_stats_ = FrontEndFrameStats{};
  matches_valid_ = false;
  if (!frame_is_usable(frame)) {
    ++rejected_frames_;
    return {core::StatusCode::invalid_input, "stereo pair is not 8-bit grey of the calibrated size"};
  }
  std::int64_t stage_start = now();
  extract_keys(frame);
  frame_stats_.sift_ns = now() - stage_start;
  stage_start = now();
  matcher_.match(left_keys_, right_keys_, matches_);
  matches_valid_ = true;
  matches_timestamp_ns_ = frame.timestamp_ns;
  frame_stats_.matching_ns = now() - stage_start;
  stage_start = now();
  const std::uint64_t frame_index = frame_counter_++;
  frame_stats_.left_keys = left_keys_.size();
  frame_stats_.right_keys = right_keys_.size();
  frame_stats_.stereo_matches = matches_.size();
  for (const StereoMatch& match : matches_) {
    const Keypoint& key = right_keys_[match.right_index];
    const IndexLookup lookup = index_.observe(key.descriptor, frame_index);
    switch (lookup.outcome) {
      case IndexLookup::Outcome::candidate: ++frame_stats_.candidate_sightings; continue;
      case IndexLookup::Outcome::new_candidate: ++frame_stats_.new_candidates; continue;
      case IndexLookup::Outcome::refused: ++frame_stats_.refused; continue;
      case IndexLookup::Outcome::landmark: break;
    }
    const StereoPoint point = triangulate(calibration_, noise_, key.x_px, key.y_px, match.disparity_px);
    core::LandmarkObservation* observation = observations.emplace_back();
    if (observation == nullptr) {
      ++frame_stats_.dropped;
      continue;
    }
    observation->landmark_id = lookup.landmark_id;
    observation->point_camera = point.point_camera;
    observation->covariance = point.covariance;
    ++frame_stats_.landmark_observations;
  }
  frame_stats_.identify_ns = now() - stage_start;
  return core::Status::success();
}

std::int64_t VisionFrontEnd::now() const { return stopwatch_ != nullptr ? stopwatch_->now_ns() : 0; }

core::Status VisionFrontEnd::scan(const core::StereoFrame& frame, core::DepthScan& scan) {
  if (!frame_is_usable(frame)) {
    ++rejected_frames_;
    return {core::StatusCode::invalid_input, "stereo pair is not 8-bit grey of the calibrated size"};
  }
  near_columns_ = 0;
  dense_.compute(frame.left, frame.right, disparity_);
  scanner_.compute(disparity_, frame.left, frame.pan_rad, frame.timestamp_ns, scan);
  if (scanner_.near_matches_used() && matches_valid_ && matches_timestamp_ns_ == frame.timestamp_ns) {
    add_near_matches(frame, scan);
  }
  return core::Status::success();
}

void VisionFrontEnd::add_near_matches(const core::StereoFrame& frame, core::DepthScan& scan) {
  near_matches_.clear();
  for (const StereoMatch& match : matches_) {
    const Keypoint& left = left_keys_[match.left_index];
    ObstacleScanner::NearMatch* near = near_matches_.emplace_back();
    if (near == nullptr) break;
    *near = {left.x_px, left.y_px, match.disparity_px};
  }
  near_columns_ = scanner_.add_near_matches(near_matches_.data(), near_matches_.size(), disparity_, frame.left,
                                            frame.right, frame.pan_rad, scan);
}

}  // namespace stereoscout::vision
