// Bridges from the core's texture types to the reference renderer's (tests and benchmarks only).
//
// Header-only and using only header-only parts of core/texture/texture.hpp, so that lr_reference
// and its users need no link dependency on lr_core. The reference samples exactly the texel values
// the core stores, including the core's own mip levels (the reference never rebuilds a mip chain).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>

#include "lineraster/core/texture/texture.hpp"
#include "tests/reference/ref_renderer.hpp"

namespace lr::ref {

// An RGB565 value (red in bits 15..11) expanded to 8 bits per channel by bit replication
// ((r5 << 3) | (r5 >> 2), (g6 << 2) | (g6 >> 4)), then divided by 255.
inline Vec3d rgb565_to_unit(uint16_t v) {
  const unsigned r5 = v >> 11u, g6 = (v >> 5u) & 63u, b5 = v & 31u;
  return {static_cast<double>((r5 << 3u) | (r5 >> 2u)) / 255.0,
          static_cast<double>((g6 << 2u) | (g6 >> 4u)) / 255.0,
          static_cast<double>((b5 << 3u) | (b5 >> 2u)) / 255.0};
}

// The core texture's levels 0 .. level_count - 1 as reference levels (rows stay bottom row
// first, as both store them). RGB888 and L8 bytes / 255; palette-8 through the RGB565 palette.
// Texels the core texture does not hold (a span too short, a palette index out of range: what
// lr::validate() refuses) come out black.
inline RefTexture from_core(const lr::Texture& t) {
  RefTexture r;
  const int n = t.level_count < kMaxMipLevels ? t.level_count : kMaxMipLevels;
  for (int l = 0; l < n; ++l) {
    const TextureLevel& src = t.levels[static_cast<size_t>(l)];
    RefLevel dst;
    dst.width = src.width;
    dst.height = src.height;
    const size_t count = level_texels(src.width, src.height);
    dst.texels.assign(count, Vec3d{0, 0, 0});
    for (size_t k = 0; k < count; ++k) {
      Vec3d& c = dst.texels[k];
      switch (t.format) {
        case TexelFormat::kRgb565:
          if (k < src.rgb565.size()) c = rgb565_to_unit(src.rgb565[k]);
          break;
        case TexelFormat::kRgb888:
          if (3 * k + 2 < src.bytes.size())
            c = {src.bytes[3 * k] / 255.0, src.bytes[3 * k + 1] / 255.0,
                 src.bytes[3 * k + 2] / 255.0};
          break;
        case TexelFormat::kL8:
          if (k < src.bytes.size())
            c = {src.bytes[k] / 255.0, src.bytes[k] / 255.0, src.bytes[k] / 255.0};
          break;
        case TexelFormat::kPalette8:
          if (k < src.bytes.size() && src.bytes[k] < t.palette.size())
            c = rgb565_to_unit(t.palette[src.bytes[k]]);
          break;
      }
    }
    r.levels.push_back(std::move(dst));
  }
  return r;
}

inline RefFilter from_core(Filter f) {
  return f == Filter::kNearest ? RefFilter::Nearest : RefFilter::Bilinear;
}
inline RefWrap from_core(Wrap w) {
  return w == Wrap::kRepeat ? RefWrap::Repeat : RefWrap::ClampToEdge;
}
inline RefMipMode from_core(MipMode m) {
  return m == MipMode::kNone      ? RefMipMode::None
         : m == MipMode::kNearest ? RefMipMode::Nearest
                                  : RefMipMode::Linear;
}
inline RefTexEnv from_core(TexEnv e) {
  return e == TexEnv::kModulate ? RefTexEnv::Modulate : RefTexEnv::Replace;
}

// Copies a core sampler's state into params (the texture pointer is left alone).
inline void set_sampler(RefParams& params, const Sampler& s) {
  params.filter = from_core(s.filter);
  params.wrap_s = from_core(s.wrap_s);
  params.wrap_t = from_core(s.wrap_t);
  params.mip = from_core(s.mip);
  params.tex_env = from_core(s.env);
}

}  // namespace lr::ref
