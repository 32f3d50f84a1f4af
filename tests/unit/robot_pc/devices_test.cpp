// The thin device layers against the real operating system, where no hardware is needed.
#include <gtest/gtest.h>

#include <string>

#include "stereoscout/robot_pc/gpio_lines.hpp"
#include "stereoscout/robot_pc/monotonic_clock.hpp"
#include "stereoscout/robot_pc/v4l2_device.hpp"

namespace stereoscout::robot_pc {
namespace {

TEST(V4l2Device, MissingDeviceAndNonCameraAreNamed) {
  std::string error;
  LinuxVideoDevice missing("/dev/video-does-not-exist");
  EXPECT_FALSE(missing.open(error));
  EXPECT_NE(error.find("/dev/video-does-not-exist: open failed"), std::string::npos) << error;
  LinuxVideoDevice not_a_camera("/dev/null");
  EXPECT_FALSE(not_a_camera.open(error));
  EXPECT_NE(error.find("/dev/null: not a V4L2 device"), std::string::npos) << error;
}

TEST(Gpio, EmergencyStopFailsSafe) {
  EXPECT_TRUE(emergency_stop_from_reading(0, true));    // active low, pressed
  EXPECT_FALSE(emergency_stop_from_reading(1, true));
  EXPECT_TRUE(emergency_stop_from_reading(1, false));   // active high, pressed
  EXPECT_FALSE(emergency_stop_from_reading(0, false));
  EXPECT_TRUE(emergency_stop_from_reading(-1, true));   // unreadable line: stop
  EXPECT_TRUE(emergency_stop_from_reading(-1, false));
}

TEST(Gpio, MissingChipIsNamedAndReadsAsStop) {
  GpiodLines lines;
  GpioLineConfig config;
  config.chip = "gpiochip-does-not-exist";
  std::string error;
  EXPECT_FALSE(lines.open(config, error));
  EXPECT_NE(error.find("GPIO chip gpiochip-does-not-exist: cannot open"), std::string::npos) << error;
  EXPECT_TRUE(lines.emergency_stop_active());
  EXPECT_EQ(lines.read_errors(), 1u);
  EXPECT_FALSE(lines.set_motor_enable(true).ok());
}

TEST(MonotonicClock, SleepsUntilTheDeadline) {
  MonotonicClock clock;
  const std::int64_t deadline = clock.now_ns() + 2'000'000;
  clock.sleep_until(deadline);
  EXPECT_GE(clock.now_ns(), deadline);
  clock.sleep_until(deadline - 1'000'000'000);  // a deadline in the past returns at once
}

}  // namespace
}  // namespace stereoscout::robot_pc
