#include "stereoscout/robot_pc/format_negotiation.hpp"

#include <algorithm>
#include <cstring>

namespace stereoscout::robot_pc {

std::string fourcc_text(std::uint32_t code) {
  std::string text(4, ' ');
  for (int i = 0; i < 4; ++i) {
    const char c = static_cast<char>((code >> (8 * i)) & 0xFFU);
    text[static_cast<std::size_t>(i)] = c >= 32 && c < 127 ? c : '?';
  }
  return text;
}

std::uint32_t choose_pixel_format(const std::vector<std::uint32_t>& offered) {
  for (std::uint32_t preferred : {kPixelFormatGrey, kPixelFormatYuyv, kPixelFormatUyvy}) {
    if (std::find(offered.begin(), offered.end(), preferred) != offered.end()) {
      return preferred;
    }
  }
  return 0;
}

bool negotiate_format(VideoDevice& device, int width, int height, VideoFormat& granted, std::string& error) {
  const std::vector<std::uint32_t> offered = device.supported_formats();
  const std::uint32_t pixel_format = choose_pixel_format(offered);
  if (pixel_format == 0) {
    std::string list;
    for (std::uint32_t code : offered) {
      list += (list.empty() ? "" : ", ") + fourcc_text(code);
    }
    error = device.name() + ": offers no usable pixel format (want GREY, YUYV or UYVY; it offers " +
            (list.empty() ? std::string("none") : list) + ")";
    return false;
  }
  if (!device.set_format({pixel_format, width, height, 0}, granted, error)) {
    return false;
  }
  if (granted.pixel_format != pixel_format || granted.width != width || granted.height != height) {
    error = device.name() + ": asked for " + fourcc_text(pixel_format) + " " + std::to_string(width) + "x" +
            std::to_string(height) + ", the driver granted " + fourcc_text(granted.pixel_format) + " " +
            std::to_string(granted.width) + "x" + std::to_string(granted.height) +
            " (set camera.width_px/height_px to a size the camera supports)";
    return false;
  }
  const int bytes_per_pixel = pixel_format == kPixelFormatGrey ? 1 : 2;
  if (granted.bytes_per_line < width * bytes_per_pixel) {
    granted.bytes_per_line = width * bytes_per_pixel;  // drivers may leave it 0: packed rows
  }
  return true;
}

bool extract_luma(const RawFrame& frame, const VideoFormat& format, int first_column, cv::Mat& grey) {
  const int bytes_per_pixel = format.pixel_format == kPixelFormatGrey ? 1 : 2;
  const int luma_offset = format.pixel_format == kPixelFormatUyvy ? 1 : 0;
  const auto needed = static_cast<std::size_t>(format.bytes_per_line) * static_cast<std::size_t>(grey.rows - 1) +
                      static_cast<std::size_t>((first_column + grey.cols) * bytes_per_pixel);
  if (frame.data == nullptr || frame.bytes < needed || grey.rows > format.height) {
    return false;
  }
  for (int row = 0; row < grey.rows; ++row) {
    const std::uint8_t* source = frame.data + static_cast<std::size_t>(row) * static_cast<std::size_t>(format.bytes_per_line) +
                                 static_cast<std::size_t>(first_column * bytes_per_pixel + luma_offset);
    auto* target = grey.ptr<std::uint8_t>(row);
    if (bytes_per_pixel == 1) {
      std::memcpy(target, source, static_cast<std::size_t>(grey.cols));
    } else {
      for (int column = 0; column < grey.cols; ++column) {
        target[column] = source[2 * column];
      }
    }
  }
  return true;
}

}  // namespace stereoscout::robot_pc
