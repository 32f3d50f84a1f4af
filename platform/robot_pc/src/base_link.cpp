#include "stereoscout/robot_pc/base_link.hpp"

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace stereoscout::robot_pc {
namespace {

constexpr int kOdometryFields = 6;  // tag, sequence, base time, x, y, theta

int hex_digit(char c) {
  if (c >= '0' && c <= '9') {
    return c - '0';
  }
  if (c >= 'A' && c <= 'F') {
    return c - 'A' + 10;
  }
  if (c >= 'a' && c <= 'f') {
    return c - 'a' + 10;
  }
  return -1;
}

speed_t baud_constant(int baud) {
  switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    default: return B0;
  }
}

}  // namespace

std::uint8_t line_checksum(const char* body, std::size_t length) {
  std::uint8_t sum = 0;
  for (std::size_t i = 0; i < length; ++i) {
    sum = static_cast<std::uint8_t>(sum ^ static_cast<std::uint8_t>(body[i]));
  }
  return sum;
}

std::size_t format_drive_line(const core::DriveCommand& command, char* out, std::size_t capacity) {
  char body[64];
  const int body_length = std::snprintf(body, sizeof body, "DRV,%.4f,%.4f", command.linear_mps, command.angular_rad_s);
  if (body_length <= 0 || static_cast<std::size_t>(body_length) >= sizeof body) {
    return 0;
  }
  const int length = std::snprintf(out, capacity, "$%s*%02X\n", body,
                                   line_checksum(body, static_cast<std::size_t>(body_length)));
  return length > 0 && static_cast<std::size_t>(length) < capacity ? static_cast<std::size_t>(length) : 0;
}

bool BaseLinkParser::feed(const std::uint8_t* bytes, std::size_t count, std::int64_t received_ns) {
  bool completed = false;
  for (std::size_t i = 0; i < count; ++i) {
    const char c = static_cast<char>(bytes[i]);
    if (c == '\n') {
      if (overlong_) {
        ++stats_.overlong;
      } else if (length_ > 0) {
        line_[length_] = '\0';
        ++stats_.lines;
        completed = parse_line(received_ns) || completed;
      }
      length_ = 0;
      overlong_ = false;
    } else if (c != '\r') {
      if (length_ < kMaxLine) {
        line_[length_++] = c;
      } else {
        overlong_ = true;
      }
    }
  }
  return completed;
}

bool BaseLinkParser::parse_line(std::int64_t received_ns) {
  const char* star = std::strchr(line_.data(), '*');
  if (line_[0] != '$' || star == nullptr || std::strlen(star) != 3) {
    ++stats_.malformed;
    return false;
  }
  const int high = hex_digit(star[1]);
  const int low = hex_digit(star[2]);
  const auto body_length = static_cast<std::size_t>(star - line_.data() - 1);
  if (high < 0 || low < 0 || line_checksum(line_.data() + 1, body_length) != high * 16 + low) {
    ++stats_.bad_checksum;
    return false;
  }
  if (std::strncmp(line_.data() + 1, "ODO,", 4) != 0) {
    return false;  // another message type: not ours to read
  }
  double values[kOdometryFields - 1] = {};
  const char* cursor = line_.data() + 5;
  for (int field = 0; field < kOdometryFields - 1; ++field) {
    char* end = nullptr;
    values[field] = std::strtod(cursor, &end);
    const char expected = field == kOdometryFields - 2 ? '*' : ',';
    if (end == cursor || *end != expected || !std::isfinite(values[field])) {
      ++stats_.malformed;
      return false;
    }
    cursor = end + 1;
  }
  latest_.sequence = static_cast<std::uint64_t>(values[0]);
  latest_.timestamp_ns = received_ns;
  latest_.pose = {values[2], values[3], values[4]};
  ++stats_.odometry;
  return true;
}

SerialBaseLink::SerialBaseLink(const core::TimeSource& clock, std::int64_t timeout_ns)
    : clock_(clock), timeout_ns_(timeout_ns) {}

SerialBaseLink::~SerialBaseLink() {
  if (fd_ >= 0) {
    ::close(fd_);
  }
}

bool SerialBaseLink::open(const std::string& device, int baud, std::string& error) {
  const speed_t speed = baud_constant(baud);
  if (speed == B0) {
    error = device + ": unsupported baud rate " + std::to_string(baud);
    return false;
  }
  fd_ = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
  if (fd_ < 0) {
    error = device + ": cannot open the base link (" + std::strerror(errno) + ")";
    return false;
  }
  termios settings{};
  if (::tcgetattr(fd_, &settings) != 0) {
    error = device + ": not a serial port (" + std::strerror(errno) + ")";
    return false;
  }
  ::cfmakeraw(&settings);
  ::cfsetispeed(&settings, speed);
  ::cfsetospeed(&settings, speed);
  settings.c_cflag |= CLOCAL | CREAD;
  if (::tcsetattr(fd_, TCSANOW, &settings) != 0) {
    error = device + ": cannot configure the serial port (" + std::strerror(errno) + ")";
    return false;
  }
  last_reading_ns_ = clock_.now_ns();
  return true;
}

core::Status SerialBaseLink::read(core::OdometryReading& reading) {
  std::uint8_t bytes[256];
  for (;;) {
    const ssize_t received = ::read(fd_, bytes, sizeof bytes);
    if (received <= 0) {
      break;
    }
    if (parser_.feed(bytes, static_cast<std::size_t>(received), clock_.now_ns())) {
      if (fresh_) {
        ++parser_.stats().skipped_readings;
      }
      fresh_ = true;
    }
  }
  if (fresh_) {
    reading = parser_.latest();
    fresh_ = false;
    last_reading_ns_ = reading.timestamp_ns;
    return core::Status::success();
  }
  if (clock_.now_ns() - last_reading_ns_ > timeout_ns_) {
    ++parser_.stats().timeouts;
    return {core::StatusCode::timeout, "no odometry from the base within its timeout"};
  }
  return {core::StatusCode::not_available, "no new odometry"};
}

core::Status SerialBaseLink::command(const core::DriveCommand& command) {
  char line[96];
  const std::size_t length = format_drive_line(command, line, sizeof line);
  if (length == 0 || ::write(fd_, line, length) != static_cast<ssize_t>(length)) {
    ++parser_.stats().write_errors;
    return {core::StatusCode::io_error, "cannot write the drive command to the base"};
  }
  return core::Status::success();
}

core::Status SerialBaseLink::stop() { return command({0.0, 0.0}); }

}  // namespace stereoscout::robot_pc
