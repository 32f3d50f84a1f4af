#pragma once
// Config section `robot_pc`: the devices of the robot's onboard computer (platform/robot_pc).
#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

inline constexpr const char* kCameraModeChoices[] = {"two_devices", "side_by_side", nullptr};

struct RobotPcConfig {
  std::string camera_mode = "two_devices";
  std::string left_device = "/dev/video0";
  std::string right_device = "/dev/video1";
  int capture_buffers = 4;
  double capture_timeout_ms = 200.0;
  double pair_tolerance_ms = 10.0;
  std::string gpio_chip = "gpiochip0";
  int emergency_stop_line = 17;
  bool emergency_stop_active_low = true;
  int motor_enable_line = 27;
  std::string base_link_device = "/dev/ttyUSB0";
  int base_link_baud = 115200;
  double base_link_timeout_ms = 500.0;
};

inline void describe(ConfigVisitor& v, RobotPcConfig& c) {
  v.begin_section("robot_pc", "Devices of the onboard computer: V4L2 cameras, GPIO lines, the serial link to the base.");
  v.choice("camera_mode", c.camera_mode, kCameraModeChoices, "Two synchronised V4L2 devices, or one device delivering left|right side by side.");
  v.text("left_device", c.left_device, "V4L2 device of the left camera (or of the side-by-side pair).");
  v.text("right_device", c.right_device, "V4L2 device of the right camera (two_devices only).");
  v.integer_field("capture_buffers", c.capture_buffers, {2, 32, "", "mmap buffers requested per device."});
  v.number("capture_timeout_ms", c.capture_timeout_ms, {1.0, 10000.0, "ms", "A device that delivers no frame for this long is reported as timed out."});
  v.number("pair_tolerance_ms", c.pair_tolerance_ms, {0.0, 1000.0, "ms", "Left and right frames whose timestamps differ by more than this are not a pair."});
  v.text("gpio_chip", c.gpio_chip, "GPIO chip name (libgpiod), e.g. gpiochip0.");
  v.integer_field("emergency_stop_line", c.emergency_stop_line, {0, 1023, "", "Line offset of the emergency stop input."});
  v.boolean("emergency_stop_active_low", c.emergency_stop_active_low, "The e-stop reads 0 when pressed (normally closed to ground).");
  v.integer_field("motor_enable_line", c.motor_enable_line, {0, 1023, "", "Line offset of the motor enable output."});
  v.text("base_link_device", c.base_link_device, "Serial device of the base controller (odometry in, drive commands out).");
  v.integer_field("base_link_baud", c.base_link_baud, {1200, 4000000, "baud", "Serial speed of the base link."});
  v.number("base_link_timeout_ms", c.base_link_timeout_ms, {1.0, 10000.0, "ms", "No odometry for this long: the link is reported as timed out."});
  v.end_section();
}

}  // namespace stereoscout::core
