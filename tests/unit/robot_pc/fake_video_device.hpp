#pragma once
// A scripted capture device: frames become available at set times on a test clock.
#include <deque>
#include <string>
#include <vector>

#include "stereoscout/core/logging.hpp"
#include "stereoscout/robot_pc/video_device.hpp"

namespace stereoscout::robot_pc {

class TestClock final : public core::TimeSource {
 public:
  std::int64_t now_ns() const override { return now; }
  std::int64_t now = 0;
};

class FakeVideoDevice final : public VideoDevice {
 public:
  struct ScriptedFrame {
    std::int64_t available_at_ns;
    std::uint32_t sequence;
    std::int64_t timestamp_ns;
    std::vector<std::uint8_t> bytes;
  };

  FakeVideoDevice(std::string name, const TestClock& clock) : name_(std::move(name)), clock_(clock) {}

  const std::string& name() const override { return name_; }
  std::vector<std::uint32_t> supported_formats() override { return offered; }
  bool set_format(const VideoFormat& wanted, VideoFormat& granted, std::string&) override {
    granted = wanted;
    if (grant_size_override) {
      granted.width = granted_width;
      granted.height = granted_height;
    }
    granted.bytes_per_line = bytes_per_line;
    return true;
  }
  bool start(int, std::string&) override {
    started = true;
    return true;
  }
  core::Status next_frame(RawFrame& frame) override {
    if (script.empty() || script.front().available_at_ns > clock_.now) {
      return {core::StatusCode::not_available, "no frame"};
    }
    current = script.front();
    script.pop_front();
    frame.data = current.bytes.data();
    frame.bytes = current.bytes.size();
    frame.sequence = current.sequence;
    frame.timestamp_ns = current.timestamp_ns;
    ++outstanding;
    return core::Status::success();
  }
  void release_frame(const RawFrame&) override { --outstanding; }
  void stop() override { started = false; }

  std::vector<std::uint32_t> offered = {kPixelFormatGrey};
  bool grant_size_override = false;
  int granted_width = 0;
  int granted_height = 0;
  int bytes_per_line = 0;
  bool started = false;
  int outstanding = 0;
  std::deque<ScriptedFrame> script;

 private:
  std::string name_;
  const TestClock& clock_;
  ScriptedFrame current;
};

}  // namespace stereoscout::robot_pc
