#pragma once
// SIFT keys of one image (cv::SIFT from features2d, byte descriptors), capped and put in a
// deterministic order: strongest response first, then row, column, size. cv::SIFT allocates
// its scale-space pyramid internally on every call; the key and descriptor buffers it fills
// are kept here and reused, so their capacity is reached after the first frames.

#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>
#include <opencv2/features2d.hpp>

#include "stereoscout/core/config/vision.hpp"
#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/vision/keypoints.hpp"

namespace stereoscout::vision {

struct SiftParams {
  int max_features = 1000;
  int octave_layers = 3;
  double contrast_threshold = 0.04;
  double edge_threshold = 10.0;
  double sigma = 1.6;
};

SiftParams sift_params_from_config(const core::VisionConfig& vision);

class SiftExtractor {
 public:
  explicit SiftExtractor(const SiftParams& params);

  // Clears `keys` and fills it with at most min(max_features, keys.capacity()) keys.
  void extract(const cv::Mat& image, core::FixedVector<Keypoint>& keys);

 private:
  SiftParams params_;
  cv::Ptr<cv::SIFT> sift_;
  std::vector<cv::KeyPoint> cv_keys_;
  cv::Mat cv_descriptors_;
  std::vector<int> order_;
};

}  // namespace stereoscout::vision
