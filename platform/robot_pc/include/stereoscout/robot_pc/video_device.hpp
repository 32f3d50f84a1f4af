#pragma once
// One video capture device as the stereo capture logic needs it. LinuxVideoDevice
// (v4l2_device.hpp) speaks V4L2 to /dev/videoN; tests use a scripted fake, so format
// negotiation, frame pairing, drops and timeouts are tested without a camera.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "stereoscout/core/status.hpp"

namespace stereoscout::robot_pc {

// V4L2 four-character codes of the pixel formats we take (values as in videodev2.h).
constexpr std::uint32_t fourcc(char a, char b, char c, char d) {
  return static_cast<std::uint32_t>(a) | (static_cast<std::uint32_t>(b) << 8) | (static_cast<std::uint32_t>(c) << 16) |
         (static_cast<std::uint32_t>(d) << 24);
}
inline constexpr std::uint32_t kPixelFormatGrey = fourcc('G', 'R', 'E', 'Y');
inline constexpr std::uint32_t kPixelFormatYuyv = fourcc('Y', 'U', 'Y', 'V');
inline constexpr std::uint32_t kPixelFormatUyvy = fourcc('U', 'Y', 'V', 'Y');
std::string fourcc_text(std::uint32_t code);

struct VideoFormat {
  std::uint32_t pixel_format = 0;
  int width = 0;
  int height = 0;
  int bytes_per_line = 0;
};

// A filled driver buffer, valid until release_frame().
struct RawFrame {
  const std::uint8_t* data = nullptr;
  std::size_t bytes = 0;
  std::uint32_t sequence = 0;     // the driver's frame counter; gaps are dropped frames
  std::int64_t timestamp_ns = 0;  // when the driver captured it (CLOCK_MONOTONIC)
  std::uint32_t buffer_index = 0;
};

class VideoDevice {
 public:
  virtual ~VideoDevice() = default;
  virtual const std::string& name() const = 0;
  // Start-up calls: they may allocate, and report failures in `error`.
  virtual std::vector<std::uint32_t> supported_formats() = 0;
  // Asks for a format; `granted` is what the driver agreed to (it may change the size).
  virtual bool set_format(const VideoFormat& wanted, VideoFormat& granted, std::string& error) = 0;
  virtual bool start(int buffer_count, std::string& error) = 0;
  // Tick-loop calls. next_frame() does not wait: not_available when no frame is ready.
  virtual core::Status next_frame(RawFrame& frame) = 0;
  virtual void release_frame(const RawFrame& frame) = 0;
  virtual void stop() = 0;
};

}  // namespace stereoscout::robot_pc
