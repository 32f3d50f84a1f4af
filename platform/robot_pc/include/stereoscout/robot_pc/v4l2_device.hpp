#pragma once
// A V4L2 capture device (/dev/videoN) with mmap streaming I/O.

#include <string>
#include <vector>

#include "stereoscout/robot_pc/video_device.hpp"

namespace stereoscout::robot_pc {

class LinuxVideoDevice final : public VideoDevice {
 public:
  explicit LinuxVideoDevice(std::string path);
  ~LinuxVideoDevice() override;
  LinuxVideoDevice(const LinuxVideoDevice&) = delete;
  LinuxVideoDevice& operator=(const LinuxVideoDevice&) = delete;

  // Opens the device and checks it captures video with streaming I/O.
  bool open(std::string& error);

  const std::string& name() const override { return path_; }
  std::vector<std::uint32_t> supported_formats() override;
  bool set_format(const VideoFormat& wanted, VideoFormat& granted, std::string& error) override;
  bool start(int buffer_count, std::string& error) override;
  core::Status next_frame(RawFrame& frame) override;
  void release_frame(const RawFrame& frame) override;
  void stop() override;

 private:
  struct Buffer {
    void* start = nullptr;
    std::size_t length = 0;
  };
  std::string path_;
  int fd_ = -1;
  bool streaming_ = false;
  std::vector<Buffer> buffers_;
};

}  // namespace stereoscout::robot_pc
