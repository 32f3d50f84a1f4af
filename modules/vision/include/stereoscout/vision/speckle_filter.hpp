#pragma once
// Removes small islands from a disparity map: a pixel whose 4-connected region of similar
// disparities (neighbours within max_step_px of each other) holds at most max_region_px
// pixels is marked invalid. Block matching on weak texture (a smooth floor tile under sensor
// noise, a row of look-alike book spines) wins at scattered wrong disparities that form such
// small islands, while a real surface forms large regions, so this turns most wrong values into
// holes rather than phantom obstacles.
// A count of pixels is a small surface near the camera and a large one far away, so a region
// is also removed when the surface it stands for is smaller than min_area_m2: a pixel at
// disparity d spans baseline_m / d metres at its depth (Z / f with Z = f B / d), so the region's
// fronto-parallel area is the sum of (B / d)^2 over its pixels. Look-alike book spines matched
// at a wrong, large disparity form regions of a few hundred pixels, past any pixel limit that
// spares real far surfaces, but only a few square centimetres at their wrong depth, within a
// metre of the camera, where they would stand as phantom obstacles in the robot's path.
// But a real surface near the camera is cut into small regions too: by holes where its
// texture repeats (a brick wall's courses fail the matcher's uniqueness test), or into strips
// where it is seen at a slant (more than max_step_px of disparity per pixel). Its pieces lie
// beside each other at about the same disparity, while a wrong match stands in front of
// everything around it. So the area rule removes a small region only when no valid pixel
// around it (within the region's own width and height of its bounding box) has a disparity
// above the region's smallest less area_apart_px, judged after the pixel rule has removed
// its regions.
//
// The regions are the connected components of a symmetric relation, so the result does not
// depend on the visiting order. Buffers are sized at construction; apply() does not allocate.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace stereoscout::vision {

struct SpeckleFilterParams {
  int max_region_px = 0;        // 0: no pixel rule
  double max_step_px = 1.0;     // neighbours this close in disparity are one region (pixel rule)
  double min_area_m2 = 0.0;     // regions of a smaller surface are removed too (0: no area rule)
  double baseline_m = 0.0;      // the stereo baseline, for the area (0: no area rule)
  double area_apart_px = 3.0;   // a region is apart when nothing around it is within this
};

class SpeckleFilter {
 public:
  SpeckleFilter(const SpeckleFilterParams& params, int width_px, int height_px);

  // disparity: CV_32FC1 of the constructed size; values < 0 are invalid (left alone).
  // Returns the number of pixels marked invalid (set to `invalid_value`).
  std::size_t apply(cv::Mat& disparity, float invalid_value);

 private:
  struct Region {
    std::size_t pixels = 0;
    double area_m2 = 0.0;  // fronto-parallel, from each pixel's disparity
    int min_x = 0, max_x = 0, min_y = 0, max_y = 0;  // bounding box
    float min_disparity = 0.0F;
  };
  // A region kept by the pixel rule but smaller than min_area_m2: its pixels are
  // candidate_pixels_[first, first + region.pixels).
  struct Candidate {
    Region region;
    std::size_t first = 0;
    bool apart = false;
  };
  Region grow_region(const float* values, int seed);
  bool stands_apart(const float* values, const Region& region) const;

  SpeckleFilterParams params_;
  int width_;
  int height_;
  std::vector<std::uint8_t> visited_;  // per pixel
  std::vector<std::int32_t> region_;   // pixel indices of the region being grown (BFS queue)
  std::vector<std::int32_t> candidate_pixels_;  // area rule only: per pixel
  std::vector<Candidate> candidates_;           // area rule only: one per region of > max_region_px
};

}  // namespace stereoscout::vision
