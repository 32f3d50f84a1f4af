#pragma once
// SHA-256 (FIPS 180-4), for the digests of a run's output files in report.json: two runs
// with the same inputs and seed must give the same digests.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace stereoscout::report {

class Sha256 {
 public:
  Sha256();
  void update(const std::uint8_t* data, std::size_t size);
  void update(const std::string& text) { update(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()); }
  std::array<std::uint8_t, 32> finish();
  // Lower-case hex of finish().
  std::string finish_hex();

 private:
  void compress(const std::uint8_t* block);
  std::array<std::uint32_t, 8> state_;
  std::array<std::uint8_t, 64> block_{};
  std::size_t block_used_ = 0;
  std::uint64_t total_bytes_ = 0;
};

// Hex digest of a file's bytes; false (and `error` naming the file) when it cannot be read.
bool sha256_file(const std::string& path, std::string& hex, std::string& error);

}  // namespace stereoscout::report
