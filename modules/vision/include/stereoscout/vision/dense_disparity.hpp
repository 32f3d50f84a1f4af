#pragma once
// Dense disparity for a rectified pair (paper section V needs depth in every column; OpenCV's
// calib3d is outside our dependency set, so the block matcher is written here).
//
// Cost: Hamming distance between 7x7 census transforms (robust to gain and bias differences
// between the two cameras), summed over a square window. Winner-take-all over disparities
// 0 .. N-1, refined to subpixel by a parabola through the three costs around the minimum.
// A pixel is marked invalid (never guessed) when
//   - its window has too little texture (mean absolute horizontal gradient; the default
//     threshold lies above what the camera's own noise gives on a blank surface),
//   - the best cost is not unique (a non-adjacent disparity costs nearly as little),
//   - the left-right check fails (the right image's own winner disagrees),
//   - the window or the search range leaves the image, or
//   - it lies in a small island of similar disparities (SpeckleFilter): scattered wrong
//     winners on weak texture, or a patch of a repeated texture matched at a wrong, large
//     disparity, which would otherwise become phantom obstacles in the scan.
// A pixel rejected for lack of texture holds kUntexturedDisparity rather than
// kInvalidDisparity: the scan tells a blank surface (no texture to match) from a pixel stereo
// was confused on (an occlusion edge, a repeated pattern). Both are negative: `d > 0` is the
// test for a valid disparity everywhere.
// The output is referenced to the LEFT image (the usual convention of stereo benchmarks):
// left pixel (x, y) with disparity d matches right pixel (x - d, y). All buffers are sized at
// construction; compute() does not allocate.

#include <cstdint>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "stereoscout/core/config/vision.hpp"
#include "stereoscout/vision/dense_disparity_kernels.hpp"
#include "stereoscout/vision/speckle_filter.hpp"

namespace stereoscout::vision {

inline constexpr float kInvalidDisparity = -1.0F;
inline constexpr float kUntexturedDisparity = -2.0F;

struct DenseDisparityParams {
  int num_disparities = 64;
  int window_px = 7;
  double uniqueness_ratio = 0.1;
  double min_texture = 2.5;
  int lr_tolerance_px = 1;
  int speckle_max_region_px = 100;  // 0: no speckle filter
  double speckle_max_step_px = 1.0;
  // Regions of a smaller surface are removed too (SpeckleFilterParams); 0: no area rule.
  double speckle_min_area_m2 = 0.0;
  double speckle_area_apart_px = 3.0;
  double baseline_m = 0.0;
  // Use the CPU's vector and popcount instructions where present (same output, bit for bit);
  // off: the portable build of the inner loops (tests compare the two).
  bool allow_simd = true;
};

// baseline_m: the rig's, for the speckle filter's area rule (0: no area rule).
DenseDisparityParams dense_params_from_config(const core::VisionConfig& vision, double baseline_m);

struct DenseDisparityStats {
  std::size_t pixels = 0;
  std::size_t valid = 0;
  std::size_t rejected_texture = 0;
  std::size_t rejected_uniqueness = 0;
  std::size_t rejected_left_right = 0;
  std::size_t rejected_speckle = 0;
  std::size_t border = 0;
};

class DenseDisparityMatcher {
 public:
  DenseDisparityMatcher(const DenseDisparityParams& params, int width_px, int height_px);

  // left, right: CV_8UC1 of the constructed size. disparity: CV_32FC1 of the same size,
  // allocated by the caller (allocate_output) and overwritten; kInvalidDisparity marks holes.
  void compute(const cv::Mat& left, const cv::Mat& right, cv::Mat& disparity);
  void allocate_output(cv::Mat& disparity) const;

  const DenseDisparityStats& stats() const { return stats_; }
  // Which build of the inner loops runs ("portable", "popcnt", "avx2").
  const char* kernels_name() const { return kernels_.name; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  void texture_integral(const cv::Mat& left);
  void cost_row(int y, std::uint8_t* costs) const;
  void aggregate_row();
  void find_winners();
  void select_row(int y, float* disparity_row);
  bool has_texture(int x, int y) const;

  DenseDisparityParams params_;
  int width_;
  int height_;
  int disparities_;
  int radius_;
  std::vector<std::uint64_t> census_left_;
  std::vector<std::uint64_t> census_right_;
  std::vector<std::uint8_t> cost_ring_;       // window rows of [disparity][x] census costs
  std::vector<std::uint16_t> column_sums_;    // [disparity][x], summed over the window rows
  std::vector<std::uint16_t> aggregated_;     // [disparity][x], summed over the window
  std::vector<std::uint16_t> box_scratch_;    // doubling levels of the box sum
  // Per-column winner search state of one row (structure of arrays, so loops vectorise).
  std::vector<std::uint16_t> best_cost_;
  std::vector<std::uint16_t> second_cost_;
  std::vector<std::int16_t> best_disparity_;
  std::vector<std::uint16_t> right_best_cost_;
  std::vector<std::int16_t> right_best_disparity_;
  detail::DenseKernels kernels_;
  std::vector<std::int32_t> gradient_integral_;  // (width + 1) x (height + 1)
  SpeckleFilter speckle_filter_;
  DenseDisparityStats stats_;
};

// Scores a left-referenced disparity map against ground truth (Middlebury convention: a
// ground-truth value of 0 is unknown; the true disparity is value / scale).
struct DisparityScore {
  std::size_t known = 0;      // pixels with ground truth
  std::size_t valid = 0;      // of those, pixels the matcher gave a value
  double bad_1 = 0.0;         // fraction of valid known pixels off by more than 1 px
  double bad_2 = 0.0;         // ... by more than 2 px
  double density = 0.0;       // valid / known
  double bad_2_all = 0.0;     // invalid pixels counted as bad (the benchmark's "all" view)
};

// disparity: CV_32FC1; ground_truth: CV_8UC1 or CV_16UC1 of the same size.
DisparityScore score_disparity(const cv::Mat& disparity, const cv::Mat& ground_truth, double scale);

}  // namespace stereoscout::vision
