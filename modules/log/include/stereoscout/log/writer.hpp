#pragma once
// LogWriter: records go into a fixed queue of preallocated slots and a background thread
// writes them to the file, so the tick loop never waits for the disk and never allocates.
// When the queue is full (the disk is slower than the sensors) the record is dropped and
// counted; the end_of_run record states the count, and replay reports it.

#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "stereoscout/core/messages.hpp"
#include "stereoscout/log/format.hpp"
#include "stereoscout/log/records.hpp"

namespace stereoscout::log {

struct LogWriterOptions {
  std::size_t queue_slots = 8;
  std::size_t max_payload_bytes = 2 * 640 * 480 + 64;  // one 640x480 stereo frame
  // Simulation: the loop runs on a virtual clock, so waiting for the disk costs no simulated
  // time, and a dropped record would make the log depend on thread timing. On the robot a
  // full queue drops the record (the loop must not wait for the disk).
  bool wait_when_full = false;
};

struct LogWriterStats {
  std::uint64_t records_written = 0;  // reached the file
  std::uint64_t records_dropped = 0;  // queue full or payload too large
  std::uint64_t bytes_written = 0;
  std::uint64_t io_errors = 0;
};

class LogWriter {
 public:
  explicit LogWriter(const LogWriterOptions& options = {});
  ~LogWriter();
  LogWriter(const LogWriter&) = delete;
  LogWriter& operator=(const LogWriter&) = delete;

  // Creates the file, writes its header and starts the writer thread. On failure `error`
  // names the file and the reason.
  bool open(const std::string& path, std::string& error);
  bool is_open() const { return file_ != nullptr; }

  // Tick-loop side. begin() returns the payload buffer of a free slot (nullptr, counted as a
  // drop, when none is free or the payload is too large); fill it, then commit().
  std::uint8_t* begin(RecordType type, std::int64_t timestamp_ns, std::size_t payload_bytes);
  void commit();

  bool write_stereo_frame(const core::StereoFrame& frame);
  bool write_odometry(const core::OdometryReading& reading);
  bool write_drive_command(std::int64_t timestamp_ns, const core::DriveCommand& command);
  bool write_gpio_event(std::int64_t timestamp_ns, const GpioEvent& event);
  bool write_ground_truth(std::int64_t timestamp_ns, const core::Pose2& pose);
  // Start-up records (their payloads may be large; written through the same queue).
  bool write_run_info(std::int64_t timestamp_ns, const RunInfo& info);
  bool write_config(std::int64_t timestamp_ns, const std::string& yaml);

  // Waits until every committed record is in the file.
  void flush();
  // Writes end_of_run, drains the queue, stops the thread and closes the file.
  void close(std::int64_t timestamp_ns = 0);

  LogWriterStats stats() const;

 private:
  struct Slot {
    std::vector<std::uint8_t> bytes;  // header + payload + CRC, sized once
    std::size_t size = 0;
  };
  void writer_loop();
  void write_slot(Slot& slot);
  template <class Encode>
  bool write_record(RecordType type, std::int64_t timestamp_ns, std::size_t payload_bytes, Encode&& encode) {
    std::uint8_t* payload = begin(type, timestamp_ns, payload_bytes);
    if (payload == nullptr) {
      return false;
    }
    encode(payload);
    commit();
    return true;
  }

  LogWriterOptions options_;
  std::vector<Slot> slots_;
  std::FILE* file_ = nullptr;
  std::thread thread_;
  mutable std::mutex mutex_;
  std::condition_variable work_ready_;
  std::condition_variable work_done_;
  std::size_t head_ = 0;    // next slot the loop fills
  std::size_t tail_ = 0;    // next slot the thread writes
  std::size_t queued_ = 0;  // committed, not yet written
  bool begun_ = false;
  bool stopping_ = false;
  LogWriterStats stats_;
};

}  // namespace stereoscout::log
