// Texel fetch: GL_NEAREST and GL_LINEAR sampling of one texture level, in batches.
//
// Coordinates come in level-0 texel units with 8 fraction bits (Q.8, "s" and "t", any int32).
// They are first reduced: for GL_REPEAT to [0, 256 x size) (a mask for powers of two), for
// GL_CLAMP_TO_EDGE clamped to [0, 256 x size - 1] (clamping the coordinate gives the same
// texels as GL's clamping of the indices). A level l of a mip chain then scales them by its size
// ratio (exact shifts for powers of two). Texels come out as 0x00RRGGBB.
//
// Bilinear (x = s - 0.5 texel, GL_LINEAR): RGB565 and palette textures blend the packed 5/6/5
// fields with 5-bit weights, RGB888 and L8 per channel with 8-bit weights
// (docs/numerics.md#packed-rgb565-bilinear-blend).
// Batches are chosen per draw (format x filter x wrap s x wrap t: one function per
// combination, from the renderer's SpanSet: span_state.hpp), so no pixel branches on texture
// state.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "lineraster/core/span/dispatch.hpp"
#include "lineraster/core/span/span_state.hpp"
#include "lineraster/core/texture/texel_fetch.hpp"
#include "lineraster/core/texture/texture.hpp"

namespace lr {

namespace detail {

// Always inlined: called per texel, where a call costs more than its body.
[[gnu::always_inline]] constexpr Texel expand565(uint32_t v) {
  uint32_t r5 = (v >> 11) & 31u, g6 = (v >> 5) & 63u, b5 = v & 31u;
  uint32_t r = (r5 << 3) | (r5 >> 2), g = (g6 << 2) | (g6 >> 4), b = (b5 << 3) | (b5 >> 2);
  return (r << 16) | (g << 8) | b;
}

constexpr uint32_t spread565(uint32_t v) {
  return (v | (v << 16)) & 0x07E0F81Fu;
}
constexpr uint32_t unspread565(uint32_t x) {
  return (x | (x >> 16)) & 0xFFFFu;
}
// Rounding constant: half of 32 in each spread field.
inline constexpr uint32_t kSpreadHalf = (16u << 21) | (16u << 11) | 16u;
// a + (b - a) w / 32 on spread values, w in [0, 32].
constexpr uint32_t lerp_spread(uint32_t a, uint32_t b, uint32_t w) {
  return ((a * (32u - w) + b * w + kSpreadHalf) >> 5) & 0x07E0F81Fu;
}

constexpr uint32_t lerp8(uint32_t a, uint32_t b, uint32_t w) {  // w in [0, 256]
  return (a * (256u - w) + b * w + 128u) >> 8;
}
constexpr Texel lerp_texel(Texel a, Texel b, uint32_t w) {
  return (lerp8((a >> 16) & 255u, (b >> 16) & 255u, w) << 16) |
         (lerp8((a >> 8) & 255u, (b >> 8) & 255u, w) << 8) | lerp8(a & 255u, b & 255u, w);
}

// Scales level-0 coordinates (>= 0) to a level of the chain: a shift when both sizes are
// powers of two, else a Q16 ratio (error < 2^-16 of the coordinate: under 1/32 texel).
struct LevelScale {
  int shift = 0;
  uint32_t ratio = 0;  // 0: use the shift
  LevelScale(uint32_t size0, uint32_t size_l) {
    if ((size0 & (size0 - 1)) == 0 && (size_l & (size_l - 1)) == 0) {
      shift = __builtin_ctz(size0) - __builtin_ctz(size_l);
    } else {
      // Level widths and heights are uint16 (TextureLevel): size_l 2^16 fits 32 bits.
      ratio = (size_l << 16) / size0;
    }
  }
  int32_t operator()(int32_t c) const {
    if (ratio == 0) return c >> shift;
    return static_cast<int32_t>((static_cast<uint64_t>(static_cast<uint32_t>(c)) * ratio) >> 16);
  }
};

// Reduces a level-0 coordinate (Q.8) by the wrap mode; period = 256 x size.
template <Wrap kW>
struct Reduce {
  int32_t period, mask;
  explicit Reduce(uint32_t size)
      : period(static_cast<int32_t>(size) * 256), mask((size & (size - 1)) == 0 ? period - 1 : 0) {}
  int32_t operator()(int32_t x) const {
    if constexpr (kW == Wrap::kRepeat) {
      if (mask != 0) return x & mask;
      int32_t r = x % period;
      return r < 0 ? r + period : r;
    } else {
      return x < 0 ? 0 : x >= period ? period - 1 : x;
    }
  }
};

template <Wrap kW>
inline int32_t wrap_index(int32_t i, int32_t size) {
  if constexpr (kW == Wrap::kRepeat) {
    if (i < 0) i += size;
    if (i >= size) i -= size;
    return i;
  } else {
    return i < 0 ? 0 : i >= size ? size - 1 : i;
  }
}

// The raw value of a texel for the packed path (RGB565 or palette) or its colour otherwise.
template <TexelFormat F>
inline uint32_t raw(const Texture& tex, const TextureLevel& l, int32_t x, int32_t y) {
  const size_t i = static_cast<size_t>(y) * l.width + static_cast<size_t>(x);
  if constexpr (F == TexelFormat::kRgb565) {
    return l.rgb565[i];
  } else if constexpr (F == TexelFormat::kPalette8) {
    return tex.palette[l.bytes[i]];
  } else if constexpr (F == TexelFormat::kL8) {
    uint32_t v = l.bytes[i];
    return (v << 16) | (v << 8) | v;
  } else {
    const uint8_t* p = &l.bytes[3 * i];
    return (uint32_t{p[0]} << 16) | (uint32_t{p[1]} << 8) | p[2];
  }
}

template <TexelFormat F>
constexpr bool kPacked565 = F == TexelFormat::kRgb565 || F == TexelFormat::kPalette8;

}  // namespace detail

template <TexelFormat F, Filter kFilter, Wrap kWs, Wrap kWt>
void fetch_batch(const Texture& tex, int level, const int32_t* s, const int32_t* t, int n,
                 Texel* out) {
  const TextureLevel& l = tex.levels[static_cast<size_t>(level)];
  const detail::Reduce<kWs> reduce_s(tex.levels[0].width);
  const detail::Reduce<kWt> reduce_t(tex.levels[0].height);
  const detail::LevelScale scale_s(tex.levels[0].width, l.width),
      scale_t(tex.levels[0].height, l.height);
  const auto w = static_cast<int32_t>(l.width), h = static_cast<int32_t>(l.height);
  if constexpr (kFilter == Filter::kNearest) {
    // A reduced coordinate, scaled to the level, is inside the level (repeat: [0, 256 size);
    // clamp: [0, 256 size - 1]; a shift or ratio keeps that), so nearest needs no index wrap.
    // Power-of-two sizes at a shift from level 0 (every mip level of them): reduce and scale
    // are a mask (repeat) or a clamp and one shift, decided here once per batch, not per texel.
    const bool pow2_s = kWs != Wrap::kRepeat || reduce_s.mask != 0;
    const bool pow2_t = kWt != Wrap::kRepeat || reduce_t.mask != 0;
    if (pow2_s && pow2_t && scale_s.ratio == 0 && scale_t.ratio == 0) {
      const int sh_s = 8 + scale_s.shift, sh_t = 8 + scale_t.shift;
      for (int k = 0; k < n; ++k) {
        int32_t a = s[k], b = t[k];
        if constexpr (kWs == Wrap::kRepeat)
          a &= reduce_s.mask;
        else
          a = a < 0 ? 0 : a >= reduce_s.period ? reduce_s.period - 1 : a;
        if constexpr (kWt == Wrap::kRepeat)
          b &= reduce_t.mask;
        else
          b = b < 0 ? 0 : b >= reduce_t.period ? reduce_t.period - 1 : b;
        const uint32_t v = detail::raw<F>(tex, l, a >> sh_s, b >> sh_t);
        out[k] = detail::kPacked565<F> ? detail::expand565(v) : v;
      }
      return;
    }
  }
  for (int k = 0; k < n; ++k) {
    const int32_t sl = scale_s(reduce_s(s[k]));
    const int32_t tl = scale_t(reduce_t(t[k]));
    if constexpr (kFilter == Filter::kNearest) {
      const uint32_t v = detail::raw<F>(tex, l, sl >> 8, tl >> 8);
      out[k] = detail::kPacked565<F> ? detail::expand565(v) : v;
    } else {
      const int32_t xs = sl - 128, ys = tl - 128;
      const int32_t xi = xs >> 8, yi = ys >> 8;
      const int32_t x0 = detail::wrap_index<kWs>(xi, w), x1 = detail::wrap_index<kWs>(xi + 1, w);
      const int32_t y0 = detail::wrap_index<kWt>(yi, h), y1 = detail::wrap_index<kWt>(yi + 1, h);
      const uint32_t fx = static_cast<uint32_t>(xs) & 255u, fy = static_cast<uint32_t>(ys) & 255u;
      const uint32_t a = detail::raw<F>(tex, l, x0, y0), b = detail::raw<F>(tex, l, x1, y0);
      const uint32_t c = detail::raw<F>(tex, l, x0, y1), d = detail::raw<F>(tex, l, x1, y1);
      if constexpr (detail::kPacked565<F>) {
        const uint32_t wx = (fx + 4) >> 3, wy = (fy + 4) >> 3;  // 5-bit weights, rounded
        const uint32_t top = detail::lerp_spread(detail::spread565(a), detail::spread565(b), wx);
        const uint32_t bot = detail::lerp_spread(detail::spread565(c), detail::spread565(d), wx);
        out[k] = detail::expand565(detail::unspread565(detail::lerp_spread(top, bot, wy)));
      } else {
        out[k] = detail::lerp_texel(detail::lerp_texel(a, b, fx), detail::lerp_texel(c, d, fx), fy);
      }
    }
  }
}

// The fetcher family (dispatch.hpp): fetch_batch per (wrap t, wrap s, filter, format), for
// textures and normal maps.
struct Fetchers {
  using Layout = FetchLayout;
  using Fn = FetchFn;
  static constexpr auto kUsed = &UsedRoutines::fetch;
  template <Wrap kWt, Wrap kWs, Filter kFilter, TexelFormat F>
  static constexpr Fn routine() {
    return &fetch_batch<F, kFilter, kWs, kWt>;
  }
};
// Environment maps: bilinear, clamped to the edge; one fetcher per format.
struct EnvFetchers {
  using Layout = EnvFetchLayout;
  using Fn = FetchFn;
  static constexpr auto kUsed = &UsedRoutines::env_fetch;
  template <TexelFormat F>
  static constexpr Fn routine() {
    return &fetch_batch<F, Filter::kBilinear, Wrap::kClampToEdge, Wrap::kClampToEdge>;
  }
};

template <SpanSet kSet = kAllSpans>
inline constexpr std::array<FetchFn, kFetchRoutines> kFetchTable = make_table<Fetchers, kSet>();
template <SpanSet kSet = kAllSpans>
inline constexpr std::array<FetchFn, kEnvFetchRoutines> kEnvFetchTable =
    make_table<EnvFetchers, kSet>();

// The fetch routine for a texture format and sampler: generated from the template and the
// state space, indexed by the state (no tree of ifs); nullptr outside kSet.
template <SpanSet kSet = kAllSpans>
constexpr FetchFn fetch_routine(TexelFormat f, Filter filter, Wrap ws, Wrap wt) {
  return kFetchTable<kSet>[fetch_index(f, filter, ws, wt)];
}
// The fetch routine of an environment map (bilinear, clamp to edge) of format f.
template <SpanSet kSet = kAllSpans>
constexpr FetchFn env_fetch_routine(TexelFormat f) {
  return kEnvFetchTable<kSet>[env_fetch_index(f)];
}

}  // namespace lr
