#include "stereoscout/vision/dense_disparity_kernels.hpp"

#include <algorithm>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#endif

namespace stereoscout::vision::detail {
namespace {

#define STEREOSCOUT_KERNEL_BODY inline __attribute__((always_inline))

// Bit 47 - k of a pixel's census is "neighbour k is darker than the centre", neighbours k in
// row-major order of the 7x7 window without its centre. Built in bytes (8 neighbours each,
// so the compares run 32 pixels to an AVX2 register instead of 4), over blocks of pixels
// on the stack, then the six bytes are joined into the 64-bit word: the same bits.
STEREOSCOUT_KERNEL_BODY void census_body(const std::uint8_t* image, std::size_t stride, int width, int height,
                                         std::uint64_t* census) {
  constexpr int kBlock = 64;
  constexpr int kGroups = 6;  // 48 neighbours / 8
  std::fill(census, census + static_cast<std::size_t>(width) * static_cast<std::size_t>(height), std::uint64_t{0});
  const int first = kCensusRadius;
  const int last = width - kCensusRadius;
  for (int y = kCensusRadius; y < height - kCensusRadius; ++y) {
    std::uint64_t* bits = census + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
    for (int start = first; start < last; start += kBlock) {
      const int count = std::min(kBlock, last - start);
      std::uint8_t groups[kGroups][kBlock] = {};
      const std::uint8_t* centre = image + static_cast<std::size_t>(y) * stride + start;
      int neighbour_index = 0;
      for (int dy = -kCensusRadius; dy <= kCensusRadius; ++dy) {
        const std::uint8_t* row = image + static_cast<std::size_t>(y + dy) * stride + start;
        for (int dx = -kCensusRadius; dx <= kCensusRadius; ++dx) {
          if (dx == 0 && dy == 0) {
            continue;
          }
          std::uint8_t* __restrict group = groups[neighbour_index / 8];
          const std::uint8_t* neighbour = row + dx;
          for (int i = 0; i < count; ++i) {
            const unsigned darker = static_cast<unsigned>(neighbour[i] < centre[i]);
            group[i] = static_cast<std::uint8_t>((static_cast<unsigned>(group[i]) << 1U) | darker);
          }
          ++neighbour_index;
        }
      }
      std::uint64_t* __restrict out = bits + start;
      for (int i = 0; i < count; ++i) {
        std::uint64_t word = 0;
        for (int g = 0; g < kGroups; ++g) {
          word = (word << 8U) | groups[g][i];
        }
        out[i] = word;
      }
    }
  }
}

// Integer popcount is exact, so the hardware instruction gives the portable result.
STEREOSCOUT_KERNEL_BODY void census_costs_body(const std::uint64_t* left, const std::uint64_t* right,
                                               std::uint8_t* out, int first, int width, int d) {
  for (int x = first; x < width; ++x) {
    out[x] = static_cast<std::uint8_t>(__builtin_popcountll(left[x] ^ right[x - d]));
  }
}

STEREOSCOUT_KERNEL_BODY void add_costs_body(std::uint16_t* __restrict sums, const std::uint8_t* __restrict costs,
                                            std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    sums[i] = static_cast<std::uint16_t>(sums[i] + costs[i]);
  }
}

STEREOSCOUT_KERNEL_BODY void subtract_costs_body(std::uint16_t* __restrict sums, const std::uint8_t* __restrict costs,
                                                 std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    sums[i] = static_cast<std::uint16_t>(sums[i] - costs[i]);
  }
}

// Box sums by doubling: P1 = the column sums, P2k[i] = Pk[i] + Pk[i + k], and a window of
// w = 2 radius + 1 columns is the sum of the P's of w's binary digits side by side (w = 7:
// P4 + P2 + P1, 4 additions per element instead of 6). Straight loops without a carried
// dependency, so they vectorise; integer sums, so the grouping does not change the result.
STEREOSCOUT_KERNEL_BODY void box_sum_body(const std::uint16_t* column_sums, std::uint16_t* aggregated,
                                          std::uint16_t* scratch, int disparities, int width, int radius) {
  const int window = 2 * radius + 1;
  const int outputs = width - window + 1;  // x = radius + i, i in [0, outputs)
  if (outputs <= 0) {
    return;
  }
  for (int d = 0; d < disparities; ++d) {
    const std::uint16_t* levels[kMaxBoxLevels + 1] = {};
    levels[0] = column_sums + static_cast<std::size_t>(d) * static_cast<std::size_t>(width);
    int top = 0;
    for (int span = 1; 2 * span <= window; span *= 2) {
      const std::uint16_t* previous = levels[top];
      std::uint16_t* __restrict next = scratch + static_cast<std::size_t>(top) * static_cast<std::size_t>(width);
      for (int i = 0; i + 2 * span <= width; ++i) {
        next[i] = static_cast<std::uint16_t>(previous[i] + previous[i + span]);
      }
      levels[++top] = next;
    }
    std::uint16_t* __restrict out =
        aggregated + static_cast<std::size_t>(d) * static_cast<std::size_t>(width) + static_cast<std::size_t>(radius);
    int offset = 0;
    bool first = true;
    for (int level = top; level >= 0; --level) {
      const int span = 1 << level;
      if ((window & span) == 0) {
        continue;
      }
      const std::uint16_t* part = levels[level] + offset;
      if (first) {
        for (int i = 0; i < outputs; ++i) {
          out[i] = part[i];
        }
        first = false;
      } else {
        for (int i = 0; i < outputs; ++i) {
          out[i] = static_cast<std::uint16_t>(out[i] + part[i]);
        }
      }
      offset += span;
    }
  }
}

// Disparities ascend, and only a strictly lower cost replaces a winner, so ties go to the
// smaller disparity.
STEREOSCOUT_KERNEL_BODY void winners_body(const WinnerBuffers& b) {
  constexpr std::uint16_t kNoCost = 0xFFFF;
  const auto width = static_cast<std::size_t>(b.width);
  std::fill(b.best_cost, b.best_cost + width, kNoCost);
  std::fill(b.second_cost, b.second_cost + width, kNoCost);
  std::fill(b.best_disparity, b.best_disparity + width, std::int16_t{0});
  std::fill(b.right_best_cost, b.right_best_cost + width, kNoCost);
  std::fill(b.right_best_disparity, b.right_best_disparity + width, std::int16_t{-1});
  std::uint16_t* __restrict best_cost = b.best_cost;
  std::int16_t* __restrict best_disparity = b.best_disparity;
  std::uint16_t* __restrict right_cost = b.right_best_cost;
  std::int16_t* __restrict right_disparity = b.right_best_disparity;
  for (int d = 0; d < b.disparities; ++d) {
    const std::uint16_t* costs = b.aggregated + static_cast<std::size_t>(d) * width;
    const auto disparity = static_cast<std::int16_t>(d);
    // Left pixel x searches d <= x - first_x.
    for (int x = b.first_x + d; x <= b.last_x; ++x) {
      const bool better = costs[x] < best_cost[x];
      best_cost[x] = better ? costs[x] : best_cost[x];
      best_disparity[x] = better ? disparity : best_disparity[x];
    }
    // Right pixel xr pairs with left pixel xr + d.
    const std::uint16_t* shifted = costs + d;
    for (int xr = b.first_x; xr + d <= b.last_x; ++xr) {
      const bool better = shifted[xr] < right_cost[xr];
      right_cost[xr] = better ? shifted[xr] : right_cost[xr];
      right_disparity[xr] = better ? disparity : right_disparity[xr];
    }
  }
  const std::int16_t* __restrict best = b.best_disparity;
  std::uint16_t* __restrict second = b.second_cost;
  for (int d = 0; d < b.disparities; ++d) {
    const std::uint16_t* costs = b.aggregated + static_cast<std::size_t>(d) * width;
    const auto disparity = static_cast<std::int16_t>(d);
    for (int x = b.first_x + d; x <= b.last_x; ++x) {
      // |d - best| > 1 with signed 16-bit compares (SSE2 has no unsigned ones).
      const auto gap = static_cast<std::int16_t>(disparity - best[x]);
      const int far = static_cast<int>(gap > 1) | static_cast<int>(gap < -1);
      // kNoCost where adjacent: an OR with all ones, so the load is unconditional (vectorises).
      const auto masked = static_cast<std::uint16_t>(costs[x] | static_cast<std::uint16_t>(far - 1));
      second[x] = masked < second[x] ? masked : second[x];
    }
  }
}

// One build of every kernel per instruction set; the bodies are inlined into each.
#define STEREOSCOUT_DEFINE_KERNELS(SUFFIX, ATTRIBUTES)                                                             \
  ATTRIBUTES void census_##SUFFIX(const std::uint8_t* image, std::size_t stride, int width, int height,            \
                                  std::uint64_t* census) {                                                         \
    census_body(image, stride, width, height, census);                                                             \
  }                                                                                                                \
  ATTRIBUTES void census_costs_##SUFFIX(const std::uint64_t* left, const std::uint64_t* right, std::uint8_t* out,  \
                                        int first, int width, int d) {                                             \
    census_costs_body(left, right, out, first, width, d);                                                          \
  }                                                                                                                \
  ATTRIBUTES void add_costs_##SUFFIX(std::uint16_t* sums, const std::uint8_t* costs, std::size_t count) {          \
    add_costs_body(sums, costs, count);                                                                            \
  }                                                                                                                \
  ATTRIBUTES void subtract_costs_##SUFFIX(std::uint16_t* sums, const std::uint8_t* costs, std::size_t count) {     \
    subtract_costs_body(sums, costs, count);                                                                       \
  }                                                                                                                \
  ATTRIBUTES void box_sum_##SUFFIX(const std::uint16_t* column_sums, std::uint16_t* aggregated,                    \
                                   std::uint16_t* scratch, int disparities, int width, int radius) {               \
    box_sum_body(column_sums, aggregated, scratch, disparities, width, radius);                                    \
  }                                                                                                                \
  ATTRIBUTES void winners_##SUFFIX(const WinnerBuffers& buffers) { winners_body(buffers); }                        \
  DenseKernels kernels_##SUFFIX() {                                                                                \
    return {census_##SUFFIX, census_costs_##SUFFIX, add_costs_##SUFFIX, subtract_costs_##SUFFIX,                   \
            box_sum_##SUFFIX,  winners_##SUFFIX,      #SUFFIX};                                                     \
  }

STEREOSCOUT_DEFINE_KERNELS(portable, )

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define STEREOSCOUT_HAS_AVX2_KERNELS 1
STEREOSCOUT_DEFINE_KERNELS(popcnt, __attribute__((target("popcnt"))))
STEREOSCOUT_DEFINE_KERNELS(avx2, __attribute__((target("avx2,popcnt"))))

// Census costs of 16 pixels at a time in AVX2 registers: the popcount of each byte of
// left ^ right from a 16-entry table (vpshufb on both nibbles), summed per 64-bit census by
// vpsadbw; the four 4-pixel results are interleaved into bytes and put back in pixel order.
// Exact integer counts, the same as the popcount instruction; the tail runs the scalar loop.
__attribute__((target("avx2,popcnt"))) void census_costs_avx2_table(const std::uint64_t* left,
                                                                    const std::uint64_t* right, std::uint8_t* out,
                                                                    int first, int width, int d) {
  const __m256i table = _mm256_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4, 0, 1, 1, 2, 1, 2, 2, 3, 1, 2,
                                         2, 3, 2, 3, 3, 4);
  const __m256i nibble = _mm256_set1_epi8(0x0F);
  const __m256i zero = _mm256_setzero_si256();
  const __m256i low_dwords = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  const __m128i pixel_order = _mm_setr_epi8(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15);
  int x = first;
  for (; x + 16 <= width; x += 16) {
    __m256i packed = zero;
    for (int k = 0; k < 4; ++k) {
      const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(left + x + 4 * k));
      const __m256i b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(right + x + 4 * k - d));
      const __m256i bits = _mm256_xor_si256(a, b);
      const __m256i low = _mm256_and_si256(bits, nibble);
      const __m256i high = _mm256_and_si256(_mm256_srli_epi16(bits, 4), nibble);
      const __m256i bytes = _mm256_add_epi8(_mm256_shuffle_epi8(table, low), _mm256_shuffle_epi8(table, high));
      // Each 64-bit lane j now holds the cost of pixel x + 4k + j (at most 64): byte k of it.
      packed = _mm256_or_si256(packed, _mm256_slli_epi64(_mm256_sad_epu8(bytes, zero), 8 * k));
    }
    // Low dword of lane j = costs of pixels x + j, x + 4 + j, x + 8 + j, x + 12 + j.
    const __m128i lanes = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(packed, low_dwords));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + x), _mm_shuffle_epi8(lanes, pixel_order));
  }
  for (; x < width; ++x) {
    out[x] = static_cast<std::uint8_t>(__builtin_popcountll(left[x] ^ right[x - d]));
  }
}

// The same with AVX-512: eight censuses to a register and the popcount instruction for
// 64-bit lanes (VPOPCNTQ), narrowed to bytes in pixel order.
#define STEREOSCOUT_AVX512_TARGET "avx512f,avx512bw,avx512vl,avx512vpopcntdq,avx2,popcnt"
STEREOSCOUT_DEFINE_KERNELS(avx512, __attribute__((target(STEREOSCOUT_AVX512_TARGET))))

__attribute__((target(STEREOSCOUT_AVX512_TARGET))) void census_costs_avx512_popcount(const std::uint64_t* left,
                                                                                     const std::uint64_t* right,
                                                                                     std::uint8_t* out, int first,
                                                                                     int width, int d) {
  int x = first;
  for (; x + 16 <= width; x += 16) {
    const __m512i low = _mm512_popcnt_epi64(_mm512_xor_si512(_mm512_loadu_si512(left + x), _mm512_loadu_si512(right + x - d)));
    const __m512i high =
        _mm512_popcnt_epi64(_mm512_xor_si512(_mm512_loadu_si512(left + x + 8), _mm512_loadu_si512(right + x + 8 - d)));
    const __m128i bytes = _mm_unpacklo_epi64(_mm512_maskz_cvtepi64_epi8(0xFF, low), _mm512_maskz_cvtepi64_epi8(0xFF, high));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + x), bytes);
  }
  for (; x < width; ++x) {
    out[x] = static_cast<std::uint8_t>(__builtin_popcountll(left[x] ^ right[x - d]));
  }
}

bool cpu_has_avx512_popcount() {
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512vpopcntdq");
}

bool cpu_has_avx2() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt"); }

DenseKernels avx512_kernels() {
  DenseKernels kernels = kernels_avx512();
  kernels.census_costs = census_costs_avx512_popcount;
  return kernels;
}

DenseKernels avx2_kernels() {
  DenseKernels kernels = kernels_avx2();
  kernels.census_costs = census_costs_avx2_table;
  return kernels;
}
#endif

}  // namespace

DenseKernels portable_dense_kernels() { return kernels_portable(); }

std::vector<DenseKernels> supported_dense_kernels() {
  std::vector<DenseKernels> kernels{kernels_portable()};
#if defined(STEREOSCOUT_HAS_AVX2_KERNELS)
  if (__builtin_cpu_supports("popcnt")) kernels.push_back(kernels_popcnt());
  if (cpu_has_avx2()) kernels.push_back(avx2_kernels());
  if (cpu_has_avx512_popcount()) kernels.push_back(avx512_kernels());
#endif
  return kernels;
}

DenseKernels fastest_dense_kernels(bool allow_simd) {
#if defined(STEREOSCOUT_HAS_AVX2_KERNELS)
  if (allow_simd && cpu_has_avx512_popcount()) {
    return avx512_kernels();
  }
  if (allow_simd && cpu_has_avx2()) {
    return avx2_kernels();
  }
  if (allow_simd && __builtin_cpu_supports("popcnt")) {
    return kernels_popcnt();
  }
#else
  static_cast<void>(allow_simd);
#endif
  return kernels_portable();
}

}  // namespace stereoscout::vision::detail
