// Textures: texel storage (flash or RAM), mip chains, and the sampler state of a draw.
//
// Conventions (OpenGL's; docs/conventions.md#textures): v = 0 at the bottom edge of the image
// file; levels store their rows bottom row first, so the texel in column i and storage row r
// has its centre at u = (i + 0.5) / width, v = (r + 0.5) / height.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "lineraster/core/output/status.hpp"

namespace lr {

// Per-vertex texture coordinates: Q12.20 in int32 (2^20 = 1.0), |u|, |v| < 2048, resolution
// 2^-20 (1/512 of a texel of a 2048-texel texture). Sampling is exact for every value: a
// coordinate is reduced to the triangle's own integer period before any product is formed.
struct TexCoord {
  static constexpr int kFracBits = 20;
  int32_t u = 0, v = 0;
  friend constexpr bool operator==(const TexCoord&, const TexCoord&) = default;
};

enum class TexelFormat : uint8_t {
  kRgb565,    // uint16 per texel, native endian, red in bits 15..11
  kRgb888,    // 3 bytes per texel: r, g, b
  kL8,        // 1 byte per texel: luminance (r = g = b)
  kPalette8,  // 1 byte per texel: index into an RGB565 palette
};

inline constexpr int kMaxTextureSize = 2048;
inline constexpr int kMaxMipLevels = 12;  // 2048 x 2048 down to 1 x 1

// One level of a texture: width x height texels, rows packed, bottom row first. Exactly one
// of the spans is used, by format: rgb565 for kRgb565, bytes for the others.
struct TextureLevel {
  std::span<const uint16_t> rgb565;
  std::span<const uint8_t> bytes;
  uint16_t width = 0, height = 0;
};

// A texture: level 0 and, when level_count > 1, its mip chain (each level half the size of the
// one before, rounded down, at least 1: GL's rule).
struct Texture {
  TexelFormat format = TexelFormat::kRgb565;
  std::array<TextureLevel, kMaxMipLevels> levels{};
  uint8_t level_count = 0;
  std::span<const uint16_t> palette;  // kPalette8: RGB565 values, native endian

  constexpr bool power_of_two() const {
    const unsigned w = levels[0].width, h = levels[0].height;
    return w != 0 && h != 0 && (w & (w - 1)) == 0 && (h & (h - 1)) == 0;
  }
};

// Checks sizes (1..kMaxTextureSize), span lengths, the mip chain's sizes and the palette
// (every index of a kPalette8 texture must be < palette.size()). kInvalidArgument otherwise.
Status validate(const Texture& texture);

// Bytes (or uint16 values for kRgb565) one level of w x h texels occupies.
constexpr size_t level_texels(uint16_t w, uint16_t h) {
  return size_t{w} * h;
}
constexpr size_t bytes_per_texel(TexelFormat f) {
  return f == TexelFormat::kRgb565 ? 2 : f == TexelFormat::kRgb888 ? 3 : 1;
}

enum class Filter : uint8_t { kNearest, kBilinear };
enum class Wrap : uint8_t { kRepeat, kClampToEdge };
enum class MipMode : uint8_t {
  kNone,     // level 0 only (GL_NEAREST / GL_LINEAR)
  kNearest,  // the nearest level (GL_*_MIPMAP_NEAREST)
  kLinear,   // blend of the two nearest levels (GL_*_MIPMAP_LINEAR: trilinear with bilinear)
};
enum class TexEnv : uint8_t {
  kModulate,  // texel x (emission + ambient + diffuse), specular added after (GL_MODULATE with
              // GL_SEPARATE_SPECULAR_COLOR); unlit: texel x vertex colour
  kReplace,   // the texel alone
};

// How a draw samples its texture.
struct Sampler {
  Filter filter = Filter::kBilinear;
  Wrap wrap_s = Wrap::kRepeat;
  Wrap wrap_t = Wrap::kRepeat;
  MipMode mip = MipMode::kNone;
  TexEnv env = TexEnv::kModulate;
};

}  // namespace lr
