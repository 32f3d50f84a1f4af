#pragma once
// Procedural textures for the simulated world, generated once at world load from a seed:
// square tiles that repeat, each with a small mip chain so that far surfaces are filtered
// instead of aliased (aliasing would differ between the two cameras and make false matches).
// Tiles are stored column-major (texel (u, v) at u * size + v): the renderer walks image
// columns, which run along v on a vertical surface.

#include <array>
#include <cstdint>
#include <vector>

#include "stereoscout/host_sim/world.hpp"

namespace stereoscout::host_sim {

class TextureBank {
 public:
  static constexpr int kBaseSizeLog2 = 9;      // 512 x 512 texels at the finest level
  static constexpr double kTexelSize_m = 0.005;  // so a tile covers 2.56 m before it repeats
  static constexpr int kLevels = 5;

  struct Level {
    int size_log2 = 0;
    double texels_per_m = 0.0;
    const std::uint8_t* texels = nullptr;  // column-major, size x size
  };

  explicit TextureBank(std::uint64_t seed);
  // Levels point into storage_: not copyable.
  TextureBank(const TextureBank&) = delete;
  TextureBank& operator=(const TextureBank&) = delete;

  // Level `level` (0 = finest) of `texture`.
  const Level& level(Texture texture, int level) const {
    return levels_[static_cast<std::size_t>(texture)][static_cast<std::size_t>(level)];
  }
  // The mip level whose texel matches a pixel footprint of `footprint_m` on the surface.
  static int level_for_footprint(double footprint_m) {
    int level = 0;
    double texel = kTexelSize_m;
    while (level + 1 < kLevels && footprint_m > 2.0 * texel) {
      texel *= 2.0;
      ++level;
    }
    return level;
  }
  // Nearest texel at surface coordinates (u_m, v_m); coordinates wrap around the tile.
  static std::uint8_t sample(const Level& level, double u_m, double v_m) {
    const int mask = (1 << level.size_log2) - 1;
    // The offset keeps the truncation a floor for the (bounded) negative world coordinates.
    const int iu = static_cast<int>((u_m + 4096.0) * level.texels_per_m) & mask;
    const int iv = static_cast<int>((v_m + 4096.0) * level.texels_per_m) & mask;
    return level.texels[(iu << level.size_log2) + iv];
  }

 private:
  std::array<std::vector<std::uint8_t>, kTextureCount> storage_;
  std::array<std::array<Level, kLevels>, kTextureCount> levels_{};
};

}  // namespace stereoscout::host_sim
