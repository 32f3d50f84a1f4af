#pragma once
// Payload layouts of the log's record types, and their encoders and decoders. Decoders
// check sizes and values and return false on a payload that does not fit (the reader then
// counts the record as invalid and replay skips it).

#include <cstddef>
#include <cstdint>
#include <string>

#include "stereoscout/core/messages.hpp"

namespace stereoscout::log {

// stereo_frame: sequence (u64), pan_rad (f64), width (u32), height (u32),
//               left pixels (width*height bytes, row-major), right pixels (same).
inline constexpr std::size_t kStereoFrameFixedBytes = 8 + 8 + 4 + 4;
std::size_t stereo_frame_payload_size(int width_px, int height_px);
void encode_stereo_frame(const core::StereoFrame& frame, std::uint8_t* payload);
// Fills `frame`, whose images must already be allocated at the logged size.
bool decode_stereo_frame(const std::uint8_t* payload, std::size_t size, std::int64_t timestamp_ns,
                         core::StereoFrame& frame);

// odometry: sequence (u64), x, y, theta (f64)
inline constexpr std::size_t kOdometryPayloadBytes = 8 + 3 * 8;
void encode_odometry(const core::OdometryReading& reading, std::uint8_t* payload);
bool decode_odometry(const std::uint8_t* payload, std::size_t size, std::int64_t timestamp_ns,
                     core::OdometryReading& reading);

// drive_command: linear (f64), angular (f64)
inline constexpr std::size_t kDriveCommandPayloadBytes = 16;
void encode_drive_command(const core::DriveCommand& command, std::uint8_t* payload);
bool decode_drive_command(const std::uint8_t* payload, std::size_t size, core::DriveCommand& command);

// ground_truth: x, y, theta (f64); the simulator's true pose, so that a replay scores itself
inline constexpr std::size_t kGroundTruthPayloadBytes = 3 * 8;
void encode_ground_truth(const core::Pose2& pose, std::uint8_t* payload);
bool decode_ground_truth(const std::uint8_t* payload, std::size_t size, core::Pose2& pose);

// gpio_event: line (u16), value (u8)
struct GpioEvent {
  enum Line : std::uint16_t { emergency_stop = 1, motor_enable = 2 };
  std::uint16_t line = 0;
  bool value = false;
};
inline constexpr std::size_t kGpioEventPayloadBytes = 3;
void encode_gpio_event(const GpioEvent& event, std::uint8_t* payload);
bool decode_gpio_event(const std::uint8_t* payload, std::size_t size, GpioEvent& event);

// run_info: seed (u64), flags (u32), version text (rest)
struct RunInfo {
  std::uint64_t seed = 0;
  std::uint32_t flags = 0;
  std::string program_version;
};
std::size_t run_info_payload_size(const RunInfo& info);
void encode_run_info(const RunInfo& info, std::uint8_t* payload);
bool decode_run_info(const std::uint8_t* payload, std::size_t size, RunInfo& info);

// end_of_run: records written before this one (u64), records dropped (u64)
struct EndOfRun {
  std::uint64_t records_written = 0;
  std::uint64_t records_dropped = 0;
};
inline constexpr std::size_t kEndOfRunPayloadBytes = 16;
void encode_end_of_run(const EndOfRun& end, std::uint8_t* payload);
bool decode_end_of_run(const std::uint8_t* payload, std::size_t size, EndOfRun& end);

}  // namespace stereoscout::log
