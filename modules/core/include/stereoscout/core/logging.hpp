#pragma once
// Logging with levels that never allocates: a message is formatted into a fixed buffer on
// the stack and handed to a sink. There is no global logger; whoever needs one is given a
// Logger& at start-up.

#include <array>
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <cstdio>

namespace stereoscout::core {

enum class LogLevel : std::uint8_t { debug = 0, info = 1, warn = 2, error = 3, off = 4 };
const char* to_string(LogLevel level);

class LogSink {
 public:
  virtual ~LogSink() = default;
  // `line` is not terminated by a newline and lives only during the call.
  virtual void write(LogLevel level, std::int64_t time_ns, const char* line, std::size_t length) = 0;
};

// Writes "[   12.345] warn  message" lines to a stdio stream (stderr by default).
class StreamSink final : public LogSink {
 public:
  explicit StreamSink(std::FILE* stream = stderr) : stream_(stream) {}
  void write(LogLevel level, std::int64_t time_ns, const char* line, std::size_t length) override;

 private:
  std::FILE* stream_;
};

// Keeps the last kLines messages in fixed storage (tests, and the tail of a run's report).
class MemorySink final : public LogSink {
 public:
  static constexpr std::size_t kLines = 64;
  static constexpr std::size_t kLineLength = 160;
  void write(LogLevel level, std::int64_t time_ns, const char* line, std::size_t length) override;
  std::size_t size() const { return count_ < kLines ? count_ : kLines; }
  // i = 0 is the oldest kept line.
  const char* line(std::size_t i) const;
  LogLevel level(std::size_t i) const;

 private:
  std::array<std::array<char, kLineLength>, kLines> lines_{};
  std::array<LogLevel, kLines> levels_{};
  std::size_t count_ = 0;
};

// Where a logger takes its timestamps from (the scheduler's clock: virtual in simulation).
class TimeSource {
 public:
  virtual ~TimeSource() = default;
  virtual std::int64_t now_ns() const = 0;
};

class Logger {
 public:
  static constexpr std::size_t kMaxLineLength = 256;  // longer messages are cut and counted

  explicit Logger(LogSink& sink, LogLevel threshold = LogLevel::info, const TimeSource* time = nullptr)
      : sink_(&sink), threshold_(threshold), time_(time) {}

  void set_threshold(LogLevel threshold) { threshold_ = threshold; }
  LogLevel threshold() const { return threshold_; }
  bool enabled(LogLevel level) const { return level >= threshold_ && level != LogLevel::off; }

  void log(LogLevel level, const char* format, ...) __attribute__((format(printf, 3, 4)));
  void debug(const char* format, ...) __attribute__((format(printf, 2, 3)));
  void info(const char* format, ...) __attribute__((format(printf, 2, 3)));
  void warn(const char* format, ...) __attribute__((format(printf, 2, 3)));
  void error(const char* format, ...) __attribute__((format(printf, 2, 3)));

  // Messages written per level (those below the threshold are not counted).
  std::uint64_t count(LogLevel level) const { return counts_[static_cast<std::size_t>(level)]; }
  std::uint64_t truncated() const { return truncated_; }

 private:
  void vlog(LogLevel level, const char* format, std::va_list arguments);

  LogSink* sink_;
  LogLevel threshold_;
  const TimeSource* time_;
  std::array<std::uint64_t, 4> counts_{};
  std::uint64_t truncated_ = 0;
};

}  // namespace stereoscout::core
