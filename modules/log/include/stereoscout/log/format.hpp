#pragma once
// The sensor log format (docs/log-format.md): everything the stack consumes, so that a
// replay reproduces a run exactly. Little-endian throughout.
//
//   file   = file header, record*
//   header = magic "SSCOUTLG" (8 bytes), format version (u16), reserved (u16), reserved (u32)
//   record = sync "REC\x1e" (4), type (u16), flags (u16), payload length (u32),
//            timestamp_ns (i64), payload (length bytes), CRC-32 (u32) of type..payload
//
// The sync word lets a reader find the next record after a damaged one; the CRC tells a
// damaged record from a whole one.

#include <array>
#include <cstddef>
#include <cstdint>

namespace stereoscout::log {

inline constexpr std::array<char, 8> kFileMagic = {'S', 'S', 'C', 'O', 'U', 'T', 'L', 'G'};
inline constexpr std::uint16_t kFormatVersion = 1;
inline constexpr std::size_t kFileHeaderSize = 16;
inline constexpr std::array<std::uint8_t, 4> kRecordSync = {'R', 'E', 'C', 0x1e};
// sync + type + flags + length + timestamp
inline constexpr std::size_t kRecordHeaderSize = 4 + 2 + 2 + 4 + 8;
inline constexpr std::size_t kRecordTrailerSize = 4;
// Largest payload a reader accepts; a length beyond it is treated as damage.
inline constexpr std::uint32_t kMaxPayloadBytes = 64U * 1024U * 1024U;

enum class RecordType : std::uint16_t {
  run_info = 1,     // seed (u64), run flags (u32), program version text
  config = 2,       // the effective configuration as YAML text
  stereo_frame = 3, // see StereoFramePayload in records.hpp
  odometry = 4,     // sequence (u64), x, y, theta (f64)
  gpio_event = 5,   // line (u16), value (u8)
  drive_command = 6,  // linear m/s, angular rad/s (f64): what the stack commanded
  end_of_run = 7,   // clean end: records written (u64), records dropped (u64)
  ground_truth = 8,  // simulation only: the true pose x, y, theta (f64) at a kept frame's time
};

const char* to_string(RecordType type);
bool is_known(std::uint16_t type);

// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320), as zlib computes it.
std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t previous = 0);

// Little-endian encoding into and out of byte buffers.
void put_u16(std::uint8_t* out, std::uint16_t value);
void put_u32(std::uint8_t* out, std::uint32_t value);
void put_u64(std::uint8_t* out, std::uint64_t value);
void put_f64(std::uint8_t* out, double value);
std::uint16_t get_u16(const std::uint8_t* in);
std::uint32_t get_u32(const std::uint8_t* in);
std::uint64_t get_u64(const std::uint8_t* in);
double get_f64(const std::uint8_t* in);

}  // namespace stereoscout::log
