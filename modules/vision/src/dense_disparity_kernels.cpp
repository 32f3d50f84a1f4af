#include "stereoscout/vision/dense_disparity_kernels.hpp"

#include <cstddef>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#endif

namespace stereoscout::vision::detail {
namespace {

// The bodies twice on x86: instrumented by the sanitizers (in a sanitizer build) for the
// portable build of the kernels, and left alone for the instruction-set builds. The sanitizers'
// checks in a loop stop it vectorising, and the instrumented matcher made the sanitizer
// suite's rendered drives 30 times slower than the release build (docs/results.md, "CI and
// build times"). Every access the checks would see in the instruction-set builds is one of
// the same source, which the sanitizer suite checks in the portable build
// (tests/unit/vision/dense_disparity_test.cpp). The attribute must be on the bodies as well
// as on the functions they are inlined into: the checks are put in before inlining.
namespace instrumented {
#define STEREOSCOUT_KERNEL_BODY inline __attribute__((always_inline))
#include "dense_disparity_kernel_bodies.inc"
#undef STEREOSCOUT_KERNEL_BODY
}  // namespace instrumented

// One build of every kernel per instruction set; the bodies are inlined into each.
#define STEREOSCOUT_DEFINE_KERNELS(SUFFIX, ATTRIBUTES, BODIES)                                                       \
  ATTRIBUTES void census_##SUFFIX(const std::uint8_t* image, std::size_t stride, int width, int height,              \
                                  std::uint64_t* census) {                                                           \
    BODIES::census_body(image, stride, width, height, census);                                                       \
  }                                                                                                                  \
  ATTRIBUTES void census_costs_##SUFFIX(const std::uint64_t* left, const std::uint64_t* right, std::uint8_t* out,    \
                                        int first, int width, int d) {                                               \
    BODIES::census_costs_body(left, right, out, first, width, d);                                                    \
  }                                                                                                                  \
  ATTRIBUTES void add_costs_##SUFFIX(std::uint16_t* sums, const std::uint8_t* costs, std::size_t count) {            \
    BODIES::add_costs_body(sums, costs, count);                                                                      \
  }                                                                                                                  \
  ATTRIBUTES void subtract_costs_##SUFFIX(std::uint16_t* sums, const std::uint8_t* costs, std::size_t count) {       \
    BODIES::subtract_costs_body(sums, costs, count);                                                                 \
  }                                                                                                                  \
  ATTRIBUTES void box_sum_##SUFFIX(const std::uint16_t* column_sums, std::uint16_t* aggregated,                      \
                                   std::uint16_t* scratch, int disparities, int width, int radius) {                 \
    BODIES::box_sum_body(column_sums, aggregated, scratch, disparities, width, radius);                              \
  }                                                                                                                  \
  ATTRIBUTES void winners_##SUFFIX(const WinnerBuffers& buffers) { BODIES::winners_body(buffers); }                  \
  DenseKernels kernels_##SUFFIX() {                                                                                  \
    return {census_##SUFFIX, census_costs_##SUFFIX, add_costs_##SUFFIX, subtract_costs_##SUFFIX,                     \
            box_sum_##SUFFIX,  winners_##SUFFIX,      #SUFFIX};                                                      \
  }

STEREOSCOUT_DEFINE_KERNELS(portable, , instrumented)

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define STEREOSCOUT_HAS_AVX2_KERNELS 1
#define STEREOSCOUT_UNSANITIZED __attribute__((no_sanitize("address", "undefined")))
namespace unsanitized {
#define STEREOSCOUT_KERNEL_BODY inline __attribute__((always_inline)) STEREOSCOUT_UNSANITIZED
#include "dense_disparity_kernel_bodies.inc"
#undef STEREOSCOUT_KERNEL_BODY
}  // namespace unsanitized

// The hand-written intrinsics below stay instrumented.
STEREOSCOUT_DEFINE_KERNELS(popcnt, __attribute__((target("popcnt"))) STEREOSCOUT_UNSANITIZED, unsanitized)
STEREOSCOUT_DEFINE_KERNELS(avx2, __attribute__((target("avx2,popcnt"))) STEREOSCOUT_UNSANITIZED, unsanitized)

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
STEREOSCOUT_DEFINE_KERNELS(avx512, __attribute__((target(STEREOSCOUT_AVX512_TARGET))) STEREOSCOUT_UNSANITIZED,
                           unsanitized)

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
