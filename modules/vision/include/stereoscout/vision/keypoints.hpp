#pragma once
// A SIFT key as the front end keeps it: position in pixels, strength, and its 128-d
// descriptor stored as bytes (OpenCV's SIFT quantises its descriptor to 0..255 anyway), so
// distances are exact integers and ties are reproducible.

#include <array>
#include <cstdint>

namespace stereoscout::vision {

inline constexpr int kDescriptorLength = 128;
using Descriptor = std::array<std::uint8_t, kDescriptorLength>;

struct Keypoint {
  float x_px = 0.0F;  // column; pixel centres at integers
  float y_px = 0.0F;  // row
  float response = 0.0F;
  float size_px = 0.0F;
  Descriptor descriptor{};
};

// Squared Euclidean distance between two descriptors (exact).
inline std::uint32_t descriptor_distance_squared(const Descriptor& a, const Descriptor& b) {
  std::uint32_t sum = 0;
  for (int i = 0; i < kDescriptorLength; ++i) {
    const int difference = static_cast<int>(a[static_cast<std::size_t>(i)]) - static_cast<int>(b[static_cast<std::size_t>(i)]);
    sum += static_cast<std::uint32_t>(difference * difference);
  }
  return sum;
}

}  // namespace stereoscout::vision
