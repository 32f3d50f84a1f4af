#pragma once
// Deterministic random numbers from a counter-based generator (Philox4x32-10, Salmon et al.,
// SC'11). A draw is a pure function of (seed, stream, counter): a particle's noise at a step
// never depends on how many numbers any other particle or step consumed, so results do not
// change with iteration order, thread partitioning or the particle count of other runs.
//
// Uniform and Gaussian sampling are implemented here with a logarithm of our own (plain
// IEEE arithmetic, no libm) so that every value is identical across standard libraries and
// CPUs; std::normal_distribution and std::log are not used for that reason.

#include <array>
#include <cstdint>

namespace stereoscout::core {

using PhiloxCounter = std::array<std::uint32_t, 4>;
using PhiloxKey = std::array<std::uint32_t, 2>;

// One Philox4x32 block with 10 rounds.
PhiloxCounter philox4x32_10(PhiloxCounter counter, PhiloxKey key);

// Names an independent stream. The purpose separates kinds of draws (motion noise, resampling,
// simulator noise, ...); step and index usually are the update number and the particle.
struct StreamId {
  std::uint32_t purpose = 0;
  std::uint32_t step = 0;
  std::uint32_t index = 0;
};

// Purposes used by the stack; new users add a value here so that no two collide.
namespace stream_purpose {
inline constexpr std::uint32_t motion_noise = 1;
inline constexpr std::uint32_t resampling = 2;
inline constexpr std::uint32_t sim_odometry = 3;
inline constexpr std::uint32_t sim_image_noise = 4;
inline constexpr std::uint32_t sim_world = 5;
inline constexpr std::uint32_t dataset_odometry = 6;
inline constexpr std::uint32_t test = 1000;
}  // namespace stream_purpose

class RandomStream {
 public:
  RandomStream(std::uint64_t seed, StreamId stream);

  std::uint32_t next_u32();
  std::uint64_t next_u64();
  // Uniform in [0, 1) with 53 random bits.
  double uniform();
  double uniform(double low, double high) { return low + (high - low) * uniform(); }
  // Uniform integer in [0, n), without modulo bias. n must be > 0.
  std::uint32_t uniform_index(std::uint32_t n);
  // Standard normal (Marsaglia's polar method).
  double gaussian();
  double gaussian(double mean, double standard_deviation) {
    return mean + standard_deviation * gaussian();
  }

  // Number of 128-bit blocks consumed so far.
  std::uint32_t blocks_used() const { return block_counter_; }

 private:
  void refill();

  PhiloxKey key_;
  StreamId stream_;
  std::uint32_t block_counter_ = 0;
  PhiloxCounter block_{};
  unsigned next_word_ = 4;
  bool has_spare_gaussian_ = false;
  double spare_gaussian_ = 0.0;
};

// Natural logarithm for x > 0 from +, *, / only: identical on every IEEE-754 platform
// (relative error below 1e-15). Returns -infinity for 0 and NaN for negative or NaN input.
double portable_log(double x);

}  // namespace stereoscout::core
