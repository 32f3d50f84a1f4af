#pragma once
// LogReader: reads a sensor log record by record. A damaged record (bad sync word, length or
// CRC) is skipped: the reader searches forward for the next sync word and goes on, counting
// the damage. A file cut short (a crash, a full disk) is read up to its last whole record.
// Records of a type this version does not know are skipped and counted (newer writers).

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "stereoscout/log/format.hpp"

namespace stereoscout::log {

struct LogRecord {
  RecordType type = RecordType::run_info;
  std::int64_t timestamp_ns = 0;
  const std::uint8_t* payload = nullptr;  // valid until the next call to next()
  std::uint32_t size = 0;
  std::uint64_t file_offset = 0;          // where the record starts
};

struct LogReaderStats {
  std::uint64_t records = 0;          // whole records returned
  std::uint64_t damaged = 0;          // places where damage was found and skipped
  std::uint64_t bytes_skipped = 0;    // bytes passed over while resynchronising
  std::uint64_t truncated_bytes = 0;  // bytes after the last whole record of a cut file
  std::uint64_t unknown_types = 0;    // intact records of a type we do not know
};

class LogReader {
 public:
  explicit LogReader(std::size_t max_payload_bytes = 4U * 1024U * 1024U);
  ~LogReader();
  LogReader(const LogReader&) = delete;
  LogReader& operator=(const LogReader&) = delete;

  // Opens a log and checks its header. On failure `error` names the file and the problem.
  bool open(const std::string& path, std::string& error);
  // The next whole record; false at the end of the file.
  bool next(LogRecord& record);
  const LogReaderStats& stats() const { return stats_; }
  std::uint16_t format_version() const { return version_; }

 private:
  enum class Attempt { record, damaged, end };
  Attempt read_at(std::uint64_t offset, LogRecord& record);
  // Offset of the next sync word at or after `from`, or the file size.
  std::uint64_t find_sync(std::uint64_t from);
  bool read_exact(std::uint64_t offset, std::uint8_t* out, std::size_t size);

  std::vector<std::uint8_t> buffer_;
  std::FILE* file_ = nullptr;
  std::uint64_t file_size_ = 0;
  std::uint64_t position_ = 0;
  std::uint16_t version_ = 0;
  LogReaderStats stats_;
};

}  // namespace stereoscout::log
