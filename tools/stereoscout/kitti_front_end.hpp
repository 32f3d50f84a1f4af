#pragma once
// The vision front end of `stereoscout slam --kitti`, stage by stage so each stage can be
// timed (report.json: SIFT, stereo matching, index lookup). It is the pipeline of
// vision::VisionFrontEnd::observe_landmarks built from the same public parts of the vision
// module (SiftExtractor, StereoMatcher, DescriptorIndex, triangulate) with the same config,
// so its observations are the front end's; only the stopwatch between stages is added.

#include <cstdint>

#include "stereoscout/core/config/vision.hpp"
#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/core/messages.hpp"
#include "stereoscout/vision/calibration.hpp"
#include "stereoscout/vision/descriptor_index.hpp"
#include "stereoscout/vision/front_end.hpp"
#include "stereoscout/vision/sift_extractor.hpp"
#include "stereoscout/vision/stereo_matcher.hpp"

namespace stereoscout::cli::kitti {

// Seconds spent per stage, summed over the frames of a run.
struct StageTimes {
  double sift_s = 0.0;
  double stereo_matching_s = 0.0;
  double index_lookup_s = 0.0;  // descriptor index and triangulation
  double filter_update_s = 0.0;
};

class TimedFrontEnd {
 public:
  TimedFrontEnd(const core::VisionConfig& vision, const vision::StereoCalibration& calibration);

  // Clears `observations` and fills it with the identified landmarks of this pair (right image
  // the reference), adding each stage's time to `times`.
  void observe(const core::StereoFrame& frame, core::FixedVector<core::LandmarkObservation>& observations,
               StageTimes& times);

  const vision::FrontEndFrameStats& last_frame_stats() const { return stats_; }
  const vision::DescriptorIndex& index() const { return index_; }
  std::size_t max_observations() const { return max_keys_; }

 private:
  vision::StereoCalibration calibration_;
  vision::StereoNoise noise_;
  std::size_t max_keys_;
  vision::SiftExtractor left_sift_;
  vision::SiftExtractor right_sift_;
  core::FixedVector<vision::Keypoint> left_keys_;
  core::FixedVector<vision::Keypoint> right_keys_;
  vision::StereoMatcher matcher_;
  core::FixedVector<vision::StereoMatch> matches_;
  vision::DescriptorIndex index_;
  std::uint64_t frame_counter_ = 0;
  vision::FrontEndFrameStats stats_;
};

}  // namespace stereoscout::cli::kitti
