#pragma once
// Stereo matching of SIFT keys (paper section IV): for every key of the right (reference)
// image, the best left key on the same row (within a tolerance) whose disparity lies within
// limits, kept only if it passes the distinctiveness (ratio) test. With cross_check on (our
// addition), the left key's own best right key must be the same key: on repetitive texture
// this removes most false matches that the ratio test lets through.
//
// Keys are bucketed by row once per frame, so a key only looks at the few rows its
// epipolar band covers; the result is identical to a brute-force search over all keys
// (ties are broken by the smaller index).

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
  bool cross_check = true;
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

// Keys of one image listed by integer row (a counting sort), rebuilt every frame.
class RowBuckets {
 public:
  RowBuckets(int image_height_px, std::size_t max_keys);
  void build(const core::FixedVector<Keypoint>& keys);
  int row_of(float y_px) const;
  int height() const { return height_; }
  std::uint32_t begin(int row) const { return row_start_[static_cast<std::size_t>(row)]; }
  std::uint32_t end(int row) const { return row_start_[static_cast<std::size_t>(row) + 1]; }
  std::uint32_t key_at(std::uint32_t position) const { return sorted_[position]; }

 private:
  int height_;
  core::FixedVector<std::uint32_t> row_start_;  // height + 1 offsets into sorted_
  core::FixedVector<std::uint32_t> row_cursor_;
  core::FixedVector<std::uint32_t> sorted_;     // key indices, by row then index
};

class StereoMatcher {
 public:
  // Buffers sized for `max_keys` keys per image and images `image_height_px` rows high.
  StereoMatcher(const StereoMatchParams& params, int image_height_px, std::size_t max_keys);

  // Clears `matches` and fills it in the order of the right keys. No heap allocation.
  void match(const core::FixedVector<Keypoint>& left, const core::FixedVector<Keypoint>& right,
             core::FixedVector<StereoMatch>& matches);

  std::uint64_t rejected_by_ratio() const { return rejected_by_ratio_; }
  std::uint64_t rejected_by_cross_check() const { return rejected_by_cross_check_; }

 private:
  struct Best {
    std::uint32_t index = 0xFFFFFFFFU;
    std::uint32_t distance = 0;
    std::uint32_t second = 0;
    bool has_second = false;
    bool found() const { return index != 0xFFFFFFFFU; }
  };
  // Best key of `others` (bucketed in `buckets`) for `key`; `key_is_right` says which image
  // `key` comes from, for the disparity sign.
  Best best_partner(const Keypoint& key, bool key_is_right, const core::FixedVector<Keypoint>& others,
                    const RowBuckets& buckets) const;

  StereoMatchParams params_;
  RowBuckets left_buckets_;
  RowBuckets right_buckets_;
  std::uint64_t rejected_by_ratio_ = 0;
  std::uint64_t rejected_by_cross_check_ = 0;
};

}  // namespace stereoscout::vision
