#include "stereoscout/robot_pc/v4l2_device.hpp"

#include <fcntl.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace stereoscout::robot_pc {
namespace {

// ioctl, retried when a signal interrupts it.
int xioctl(int fd, unsigned long request, void* argument) {
  int result = 0;
  do {
    result = ::ioctl(fd, request, argument);
  } while (result == -1 && errno == EINTR);
  return result;
}

std::string failure(const std::string& path, const char* what) {
  return path + ": " + what + " failed (" + std::strerror(errno) + ")";
}

constexpr std::int64_t kNanosecondsPerSecond = 1'000'000'000;
constexpr std::int64_t kNanosecondsPerMicrosecond = 1000;

}  // namespace

LinuxVideoDevice::LinuxVideoDevice(std::string path) : path_(std::move(path)) {}

LinuxVideoDevice::~LinuxVideoDevice() {
  stop();
  if (fd_ >= 0) {
    ::close(fd_);
  }
}

bool LinuxVideoDevice::open(std::string& error) {
  fd_ = ::open(path_.c_str(), O_RDWR | O_NONBLOCK);
  if (fd_ < 0) {
    error = failure(path_, "open");
    return false;
  }
  v4l2_capability capability{};
  if (xioctl(fd_, VIDIOC_QUERYCAP, &capability) == -1) {
    error = path_ + ": not a V4L2 device (VIDIOC_QUERYCAP: " + std::strerror(errno) + ")";
    return false;
  }
  const std::uint32_t caps = (capability.capabilities & V4L2_CAP_DEVICE_CAPS) != 0 ? capability.device_caps
                                                                                    : capability.capabilities;
  if ((caps & V4L2_CAP_VIDEO_CAPTURE) == 0 || (caps & V4L2_CAP_STREAMING) == 0) {
    error = path_ + ": does not capture video with streaming I/O";
    return false;
  }
  return true;
}

std::vector<std::uint32_t> LinuxVideoDevice::supported_formats() {
  std::vector<std::uint32_t> formats;
  v4l2_fmtdesc description{};
  description.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  while (xioctl(fd_, VIDIOC_ENUM_FMT, &description) == 0) {
    formats.push_back(description.pixelformat);
    ++description.index;
  }
  return formats;
}

bool LinuxVideoDevice::set_format(const VideoFormat& wanted, VideoFormat& granted, std::string& error) {
  v4l2_format format{};
  format.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  format.fmt.pix.width = static_cast<std::uint32_t>(wanted.width);
  format.fmt.pix.height = static_cast<std::uint32_t>(wanted.height);
  format.fmt.pix.pixelformat = wanted.pixel_format;
  format.fmt.pix.field = V4L2_FIELD_NONE;
  if (xioctl(fd_, VIDIOC_S_FMT, &format) == -1) {
    error = failure(path_, "VIDIOC_S_FMT");
    return false;
  }
  granted = {format.fmt.pix.pixelformat, static_cast<int>(format.fmt.pix.width),
             static_cast<int>(format.fmt.pix.height), static_cast<int>(format.fmt.pix.bytesperline)};
  return true;
}

bool LinuxVideoDevice::start(int buffer_count, std::string& error) {
  v4l2_requestbuffers request{};
  request.count = static_cast<std::uint32_t>(buffer_count);
  request.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  request.memory = V4L2_MEMORY_MMAP;
  if (xioctl(fd_, VIDIOC_REQBUFS, &request) == -1) {
    error = failure(path_, "VIDIOC_REQBUFS (mmap streaming)");
    return false;
  }
  if (request.count < 2) {
    error = path_ + ": the driver granted fewer than 2 capture buffers";
    return false;
  }
  buffers_.resize(request.count);
  for (std::uint32_t i = 0; i < request.count; ++i) {
    v4l2_buffer buffer{};
    buffer.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buffer.memory = V4L2_MEMORY_MMAP;
    buffer.index = i;
    if (xioctl(fd_, VIDIOC_QUERYBUF, &buffer) == -1) {
      error = failure(path_, "VIDIOC_QUERYBUF");
      return false;
    }
    void* start = ::mmap(nullptr, buffer.length, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, buffer.m.offset);
    if (start == MAP_FAILED) {
      error = failure(path_, "mmap of a capture buffer");
      return false;
    }
    buffers_[i] = {start, buffer.length};
    if (xioctl(fd_, VIDIOC_QBUF, &buffer) == -1) {
      error = failure(path_, "VIDIOC_QBUF");
      return false;
    }
  }
  int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  if (xioctl(fd_, VIDIOC_STREAMON, &type) == -1) {
    error = failure(path_, "VIDIOC_STREAMON");
    return false;
  }
  streaming_ = true;
  return true;
}

core::Status LinuxVideoDevice::next_frame(RawFrame& frame) {
  pollfd ready{fd_, POLLIN, 0};
  const int polled = ::poll(&ready, 1, 0);
  if (polled == 0) {
    return {core::StatusCode::not_available, "no frame ready"};
  }
  if (polled < 0 || (ready.revents & (POLLERR | POLLHUP | POLLNVAL)) != 0) {
    return {core::StatusCode::io_error, "camera device failed (poll)"};
  }
  v4l2_buffer buffer{};
  buffer.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  buffer.memory = V4L2_MEMORY_MMAP;
  if (xioctl(fd_, VIDIOC_DQBUF, &buffer) == -1) {
    return errno == EAGAIN ? core::Status{core::StatusCode::not_available, "no frame ready"}
                           : core::Status{core::StatusCode::io_error, "camera device failed (VIDIOC_DQBUF)"};
  }
  if (buffer.index >= buffers_.size()) {
    return {core::StatusCode::io_error, "camera driver returned an unknown buffer"};
  }
  frame.data = static_cast<const std::uint8_t*>(buffers_[buffer.index].start);
  frame.bytes = buffer.bytesused;
  frame.sequence = buffer.sequence;
  frame.timestamp_ns = static_cast<std::int64_t>(buffer.timestamp.tv_sec) * kNanosecondsPerSecond +
                       static_cast<std::int64_t>(buffer.timestamp.tv_usec) * kNanosecondsPerMicrosecond;
  frame.buffer_index = buffer.index;
  return core::Status::success();
}

void LinuxVideoDevice::release_frame(const RawFrame& frame) {
  v4l2_buffer buffer{};
  buffer.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  buffer.memory = V4L2_MEMORY_MMAP;
  buffer.index = frame.buffer_index;
  xioctl(fd_, VIDIOC_QBUF, &buffer);  // a failure shows up as the next frame missing
}

void LinuxVideoDevice::stop() {
  if (streaming_) {
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    xioctl(fd_, VIDIOC_STREAMOFF, &type);
    streaming_ = false;
  }
  for (Buffer& buffer : buffers_) {
    if (buffer.start != nullptr) {
      ::munmap(buffer.start, buffer.length);
    }
  }
  buffers_.clear();
}

}  // namespace stereoscout::robot_pc
