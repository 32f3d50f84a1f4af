#include "stereoscout/robot_pc/gpio_lines.hpp"

#include <gpiod.h>

#include <cerrno>
#include <cstring>

namespace stereoscout::robot_pc {
namespace {
constexpr const char* kConsumer = "stereoscout";
}

bool emergency_stop_from_reading(int value, bool active_low) {
  if (value < 0) {
    return true;
  }
  return active_low ? value == 0 : value != 0;
}

GpiodLines::~GpiodLines() {
  if (motor_enable_ != nullptr) {
    gpiod_line_set_value(motor_enable_, 0);
    gpiod_line_release(motor_enable_);
  }
  if (emergency_stop_ != nullptr) {
    gpiod_line_release(emergency_stop_);
  }
  if (chip_ != nullptr) {
    gpiod_chip_close(chip_);
  }
}

bool GpiodLines::open(const GpioLineConfig& config, std::string& error) {
  active_low_ = config.emergency_stop_active_low;
  chip_ = gpiod_chip_open_by_name(config.chip.c_str());
  if (chip_ == nullptr) {
    error = "GPIO chip " + config.chip + ": cannot open (" + std::strerror(errno) + ")";
    return false;
  }
  emergency_stop_ = gpiod_chip_get_line(chip_, config.emergency_stop_line);
  if (emergency_stop_ == nullptr || gpiod_line_request_input(emergency_stop_, kConsumer) != 0) {
    error = "GPIO chip " + config.chip + " line " + std::to_string(config.emergency_stop_line) +
            ": cannot request the emergency stop input (" + std::strerror(errno) + ")";
    emergency_stop_ = nullptr;
    return false;
  }
  motor_enable_ = gpiod_chip_get_line(chip_, config.motor_enable_line);
  if (motor_enable_ == nullptr || gpiod_line_request_output(motor_enable_, kConsumer, 0) != 0) {
    error = "GPIO chip " + config.chip + " line " + std::to_string(config.motor_enable_line) +
            ": cannot request the motor enable output (" + std::strerror(errno) + ")";
    motor_enable_ = nullptr;
    return false;
  }
  return true;
}

bool GpiodLines::emergency_stop_active() {
  const int value = emergency_stop_ != nullptr ? gpiod_line_get_value(emergency_stop_) : -1;
  if (value < 0) {
    ++read_errors_;
  }
  return emergency_stop_from_reading(value, active_low_);
}

core::Status GpiodLines::set_motor_enable(bool enabled) {
  if (motor_enable_ == nullptr || gpiod_line_set_value(motor_enable_, enabled ? 1 : 0) != 0) {
    return {core::StatusCode::io_error, "cannot set the motor enable line"};
  }
  return core::Status::success();
}

}  // namespace stereoscout::robot_pc
