#include "stereoscout/host_dataset/kitti_camera.hpp"

#include <cmath>

#include <opencv2/imgcodecs.hpp>

namespace stereoscout::host_dataset {

core::Status KittiCamera::grab(core::StereoFrame& frame) {
  if (finished()) return {core::StatusCode::not_available, "KITTI sequence finished"};
  const std::size_t index = next_++;
  const KittiCalibration& calibration = sequence_.calibration;
  cv::Mat* targets[2] = {&frame.left, &frame.right};
  for (int camera = 0; camera < 2; ++camera) {
    const std::string path = kitti_image_path(sequence_.folder, camera, index);
    const cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
    if (image.empty()) {
      ++skipped_;
      last_failed_path_ = path;
      return {core::StatusCode::io_error, "KITTI image missing or unreadable"};
    }
    if (image.cols != calibration.width_px || image.rows != calibration.height_px) {
      ++skipped_;
      last_failed_path_ = path;
      return {core::StatusCode::invalid_input, "KITTI image size differs from frame 0"};
    }
    image.copyTo(*targets[camera]);
  }
  frame.timestamp_ns = static_cast<std::int64_t>(std::llround(sequence_.times_s[index] * 1e9));
  frame.sequence = index;
  frame.pan_rad = 0.0;
  ++delivered_;
  return core::Status::success();
}

}  // namespace stereoscout::host_dataset
