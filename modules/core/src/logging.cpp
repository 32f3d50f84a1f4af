#include "stereoscout/core/logging.hpp"

#include <cstring>

namespace stereoscout::core {

const char* to_string(LogLevel level) {
  switch (level) {
    case LogLevel::debug: return "debug";
    case LogLevel::info: return "info";
    case LogLevel::warn: return "warn";
    case LogLevel::error: return "error";
    case LogLevel::off: return "off";
  }
  return "?";
}

void StreamSink::write(LogLevel level, std::int64_t time_ns, const char* line, std::size_t length) {
  const double seconds = static_cast<double>(time_ns) * 1e-9;
  std::fprintf(stream_, "[%10.3f] %-5s %.*s\n", seconds, to_string(level), static_cast<int>(length), line);
}

void MemorySink::write(LogLevel level, std::int64_t /*time_ns*/, const char* line, std::size_t length) {
  const std::size_t slot = count_ % kLines;
  const std::size_t kept = length < kLineLength - 1 ? length : kLineLength - 1;
  std::memcpy(lines_[slot].data(), line, kept);
  lines_[slot][kept] = '\0';
  levels_[slot] = level;
  ++count_;
}

const char* MemorySink::line(std::size_t i) const {
  const std::size_t oldest = count_ < kLines ? 0 : count_ % kLines;
  return lines_[(oldest + i) % kLines].data();
}

LogLevel MemorySink::level(std::size_t i) const {
  const std::size_t oldest = count_ < kLines ? 0 : count_ % kLines;
  return levels_[(oldest + i) % kLines];
}

void Logger::vlog(LogLevel level, const char* format, std::va_list arguments) {
  if (!enabled(level)) {
    return;
  }
  char buffer[kMaxLineLength];
  const int written = std::vsnprintf(buffer, sizeof buffer, format, arguments);
  if (written < 0) {
    return;
  }
  std::size_t length = static_cast<std::size_t>(written);
  if (length >= sizeof buffer) {
    length = sizeof buffer - 1;
    ++truncated_;
  }
  ++counts_[static_cast<std::size_t>(level)];
  sink_->write(level, time_ != nullptr ? time_->now_ns() : 0, buffer, length);
}

#define STEREOSCOUT_LOG_AT(level_value)       \
  std::va_list arguments;                     \
  va_start(arguments, format);                \
  vlog((level_value), format, arguments);     \
  va_end(arguments)

void Logger::log(LogLevel level, const char* format, ...) { STEREOSCOUT_LOG_AT(level); }
void Logger::debug(const char* format, ...) { STEREOSCOUT_LOG_AT(LogLevel::debug); }
void Logger::info(const char* format, ...) { STEREOSCOUT_LOG_AT(LogLevel::info); }
void Logger::warn(const char* format, ...) { STEREOSCOUT_LOG_AT(LogLevel::warn); }
void Logger::error(const char* format, ...) { STEREOSCOUT_LOG_AT(LogLevel::error); }

#undef STEREOSCOUT_LOG_AT

}  // namespace stereoscout::core
