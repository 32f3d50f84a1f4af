#include "stereoscout/vision/dense_disparity.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "stereoscout/core/check.hpp"

namespace stereoscout::vision {
namespace {

using detail::kCensusRadius;
using detail::kMaxCensusCost;

}  // namespace

DenseDisparityParams dense_params_from_config(const core::VisionConfig& vision, double baseline_m) {
  DenseDisparityParams params;
  params.num_disparities = vision.dense_num_disparities;
  params.window_px = vision.dense_window_px;
  params.uniqueness_ratio = vision.dense_uniqueness_ratio;
  params.min_texture = vision.dense_min_texture;
  params.lr_tolerance_px = vision.dense_lr_tolerance_px;
  params.speckle_max_region_px = vision.dense_speckle_max_region_px;
  params.speckle_max_step_px = vision.dense_speckle_max_step_px;
  params.speckle_min_area_m2 = vision.dense_speckle_min_area_m2;
  params.speckle_area_apart_px = vision.dense_speckle_area_apart_px;
  params.baseline_m = baseline_m;
  return params;
}

DenseDisparityMatcher::DenseDisparityMatcher(const DenseDisparityParams& params, int width_px, int height_px)
    : params_(params),
      width_(width_px),
      height_(height_px),
      disparities_(params.num_disparities),
      radius_(params.window_px / 2),
      speckle_filter_({params.speckle_max_region_px, params.speckle_max_step_px, params.speckle_min_area_m2, params.baseline_m,
                       params.speckle_area_apart_px},
                      width_px, height_px) {
  STEREOSCOUT_CHECK(width_px > 0 && height_px > 0 && disparities_ >= 2, "DenseDisparityMatcher: bad size");
  const auto pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  const auto row_costs = static_cast<std::size_t>(disparities_) * static_cast<std::size_t>(width_);
  census_left_.resize(pixels);
  census_right_.resize(pixels);
  cost_ring_.resize(row_costs * static_cast<std::size_t>(2 * radius_ + 1));
  column_sums_.resize(row_costs);
  aggregated_.resize(row_costs);
  box_scratch_.resize(static_cast<std::size_t>(detail::kMaxBoxLevels) * static_cast<std::size_t>(width_));
  best_cost_.resize(static_cast<std::size_t>(width_));
  second_cost_.resize(static_cast<std::size_t>(width_));
  best_disparity_.resize(static_cast<std::size_t>(width_));
  right_best_cost_.resize(static_cast<std::size_t>(width_));
  right_best_disparity_.resize(static_cast<std::size_t>(width_));
  kernels_ = detail::fastest_dense_kernels(params.allow_simd);
  gradient_integral_.resize(static_cast<std::size_t>(width_ + 1) * static_cast<std::size_t>(height_ + 1));
}

void DenseDisparityMatcher::allocate_output(cv::Mat& disparity) const {
  disparity.create(height_, width_, CV_32FC1);
}

// Integral image of the absolute horizontal gradient of the left image (texture check).
void DenseDisparityMatcher::texture_integral(const cv::Mat& left) {
  const auto stride = static_cast<std::size_t>(width_ + 1);
  std::fill(gradient_integral_.begin(), gradient_integral_.begin() + static_cast<std::ptrdiff_t>(stride), 0);
  for (int y = 0; y < height_; ++y) {
    const std::uint8_t* row = left.ptr<std::uint8_t>(y);
    std::int32_t* out = &gradient_integral_[static_cast<std::size_t>(y + 1) * stride];
    const std::int32_t* above = &gradient_integral_[static_cast<std::size_t>(y) * stride];
    out[0] = 0;
    std::int32_t row_sum = 0;
    for (int x = 0; x < width_; ++x) {
      const int before = row[std::max(x - 1, 0)];
      const int after = row[std::min(x + 1, width_ - 1)];
      row_sum += std::abs(after - before);
      out[x + 1] = above[x + 1] + row_sum;
    }
  }
}

bool DenseDisparityMatcher::has_texture(int x, int y) const {
  const auto stride = static_cast<std::size_t>(width_ + 1);
  const auto at = [&](int xx, int yy) {
    return gradient_integral_[static_cast<std::size_t>(yy) * stride + static_cast<std::size_t>(xx)];
  };
  const int x0 = x - radius_;
  const int x1 = x + radius_ + 1;
  const int y0 = y - radius_;
  const int y1 = y + radius_ + 1;
  const std::int32_t sum = at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
  const double area = static_cast<double>(params_.window_px) * static_cast<double>(params_.window_px);
  return static_cast<double>(sum) >= params_.min_texture * area;
}

// Census cost of left pixel (x, y) against right pixel (x - d, y), laid out [d][x].
void DenseDisparityMatcher::cost_row(int y, std::uint8_t* costs) const {
  const std::uint64_t* left = &census_left_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_)];
  const std::uint64_t* right = &census_right_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_)];
  for (int d = 0; d < disparities_; ++d) {
    std::uint8_t* out = costs + static_cast<std::ptrdiff_t>(d) * width_;
    const int first = std::min(d + kCensusRadius, width_);
    for (int x = 0; x < first; ++x) {
      out[x] = kMaxCensusCost;
    }
    kernels_.census_costs(left, right, out, first, width_, d);
  }
}

// Horizontal box sum of the column sums, per disparity.
void DenseDisparityMatcher::aggregate_row() {
  kernels_.box_sum(column_sums_.data(), aggregated_.data(), box_scratch_.data(), disparities_, width_, radius_);
}

// Winners of one row for every left pixel (best and best non-adjacent cost) and for every
// right pixel (for the left-right check).
void DenseDisparityMatcher::find_winners() {
  detail::WinnerBuffers buffers;
  buffers.aggregated = aggregated_.data();
  buffers.width = width_;
  buffers.disparities = disparities_;
  buffers.first_x = radius_ + kCensusRadius;
  buffers.last_x = width_ - 1 - radius_ - kCensusRadius;
  buffers.best_cost = best_cost_.data();
  buffers.second_cost = second_cost_.data();
  buffers.best_disparity = best_disparity_.data();
  buffers.right_best_cost = right_best_cost_.data();
  buffers.right_best_disparity = right_best_disparity_.data();
  kernels_.winners(buffers);
}

// Validity checks and subpixel refinement of one row's winners.
void DenseDisparityMatcher::select_row(int y, float* disparity_row) {
  find_winners();
  const int first_x = radius_ + kCensusRadius;
  const int last_x = width_ - 1 - radius_ - kCensusRadius;
  const auto cost_at = [&](int d, int x) {
    return aggregated_[static_cast<std::size_t>(d) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)];
  };
  for (int x = first_x; x <= last_x; ++x) {
    const auto column = static_cast<std::size_t>(x);
    const int max_d = std::min(disparities_ - 1, x - first_x);
    const int best = best_disparity_[column];
    const std::uint16_t best_cost = best_cost_[column];
    const std::uint16_t second = second_cost_[column];
    float& out = disparity_row[x];
    out = kInvalidDisparity;
    if (!has_texture(x, y)) {
      out = kUntexturedDisparity;
      ++stats_.rejected_texture;
      continue;
    }
    if (second != 0xFFFF && static_cast<double>(best_cost) * (1.0 + params_.uniqueness_ratio) >= static_cast<double>(second)) {
      ++stats_.rejected_uniqueness;
      continue;
    }
    const int right_choice = right_best_disparity_[static_cast<std::size_t>(x - best)];
    if (right_choice < 0 || std::abs(right_choice - best) > params_.lr_tolerance_px) {
      ++stats_.rejected_left_right;
      continue;
    }
    double refined = best;
    if (best > 0 && best < max_d) {
      // Parabola through the costs at best - 1, best, best + 1.
      const double before = cost_at(best - 1, x);
      const double at = best_cost;
      const double after = cost_at(best + 1, x);
      const double curvature = before - 2.0 * at + after;
      if (curvature > 0.0) {
        refined += std::clamp(0.5 * (before - after) / curvature, -0.5, 0.5);
      }
    }
    out = static_cast<float>(refined);
    ++stats_.valid;
  }
}

void DenseDisparityMatcher::compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity) {
  STEREOSCOUT_CHECK(left.type() == CV_8UC1 && right.type() == CV_8UC1 && left.cols == width_ &&
                        left.rows == height_ && right.cols == width_ && right.rows == height_,
                    "DenseDisparityMatcher::compute: images must be 8-bit grey of the constructed size");
  STEREOSCOUT_CHECK(disparity.type() == CV_32FC1 && disparity.cols == width_ && disparity.rows == height_,
                    "DenseDisparityMatcher::compute: output not allocated (allocate_output)");
  stats_ = DenseDisparityStats{};
  stats_.pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  for (int y = 0; y < height_; ++y) {
    float* row = disparity.ptr<float>(y);
    std::fill(row, row + width_, kInvalidDisparity);  // cv::Mat::setTo would allocate
  }
  kernels_.census(left.ptr<std::uint8_t>(0), left.step[0], width_, height_, census_left_.data());
  kernels_.census(right.ptr<std::uint8_t>(0), right.step[0], width_, height_, census_right_.data());
  texture_integral(left);
  const int first_y = radius_ + kCensusRadius;
  const int last_y = height_ - 1 - radius_ - kCensusRadius;
  const int window = 2 * radius_ + 1;
  const std::size_t row_costs = column_sums_.size();
  const auto slot = [&](int row) { return &cost_ring_[static_cast<std::size_t>(row % window) * row_costs]; };
  std::fill(column_sums_.begin(), column_sums_.end(), 0);
  for (int y = first_y; y <= last_y; ++y) {
    if (y == first_y) {
      for (int row = y - radius_; row <= y + radius_; ++row) {
        std::uint8_t* costs = slot(row);
        cost_row(row, costs);
        kernels_.add_costs(column_sums_.data(), costs, row_costs);
      }
    } else {
      // The row leaving the window and the row entering it share a ring slot.
      std::uint8_t* costs = slot(y + radius_);
      kernels_.subtract_costs(column_sums_.data(), costs, row_costs);
      cost_row(y + radius_, costs);
      kernels_.add_costs(column_sums_.data(), costs, row_costs);
    }
    aggregate_row();
    select_row(y, disparity.ptr<float>(y));
  }
  stats_.rejected_speckle = speckle_filter_.apply(disparity, kInvalidDisparity);
  stats_.valid -= stats_.rejected_speckle;
  stats_.border = stats_.pixels - stats_.valid - stats_.rejected_texture - stats_.rejected_uniqueness -
                  stats_.rejected_left_right - stats_.rejected_speckle;
}

DisparityScore score_disparity(const cv::Mat& disparity, const cv::Mat& ground_truth, double scale) {
  STEREOSCOUT_CHECK(disparity.type() == CV_32FC1 && disparity.size() == ground_truth.size() &&
                        (ground_truth.type() == CV_8UC1 || ground_truth.type() == CV_16UC1),
                    "score_disparity: maps of different sizes or types");
  DisparityScore score;
  std::size_t bad_1 = 0;
  std::size_t bad_2 = 0;
  for (int y = 0; y < disparity.rows; ++y) {
    for (int x = 0; x < disparity.cols; ++x) {
      const double raw = ground_truth.type() == CV_8UC1 ? ground_truth.at<std::uint8_t>(y, x)
                                                        : ground_truth.at<std::uint16_t>(y, x);
      if (raw <= 0.0) {
        continue;
      }
      ++score.known;
      const float value = disparity.at<float>(y, x);
      if (value < 0.0F) {
        continue;
      }
      ++score.valid;
      const double error = std::abs(static_cast<double>(value) - raw / scale);
      bad_1 += error > 1.0 ? 1U : 0U;
      bad_2 += error > 2.0 ? 1U : 0U;
    }
  }
  if (score.valid > 0) {
    score.bad_1 = static_cast<double>(bad_1) / static_cast<double>(score.valid);
    score.bad_2 = static_cast<double>(bad_2) / static_cast<double>(score.valid);
  }
  if (score.known > 0) {
    score.density = static_cast<double>(score.valid) / static_cast<double>(score.known);
    score.bad_2_all = static_cast<double>(bad_2 + score.known - score.valid) / static_cast<double>(score.known);
  }
  return score;
}

}  // namespace stereoscout::vision
