#include "stereoscout/host_replay/log_replay.hpp"

namespace stereoscout::host_replay {

LogReplay::LogReplay(const LogReplayOptions& options)
    : options_(options), reader_(options.max_payload_bytes), odometry_(options.odometry_queue) {
  pending_frame_.allocate(options.width_px, options.height_px);
}

bool LogReplay::open(const std::string& path, std::string& error) {
  if (!reader_.open(path, error)) {
    return false;
  }
  // Start-up records come first; deliver them and stop at the first sensor record. The
  // live loop's clock started at the run_info record's time, so the replayed loop starts
  // there too and its tasks fall due at the same instants (a log without run_info starts at
  // its first record).
  bool has_start_time = false;
  std::int64_t start_ns = 0;
  while (read_next()) {
    if (lookahead_.type != log::RecordType::run_info && lookahead_.type != log::RecordType::config) {
      break;
    }
    if (lookahead_.type == log::RecordType::run_info && !has_start_time) {
      has_start_time = true;
      start_ns = lookahead_.timestamp_ns;
    }
    deliver(lookahead_);
    has_lookahead_ = false;
  }
  if (has_start_time) {
    clock_.sleep_until(start_ns);
  } else if (has_lookahead_) {
    clock_.sleep_until(lookahead_.timestamp_ns);
  }
  return true;
}

bool LogReplay::read_next() {
  has_lookahead_ = reader_.next(lookahead_);
  exhausted_ = !has_lookahead_;
  return has_lookahead_;
}

void LogReplay::pump() {
  while (!exhausted_) {
    if (!has_lookahead_ && !read_next()) {
      return;
    }
    if (lookahead_.timestamp_ns > now()) {
      return;
    }
    deliver(lookahead_);
    has_lookahead_ = false;
  }
}

void LogReplay::deliver(const log::LogRecord& record) {
  switch (record.type) {
    case log::RecordType::stereo_frame: {
      // Checked before anything is written, so a bad record leaves a pending frame intact.
      const bool had_frame = has_frame_;
      if (!log::decode_stereo_frame(record.payload, record.size, record.timestamp_ns, pending_frame_)) {
        ++stats_.invalid_records;
        break;
      }
      if (had_frame) {
        ++stats_.frames_superseded;
      }
      has_frame_ = true;
      break;
    }
    case log::RecordType::odometry: {
      core::OdometryReading reading;
      if (!log::decode_odometry(record.payload, record.size, record.timestamp_ns, reading)) {
        ++stats_.invalid_records;
        break;
      }
      if (odometry_.full()) {
        ++stats_.odometry_overflow;
      }
      odometry_.push_overwrite(reading);
      break;
    }
    case log::RecordType::gpio_event: {
      log::GpioEvent event;
      if (!log::decode_gpio_event(record.payload, record.size, event)) {
        ++stats_.invalid_records;
      } else if (event.line == log::GpioEvent::emergency_stop) {
        emergency_stop_ = event.value;
        ++stats_.gpio_events;
      }
      break;
    }
    case log::RecordType::run_info:
      if (!log::decode_run_info(record.payload, record.size, run_info_)) {
        ++stats_.invalid_records;
      }
      break;
    case log::RecordType::config:
      config_yaml_.assign(reinterpret_cast<const char*>(record.payload), record.size);
      break;
    case log::RecordType::end_of_run:
      saw_end_of_run_ = log::decode_end_of_run(record.payload, record.size, end_of_run_);
      end_of_run_ns_ = record.timestamp_ns;
      break;
    case log::RecordType::ground_truth:
      if (log::decode_ground_truth(record.payload, record.size, ground_truth_.pose)) {
        ground_truth_.timestamp_ns = record.timestamp_ns;
        has_ground_truth_ = true;
      } else {
        ++stats_.invalid_records;
      }
      break;
    case log::RecordType::drive_command:
      break;  // what the live run commanded; replay recomputes it
  }
}

core::Status LogReplay::ReplayCamera::grab(core::StereoFrame& frame) {
  replay_.pump();
  if (!replay_.has_frame_) {
    return {core::StatusCode::not_available, "no logged frame due yet"};
  }
  frame.timestamp_ns = replay_.pending_frame_.timestamp_ns;
  frame.sequence = replay_.pending_frame_.sequence;
  frame.pan_rad = replay_.pending_frame_.pan_rad;
  replay_.pending_frame_.left.copyTo(frame.left);  // same size and type: no allocation
  replay_.pending_frame_.right.copyTo(frame.right);
  replay_.has_frame_ = false;
  ++replay_.stats_.frames;
  return core::Status::success();
}

core::Status LogReplay::ReplayOdometry::read(core::OdometryReading& reading) {
  replay_.pump();
  if (replay_.odometry_.empty()) {
    return {core::StatusCode::not_available, "no logged odometry due yet"};
  }
  reading = replay_.odometry_.front();
  replay_.odometry_.pop_front();
  ++replay_.stats_.odometry;
  return core::Status::success();
}

bool LogReplay::ReplayGpio::emergency_stop_active() {
  replay_.pump();
  return replay_.emergency_stop_;
}

}  // namespace stereoscout::host_replay
