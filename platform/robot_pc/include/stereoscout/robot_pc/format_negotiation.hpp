#pragma once
// Choosing and setting the pixel format of a capture device, and turning its frames into the
// 8-bit grey images the stack uses.

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "stereoscout/robot_pc/video_device.hpp"

namespace stereoscout::robot_pc {

// Our preference among what the device offers: 8-bit grey (no conversion), then the packed
// YUV 4:2:2 formats, whose luma is the grey image. 0 when none is offered.
std::uint32_t choose_pixel_format(const std::vector<std::uint32_t>& offered);

// Picks a format and sets width x height on the device; fails, naming the device, when it
// offers no usable format or the driver grants another size than asked.
bool negotiate_format(VideoDevice& device, int width, int height, VideoFormat& granted, std::string& error);

// Copies the luma of `columns` x `rows` pixels starting at column `first_column` of a frame in
// `format` into `grey` (CV_8UC1, already allocated at that size). False when the frame is too
// short for the format (a truncated buffer).
bool extract_luma(const RawFrame& frame, const VideoFormat& format, int first_column, cv::Mat& grey);

}  // namespace stereoscout::robot_pc
