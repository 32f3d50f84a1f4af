#include "stereoscout/log/writer.hpp"

#include <cerrno>
#include <cstring>

namespace stereoscout::log {

LogWriter::LogWriter(const LogWriterOptions& options) : options_(options), slots_(options.queue_slots) {
  for (Slot& slot : slots_) {
    slot.bytes.resize(kRecordHeaderSize + options.max_payload_bytes + kRecordTrailerSize);
  }
}

LogWriter::~LogWriter() { close(); }

bool LogWriter::open(const std::string& path, std::string& error) {
  if (slots_.empty()) {
    error = path + ": the log writer needs at least one queue slot";
    return false;
  }
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) {
    error = path + ": cannot create the log file (" + std::strerror(errno) + ")";
    return false;
  }
  std::uint8_t header[kFileHeaderSize] = {};
  std::memcpy(header, kFileMagic.data(), kFileMagic.size());
  put_u16(header + 8, kFormatVersion);
  if (std::fwrite(header, 1, sizeof header, file_) != sizeof header) {
    error = path + ": cannot write the log header (" + std::strerror(errno) + ")";
    std::fclose(file_);
    file_ = nullptr;
    return false;
  }
  stats_.bytes_written = sizeof header;
  stopping_ = false;
  thread_ = std::thread(&LogWriter::writer_loop, this);
  return true;
}

std::uint8_t* LogWriter::begin(RecordType type, std::int64_t timestamp_ns, std::size_t payload_bytes) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (options_.wait_when_full && file_ != nullptr && !stopping_) {
    work_done_.wait(lock, [this] { return queued_ < slots_.size(); });
  }
  if (file_ == nullptr || begun_ || queued_ == slots_.size() || payload_bytes > options_.max_payload_bytes) {
    ++stats_.records_dropped;
    return nullptr;
  }
  begun_ = true;
  Slot& slot = slots_[head_];
  lock.unlock();
  std::uint8_t* bytes = slot.bytes.data();
  std::memcpy(bytes, kRecordSync.data(), kRecordSync.size());
  put_u16(bytes + 4, static_cast<std::uint16_t>(type));
  put_u16(bytes + 6, 0);
  put_u32(bytes + 8, static_cast<std::uint32_t>(payload_bytes));
  put_u64(bytes + 12, static_cast<std::uint64_t>(timestamp_ns));
  slot.size = kRecordHeaderSize + payload_bytes + kRecordTrailerSize;
  return bytes + kRecordHeaderSize;
}

void LogWriter::commit() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!begun_) {
    return;
  }
  Slot& slot = slots_[head_];
  const std::size_t covered = slot.size - kRecordTrailerSize - kRecordSync.size();
  put_u32(slot.bytes.data() + slot.size - kRecordTrailerSize, crc32(slot.bytes.data() + kRecordSync.size(), covered));
  begun_ = false;
  head_ = (head_ + 1) % slots_.size();
  ++queued_;
  work_ready_.notify_one();
}

void LogWriter::writer_loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    work_ready_.wait(lock, [this] { return queued_ > 0 || stopping_; });
    if (queued_ == 0) {
      return;  // stopping, and everything is written
    }
    Slot& slot = slots_[tail_];
    lock.unlock();
    write_slot(slot);
    lock.lock();
    tail_ = (tail_ + 1) % slots_.size();
    --queued_;
    work_done_.notify_all();
  }
}

void LogWriter::write_slot(Slot& slot) {
  const std::size_t written = std::fwrite(slot.bytes.data(), 1, slot.size, file_);
  std::lock_guard<std::mutex> lock(mutex_);
  stats_.bytes_written += written;
  if (written == slot.size) {
    ++stats_.records_written;
  } else {
    ++stats_.io_errors;
  }
}

void LogWriter::flush() {
  std::unique_lock<std::mutex> lock(mutex_);
  work_done_.wait(lock, [this] { return queued_ == 0; });
  if (file_ != nullptr && std::fflush(file_) != 0) {
    ++stats_.io_errors;
  }
}

void LogWriter::close(std::int64_t timestamp_ns) {
  if (file_ == nullptr) {
    return;
  }
  flush();
  const LogWriterStats before = stats();
  if (std::uint8_t* payload = begin(RecordType::end_of_run, timestamp_ns, kEndOfRunPayloadBytes)) {
    encode_end_of_run({before.records_written, before.records_dropped}, payload);
    commit();
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  work_ready_.notify_one();
  thread_.join();
  if (std::fclose(file_) != 0) {
    ++stats_.io_errors;
  }
  file_ = nullptr;
}

LogWriterStats LogWriter::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

bool LogWriter::write_stereo_frame(const core::StereoFrame& frame) {
  return write_record(RecordType::stereo_frame, frame.timestamp_ns,
                      stereo_frame_payload_size(frame.right.cols, frame.right.rows),
                      [&frame](std::uint8_t* payload) { encode_stereo_frame(frame, payload); });
}

bool LogWriter::write_odometry(const core::OdometryReading& reading) {
  return write_record(RecordType::odometry, reading.timestamp_ns, kOdometryPayloadBytes,
                      [&reading](std::uint8_t* payload) { encode_odometry(reading, payload); });
}

bool LogWriter::write_drive_command(std::int64_t timestamp_ns, const core::DriveCommand& command) {
  return write_record(RecordType::drive_command, timestamp_ns, kDriveCommandPayloadBytes,
                      [&command](std::uint8_t* payload) { encode_drive_command(command, payload); });
}

bool LogWriter::write_gpio_event(std::int64_t timestamp_ns, const GpioEvent& event) {
  return write_record(RecordType::gpio_event, timestamp_ns, kGpioEventPayloadBytes,
                      [&event](std::uint8_t* payload) { encode_gpio_event(event, payload); });
}

bool LogWriter::write_ground_truth(std::int64_t timestamp_ns, const core::Pose2& pose) {
  return write_record(RecordType::ground_truth, timestamp_ns, kGroundTruthPayloadBytes,
                      [&pose](std::uint8_t* payload) { encode_ground_truth(pose, payload); });
}

bool LogWriter::write_run_info(std::int64_t timestamp_ns, const RunInfo& info) {
  return write_record(RecordType::run_info, timestamp_ns, run_info_payload_size(info),
                      [&info](std::uint8_t* payload) { encode_run_info(info, payload); });
}

bool LogWriter::write_config(std::int64_t timestamp_ns, const std::string& yaml) {
  return write_record(RecordType::config, timestamp_ns, yaml.size(),
                      [&yaml](std::uint8_t* payload) { std::memcpy(payload, yaml.data(), yaml.size()); });
}

}  // namespace stereoscout::log
