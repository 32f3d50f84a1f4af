#pragma once
// Removes small islands from a disparity map: a pixel whose 4-connected region of similar
// disparities (neighbours within max_step_px of each other) holds at most max_region_px
// pixels is marked invalid. Block matching on weak texture (a smooth floor tile under sensor
// noise, a row of look-alike book spines) wins at scattered wrong disparities that form such
// small islands, while a real surface forms large regions, so this turns most wrong values into
// holes rather than phantom obstacles.
//
// The regions are the connected components of a symmetric relation, so the result does not
// depend on the visiting order. Buffers are sized at construction; apply() does not allocate.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace stereoscout::vision {

struct SpeckleFilterParams {
  int max_region_px = 0;        // 0 switches the filter off
  double max_step_px = 1.0;     // neighbours closer than this in disparity are one region
};

class SpeckleFilter {
 public:
  SpeckleFilter(const SpeckleFilterParams& params, int width_px, int height_px);

  // disparity: CV_32FC1 of the constructed size; values < 0 are invalid (left alone).
  // Returns the number of pixels marked invalid (set to `invalid_value`).
  std::size_t apply(cv::Mat& disparity, float invalid_value);

 private:
  std::size_t grow_region(cv::Mat& disparity, int seed);

  SpeckleFilterParams params_;
  int width_;
  int height_;
  std::vector<std::uint8_t> visited_;  // per pixel
  std::vector<std::int32_t> region_;   // pixel indices of the region being grown (BFS queue)
};

}  // namespace stereoscout::vision
