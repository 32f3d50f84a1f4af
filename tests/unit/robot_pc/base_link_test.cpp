#include <gtest/gtest.h>

#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstring>
#include <string>

#include "stereoscout/robot_pc/base_link.hpp"

namespace stereoscout::robot_pc {
namespace {

class TestClock final : public core::TimeSource {
 public:
  std::int64_t now_ns() const override { return now; }
  std::int64_t now = 1000;
};

// A correct line for `body`, checksum and all.
std::string line_for(const std::string& body, const std::string& ending = "\r\n") {
  char checksum[3];
  std::snprintf(checksum, sizeof checksum, "%02X", line_checksum(body.data(), body.size()));
  return "$" + body + "*" + checksum + ending;
}

bool feed(BaseLinkParser& parser, const std::string& text, std::int64_t at = 5) {
  return parser.feed(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), at);
}

TEST(BaseLinkParser, ReadsAnOdometryLine) {
  BaseLinkParser parser;
  EXPECT_TRUE(feed(parser, line_for("ODO,42,123456,1.25,-0.5,0.3"), 777));
  EXPECT_EQ(parser.latest().sequence, 42u);
  EXPECT_EQ(parser.latest().timestamp_ns, 777);
  EXPECT_DOUBLE_EQ(parser.latest().pose.x, 1.25);
  EXPECT_DOUBLE_EQ(parser.latest().pose.y, -0.5);
  EXPECT_DOUBLE_EQ(parser.latest().pose.theta, 0.3);
  EXPECT_EQ(parser.stats().odometry, 1u);
}

TEST(BaseLinkParser, LinesSplitAcrossReadsAreJoined) {
  BaseLinkParser parser;
  const std::string line = line_for("ODO,1,0,0.1,0.2,0.3");
  EXPECT_FALSE(feed(parser, line.substr(0, 9)));
  EXPECT_TRUE(feed(parser, line.substr(9)));
  EXPECT_DOUBLE_EQ(parser.latest().pose.y, 0.2);
}

TEST(BaseLinkParser, DamagedLinesAreCountedNotRead) {
  BaseLinkParser parser;
  std::string corrupted = line_for("ODO,1,0,0.1,0.2,0.3");
  corrupted[8] = '9';
  EXPECT_FALSE(feed(parser, corrupted));
  EXPECT_EQ(parser.stats().bad_checksum, 1u);
  EXPECT_FALSE(feed(parser, line_for("ODO,1,0,0.1,nan,0.3")));
  EXPECT_FALSE(feed(parser, line_for("ODO,1,0,0.1,0.2")));
  EXPECT_FALSE(feed(parser, "garbage without framing\n"));
  EXPECT_EQ(parser.stats().malformed, 3u);
  EXPECT_FALSE(feed(parser, std::string(500, 'x') + "\n"));
  EXPECT_EQ(parser.stats().overlong, 1u);
  EXPECT_EQ(parser.stats().odometry, 0u);
  EXPECT_TRUE(feed(parser, line_for("ODO,2,0,1,2,3")));  // and the link goes on
}

TEST(BaseLinkParser, OtherMessageTypesAreIgnored) {
  BaseLinkParser parser;
  EXPECT_FALSE(feed(parser, line_for("BAT,12.4")));
  EXPECT_EQ(parser.stats().malformed, 0u);
  EXPECT_EQ(parser.stats().bad_checksum, 0u);
}

TEST(BaseLink, DriveLineHasAValidChecksum) {
  char line[96];
  const std::size_t length = format_drive_line({0.12, -0.1396}, line, sizeof line);
  ASSERT_GT(length, 0u);
  EXPECT_EQ(std::string(line, length), line_for("DRV,0.1200,-0.1396", "\n"));
}

// The real serial path over a pseudo-terminal: we play the base on the master side.
TEST(SerialBaseLink, TalksToABaseOverATty) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  const std::string slave = ::ptsname(master);
  TestClock clock;
  SerialBaseLink link(clock, 500'000'000);
  std::string error;
  ASSERT_TRUE(link.open(slave, 115200, error)) << error;

  core::OdometryReading reading;
  EXPECT_EQ(link.read(reading).code, core::StatusCode::not_available);
  const std::string lines = line_for("ODO,1,100,0.5,0,0") + line_for("ODO,2,200,0.6,0.01,0.02");
  ASSERT_EQ(::write(master, lines.data(), lines.size()), static_cast<ssize_t>(lines.size()));
  clock.now = 2000;
  // The pty hands bytes over through a kernel worker: poll (bounded) rather than guess a delay.
  core::Status status = link.read(reading);
  for (int attempt = 0; attempt < 500 && status.code == core::StatusCode::not_available; ++attempt) {
    ::usleep(2000);
    status = link.read(reading);
  }
  ASSERT_TRUE(status.ok()) << status.message;
  EXPECT_EQ(reading.sequence, 2u);  // the newest reading; the pose is integrated, so none is lost
  EXPECT_DOUBLE_EQ(reading.pose.x, 0.6);
  EXPECT_EQ(reading.timestamp_ns, 2000);

  ASSERT_TRUE(link.command({0.1, 0.0}).ok());
  ASSERT_TRUE(link.stop().ok());
  const std::string expected = line_for("DRV,0.1000,0.0000", "\n") + line_for("DRV,0.0000,0.0000", "\n");
  std::string received;
  for (int attempt = 0; attempt < 500 && received.size() < expected.size(); ++attempt) {
    char buffer[128];
    const ssize_t count = ::read(master, buffer, sizeof buffer);
    if (count > 0) {
      received.append(buffer, static_cast<std::size_t>(count));
    } else {
      ::usleep(2000);
    }
  }
  EXPECT_EQ(received, expected);

  clock.now = 2000 + 600'000'000;
  EXPECT_EQ(link.read(reading).code, core::StatusCode::timeout);
  EXPECT_EQ(link.stats().timeouts, 1u);
  ::close(master);
}

TEST(SerialBaseLink, BadDevicesAreNamed) {
  TestClock clock;
  SerialBaseLink missing(clock, 1);
  std::string error;
  EXPECT_FALSE(missing.open("/dev/does-not-exist", 115200, error));
  EXPECT_NE(error.find("/dev/does-not-exist: cannot open the base link"), std::string::npos);
  SerialBaseLink not_a_tty(clock, 1);
  EXPECT_FALSE(not_a_tty.open("/dev/null", 115200, error));
  EXPECT_NE(error.find("/dev/null: not a serial port"), std::string::npos);
  SerialBaseLink odd_baud(clock, 1);
  EXPECT_FALSE(odd_baud.open("/dev/null", 12345, error));
  EXPECT_EQ(error, "/dev/null: unsupported baud rate 12345");
}

}  // namespace
}  // namespace stereoscout::robot_pc
