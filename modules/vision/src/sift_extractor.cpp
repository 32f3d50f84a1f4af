#include "stereoscout/vision/sift_extractor.hpp"

#include <algorithm>
#include <numeric>

#include "stereoscout/core/check.hpp"

namespace stereoscout::vision {

SiftParams sift_params_from_config(const core::VisionConfig& vision) {
  SiftParams params;
  params.max_features = vision.max_features;
  params.octave_layers = vision.sift_octave_layers;
  params.contrast_threshold = vision.sift_contrast_threshold;
  params.edge_threshold = vision.sift_edge_threshold;
  params.sigma = vision.sift_sigma;
  return params;
}

SiftExtractor::SiftExtractor(const SiftParams& params)
    : params_(params),
      sift_(cv::SIFT::create(params.max_features, params.octave_layers, params.contrast_threshold,
                             params.edge_threshold, params.sigma, CV_8U)) {
  // Room for what SIFT returns before the cap (it may keep ties above the cap).
  const auto reserve = static_cast<std::size_t>(params.max_features) * 2;
  cv_keys_.reserve(reserve);
  order_.reserve(reserve);
}

void SiftExtractor::extract(const cv::Mat& image, core::FixedVector<Keypoint>& keys) {
  keys.clear();
  sift_->detectAndCompute(image, cv::noArray(), cv_keys_, cv_descriptors_);
  STEREOSCOUT_CHECK(cv_descriptors_.empty() || (cv_descriptors_.type() == CV_8UC1 &&
                                                 cv_descriptors_.cols == kDescriptorLength),
                    "SIFT returned descriptors of an unexpected type");
  order_.resize(cv_keys_.size());
  std::iota(order_.begin(), order_.end(), 0);
  // A total order on key properties, so the kept set and its order never depend on how
  // OpenCV's threads happened to collect the extrema.
  const auto stronger = [&](int a, int b) {
    const cv::KeyPoint& ka = cv_keys_[static_cast<std::size_t>(a)];
    const cv::KeyPoint& kb = cv_keys_[static_cast<std::size_t>(b)];
    if (ka.response != kb.response) return ka.response > kb.response;
    if (ka.pt.y != kb.pt.y) return ka.pt.y < kb.pt.y;
    if (ka.pt.x != kb.pt.x) return ka.pt.x < kb.pt.x;
    if (ka.size != kb.size) return ka.size < kb.size;
    if (ka.angle != kb.angle) return ka.angle < kb.angle;
    return a < b;
  };
  std::sort(order_.begin(), order_.end(), stronger);
  const std::size_t keep = std::min({order_.size(), static_cast<std::size_t>(params_.max_features), keys.capacity()});
  for (std::size_t i = 0; i < keep; ++i) {
    const int source = order_[i];
    const cv::KeyPoint& cv_key = cv_keys_[static_cast<std::size_t>(source)];
    Keypoint* key = keys.emplace_back();
    key->x_px = cv_key.pt.x;
    key->y_px = cv_key.pt.y;
    key->response = cv_key.response;
    key->size_px = cv_key.size;
    const std::uint8_t* row = cv_descriptors_.ptr<std::uint8_t>(source);
    std::copy(row, row + kDescriptorLength, key->descriptor.begin());
  }
}

}  // namespace stereoscout::vision
