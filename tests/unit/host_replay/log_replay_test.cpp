#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "stereoscout/host_replay/log_replay.hpp"
#include "stereoscout/log/writer.hpp"

namespace stereoscout::host_replay {
namespace {

constexpr std::int64_t kMs = 1'000'000;
constexpr int kWidth = 16;
constexpr int kHeight = 8;

core::StereoFrame make_frame(std::int64_t time_ns, std::uint64_t sequence, std::uint8_t value, int width = kWidth) {
  core::StereoFrame frame;
  frame.allocate(width, kHeight);
  frame.left.setTo(value);
  frame.right.setTo(static_cast<std::uint8_t>(value + 1));
  frame.timestamp_ns = time_ns;
  frame.sequence = sequence;
  frame.pan_rad = 0.25;
  return frame;
}

core::OdometryReading odometry_at(std::int64_t time_ns, std::uint64_t sequence, double x) {
  core::OdometryReading reading;
  reading.timestamp_ns = time_ns;
  reading.sequence = sequence;
  reading.pose = {x, 0.0, 0.0};
  return reading;
}

// run_info, config, then odometry at 100 ms, a frame at 150, odometry at 285, the e-stop at
// 300, a frame of the wrong size at 350, a frame at 400.
std::string write_run(const std::string& name) {
  const std::string path = ::testing::TempDir() + name;
  log::LogWriter writer;
  std::string error;
  EXPECT_TRUE(writer.open(path, error)) << error;
  writer.write_run_info(0, {7, 0, "test"});
  writer.write_config(0, "filter:\n  particles: 10\n");
  writer.write_odometry(odometry_at(100 * kMs, 0, 0.0));
  writer.write_stereo_frame(make_frame(150 * kMs, 0, 10));
  writer.write_odometry(odometry_at(285 * kMs, 1, 0.05));
  writer.write_gpio_event(300 * kMs, {log::GpioEvent::emergency_stop, true});
  writer.write_stereo_frame(make_frame(350 * kMs, 1, 99, kWidth / 2));
  writer.write_stereo_frame(make_frame(400 * kMs, 2, 20));
  writer.close(500 * kMs);
  return path;
}

LogReplayOptions options() {
  LogReplayOptions result;
  result.width_px = kWidth;
  result.height_px = kHeight;
  return result;
}

TEST(LogReplay, DeliversRecordsWhenTheClockReachesThem) {
  LogReplay replay(options());
  std::string error;
  ASSERT_TRUE(replay.open(write_run("replay.log"), error)) << error;
  EXPECT_EQ(replay.run_info().seed, 7u);
  EXPECT_EQ(replay.config_yaml(), "filter:\n  particles: 10\n");
  EXPECT_EQ(replay.clock().now_ns(), 0);  // starts where the live loop started: run_info's time
  replay.clock().sleep_until(100 * kMs);

  core::StereoFrame frame;
  frame.allocate(kWidth, kHeight);
  core::OdometryReading reading;
  EXPECT_EQ(replay.camera().capture(frame).code, core::StatusCode::not_available);
  ASSERT_TRUE(replay.odometry().read(reading).ok());
  EXPECT_EQ(reading.timestamp_ns, 100 * kMs);
  EXPECT_FALSE(replay.gpio().emergency_stop_active());

  replay.clock().sleep_until(150 * kMs);
  ASSERT_TRUE(replay.camera().capture(frame).ok());
  EXPECT_EQ(frame.left.at<std::uint8_t>(0, 0), 10);
  EXPECT_EQ(frame.right.at<std::uint8_t>(7, 15), 11);
  EXPECT_EQ(frame.pan_rad, 0.25);
  EXPECT_EQ(replay.odometry().read(reading).code, core::StatusCode::not_available);

  replay.clock().sleep_until(300 * kMs);
  ASSERT_TRUE(replay.odometry().read(reading).ok());
  EXPECT_EQ(reading.pose.x, 0.05);
  EXPECT_TRUE(replay.gpio().emergency_stop_active());

  replay.clock().sleep_until(450 * kMs);
  ASSERT_TRUE(replay.camera().capture(frame).ok());
  EXPECT_EQ(frame.sequence, 2u);
  EXPECT_EQ(replay.stats().invalid_records, 1u);  // the frame of the wrong size
  EXPECT_FALSE(replay.finished());
  replay.clock().sleep_until(500 * kMs);
  EXPECT_EQ(replay.camera().capture(frame).code, core::StatusCode::not_available);
  EXPECT_TRUE(replay.finished());
  EXPECT_TRUE(replay.saw_end_of_run());
  EXPECT_EQ(replay.end_of_run().records_written, 8u);
}

TEST(LogReplay, DamagedFrameIsSkippedAndTheRestReplays) {
  const std::string path = write_run("replay_damaged.log");
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  // Damage the first frame's pixels: it is the fourth record, after two small ones.
  const std::string frame_marker = "REC\x1e";
  std::size_t at = 0;
  for (int record = 0; record < 4; ++record) {
    at = std::string(bytes.begin(), bytes.end()).find(frame_marker, at + 1);
  }
  bytes[at + 40] ^= 0x55;
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));

  LogReplay replay(options());
  std::string error;
  ASSERT_TRUE(replay.open(path, error)) << error;
  core::StereoFrame frame;
  frame.allocate(kWidth, kHeight);
  replay.clock().sleep_until(1000 * kMs);
  ASSERT_TRUE(replay.camera().capture(frame).ok());
  EXPECT_EQ(frame.sequence, 2u);  // the damaged frame 0 is gone, frame 2 plays
  EXPECT_EQ(replay.reader_stats().damaged, 1u);
  core::OdometryReading reading;
  EXPECT_TRUE(replay.odometry().read(reading).ok());
  EXPECT_TRUE(replay.odometry().read(reading).ok());
}

TEST(LogReplay, MissingLogIsNamed) {
  LogReplay replay(options());
  std::string error;
  EXPECT_FALSE(replay.open("/nonexistent/run.log", error));
  EXPECT_NE(error.find("/nonexistent/run.log: cannot open the log"), std::string::npos);
}

}  // namespace
}  // namespace stereoscout::host_replay
