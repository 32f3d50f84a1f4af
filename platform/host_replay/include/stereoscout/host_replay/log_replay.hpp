#pragma once
// Plays a recorded sensor log back through the platform interfaces, on a virtual clock, so
// the stack runs exactly as it did live: a record becomes visible once the clock reaches its
// timestamp, in the order it was recorded.
//
//   LogReplay replay(options);
//   replay.open("run/sensors.log", error);     // reads run_info and config first
//   ... the scheduler advances replay.clock(); the stack reads replay.camera(),
//       replay.odometry(), replay.gpio() like any other platform.
//
// Damaged or truncated parts of the log are skipped by the reader and counted; a record
// that does not decode (wrong frame size, NaN pose) is skipped and counted here.

#include <cstdint>
#include <string>

#include "stereoscout/core/ring_buffer.hpp"
#include "stereoscout/log/reader.hpp"
#include "stereoscout/log/records.hpp"
#include "stereoscout/platform/camera.hpp"
#include "stereoscout/platform/clock.hpp"
#include "stereoscout/platform/gpio.hpp"
#include "stereoscout/platform/odometry.hpp"

namespace stereoscout::host_replay {

struct LogReplayOptions {
  int width_px = 640;  // size of the frames in the log (the camera config of the run)
  int height_px = 480;
  std::size_t odometry_queue = 64;
  std::size_t max_payload_bytes = 4U * 1024U * 1024U;
};

struct LogReplayStats {
  std::uint64_t frames = 0;
  std::uint64_t odometry = 0;
  std::uint64_t gpio_events = 0;
  std::uint64_t invalid_records = 0;   // intact but undecodable (wrong size, NaN)
  std::uint64_t frames_superseded = 0;  // a newer frame arrived before grab() took one
  std::uint64_t odometry_overflow = 0;  // queue full: oldest reading dropped
};

// Virtual time: sleep_until jumps there.
class VirtualClock final : public platform::Clock {
 public:
  std::int64_t now_ns() const override { return now_ns_; }
  void sleep_until(std::int64_t deadline_ns) override {
    if (deadline_ns > now_ns_) {
      now_ns_ = deadline_ns;
    }
  }

 private:
  std::int64_t now_ns_ = 0;
};

class LogReplay {
 public:
  explicit LogReplay(const LogReplayOptions& options = {});

  // Opens the log and reads up to the first sensor record: run_info and config become
  // available. On failure `error` names the file and the problem.
  bool open(const std::string& path, std::string& error);

  const log::RunInfo& run_info() const { return run_info_; }
  const std::string& config_yaml() const { return config_yaml_; }
  // True once every record has been delivered.
  bool finished() const { return exhausted_ && !has_frame_ && odometry_.empty(); }
  // Timestamp of the next record not yet visible (for a loop that sleeps until then).
  std::int64_t next_record_ns() const { return has_lookahead_ ? lookahead_.timestamp_ns : now(); }

  platform::Camera& camera() { return camera_; }
  platform::Odometry& odometry() { return odometry_source_; }
  platform::Gpio& gpio() { return gpio_; }
  VirtualClock& clock() { return clock_; }

  const LogReplayStats& stats() const { return stats_; }
  const log::LogReaderStats& reader_stats() const { return reader_.stats(); }
  const log::EndOfRun& end_of_run() const { return end_of_run_; }
  bool saw_end_of_run() const { return saw_end_of_run_; }
  // The clock time the live run ended at (valid once saw_end_of_run()).
  std::int64_t end_of_run_ns() const { return end_of_run_ns_; }
  // The newest ground_truth record visible so far (simulated runs log the true pose).
  bool latest_ground_truth(std::int64_t& timestamp_ns, core::Pose2& pose) const {
    timestamp_ns = ground_truth_.timestamp_ns;
    pose = ground_truth_.pose;
    return has_ground_truth_;
  }

 private:
  class ReplayCamera final : public platform::Camera {
   public:
    explicit ReplayCamera(LogReplay& replay) : replay_(replay) {}
    core::Status grab(core::StereoFrame& frame) override;
    void command_pan(double) override {}  // the log holds the pan angle each frame had
   private:
    LogReplay& replay_;
  };
  class ReplayOdometry final : public platform::Odometry {
   public:
    explicit ReplayOdometry(LogReplay& replay) : replay_(replay) {}
    core::Status read(core::OdometryReading& reading) override;
   private:
    LogReplay& replay_;
  };
  class ReplayGpio final : public platform::Gpio {
   public:
    explicit ReplayGpio(LogReplay& replay) : replay_(replay) {}
    bool emergency_stop_active() override;
    core::Status set_motor_enable(bool) override { return core::Status::success(); }
   private:
    LogReplay& replay_;
  };

  std::int64_t now() const { return clock_.now_ns(); }
  // Makes every record with a timestamp up to now visible.
  void pump();
  bool read_next();
  void deliver(const log::LogRecord& record);

  LogReplayOptions options_;
  log::LogReader reader_;
  VirtualClock clock_;
  ReplayCamera camera_{*this};
  ReplayOdometry odometry_source_{*this};
  ReplayGpio gpio_{*this};
  log::LogRecord lookahead_;
  bool has_lookahead_ = false;
  bool exhausted_ = false;
  core::StereoFrame pending_frame_;
  bool has_frame_ = false;
  core::RingBuffer<core::OdometryReading> odometry_;
  bool emergency_stop_ = false;
  log::RunInfo run_info_;
  std::string config_yaml_;
  log::EndOfRun end_of_run_;
  bool saw_end_of_run_ = false;
  std::int64_t end_of_run_ns_ = 0;
  struct StampedPose {
    std::int64_t timestamp_ns = 0;
    core::Pose2 pose;
  };
  StampedPose ground_truth_;
  bool has_ground_truth_ = false;
  LogReplayStats stats_;
};

}  // namespace stereoscout::host_replay
