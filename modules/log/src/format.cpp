#include "stereoscout/log/format.hpp"

#include <cstring>

namespace stereoscout::log {
namespace {

constexpr std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t value = i;
    for (int bit = 0; bit < 8; ++bit) {
      value = (value & 1U) != 0 ? 0xEDB88320U ^ (value >> 1) : value >> 1;
    }
    table[i] = value;
  }
  return table;
}

constexpr std::array<std::uint32_t, 256> kCrcTable = make_crc_table();

}  // namespace

const char* to_string(RecordType type) {
  switch (type) {
    case RecordType::run_info: return "run_info";
    case RecordType::config: return "config";
    case RecordType::stereo_frame: return "stereo_frame";
    case RecordType::odometry: return "odometry";
    case RecordType::gpio_event: return "gpio_event";
    case RecordType::drive_command: return "drive_command";
    case RecordType::end_of_run: return "end_of_run";
    case RecordType::ground_truth: return "ground_truth";
  }
  return "unknown";
}

bool is_known(std::uint16_t type) {
  return type >= static_cast<std::uint16_t>(RecordType::run_info) &&
         type <= static_cast<std::uint16_t>(RecordType::ground_truth);
}

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t previous) {
  std::uint32_t crc = ~previous;
  for (std::size_t i = 0; i < size; ++i) {
    crc = kCrcTable[(crc ^ data[i]) & 0xFFU] ^ (crc >> 8);
  }
  return ~crc;
}

void put_u16(std::uint8_t* out, std::uint16_t value) {
  out[0] = static_cast<std::uint8_t>(value);
  out[1] = static_cast<std::uint8_t>(value >> 8);
}

void put_u32(std::uint8_t* out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) {
    out[i] = static_cast<std::uint8_t>(value >> (8 * i));
  }
}

void put_u64(std::uint8_t* out, std::uint64_t value) {
  for (int i = 0; i < 8; ++i) {
    out[i] = static_cast<std::uint8_t>(value >> (8 * i));
  }
}

void put_f64(std::uint8_t* out, double value) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  put_u64(out, bits);
}

std::uint16_t get_u16(const std::uint8_t* in) {
  return static_cast<std::uint16_t>(in[0] | (in[1] << 8));
}

std::uint32_t get_u32(const std::uint8_t* in) {
  std::uint32_t value = 0;
  for (int i = 3; i >= 0; --i) {
    value = (value << 8) | in[i];
  }
  return value;
}

std::uint64_t get_u64(const std::uint8_t* in) {
  std::uint64_t value = 0;
  for (int i = 7; i >= 0; --i) {
    value = (value << 8) | in[i];
  }
  return value;
}

double get_f64(const std::uint8_t* in) {
  const std::uint64_t bits = get_u64(in);
  double value = 0.0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}  // namespace stereoscout::log
