#pragma once
// Stereo matching of SIFT keys (paper section IV): for every key of the right (reference)
// image, the best left key on the same row (within a tolerance) whose disparity lies within
// limits, kept only if it passes the distinctiveness (ratio) test.
//
// Left keys are bucketed by row once per frame, so a right key only looks at the few rows
// its epipolar band covers; the result is identical to a brute-force search over all left
// keys (ties are broken by the smaller left index).

#include <cstdint>

#include "stereoscout/core/config/vision.hpp"
#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/vision/keypoints.hpp"

namespace stereoscout::vision {

struct StereoMatchParams {
  double epipolar_tolerance_px = 2.0;
  double min_disparity_px = 1.0;
  double max_disparity_px = 128.0;
  double ratio = 0.8;  // best distance < ratio * second best distance
};

StereoMatchParams match_params_from_config(const core::VisionConfig& vision);

struct StereoMatch {
  std::uint32_t right_index = 0;
  std::uint32_t left_index = 0;
  float disparity_px = 0.0F;            // x_left - x_right
  std::uint32_t distance_squared = 0;   // descriptor distance of the best left key
};

// True when the pair (left, right) may match: epipolar band and disparity limits.
bool is_stereo_candidate(const StereoMatchParams& params, const Keypoint& left, const Keypoint& right);
// The ratio test on squared distances; a key with no second candidate passes.
bool passes_ratio_test(double ratio, std::uint32_t best_squared, std::uint32_t second_squared, bool has_second);

class StereoMatcher {
 public:
  // Buffers sized for `max_keys` left keys and images `image_height_px` rows high.
  StereoMatcher(const StereoMatchParams& params, int image_height_px, std::size_t max_keys);

  // Clears `matches` and fills it in the order of the right keys. No heap allocation.
  void match(const core::FixedVector<Keypoint>& left, const core::FixedVector<Keypoint>& right,
             core::FixedVector<StereoMatch>& matches);

  std::uint64_t rejected_by_ratio() const { return rejected_by_ratio_; }

 private:
  void bucket_left_keys(const core::FixedVector<Keypoint>& left);
  int row_of(float y_px) const;

  StereoMatchParams params_;
  int height_;
  core::FixedVector<std::uint32_t> row_start_;    // height + 1 offsets into sorted_left_
  core::FixedVector<std::uint32_t> row_cursor_;   // placement cursor per row
  core::FixedVector<std::uint32_t> sorted_left_;  // left key indices, by row then index
  std::uint64_t rejected_by_ratio_ = 0;
};

}  // namespace stereoscout::vision
