#pragma once
// Procedural textures for the simulated world, generated once at world load from a seed:
// square tiles, one or more of each texture (World::texture_variants), each with a small mip
// chain so that far surfaces are filtered instead of aliased (aliasing would differ between
// the two cameras and make false matches).
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
  static constexpr int kMaxVariants = 32;       // world key texture_variants, at most

  struct Level {
    int size_log2 = 0;
    double texels_per_m = 0.0;
    const std::uint8_t* texels = nullptr;  // column-major, size x size
  };

  // The tiles of `world` (its texture_seed and texture_variants): variant 0 of every texture,
  // and the other variants of each texture a surface of the world shows.
  explicit TextureBank(const World& world);
  // Levels point into storage_: not copyable.
  TextureBank(const TextureBank&) = delete;
  TextureBank& operator=(const TextureBank&) = delete;

  // Level `level` (0 = finest) of `texture`'s first tile (the variants share its sizes).
  const Level& level(Texture texture, int level) const {
    return levels_[slot(texture, 0)][static_cast<std::size_t>(level)];
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
  // A surface coordinate in texels of `level` (finest: 0), unwrapped. The offset keeps the
  // truncation a floor for the (bounded) negative world coordinates.
  static int texel_coordinate(int level, double coordinate_m) {
    return static_cast<int>((coordinate_m + 4096.0) * (1.0 / (kTexelSize_m * static_cast<double>(1 << level))));
  }
  // Nearest texel of `texture` at mip `level` and unwrapped texel coordinates (u, v). A surface
  // is cut into cells of one tile; with one variant every cell shows the tile (it repeats every
  // 2.56 m), with more each cell shows the variant, mirrored across u or not, that a hash of
  // the cell picks, so that two places of one texture do not look alike to the matcher.
  std::uint8_t texel(Texture texture, int level, int u, int v) const {
    const int size_log2 = kBaseSizeLog2 - level;
    const int mask = (1 << size_log2) - 1;
    int iu = u & mask;
    int variant = 0;
    if (variants_ > 1) {
      const std::uint32_t look = cell_look(texture, u >> size_log2, v >> size_log2);
      variant = static_cast<int>(look % static_cast<std::uint32_t>(variants_));
      if ((look >> 16U) & 1U) iu = mask - iu;
    }
    return levels_[slot(texture, variant)][static_cast<std::size_t>(level)].texels[(iu << size_log2) + (v & mask)];
  }
  // The same at surface coordinates (u_m, v_m).
  std::uint8_t sample(Texture texture, int level, double u_m, double v_m) const {
    return texel(texture, level, texel_coordinate(level, u_m), texel_coordinate(level, v_m));
  }

 private:
  std::size_t slot(Texture texture, int variant) const {
    return static_cast<std::size_t>(texture) * static_cast<std::size_t>(variants_) + static_cast<std::size_t>(variant);
  }
  std::uint32_t cell_look(Texture texture, int cell_u, int cell_v) const {
    std::uint64_t h = look_salt_ ^ (static_cast<std::uint64_t>(texture) << 48U) ^
                      (static_cast<std::uint64_t>(static_cast<std::uint32_t>(cell_u)) << 24U) ^
                      static_cast<std::uint64_t>(static_cast<std::uint32_t>(cell_v));
    // splitmix64's finaliser: every input bit reaches every output bit.
    h = (h ^ (h >> 30U)) * 0xBF58476D1CE4E5B9ULL;
    h = (h ^ (h >> 27U)) * 0x94D049BB133111EBULL;
    return static_cast<std::uint32_t>(h ^ (h >> 31U));
  }
  void build(Texture texture, int variant, std::uint64_t seed);

  int variants_ = 1;
  std::uint64_t look_salt_ = 0;
  std::vector<std::vector<std::uint8_t>> storage_;    // per slot: all levels, finest first
  // Per slot (texture x variants_ + variant). A texture the world does not show, and blank, has
  // only variant 0's tile: its other slots point to it.
  std::vector<std::array<Level, kLevels>> levels_;
};

}  // namespace stereoscout::host_sim
