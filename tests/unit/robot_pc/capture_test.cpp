#include <gtest/gtest.h>

#include "fake_video_device.hpp"
#include "stereoscout/robot_pc/format_negotiation.hpp"
#include "stereoscout/robot_pc/stereo_capture.hpp"

namespace stereoscout::robot_pc {
namespace {

constexpr int kWidth = 8;
constexpr int kHeight = 4;
constexpr std::int64_t kMs = 1'000'000;

std::vector<std::uint8_t> grey_image(std::uint8_t value, int width = kWidth) {
  return std::vector<std::uint8_t>(static_cast<std::size_t>(width * kHeight), value);
}

StereoCaptureOptions options() {
  StereoCaptureOptions result;
  result.width_px = kWidth;
  result.height_px = kHeight;
  result.pair_tolerance_ns = 5 * kMs;
  result.timeout_ns = 200 * kMs;
  return result;
}

TEST(FormatNegotiation, PrefersGreyThenPackedYuv) {
  EXPECT_EQ(choose_pixel_format({kPixelFormatYuyv, kPixelFormatGrey}), kPixelFormatGrey);
  EXPECT_EQ(choose_pixel_format({fourcc('M', 'J', 'P', 'G'), kPixelFormatUyvy}), kPixelFormatUyvy);
  EXPECT_EQ(choose_pixel_format({fourcc('M', 'J', 'P', 'G')}), 0u);
}

TEST(FormatNegotiation, RejectsDevicesWithoutAUsableFormatNamingThem) {
  TestClock clock;
  FakeVideoDevice device("/dev/video7", clock);
  device.offered = {fourcc('M', 'J', 'P', 'G'), fourcc('H', '2', '6', '4')};
  VideoFormat granted;
  std::string error;
  EXPECT_FALSE(negotiate_format(device, 640, 480, granted, error));
  EXPECT_EQ(error, "/dev/video7: offers no usable pixel format (want GREY, YUYV or UYVY; it offers MJPG, H264)");
}

TEST(FormatNegotiation, RejectsASizeTheDriverChanged) {
  TestClock clock;
  FakeVideoDevice device("/dev/video0", clock);
  device.grant_size_override = true;
  device.granted_width = 640;
  device.granted_height = 360;
  VideoFormat granted;
  std::string error;
  EXPECT_FALSE(negotiate_format(device, 640, 480, granted, error));
  EXPECT_NE(error.find("asked for GREY 640x480, the driver granted GREY 640x360"), std::string::npos) << error;
}

TEST(FormatNegotiation, LumaOfYuyvAndUyvyWithRowPadding) {
  const VideoFormat yuyv{kPixelFormatYuyv, 2, 2, 6};  // 4 bytes of pixels + 2 of padding per row
  RawFrame frame;
  const std::vector<std::uint8_t> bytes = {10, 1, 20, 2, 0, 0, 30, 3, 40, 4, 0, 0};
  frame.data = bytes.data();
  frame.bytes = bytes.size();
  cv::Mat grey(2, 2, CV_8UC1);
  ASSERT_TRUE(extract_luma(frame, yuyv, 0, grey));
  EXPECT_EQ(grey.at<std::uint8_t>(0, 0), 10);
  EXPECT_EQ(grey.at<std::uint8_t>(0, 1), 20);
  EXPECT_EQ(grey.at<std::uint8_t>(1, 0), 30);
  EXPECT_EQ(grey.at<std::uint8_t>(1, 1), 40);
  const VideoFormat uyvy{kPixelFormatUyvy, 2, 2, 6};
  ASSERT_TRUE(extract_luma(frame, uyvy, 0, grey));
  EXPECT_EQ(grey.at<std::uint8_t>(0, 0), 1);
  EXPECT_EQ(grey.at<std::uint8_t>(1, 1), 4);
  frame.bytes = 7;  // truncated buffer
  EXPECT_FALSE(extract_luma(frame, yuyv, 0, grey));
}

struct PairFixture : ::testing::Test {
  TestClock clock;
  FakeVideoDevice left{"/dev/video0", clock};
  FakeVideoDevice right{"/dev/video1", clock};
  StereoCapture capture{left, right, clock, options()};
  core::StereoFrame frame;

  void SetUp() override {
    frame.allocate(kWidth, kHeight);
    std::string error;
    ASSERT_TRUE(capture.start(error)) << error;
  }
  void add(FakeVideoDevice& device, std::uint32_t sequence, std::int64_t time_ns, std::uint8_t value) {
    device.script.push_back({time_ns, sequence, time_ns, grey_image(value)});
  }
};

TEST_F(PairFixture, PairsFramesByTimestamp) {
  for (std::uint32_t i = 0; i < 3; ++i) {
    const std::int64_t t = static_cast<std::int64_t>(i) * 66 * kMs;
    add(left, i, t, static_cast<std::uint8_t>(10 + i));
    add(right, i, t + 2 * kMs, static_cast<std::uint8_t>(100 + i));
  }
  clock.now = 300 * kMs;
  for (std::uint8_t i = 0; i < 3; ++i) {
    ASSERT_TRUE(capture.capture(frame).ok());
    EXPECT_EQ(frame.left.at<std::uint8_t>(0, 0), 10 + i);
    EXPECT_EQ(frame.right.at<std::uint8_t>(3, 7), 100 + i);
    EXPECT_EQ(frame.sequence, i);
    EXPECT_EQ(frame.timestamp_ns, static_cast<std::int64_t>(i) * 66 * kMs + 2 * kMs);  // the right image's time
  }
  EXPECT_EQ(capture.capture(frame).code, core::StatusCode::not_available);
  EXPECT_EQ(capture.stats().pairs, 3u);
  EXPECT_EQ(capture.stats().unpaired_dropped, 0u);
  EXPECT_EQ(left.outstanding, 0);
  EXPECT_EQ(right.outstanding, 0);
}

TEST_F(PairFixture, FrameWithoutPartnerIsDroppedAndDriverGapsCounted) {
  add(left, 0, 0, 1);
  add(right, 0, 1 * kMs, 2);
  add(left, 1, 66 * kMs, 3);  // its right partner was lost by the driver (sequence 1)
  add(left, 2, 133 * kMs, 5);
  add(right, 2, 134 * kMs, 6);
  clock.now = 200 * kMs;
  ASSERT_TRUE(capture.capture(frame).ok());
  ASSERT_TRUE(capture.capture(frame).ok());
  EXPECT_EQ(frame.left.at<std::uint8_t>(0, 0), 5);
  EXPECT_EQ(frame.right.at<std::uint8_t>(0, 0), 6);
  EXPECT_EQ(capture.stats().pairs, 2u);
  EXPECT_EQ(capture.stats().unpaired_dropped, 1u);
  EXPECT_EQ(capture.stats().driver_dropped, 1u);
}

TEST_F(PairFixture, OneSidedFrameWaitsForItsPartner) {
  add(left, 0, 0, 1);
  add(right, 0, 1 * kMs, 2);
  right.script.back().available_at_ns = 20 * kMs;  // right arrives later than left
  clock.now = 5 * kMs;
  EXPECT_EQ(capture.capture(frame).code, core::StatusCode::not_available);
  clock.now = 25 * kMs;
  EXPECT_TRUE(capture.capture(frame).ok());
  EXPECT_EQ(capture.stats().unpaired_dropped, 0u);
}

TEST_F(PairFixture, SilenceBecomesATimeout) {
  clock.now = 150 * kMs;
  EXPECT_EQ(capture.capture(frame).code, core::StatusCode::not_available);
  clock.now = 250 * kMs;
  EXPECT_EQ(capture.capture(frame).code, core::StatusCode::timeout);
  EXPECT_EQ(capture.stats().timeouts, 1u);
  add(left, 0, 260 * kMs, 1);
  add(right, 0, 260 * kMs, 2);
  clock.now = 270 * kMs;
  EXPECT_TRUE(capture.capture(frame).ok());  // recovers when frames come back
}

TEST(SideBySide, SplitsTheFrameIntoLeftAndRight) {
  TestClock clock;
  FakeVideoDevice device("/dev/video0", clock);
  StereoCapture capture(device, clock, options());
  std::string error;
  ASSERT_TRUE(capture.start(error)) << error;
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(2 * kWidth * kHeight));
  for (int row = 0; row < kHeight; ++row) {
    for (int column = 0; column < 2 * kWidth; ++column) {
      bytes[static_cast<std::size_t>(row * 2 * kWidth + column)] = column < kWidth ? 50 : 200;
    }
  }
  device.script.push_back({0, 0, 0, bytes});
  core::StereoFrame frame;
  frame.allocate(kWidth, kHeight);
  ASSERT_TRUE(capture.capture(frame).ok());
  EXPECT_EQ(frame.left.at<std::uint8_t>(2, kWidth - 1), 50);
  EXPECT_EQ(frame.right.at<std::uint8_t>(2, 0), 200);
  device.script.push_back({0, 1, 1, grey_image(1)});  // half as wide as promised
  EXPECT_EQ(capture.capture(frame).code, core::StatusCode::not_available);
  EXPECT_EQ(capture.stats().bad_frames, 1u);
}

}  // namespace
}  // namespace stereoscout::robot_pc
