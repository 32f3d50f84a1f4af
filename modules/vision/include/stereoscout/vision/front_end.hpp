#pragma once
// The vision front end of one stereo sensor (paper sections IV and V), wired from config:
//
//   StereoFrame --SIFT (left, right)--> keys --epipolar matching--> stereo matches
//     --eq. 3, C = J S J^T--> 3D points --descriptor index--> LandmarkObservation list
//   StereoFrame --census block matcher--> disparity --column scan--> DepthScan
//
// Everything is sized at construction from config and the calibration. After that only
// cv::SIFT allocates (its pyramid, inside OpenCV); matching, triangulation, the index, the
// dense matcher and the scan do not touch the heap.
// scan() writes only the dense matcher's and the scanner's parts; with
// vision.scan_near_min_matches it reads the stereo matches observe_landmarks() found in the
// same pair. So the stack runs scan() on a thread of its own once observe_landmarks() has
// returned, beside the filter update (vision.scan_parallel); rejected_frames() is atomic.

#include <atomic>
#include <cstdint>

#include <opencv2/core/mat.hpp>

#include "stereoscout/core/config/robot.hpp"
#include "stereoscout/core/config/vision.hpp"
#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/logging.hpp"
#include "stereoscout/core/messages.hpp"
#include "stereoscout/core/status.hpp"
#include "stereoscout/vision/calibration.hpp"
#include "stereoscout/vision/dense_disparity.hpp"
#include "stereoscout/vision/descriptor_index.hpp"
#include "stereoscout/vision/obstacle_scan.hpp"
#include "stereoscout/vision/sift_extractor.hpp"
#include "stereoscout/vision/stereo_matcher.hpp"

namespace stereoscout::vision {

struct FrontEndFrameStats {
  std::size_t left_keys = 0;
  std::size_t right_keys = 0;
  std::size_t stereo_matches = 0;
  std::size_t landmark_observations = 0;  // handed to the filter
  std::size_t candidate_sightings = 0;    // matched a candidate not yet seen often enough
  std::size_t new_candidates = 0;
  std::size_t refused = 0;                // index full (see DescriptorIndex)
  std::size_t dropped = 0;                // observation list full
  // Stage times of this frame, when a stopwatch is set (set_stopwatch); 0 otherwise.
  std::int64_t sift_ns = 0;
  std::int64_t matching_ns = 0;
  std::int64_t identify_ns = 0;           // descriptor index and triangulation
};

class VisionFrontEnd {
 public:
  VisionFrontEnd(const core::VisionConfig& vision, const core::RobotConfig& robot,
                 const StereoCalibration& calibration, const core::CameraMount& mount);

  // Clears `observations` and fills it with the identified landmarks of this pair, in the
  // order of the right image's keys (strongest first). Each call is one frame of the index.
  // A pair that is not two 8-bit grey images of the calibrated size is skipped, counted in
  // rejected_frames(), and reported as invalid_input.
  core::Status observe_landmarks(const core::StereoFrame& frame, core::FixedVector<core::LandmarkObservation>& observations);

  // The stereo matches of the last observe_landmarks call, with the keys they refer to.
  const core::FixedVector<StereoMatch>& last_matches() const { return matches_; }
  const core::FixedVector<Keypoint>& last_left_keys() const { return left_keys_; }
  const core::FixedVector<Keypoint>& last_right_keys() const { return right_keys_; }

  void allocate_scan(core::DepthScan& scan) const { scanner_.allocate(scan); }
  // Dense disparity and the 2.5D scan of this pair (scan sized by allocate_scan), with the
  // surfaces nearer than the dense matcher reaches taken from the stereo matches when
  // observe_landmarks() was called on this pair last (ObstacleScanner::add_near_matches). A
  // bad pair is skipped (scan unchanged), counted, and reported as invalid_input.
  core::Status scan(const core::StereoFrame& frame, core::DepthScan& scan);
  std::uint64_t rejected_frames() const { return rejected_frames_; }
  const cv::Mat& last_disparity() const { return disparity_; }
  // Scan columns the last scan() took from the stereo matches (vision.scan_near_min_matches).
  std::size_t last_near_columns() const { return near_columns_; }

  const FrontEndFrameStats& last_frame_stats() const { return frame_stats_; }
  // Times each stage of observe_landmarks for reports. Measurement only: what the front end
  // computes never depends on it. nullptr (the default) turns timing off.
  void set_stopwatch(const core::TimeSource* stopwatch) { stopwatch_ = stopwatch; }
  const DescriptorIndex& index() const { return index_; }
  std::size_t max_observations() const { return max_keys_; }

 private:
  void extract_keys(const core::StereoFrame& frame);
  std::int64_t now() const;
  bool frame_is_usable(const core::StereoFrame& frame) const;
  void add_near_matches(const core::StereoFrame& frame, core::DepthScan& scan);

  StereoCalibration calibration_;
  StereoNoise noise_;
  bool parallel_sift_;
  std::size_t max_keys_;
  SiftExtractor left_sift_;
  SiftExtractor right_sift_;
  core::FixedVector<Keypoint> left_keys_;
  core::FixedVector<Keypoint> right_keys_;
  StereoMatcher matcher_;
  core::FixedVector<StereoMatch> matches_;
  bool matches_valid_ = false;           // matches_ are of the pair stamped matches_timestamp_ns_
  std::int64_t matches_timestamp_ns_ = 0;
  core::FixedVector<ObstacleScanner::NearMatch> near_matches_;
  std::size_t near_columns_ = 0;
  DescriptorIndex index_;
  DenseDisparityMatcher dense_;
  cv::Mat disparity_;
  ObstacleScanner scanner_;
  std::uint64_t frame_counter_ = 0;
  std::atomic<std::uint64_t> rejected_frames_{0};
  FrontEndFrameStats frame_stats_;
  const core::TimeSource* stopwatch_ = nullptr;
};

}  // namespace stereoscout::vision
