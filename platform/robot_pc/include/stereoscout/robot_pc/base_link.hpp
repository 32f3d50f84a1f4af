#pragma once
// The serial link to the robot base's motor controller: wheel odometry in, velocity
// commands out. One text line per message, NMEA style, so a person can read it on a
// terminal and a damaged line is caught by its checksum:
//
//   base -> us   $ODO,<sequence>,<base time us>,<x m>,<y m>,<theta rad>*<XX>\n
//   us -> base   $DRV,<linear m/s>,<angular rad/s>*<XX>\n
//
// XX is the XOR of the bytes between '$' and '*', as two upper-case hex digits. Readings
// carry the time they were received on our clock (the scheduler's), not the base's.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "stereoscout/core/logging.hpp"
#include "stereoscout/platform/drive.hpp"
#include "stereoscout/platform/odometry.hpp"

namespace stereoscout::robot_pc {

struct BaseLinkStats {
  std::uint64_t lines = 0;
  std::uint64_t odometry = 0;
  std::uint64_t bad_checksum = 0;
  std::uint64_t malformed = 0;      // wrong field count, unparsable or non-finite numbers
  std::uint64_t overlong = 0;       // lines longer than the buffer, discarded
  std::uint64_t skipped_readings = 0;  // readings superseded before read() took them
  std::uint64_t timeouts = 0;
  std::uint64_t write_errors = 0;
};

// Turns received bytes into odometry readings; no allocation.
class BaseLinkParser {
 public:
  static constexpr std::size_t kMaxLine = 128;
  // Feeds bytes; returns true when at least one new reading was completed (kept in latest()).
  bool feed(const std::uint8_t* bytes, std::size_t count, std::int64_t received_ns);
  const core::OdometryReading& latest() const { return latest_; }
  BaseLinkStats& stats() { return stats_; }
  const BaseLinkStats& stats() const { return stats_; }

 private:
  bool parse_line(std::int64_t received_ns);
  std::array<char, kMaxLine + 1> line_{};
  std::size_t length_ = 0;
  bool overlong_ = false;
  core::OdometryReading latest_;
  BaseLinkStats stats_;
};

// NMEA checksum of `body` (the text between '$' and '*').
std::uint8_t line_checksum(const char* body, std::size_t length);
// Formats a drive command line into `out`; returns its length (0 if it does not fit).
std::size_t format_drive_line(const core::DriveCommand& command, char* out, std::size_t capacity);

// The link over a serial port: Odometry and Drive of the robot_pc platform.
class SerialBaseLink final : public platform::Odometry, public platform::Drive {
 public:
  SerialBaseLink(const core::TimeSource& clock, std::int64_t timeout_ns);
  ~SerialBaseLink() override;
  SerialBaseLink(const SerialBaseLink&) = delete;
  SerialBaseLink& operator=(const SerialBaseLink&) = delete;

  // Opens the tty raw (8N1) at `baud`. On failure `error` names the device.
  bool open(const std::string& device, int baud, std::string& error);

  core::Status read(core::OdometryReading& reading) override;
  core::Status command(const core::DriveCommand& command) override;
  core::Status stop() override;
  const BaseLinkStats& stats() const { return parser_.stats(); }

 private:
  const core::TimeSource& clock_;
  std::int64_t timeout_ns_;
  int fd_ = -1;
  BaseLinkParser parser_;
  bool fresh_ = false;
  std::int64_t last_reading_ns_ = 0;
};

}  // namespace stereoscout::robot_pc
