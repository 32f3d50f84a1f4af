#include "stereoscout/vision/speckle_filter.hpp"

#include <algorithm>
#include <cmath>

#include "stereoscout/core/check.hpp"

namespace stereoscout::vision {

SpeckleFilter::SpeckleFilter(const SpeckleFilterParams& params, int width_px, int height_px)
    : params_(params), width_(width_px), height_(height_px) {
  STEREOSCOUT_CHECK(width_px > 0 && height_px > 0 && params.max_region_px >= 0 && params.max_step_px >= 0.0 &&
                        params.min_area_m2 >= 0.0 && params.baseline_m >= 0.0 && params.area_apart_px >= 0.0,
                    "SpeckleFilter: bad size or parameters");
  const auto pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  visited_.resize(pixels);
  region_.resize(pixels);
  if (params.min_area_m2 > 0.0 && params.baseline_m > 0.0) {
    candidate_pixels_.resize(pixels);
    candidates_.resize(pixels / (static_cast<std::size_t>(std::max(params.max_region_px, 0)) + 1U) + 1U);
  }
}

// Breadth-first growth from `seed` over unvisited valid neighbours within max_step_px; the
// queue keeps every member, so a small region can be erased afterwards.
SpeckleFilter::Region SpeckleFilter::grow_region(const float* values, int seed) {
  const auto step = static_cast<float>(params_.max_step_px);
  const double baseline = params_.baseline_m;
  // A pixel at disparity 0 is at infinity: any region holding one is larger than every limit.
  const auto pixel_area = [&](float d) {
    return d > 0.0F ? (baseline * baseline) / (static_cast<double>(d) * static_cast<double>(d)) : 1e9;
  };
  Region region;
  region.min_x = region.max_x = seed % width_;
  region.min_y = region.max_y = seed / width_;
  region.min_disparity = values[seed];
  std::size_t size = 0;
  std::size_t next = 0;
  region_[size++] = seed;
  visited_[static_cast<std::size_t>(seed)] = 1;
  while (next < size) {
    const std::int32_t pixel = region_[next++];
    const int x = pixel % width_;
    const int y = pixel / width_;
    const float value = values[pixel];
    region.area_m2 += pixel_area(value);
    region.min_x = std::min(region.min_x, x);
    region.max_x = std::max(region.max_x, x);
    region.min_y = std::min(region.min_y, y);
    region.max_y = std::max(region.max_y, y);
    region.min_disparity = std::min(region.min_disparity, value);
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
  region.pixels = size;
  return region;
}

// Whether no valid pixel around the region, within its own width and height of its bounding
// box, is as near as the region, or nearer, up to area_apart_px: then it stands in front of
// everything around it.
bool SpeckleFilter::stands_apart(const float* values, const Region& region) const {
  const int width = region.max_x - region.min_x + 1;
  const int height = region.max_y - region.min_y + 1;
  const int x0 = std::max(0, region.min_x - width);
  const int x1 = std::min(width_ - 1, region.max_x + width);
  const int y0 = std::max(0, region.min_y - height);
  const int y1 = std::min(height_ - 1, region.max_y + height);
  const float near_as = region.min_disparity - static_cast<float>(params_.area_apart_px);
  for (int y = y0; y <= y1; ++y) {
    const float* row = values + static_cast<std::ptrdiff_t>(y) * width_;
    for (int x = x0; x <= x1; ++x) {
      const bool inside = x >= region.min_x && x <= region.max_x && y >= region.min_y && y <= region.max_y;
      if (!inside && row[x] >= 0.0F && row[x] >= near_as) return false;
    }
  }
  return true;
}

std::size_t SpeckleFilter::apply(cv::Mat& disparity, float invalid_value) {
  STEREOSCOUT_CHECK(disparity.type() == CV_32FC1 && disparity.cols == width_ && disparity.rows == height_ &&
                        disparity.isContinuous(),
                    "SpeckleFilter::apply: disparity must be a continuous CV_32FC1 map of the constructed size");
  const bool area_rule = params_.min_area_m2 > 0.0 && params_.baseline_m > 0.0;
  if (params_.max_region_px <= 0 && !area_rule) {
    return 0;
  }
  std::fill(visited_.begin(), visited_.end(), std::uint8_t{0});
  float* values = disparity.ptr<float>(0);
  const auto erase = [&](const std::int32_t* pixels, std::size_t count) {
    for (std::size_t i = 0; i < count; ++i) values[pixels[i]] = invalid_value;
    return count;
  };
  const auto limit = static_cast<std::size_t>(std::max(params_.max_region_px, 0));
  std::size_t removed = 0;
  std::size_t candidates = 0;
  std::size_t candidate_pixels = 0;
  const int pixels = width_ * height_;
  for (int pixel = 0; pixel < pixels; ++pixel) {
    if (visited_[static_cast<std::size_t>(pixel)] != 0 || !(values[pixel] >= 0.0F)) {
      continue;
    }
    const Region region = grow_region(values, pixel);
    if (region.pixels <= limit) {
      removed += erase(region_.data(), region.pixels);
    } else if (area_rule && region.area_m2 < params_.min_area_m2) {
      // Each candidate holds more than `limit` pixels, so they fit the buffers sized for them.
      std::copy_n(region_.begin(), region.pixels, candidate_pixels_.begin() + static_cast<std::ptrdiff_t>(candidate_pixels));
      candidates_[candidates++] = {region, candidate_pixels, false};
      candidate_pixels += region.pixels;
    }
  }
  // Every candidate is judged against the same map before any is erased, so the result does
  // not depend on the order they were found in.
  for (std::size_t i = 0; i < candidates; ++i) {
    candidates_[i].apart = stands_apart(values, candidates_[i].region);
  }
  for (std::size_t i = 0; i < candidates; ++i) {
    if (candidates_[i].apart) removed += erase(&candidate_pixels_[candidates_[i].first], candidates_[i].region.pixels);
  }
  return removed;
}

}  // namespace stereoscout::vision
