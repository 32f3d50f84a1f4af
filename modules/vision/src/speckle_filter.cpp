#include "stereoscout/vision/speckle_filter.hpp"

#include <algorithm>
#include <cmath>

#include "stereoscout/core/check.hpp"

namespace stereoscout::vision {

SpeckleFilter::SpeckleFilter(const SpeckleFilterParams& params, int width_px, int height_px)
    : params_(params), width_(width_px), height_(height_px) {
  STEREOSCOUT_CHECK(width_px > 0 && height_px > 0 && params.max_region_px >= 0 && params.max_step_px >= 0.0,
                    "SpeckleFilter: bad size or parameters");
  const auto pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  visited_.resize(pixels);
  region_.resize(pixels);
}

// Breadth-first growth from `seed` over unvisited valid neighbours within max_step_px; the
// queue keeps every member, so a small region can be erased afterwards. Returns its size.
std::size_t SpeckleFilter::grow_region(cv::Mat& disparity, int seed) {
  const auto* values = disparity.ptr<float>(0);
  const auto step = static_cast<float>(params_.max_step_px);
  std::size_t size = 0;
  std::size_t next = 0;
  region_[size++] = seed;
  visited_[static_cast<std::size_t>(seed)] = 1;
  while (next < size) {
    const std::int32_t pixel = region_[next++];
    const int x = pixel % width_;
    const int y = pixel / width_;
    const float value = values[pixel];
    const auto visit = [&](std::int32_t neighbour) {
      const auto index = static_cast<std::size_t>(neighbour);
      if (visited_[index] != 0 || !(values[index] >= 0.0F) || std::fabs(values[index] - value) > step) {
        return;
      }
      visited_[index] = 1;
      region_[size++] = neighbour;
    };
    if (x > 0) visit(pixel - 1);
    if (x + 1 < width_) visit(pixel + 1);
    if (y > 0) visit(pixel - width_);
    if (y + 1 < height_) visit(pixel + width_);
  }
  return size;
}

std::size_t SpeckleFilter::apply(cv::Mat& disparity, float invalid_value) {
  STEREOSCOUT_CHECK(disparity.type() == CV_32FC1 && disparity.cols == width_ && disparity.rows == height_ &&
                        disparity.isContinuous(),
                    "SpeckleFilter::apply: disparity must be a continuous CV_32FC1 map of the constructed size");
  if (params_.max_region_px <= 0) {
    return 0;
  }
  std::fill(visited_.begin(), visited_.end(), std::uint8_t{0});
  float* values = disparity.ptr<float>(0);
  const int pixels = width_ * height_;
  std::size_t removed = 0;
  for (int pixel = 0; pixel < pixels; ++pixel) {
    if (visited_[static_cast<std::size_t>(pixel)] != 0 || !(values[pixel] >= 0.0F)) {
      continue;
    }
    const std::size_t size = grow_region(disparity, pixel);
    if (size <= static_cast<std::size_t>(params_.max_region_px)) {
      for (std::size_t i = 0; i < size; ++i) {
        values[region_[i]] = invalid_value;
      }
      removed += size;
    }
  }
  return removed;
}

}  // namespace stereoscout::vision
