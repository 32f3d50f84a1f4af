#include "stereoscout/vision/stereo_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stereoscout::vision {

StereoMatchParams match_params_from_config(const core::VisionConfig& vision) {
  return {vision.epipolar_tolerance_px, vision.min_disparity_px, vision.max_disparity_px, vision.match_ratio,
          vision.stereo_cross_check};
}

bool is_stereo_candidate(const StereoMatchParams& params, const Keypoint& left, const Keypoint& right) {
  const double row_difference = std::fabs(static_cast<double>(left.y_px) - static_cast<double>(right.y_px));
  const double disparity = static_cast<double>(left.x_px) - static_cast<double>(right.x_px);
  return row_difference <= params.epipolar_tolerance_px && disparity >= params.min_disparity_px &&
         disparity <= params.max_disparity_px;
}

bool passes_ratio_test(double ratio, std::uint32_t best_squared, std::uint32_t second_squared, bool has_second) {
  if (!has_second) {
    return true;
  }
  // Lowe's distinctiveness test, compared on squared distances.
  return static_cast<double>(best_squared) < ratio * ratio * static_cast<double>(second_squared);
}

RowBuckets::RowBuckets(int image_height_px, std::size_t max_keys)
    : height_(std::max(image_height_px, 1)),
      row_start_(static_cast<std::size_t>(height_) + 1),
      row_cursor_(static_cast<std::size_t>(height_)),
      sorted_(max_keys) {
  for (int i = 0; i <= height_; ++i) {
    row_start_.push_back(0);
    if (i < height_) {
      row_cursor_.push_back(0);
    }
  }
  for (std::size_t i = 0; i < max_keys; ++i) {
    sorted_.push_back(0);
  }
}

int RowBuckets::row_of(float y_px) const {
  const int row = static_cast<int>(std::floor(y_px));
  return std::clamp(row, 0, height_ - 1);
}

// Counting sort by row: stable, so each row lists its keys by index.
void RowBuckets::build(const core::FixedVector<Keypoint>& keys) {
  STEREOSCOUT_CHECK(keys.size() <= sorted_.size(), "RowBuckets: more keys than its capacity");
  for (std::uint32_t& start : row_start_) {
    start = 0;
  }
  for (const Keypoint& key : keys) {
    ++row_start_[static_cast<std::size_t>(row_of(key.y_px)) + 1];
  }
  for (std::size_t row = 1; row < row_start_.size(); ++row) {
    row_start_[row] += row_start_[row - 1];
  }
  for (std::size_t row = 0; row < row_cursor_.size(); ++row) {
    row_cursor_[row] = row_start_[row];
  }
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const auto row = static_cast<std::size_t>(row_of(keys[i].y_px));
    sorted_[row_cursor_[row]++] = static_cast<std::uint32_t>(i);
  }
}

StereoMatcher::StereoMatcher(const StereoMatchParams& params, int image_height_px, std::size_t max_keys)
    : params_(params), left_buckets_(image_height_px, max_keys), right_buckets_(image_height_px, max_keys) {}

StereoMatcher::Best StereoMatcher::best_partner(const Keypoint& key, bool key_is_right,
                                                const core::FixedVector<Keypoint>& others,
                                                const RowBuckets& buckets) const {
  Best best;
  const auto tolerance = static_cast<float>(params_.epipolar_tolerance_px);
  const int first_row = buckets.row_of(key.y_px - tolerance);
  const int last_row = buckets.row_of(key.y_px + tolerance);
  for (int row = first_row; row <= last_row; ++row) {
    for (std::uint32_t k = buckets.begin(row); k < buckets.end(row); ++k) {
      const std::uint32_t other = buckets.key_at(k);
      const bool candidate = key_is_right ? is_stereo_candidate(params_, others[other], key)
                                          : is_stereo_candidate(params_, key, others[other]);
      if (!candidate) {
        continue;
      }
      const std::uint32_t distance = descriptor_distance_squared(others[other].descriptor, key.descriptor);
      if (!best.found() || distance < best.distance || (distance == best.distance && other < best.index)) {
        if (best.found()) {
          best.second = best.distance;
          best.has_second = true;
        }
        best.index = other;
        best.distance = distance;
      } else if (!best.has_second || distance < best.second) {
        best.second = distance;
        best.has_second = true;
      }
    }
  }
  return best;
}

void StereoMatcher::match(const core::FixedVector<Keypoint>& left, const core::FixedVector<Keypoint>& right,
                          core::FixedVector<StereoMatch>& matches) {
  matches.clear();
  left_buckets_.build(left);
  if (params_.cross_check) {
    right_buckets_.build(right);
  }
  for (std::size_t r = 0; r < right.size(); ++r) {
    const Best best = best_partner(right[r], true, left, left_buckets_);
    if (!best.found()) {
      continue;
    }
    if (!passes_ratio_test(params_.ratio, best.distance, best.second, best.has_second)) {
      ++rejected_by_ratio_;
      continue;
    }
    if (params_.cross_check && best_partner(left[best.index], false, right, right_buckets_).index != r) {
      ++rejected_by_cross_check_;
      continue;
    }
    StereoMatch match;
    match.right_index = static_cast<std::uint32_t>(r);
    match.left_index = best.index;
    match.disparity_px = left[best.index].x_px - right[r].x_px;
    match.distance_squared = best.distance;
    matches.push_back(match);
  }
}

}  // namespace stereoscout::vision
