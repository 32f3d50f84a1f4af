#include "stereoscout/log/records.hpp"

#include <cmath>
#include <cstring>

#include "stereoscout/log/format.hpp"

namespace stereoscout::log {

std::size_t stereo_frame_payload_size(int width_px, int height_px) {
  return kStereoFrameFixedBytes + 2 * static_cast<std::size_t>(width_px) * static_cast<std::size_t>(height_px);
}

namespace {

void copy_image_out(const cv::Mat& image, std::uint8_t* out) {
  const auto row_bytes = static_cast<std::size_t>(image.cols);
  for (int row = 0; row < image.rows; ++row) {
    std::memcpy(out + static_cast<std::size_t>(row) * row_bytes, image.ptr<std::uint8_t>(row), row_bytes);
  }
}

void copy_image_in(const std::uint8_t* in, cv::Mat& image) {
  const auto row_bytes = static_cast<std::size_t>(image.cols);
  for (int row = 0; row < image.rows; ++row) {
    std::memcpy(image.ptr<std::uint8_t>(row), in + static_cast<std::size_t>(row) * row_bytes, row_bytes);
  }
}

}  // namespace

void encode_stereo_frame(const core::StereoFrame& frame, std::uint8_t* payload) {
  put_u64(payload, frame.sequence);
  put_f64(payload + 8, frame.pan_rad);
  put_u32(payload + 16, static_cast<std::uint32_t>(frame.right.cols));
  put_u32(payload + 20, static_cast<std::uint32_t>(frame.right.rows));
  const std::size_t image_bytes = frame.right.total();
  copy_image_out(frame.left, payload + kStereoFrameFixedBytes);
  copy_image_out(frame.right, payload + kStereoFrameFixedBytes + image_bytes);
}

bool decode_stereo_frame(const std::uint8_t* payload, std::size_t size, std::int64_t timestamp_ns,
                         core::StereoFrame& frame) {
  if (size < kStereoFrameFixedBytes) {
    return false;
  }
  const std::uint32_t width = get_u32(payload + 16);
  const std::uint32_t height = get_u32(payload + 20);
  if (static_cast<int>(width) != frame.right.cols || static_cast<int>(height) != frame.right.rows ||
      frame.left.size() != frame.right.size() || frame.left.type() != CV_8UC1 ||
      size != stereo_frame_payload_size(static_cast<int>(width), static_cast<int>(height))) {
    return false;
  }
  const double pan = get_f64(payload + 8);
  if (!std::isfinite(pan)) {
    return false;
  }
  frame.timestamp_ns = timestamp_ns;
  frame.sequence = get_u64(payload);
  frame.pan_rad = pan;
  copy_image_in(payload + kStereoFrameFixedBytes, frame.left);
  copy_image_in(payload + kStereoFrameFixedBytes + frame.right.total(), frame.right);
  return true;
}

void encode_odometry(const core::OdometryReading& reading, std::uint8_t* payload) {
  put_u64(payload, reading.sequence);
  put_f64(payload + 8, reading.pose.x);
  put_f64(payload + 16, reading.pose.y);
  put_f64(payload + 24, reading.pose.theta);
}

bool decode_odometry(const std::uint8_t* payload, std::size_t size, std::int64_t timestamp_ns,
                     core::OdometryReading& reading) {
  if (size != kOdometryPayloadBytes) {
    return false;
  }
  const core::Pose2 pose{get_f64(payload + 8), get_f64(payload + 16), get_f64(payload + 24)};
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    return false;  // NaN odometry is bad input: skipped and counted by the caller
  }
  reading.timestamp_ns = timestamp_ns;
  reading.sequence = get_u64(payload);
  reading.pose = pose;
  return true;
}

void encode_ground_truth(const core::Pose2& pose, std::uint8_t* payload) {
  put_f64(payload, pose.x);
  put_f64(payload + 8, pose.y);
  put_f64(payload + 16, pose.theta);
}

bool decode_ground_truth(const std::uint8_t* payload, std::size_t size, core::Pose2& pose) {
  if (size != kGroundTruthPayloadBytes) {
    return false;
  }
  pose = core::Pose2{get_f64(payload), get_f64(payload + 8), get_f64(payload + 16)};
  return std::isfinite(pose.x) && std::isfinite(pose.y) && std::isfinite(pose.theta);
}

void encode_drive_command(const core::DriveCommand& command, std::uint8_t* payload) {
  put_f64(payload, command.linear_mps);
  put_f64(payload + 8, command.angular_rad_s);
}

bool decode_drive_command(const std::uint8_t* payload, std::size_t size, core::DriveCommand& command) {
  if (size != kDriveCommandPayloadBytes) {
    return false;
  }
  command.linear_mps = get_f64(payload);
  command.angular_rad_s = get_f64(payload + 8);
  return std::isfinite(command.linear_mps) && std::isfinite(command.angular_rad_s);
}

void encode_gpio_event(const GpioEvent& event, std::uint8_t* payload) {
  put_u16(payload, event.line);
  payload[2] = event.value ? 1 : 0;
}

bool decode_gpio_event(const std::uint8_t* payload, std::size_t size, GpioEvent& event) {
  if (size != kGpioEventPayloadBytes || payload[2] > 1) {
    return false;
  }
  event.line = get_u16(payload);
  event.value = payload[2] == 1;
  return true;
}

std::size_t run_info_payload_size(const RunInfo& info) { return 12 + info.program_version.size(); }

void encode_run_info(const RunInfo& info, std::uint8_t* payload) {
  put_u64(payload, info.seed);
  put_u32(payload + 8, info.flags);
  std::memcpy(payload + 12, info.program_version.data(), info.program_version.size());
}

bool decode_run_info(const std::uint8_t* payload, std::size_t size, RunInfo& info) {
  if (size < 12) {
    return false;
  }
  info.seed = get_u64(payload);
  info.flags = get_u32(payload + 8);
  info.program_version.assign(reinterpret_cast<const char*>(payload + 12), size - 12);
  return true;
}

void encode_end_of_run(const EndOfRun& end, std::uint8_t* payload) {
  put_u64(payload, end.records_written);
  put_u64(payload + 8, end.records_dropped);
}

bool decode_end_of_run(const std::uint8_t* payload, std::size_t size, EndOfRun& end) {
  if (size != kEndOfRunPayloadBytes) {
    return false;
  }
  end.records_written = get_u64(payload);
  end.records_dropped = get_u64(payload + 8);
  return true;
}

}  // namespace stereoscout::log
