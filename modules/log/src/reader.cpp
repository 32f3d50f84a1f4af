#include "stereoscout/log/reader.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>

namespace stereoscout::log {

LogReader::LogReader(std::size_t max_payload_bytes) : buffer_(kRecordHeaderSize + max_payload_bytes + kRecordTrailerSize) {}

LogReader::~LogReader() {
  if (file_ != nullptr) {
    std::fclose(file_);
  }
}

bool LogReader::open(const std::string& path, std::string& error) {
  file_ = std::fopen(path.c_str(), "rb");
  if (file_ == nullptr) {
    error = path + ": cannot open the log (" + std::strerror(errno) + ")";
    return false;
  }
  if (fseeko(file_, 0, SEEK_END) != 0) {
    error = path + ": cannot seek in the log";
    return false;
  }
  file_size_ = static_cast<std::uint64_t>(ftello(file_));
  std::uint8_t header[kFileHeaderSize] = {};
  if (!read_exact(0, header, sizeof header)) {
    error = path + ": not a stereoscout log (shorter than its " + std::to_string(kFileHeaderSize) + "-byte header)";
    return false;
  }
  if (std::memcmp(header, kFileMagic.data(), kFileMagic.size()) != 0) {
    error = path + ": not a stereoscout log (wrong magic bytes)";
    return false;
  }
  version_ = get_u16(header + 8);
  if (version_ != kFormatVersion) {
    error = path + ": log format version " + std::to_string(version_) + " is not supported (this build reads version " +
            std::to_string(kFormatVersion) + ")";
    return false;
  }
  position_ = kFileHeaderSize;
  return true;
}

bool LogReader::read_exact(std::uint64_t offset, std::uint8_t* out, std::size_t size) {
  if (offset + size > file_size_ || fseeko(file_, static_cast<off_t>(offset), SEEK_SET) != 0) {
    return false;
  }
  return std::fread(out, 1, size, file_) == size;
}

std::uint64_t LogReader::find_sync(std::uint64_t from) {
  std::array<std::uint8_t, 4096> chunk{};
  while (from + kRecordSync.size() <= file_size_) {
    const std::size_t wanted = static_cast<std::size_t>(std::min<std::uint64_t>(chunk.size(), file_size_ - from));
    if (!read_exact(from, chunk.data(), wanted)) {
      break;
    }
    const std::uint8_t* begin = chunk.data();
    const std::uint8_t* end = begin + wanted;
    const std::uint8_t* found = std::search(begin, end, kRecordSync.begin(), kRecordSync.end());
    if (found != end) {
      return from + static_cast<std::uint64_t>(found - begin);
    }
    // Step back so a sync word split across two chunks is still found.
    from += wanted - (kRecordSync.size() - 1);
  }
  return file_size_;
}

LogReader::Attempt LogReader::read_at(std::uint64_t offset, LogRecord& record) {
  std::uint8_t* bytes = buffer_.data();
  if (offset + kRecordHeaderSize > file_size_) {
    return Attempt::end;
  }
  if (!read_exact(offset, bytes, kRecordHeaderSize) ||
      std::memcmp(bytes, kRecordSync.data(), kRecordSync.size()) != 0) {
    return Attempt::damaged;
  }
  const std::uint32_t size = get_u32(bytes + 8);
  const std::uint64_t total = kRecordHeaderSize + static_cast<std::uint64_t>(size) + kRecordTrailerSize;
  if (size > kMaxPayloadBytes || total > buffer_.size()) {
    return Attempt::damaged;
  }
  if (offset + total > file_size_) {
    return Attempt::end;  // the caller tells a cut file from a damaged length
  }
  if (!read_exact(offset + kRecordHeaderSize, bytes + kRecordHeaderSize, size + kRecordTrailerSize)) {
    return Attempt::damaged;
  }
  const std::size_t covered = kRecordHeaderSize - kRecordSync.size() + size;
  if (crc32(bytes + kRecordSync.size(), covered) != get_u32(bytes + kRecordHeaderSize + size)) {
    return Attempt::damaged;
  }
  record.type = static_cast<RecordType>(get_u16(bytes + 4));
  record.timestamp_ns = static_cast<std::int64_t>(get_u64(bytes + 12));
  record.payload = bytes + kRecordHeaderSize;
  record.size = size;
  record.file_offset = offset;
  position_ = offset + total;
  return Attempt::record;
}

bool LogReader::next(LogRecord& record) {
  while (file_ != nullptr && position_ < file_size_) {
    const Attempt attempt = read_at(position_, record);
    if (attempt == Attempt::record) {
      if (!is_known(static_cast<std::uint16_t>(record.type))) {
        ++stats_.unknown_types;
        continue;
      }
      ++stats_.records;
      return true;
    }
    const std::uint64_t next_sync = find_sync(position_ + 1);
    if (attempt == Attempt::end && next_sync == file_size_) {
      // Nothing whole follows: the file was cut inside its last record.
      stats_.truncated_bytes += file_size_ - position_;
      position_ = file_size_;
      return false;
    }
    ++stats_.damaged;
    stats_.bytes_skipped += next_sync - position_;
    position_ = next_sync;
  }
  return false;
}

}  // namespace stereoscout::log
