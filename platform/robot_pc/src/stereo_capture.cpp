#include "stereoscout/robot_pc/stereo_capture.hpp"

#include "stereoscout/robot_pc/format_negotiation.hpp"

namespace stereoscout::robot_pc {

StereoCapture::StereoCapture(VideoDevice& left, VideoDevice& right, const core::TimeSource& clock,
                             const StereoCaptureOptions& options)
    : clock_(clock), options_(options) {
  left_.device = &left;
  right_.device = &right;
}

StereoCapture::StereoCapture(VideoDevice& side_by_side, const core::TimeSource& clock,
                             const StereoCaptureOptions& options)
    : side_by_side_(true), clock_(clock), options_(options) {
  left_.device = &side_by_side;
}

bool StereoCapture::start(std::string& error) {
  if (side_by_side_) {
    if (!negotiate_format(*left_.device, 2 * options_.width_px, options_.height_px, left_.format, error) ||
        !left_.device->start(options_.buffers, error)) {
      return false;
    }
  } else {
    for (Side* side : {&left_, &right_}) {
      if (!negotiate_format(*side->device, options_.width_px, options_.height_px, side->format, error) ||
          !side->device->start(options_.buffers, error)) {
        return false;
      }
    }
  }
  last_pair_ns_ = clock_.now_ns();
  return true;
}

void StereoCapture::stop() {
  for (Side* side : {&left_, &right_}) {
    if (side->device != nullptr) {
      drop_pending(*side);
      side->device->stop();
    }
  }
}

void StereoCapture::command_pan(double /*pan_rad*/) { ++stats_.pan_commands_ignored; }

void StereoCapture::count_sequence(Side& side, std::uint32_t sequence) {
  if (side.seen_any && sequence > side.last_sequence + 1) {
    stats_.driver_dropped += sequence - side.last_sequence - 1;
  }
  side.seen_any = true;
  side.last_sequence = sequence;
}

core::Status StereoCapture::fill_pending(Side& side) {
  if (side.has_pending) {
    return core::Status::success();
  }
  const core::Status status = side.device->next_frame(side.pending);
  if (status.ok()) {
    side.has_pending = true;
    count_sequence(side, side.pending.sequence);
  } else if (status.code != core::StatusCode::not_available) {
    ++stats_.device_errors;
  }
  return status;
}

void StereoCapture::drop_pending(Side& side) {
  if (side.has_pending) {
    side.device->release_frame(side.pending);
    side.has_pending = false;
  }
}

core::Status StereoCapture::no_pair_yet() {
  if (clock_.now_ns() - last_pair_ns_ > options_.timeout_ns) {
    ++stats_.timeouts;
    return {core::StatusCode::timeout, "no stereo pair within camera timeout"};
  }
  return {core::StatusCode::not_available, "no new stereo pair"};
}

core::Status StereoCapture::grab(core::StereoFrame& frame) {
  return side_by_side_ ? capture_side_by_side(frame) : capture_pair(frame);
}

core::Status StereoCapture::capture_pair(core::StereoFrame& frame) {
  for (;;) {
    const core::Status left_status = fill_pending(left_);
    const core::Status right_status = fill_pending(right_);
    if (!left_status.ok() || !right_status.ok()) {
      return no_pair_yet();
    }
    const std::int64_t gap_ns = left_.pending.timestamp_ns - right_.pending.timestamp_ns;
    if (gap_ns > options_.pair_tolerance_ns) {
      drop_pending(right_);  // the right frame is older than any left frame to come
      ++stats_.unpaired_dropped;
      continue;
    }
    if (-gap_ns > options_.pair_tolerance_ns) {
      drop_pending(left_);
      ++stats_.unpaired_dropped;
      continue;
    }
    const bool converted = extract_luma(left_.pending, left_.format, 0, frame.left) &&
                            extract_luma(right_.pending, right_.format, 0, frame.right);
    const std::int64_t timestamp_ns = right_.pending.timestamp_ns;  // the right image is the reference
    drop_pending(left_);
    drop_pending(right_);
    if (finish_pair(converted, timestamp_ns, frame)) {
      return core::Status::success();
    }
  }
}

bool StereoCapture::finish_pair(bool converted, std::int64_t timestamp_ns, core::StereoFrame& frame) {
  if (!converted) {
    ++stats_.bad_frames;
    return false;
  }
  frame.timestamp_ns = timestamp_ns;
  frame.sequence = pair_sequence_++;
  frame.pan_rad = 0.0;
  last_pair_ns_ = clock_.now_ns();
  ++stats_.pairs;
  return true;
}

core::Status StereoCapture::capture_side_by_side(core::StereoFrame& frame) {
  for (;;) {
    if (!fill_pending(left_).ok()) {
      return no_pair_yet();
    }
    const bool converted = extract_luma(left_.pending, left_.format, 0, frame.left) &&
                           extract_luma(left_.pending, left_.format, options_.width_px, frame.right);
    const std::int64_t timestamp_ns = left_.pending.timestamp_ns;
    drop_pending(left_);
    if (finish_pair(converted, timestamp_ns, frame)) {
      return core::Status::success();
    }
  }
}

}  // namespace stereoscout::robot_pc
