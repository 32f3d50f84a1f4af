#pragma once
// Emergency stop input and motor enable output through libgpiod (v1 API).

#include <cstdint>
#include <string>

#include "stereoscout/platform/gpio.hpp"

struct gpiod_chip;
struct gpiod_line;

namespace stereoscout::robot_pc {

// Whether a raw line reading means "stop". A failed read (negative) means stop: fail safe.
bool emergency_stop_from_reading(int value, bool active_low);

struct GpioLineConfig {
  std::string chip = "gpiochip0";
  unsigned emergency_stop_line = 17;
  bool emergency_stop_active_low = true;
  unsigned motor_enable_line = 27;
};

class GpiodLines final : public platform::Gpio {
 public:
  GpiodLines() = default;
  ~GpiodLines() override;
  GpiodLines(const GpiodLines&) = delete;
  GpiodLines& operator=(const GpiodLines&) = delete;

  // Requests the lines (motor enable starts off). On failure `error` names chip and line.
  bool open(const GpioLineConfig& config, std::string& error);

  bool emergency_stop_active() override;
  core::Status set_motor_enable(bool enabled) override;
  std::uint64_t read_errors() const { return read_errors_; }

 private:
  gpiod_chip* chip_ = nullptr;
  gpiod_line* emergency_stop_ = nullptr;
  gpiod_line* motor_enable_ = nullptr;
  bool active_low_ = true;
  std::uint64_t read_errors_ = 0;
};

}  // namespace stereoscout::robot_pc
