#pragma once
// The integer inner loops of the dense block matcher (an implementation detail of
// DenseDisparityMatcher), compiled for the baseline instruction set and, on x86-64, also with
// the popcount instruction, with AVX2 and with AVX-512 (chosen at run time by what the CPU has). Integer
// arithmetic only, so every build gives bit-identical results (a DenseDisparity test compares
// them); elsewhere, and with DenseDisparityParams::allow_simd off, the portable build runs.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace stereoscout::vision::detail {

inline constexpr int kCensusRadius = 3;  // 7x7 census: 48 comparisons, fits 64 bits
inline constexpr std::uint8_t kMaxCensusCost = 48;
// Doubling levels of the box sum beyond the column sums: enough for windows up to 63 wide.
inline constexpr int kMaxBoxLevels = 5;

struct WinnerBuffers {
  const std::uint16_t* aggregated = nullptr;  // [disparity][x]
  int width = 0;
  int disparities = 0;
  int first_x = 0;
  int last_x = 0;
  std::uint16_t* best_cost = nullptr;
  std::uint16_t* second_cost = nullptr;
  std::int16_t* best_disparity = nullptr;
  std::uint16_t* right_best_cost = nullptr;
  std::int16_t* right_best_disparity = nullptr;
};

struct DenseKernels {
  // 7x7 census of a whole image (borders left 0).
  void (*census)(const std::uint8_t* image, std::size_t stride, int width, int height, std::uint64_t* census) = nullptr;
  // out[x] = popcount(left[x] ^ right[x - d]) for x in [first, width).
  void (*census_costs)(const std::uint64_t* left, const std::uint64_t* right, std::uint8_t* out, int first, int width,
                       int d) = nullptr;
  void (*add_costs)(std::uint16_t* sums, const std::uint8_t* costs, std::size_t count) = nullptr;
  void (*subtract_costs)(std::uint16_t* sums, const std::uint8_t* costs, std::size_t count) = nullptr;
  // Horizontal box sum (2 radius + 1 wide) of every disparity's column sums, x in [radius,
  // width - radius); scratch: kMaxBoxLevels x width.
  void (*box_sum)(const std::uint16_t* column_sums, std::uint16_t* aggregated, std::uint16_t* scratch, int disparities,
                  int width, int radius) = nullptr;
  // Best and best non-adjacent cost per left pixel, best per right pixel (ties: smaller disparity).
  void (*winners)(const WinnerBuffers& buffers) = nullptr;
  const char* name = "";
};

DenseKernels portable_dense_kernels();
// With allow_simd: the AVX-512 build if the CPU runs it, else AVX2, else the popcount one,
// else portable.
DenseKernels fastest_dense_kernels(bool allow_simd);
// Every build this CPU runs, portable first (for the tests that compare them).
std::vector<DenseKernels> supported_dense_kernels();

}  // namespace stereoscout::vision::detail
