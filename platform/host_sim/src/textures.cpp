// Procedural texture tiles. Every generator draws into a float canvas indexed (v, u) with v
// pointing up the surface, using only the world's seeded RandomStream, so the same seed gives
// the same texels on every machine. Patterns are chosen for what SIFT needs: blobs and corners
// at several scales (posters, book spines, bricks, wood planks, noise), or nothing (blank).
#include "stereoscout/host_sim/textures.hpp"

#include <algorithm>
#include <cmath>

#include "stereoscout/core/random.hpp"

namespace stereoscout::host_sim {
namespace {

constexpr int kSize = 1 << TextureBank::kBaseSizeLog2;

class Canvas {
 public:
  Canvas() : values_(static_cast<std::size_t>(kSize) * kSize, 0.5F) {}
  float& at(int u, int v) { return values_[index(u, v)]; }
  float at(int u, int v) const { return values_[index(u, v)]; }
  // Fills the rectangle [u0, u1) x [v0, v1), wrapping around the tile.
  void fill(int u0, int v0, int u1, int v1, float value) {
    for (int u = u0; u < u1; ++u) {
      for (int v = v0; v < v1; ++v) at(u, v) = value;
    }
  }
  void fill_disc(int cu, int cv, int radius, float value) {
    for (int du = -radius; du <= radius; ++du) {
      for (int dv = -radius; dv <= radius; ++dv) {
        if (du * du + dv * dv <= radius * radius) at(cu + du, cv + dv) = value;
      }
    }
  }
  void add(float amount, const Canvas& other) {
    for (std::size_t i = 0; i < values_.size(); ++i) values_[i] += amount * other.values_[i];
  }
  const std::vector<float>& values() const { return values_; }

 private:
  static std::size_t index(int u, int v) {
    return static_cast<std::size_t>(v & (kSize - 1)) * kSize + static_cast<std::size_t>(u & (kSize - 1));
  }
  std::vector<float> values_;
};

// Smooth random field in [0, 1]: random values on a grid of `cell` texels (a power of two),
// bilinearly interpolated, wrapping so the tile repeats seamlessly.
Canvas value_noise(core::RandomStream& random, int cell) {
  int cell_log2 = 0;
  while ((1 << cell_log2) < cell) ++cell_log2;
  const int cells = kSize >> cell_log2;
  std::vector<float> grid(static_cast<std::size_t>(cells * cells));
  for (float& g : grid) g = static_cast<float>(random.uniform());
  const auto node = [&](int i, int j) {
    return grid[static_cast<std::size_t>((j & (cells - 1)) * cells + (i & (cells - 1)))];
  };
  const float inverse_cell = 1.0F / static_cast<float>(1 << cell_log2);
  Canvas canvas;
  for (int v = 0; v < kSize; ++v) {
    const int j = v >> cell_log2;
    const float fv = static_cast<float>(v & ((1 << cell_log2) - 1)) * inverse_cell;
    for (int u = 0; u < kSize; ++u) {
      const int i = u >> cell_log2;
      const float fu = static_cast<float>(u & ((1 << cell_log2) - 1)) * inverse_cell;
      const float bottom = node(i, j) * (1.0F - fu) + node(i + 1, j) * fu;
      const float top = node(i, j + 1) * (1.0F - fu) + node(i + 1, j + 1) * fu;
      canvas.at(u, v) = bottom * (1.0F - fv) + top * fv;
    }
  }
  return canvas;
}

Canvas fractal_noise(core::RandomStream& random, int finest_cell, int octaves) {
  Canvas sum;
  sum.fill(0, 0, kSize, kSize, 0.0F);
  float weight_total = 0.0F;
  float weight = 1.0F;
  for (int octave = octaves - 1, cell = finest_cell << (octaves - 1); octave >= 0; --octave, cell /= 2) {
    sum.add(weight, value_noise(random, cell));
    weight_total += weight;
    weight *= 0.6F;
  }
  Canvas result;
  for (int v = 0; v < kSize; ++v) {
    for (int u = 0; u < kSize; ++u) {
      // Stretch the averaged octaves (which bunch around 0.5) back over [0, 1].
      result.at(u, v) = std::clamp(0.5F + 2.2F * (sum.at(u, v) / weight_total - 0.5F), 0.0F, 1.0F);
    }
  }
  return result;
}

float shade(core::RandomStream& random, double low, double high) { return static_cast<float>(random.uniform(low, high)); }
int integer(core::RandomStream& random, int low, int high) {
  return low + static_cast<int>(random.uniform_index(static_cast<std::uint32_t>(high - low + 1)));
}

Canvas make_low(core::RandomStream& random) {
  Canvas canvas = value_noise(random, 64);
  for (int v = 0; v < kSize; ++v) {
    for (int u = 0; u < kSize; ++u) canvas.at(u, v) = 0.5F + 0.08F * (canvas.at(u, v) - 0.5F);
  }
  return canvas;
}

// Bricks 215 x 65 mm with 10 mm mortar joints, each brick its own shade.
Canvas make_brick(core::RandomStream& random) {
  Canvas canvas;
  canvas.fill(0, 0, kSize, kSize, 0.85F);
  const Canvas grain = value_noise(random, 4);
  const int course = 15;  // 75 mm: brick + mortar
  const int length = 45;  // 225 mm
  for (int row = 0; row * course < kSize; ++row) {
    const int shift = (row % 2) * (length / 2);
    for (int u0 = -length; u0 < kSize; u0 += length) {
      const float brick = shade(random, 0.1, 0.7);
      for (int u = u0 + shift + 2; u < u0 + shift + length; ++u) {
        for (int v = row * course + 2; v < (row + 1) * course; ++v) canvas.at(u, v) = brick + 0.25F * (grain.at(u, v) - 0.5F);
      }
    }
  }
  return canvas;
}

// Horizontal planks 20 cm wide with grain stripes and knots.
Canvas make_wood(core::RandomStream& random) {
  Canvas canvas;
  const Canvas grain = value_noise(random, 8);
  const int plank = 40;
  for (int row = 0; row * plank < kSize; ++row) {
    const float base = shade(random, 0.35, 0.65);
    const float frequency = shade(random, 0.15, 0.4);
    const float phase = shade(random, 0.0, 6.28);
    for (int v = row * plank; v < (row + 1) * plank; ++v) {
      for (int u = 0; u < kSize; ++u) {
        const float wave = std::sin(frequency * static_cast<float>(v) + 3.0F * grain.at(u, v) + phase);
        canvas.at(u, v) = (v % plank < 2) ? 0.1F : base + 0.18F * wave;
      }
    }
    for (int knot = 0; knot < 3; ++knot) {
      canvas.fill_disc(integer(random, 0, kSize - 1), row * plank + integer(random, 8, plank - 8), integer(random, 3, 7), 0.15F);
    }
  }
  return canvas;
}

// Posters: light paper with blocks, discs, stripes and rows of "text" at many scales.
Canvas make_poster(core::RandomStream& random) {
  Canvas canvas;
  canvas.fill(0, 0, kSize, kSize, 0.85F);
  for (int i = 0; i < 90; ++i) {
    const int u = integer(random, 0, kSize - 1);
    const int v = integer(random, 0, kSize - 1);
    canvas.fill(u, v, u + integer(random, 6, 70), v + integer(random, 6, 70), shade(random, 0.0, 1.0));
  }
  for (int i = 0; i < 70; ++i) {
    canvas.fill_disc(integer(random, 0, kSize - 1), integer(random, 0, kSize - 1), integer(random, 3, 24), shade(random, 0.0, 1.0));
  }
  for (int line = 0; line < 40; ++line) {
    const int u0 = integer(random, 0, kSize - 1);
    const int v = integer(random, 0, kSize - 1);
    const float ink = shade(random, 0.0, 0.3);
    for (int letter = 0, u = u0; letter < 14; ++letter) {
      const int width = integer(random, 2, 5);
      canvas.fill(u, v, u + width, v + integer(random, 4, 7), ink);
      u += width + integer(random, 2, 4);
    }
  }
  return canvas;
}

// Bookcase shelves: rows 35 cm high, a board below, books of random width, height and shade
// with a title band.
Canvas make_books(core::RandomStream& random) {
  Canvas canvas;
  canvas.fill(0, 0, kSize, kSize, 0.08F);  // the dark back of the shelf
  const int row_height = 64;
  for (int row = 0; row * row_height < kSize; ++row) {
    const int v0 = row * row_height;
    canvas.fill(0, v0, kSize, v0 + 5, 0.55F);  // shelf board
    for (int u = 0; u < kSize;) {
      const int width = integer(random, 4, 12);
      if (random.uniform() < 0.08) {  // a gap in the row
        u += width;
        continue;
      }
      const int height = integer(random, 36, row_height - 8);
      const float cover = shade(random, 0.15, 0.95);
      canvas.fill(u, v0 + 5, u + width - 1, v0 + 5 + height, cover);
      const int band = v0 + 5 + integer(random, 8, height - 8);
      canvas.fill(u + 1, band, u + width - 2, band + integer(random, 2, 6), cover > 0.5F ? cover - 0.45F : cover + 0.45F);
      u += width;
    }
  }
  return canvas;
}

// Floor tiles 30 cm with 1 cm grout, slightly mottled.
Canvas make_tile(core::RandomStream& random) {
  const Canvas mottle = value_noise(random, 16);
  Canvas canvas;
  const int tile = 64;
  for (int v = 0; v < kSize; ++v) {
    for (int u = 0; u < kSize; ++u) {
      const bool grout = (u % tile) < 2 || (v % tile) < 2;
      const float base = ((u / tile + v / tile) % 2 == 0) ? 0.62F : 0.5F;
      canvas.at(u, v) = grout ? 0.15F : base + 0.2F * (mottle.at(u, v) - 0.5F);
    }
  }
  return canvas;
}

Canvas make_carpet(core::RandomStream& random) {
  Canvas canvas = fractal_noise(random, 2, 4);
  for (int v = 0; v < kSize; ++v) {
    for (int u = 0; u < kSize; ++u) canvas.at(u, v) = 0.5F + 0.5F * (canvas.at(u, v) - 0.5F);
  }
  return canvas;
}

Canvas make_texture(Texture texture, core::RandomStream& random) {
  switch (texture) {
    case Texture::blank: return Canvas();
    case Texture::low: return make_low(random);
    case Texture::noise: return fractal_noise(random, 2, 5);
    case Texture::brick: return make_brick(random);
    case Texture::wood: return make_wood(random);
    case Texture::poster: return make_poster(random);
    case Texture::books: return make_books(random);
    case Texture::tile: return make_tile(random);
    case Texture::carpet: return make_carpet(random);
  }
  return Canvas();
}

// The textures a surface of `world` shows.
std::array<bool, kTextureCount> textures_shown(const World& world) {
  std::array<bool, kTextureCount> shown{};
  const auto show = [&](const Surface& surface) { shown[static_cast<std::size_t>(surface.texture)] = true; };
  show(world.floor);
  show(world.ceiling);
  for (const WallPiece& wall : world.walls) show(wall.surface);
  for (const Prism& prism : world.prisms) show(prism.surface);
  for (const Cylinder& cylinder : world.cylinders) show(cylinder.surface);
  for (const Person& person : world.people) show(person.surface);
  for (const FloorRegion& region : world.floor_regions) show(region.surface);
  return shown;
}

}  // namespace

TextureBank::TextureBank(const World& world)
    : variants_(std::clamp(world.texture_variants, 1, kMaxVariants)),
      look_salt_(world.texture_seed * 0x9E3779B97F4A7C15ULL),
      storage_(static_cast<std::size_t>(kTextureCount * variants_)),
      levels_(static_cast<std::size_t>(kTextureCount * variants_)) {
  const std::array<bool, kTextureCount> shown = textures_shown(world);
  for (int t = 0; t < kTextureCount; ++t) {
    const auto texture = static_cast<Texture>(t);
    // A blank surface has one look, however many variants.
    const int count = shown[static_cast<std::size_t>(t)] && texture != Texture::blank ? variants_ : 1;
    for (int variant = 0; variant < count; ++variant) build(texture, variant, world.texture_seed);
    for (int variant = count; variant < variants_; ++variant) levels_[slot(texture, variant)] = levels_[slot(texture, 0)];
  }
}

void TextureBank::build(Texture texture, int variant, std::uint64_t seed) {
  const auto t = static_cast<std::uint32_t>(texture);
  // Variant 0 draws from the stream the one tile of a world without variants drew from.
  core::RandomStream random(seed, {core::stream_purpose::sim_world, t, 1U + static_cast<std::uint32_t>(variant)});
  const Canvas canvas = make_texture(texture, random);
  std::size_t total = 0;
  for (int level = 0; level < kLevels; ++level) total += static_cast<std::size_t>(kSize >> level) * static_cast<std::size_t>(kSize >> level);
  const std::size_t index = slot(texture, variant);
  std::vector<std::uint8_t>& store = storage_[index];
  store.resize(total);
  // Level 0 quantised from the canvas, each coarser level the 2x2 mean of the one before.
  std::vector<float> current = canvas.values();  // row-major (v, u)
  std::size_t offset = 0;
  for (int level = 0; level < kLevels; ++level) {
    const int size = kSize >> level;
    if (level > 0) {
      std::vector<float> coarser(static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
      const int fine = size * 2;
      for (int v = 0; v < size; ++v) {
        for (int u = 0; u < size; ++u) {
          auto f = [&](int du, int dv) { return current[static_cast<std::size_t>((2 * v + dv) * fine + 2 * u + du)]; };
          coarser[static_cast<std::size_t>(v * size + u)] = 0.25F * (f(0, 0) + f(1, 0) + f(0, 1) + f(1, 1));
        }
      }
      current.swap(coarser);
    }
    for (int u = 0; u < size; ++u) {
      for (int v = 0; v < size; ++v) {
        const float value = std::clamp(current[static_cast<std::size_t>(v * size + u)], 0.0F, 1.0F);
        store[offset + static_cast<std::size_t>(u * size + v)] = static_cast<std::uint8_t>(std::lround(value * 255.0F));
      }
    }
    Level& entry = levels_[index][static_cast<std::size_t>(level)];
    entry.size_log2 = kBaseSizeLog2 - level;
    entry.texels_per_m = 1.0 / (kTexelSize_m * static_cast<double>(1 << level));
    entry.texels = store.data() + offset;
    offset += static_cast<std::size_t>(size) * static_cast<std::size_t>(size);
  }
}

}  // namespace stereoscout::host_sim
