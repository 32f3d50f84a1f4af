#include "stereoscout/vision/stereo_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stereoscout::vision {

StereoMatchParams match_params_from_config(const core::VisionConfig& vision) {
  return {vision.epipolar_tolerance_px, vision.min_disparity_px, vision.max_disparity_px, vision.match_ratio};
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

StereoMatcher::StereoMatcher(const StereoMatchParams& params, int image_height_px, std::size_t max_keys)
    : params_(params),
      height_(std::max(image_height_px, 1)),
      row_start_(static_cast<std::size_t>(height_) + 1),
      row_cursor_(static_cast<std::size_t>(height_)),
      sorted_left_(max_keys) {
  for (int i = 0; i <= height_; ++i) {
    row_start_.push_back(0);
    if (i < height_) {
      row_cursor_.push_back(0);
    }
  }
  for (std::size_t i = 0; i < max_keys; ++i) {
    sorted_left_.push_back(0);
  }
}

int StereoMatcher::row_of(float y_px) const {
  const int row = static_cast<int>(std::floor(y_px));
  return std::clamp(row, 0, height_ - 1);
}

// Counting sort of the left keys by row: stable, so each row lists its keys by index.
void StereoMatcher::bucket_left_keys(const core::FixedVector<Keypoint>& left) {
  for (std::uint32_t& start : row_start_) {
    start = 0;
  }
  for (const Keypoint& key : left) {
    ++row_start_[static_cast<std::size_t>(row_of(key.y_px)) + 1];
  }
  for (std::size_t row = 1; row < row_start_.size(); ++row) {
    row_start_[row] += row_start_[row - 1];
  }
  for (std::size_t row = 0; row + 1 < row_start_.size(); ++row) {
    row_cursor_[row] = row_start_[row];
  }
  for (std::size_t i = 0; i < left.size(); ++i) {
    const auto row = static_cast<std::size_t>(row_of(left[i].y_px));
    sorted_left_[row_cursor_[row]++] = static_cast<std::uint32_t>(i);
  }
}

void StereoMatcher::match(const core::FixedVector<Keypoint>& left, const core::FixedVector<Keypoint>& right,
                          core::FixedVector<StereoMatch>& matches) {
  matches.clear();
  STEREOSCOUT_CHECK(left.size() <= sorted_left_.size(), "StereoMatcher: more left keys than its capacity");
  bucket_left_keys(left);
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  for (std::size_t r = 0; r < right.size(); ++r) {
    const Keypoint& right_key = right[r];
    const auto tolerance = static_cast<float>(params_.epipolar_tolerance_px);
    const int first_row = row_of(right_key.y_px - tolerance);
    const int last_row = row_of(right_key.y_px + tolerance);
    std::uint32_t best = kNone;
    std::uint32_t best_distance = std::numeric_limits<std::uint32_t>::max();
    std::uint32_t second_distance = std::numeric_limits<std::uint32_t>::max();
    bool has_second = false;
    for (int row = first_row; row <= last_row; ++row) {
      const std::uint32_t begin = row_start_[static_cast<std::size_t>(row)];
      const std::uint32_t end = row_start_[static_cast<std::size_t>(row) + 1];
      for (std::uint32_t k = begin; k < end; ++k) {
        const std::uint32_t l = sorted_left_[k];
        if (!is_stereo_candidate(params_, left[l], right_key)) {
          continue;
        }
        const std::uint32_t distance = descriptor_distance_squared(left[l].descriptor, right_key.descriptor);
        if (best == kNone || distance < best_distance || (distance == best_distance && l < best)) {
          if (best != kNone) {
            second_distance = best_distance;
            has_second = true;
          }
          best = l;
          best_distance = distance;
        } else if (!has_second || distance < second_distance) {
          second_distance = distance;
          has_second = true;
        }
      }
    }
    if (best == kNone) {
      continue;
    }
    if (!passes_ratio_test(params_.ratio, best_distance, second_distance, has_second)) {
      ++rejected_by_ratio_;
      continue;
    }
    StereoMatch match;
    match.right_index = static_cast<std::uint32_t>(r);
    match.left_index = best;
    match.disparity_px = left[best].x_px - right_key.x_px;
    match.distance_squared = best_distance;
    matches.push_back(match);
  }
}

}  // namespace stereoscout::vision
