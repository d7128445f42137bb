// Textured span routines.
//
// A span is processed in chunks of up to 32 pixels. Per chunk: the mip level is chosen (level
// of detail from the texel coordinates' screen-space derivatives at the chunk's centre pixel);
// pass A tests depth pixel by pixel and, for the pixels that pass only, computes the
// texel coordinates and colours; the fetch routine of the draw (format x filter x wrap, see
// sampler.hpp) reads their texels in one batch; pass B combines texel and colour and writes.
// So pixels hidden by depth cost no texel fetch and no colour, and no pixel branches on state:
// the routine is a template instance per (depth, perspective mode, texture environment, mip
// mode), the fetch a function per texture state, called once per chunk.
//
// Perspective modes (docs/conventions.md#textures):
//   kExact: s = (s q)/q per pixel with a ~30-bit reciprocal of q (a 17-bit estimate by one
//           32-bit division, one Newton step in 64 bits); level of detail every 8 pixels.
//   kSpan:  exact at the first pixel of each chunk of span_len (8, 16, 32) pixels and at the
//           chunk's end (the last chunk ends on the span's last pixel), linear in between.
//   kAffine: s linear in screen space; level of detail once per span.
// Level of detail: docs/conventions.md#textures (the rule) and docs/numerics.md#level-of-detail.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "lineraster/core/binning/draw_record.hpp"
#include "lineraster/core/math/pow_table.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/span/sampler.hpp"
#include "lineraster/core/span/span.hpp"
#include "lineraster/core/span/tex_exact_span.hpp"

namespace lr {

namespace detail {

// R ~ 2^63 / (q << shift) for a Q1.30 plane value q (values below 1 count as 1).
// One Newton step on a 17-bit estimate: docs/numerics.md#perspective-correct-attributes.
struct PreciseRecip {
  uint32_t r;
  int shift;
  explicit PreciseRecip(uint32_t plane_q) {
    const int32_t qi = static_cast<int32_t>(plane_q);
    const uint32_t q = qi < 1 ? 1u : static_cast<uint32_t>(qi);
    shift = clz32(q);
    const uint32_t qn = q << shift;                                // [2^31, 2^32)
    const uint64_t r0 = uint64_t{0xFFFFFFFFu / (qn >> 16)} << 15;  // 17 bits, <= 2^32
    const auto e = static_cast<int64_t>((uint64_t{1} << 63) - uint64_t{qn} * r0);  // |e| < 2^49
    const int64_t r1 = static_cast<int64_t>(r0) + ((static_cast<int64_t>(r0) * (e >> 18)) >> 45);
    r = r1 > 0xFFFFFFFF ? 0xFFFFFFFFu : r1 < 0 ? 0u : static_cast<uint32_t>(r1);
  }
  // a 2^m / q for a plane value a (int32) that holds x q / 2^m.
  int32_t div(uint32_t a, int m) const {
    return static_cast<int32_t>((int64_t{static_cast<int32_t>(a)} * r) >> (63 - m - shift));
  }
};

// round(256 log2(1 + i / 256)), from the specular power table's log2 (Q8.24, 257 entries).
consteval std::array<uint8_t, 256> make_log2_frac_table() {
  std::array<uint8_t, 256> t{};
  for (size_t i = 0; i < 256; ++i) {
    const int32_t v = (DefaultPowTable::kLog2[i] + (1 << 15)) >> 16;
    t[i] = static_cast<uint8_t>(v > 255 ? 255 : v);
  }
  return t;
}
inline constexpr std::array<uint8_t, 256> kLog2Frac = make_log2_frac_table();

// log2(x) in Q.8 for x > 0.
inline int32_t log2_q8(uint64_t x) {
  const int e = 63 - clz64(x);
  const auto m = static_cast<size_t>(e >= 8 ? (x >> (e - 8)) & 255u : (x << (8 - e)) & 255u);
  return e * 256 + kLog2Frac[m];
}

// Level of detail (Q.8, log2 of level-0 texels per pixel) from derivatives in level-0 Q.8 texels.
inline int32_t lod_q8(int64_t dsdx, int64_t dtdx, int64_t dsdy, int64_t dtdy) {
  auto sq = [](int64_t d) {
    const int64_t c = d < -(1 << 30) ? -(1 << 30) : d > (1 << 30) ? (1 << 30) : d;
    return static_cast<uint64_t>(c * c);
  };
  const uint64_t lx = sq(dsdx) + sq(dtdx), ly = sq(dsdy) + sq(dtdy);
  const uint64_t l2 = lx > ly ? lx : ly;
  if (l2 == 0) return -(1 << 15);
  return (log2_q8(l2) >> 1) - 8 * 256;
}

// The level(s) for a level of detail (GL's rules): nearest-mip rounds, linear-mip blends.
struct LevelChoice {
  int level0 = 0, level1 = 0;
  uint32_t weight = 0;  // of level1, 0..255
};
template <MipMode kMip>
inline LevelChoice choose_levels(int32_t lod, int last) {
  LevelChoice c;
  if constexpr (kMip == MipMode::kNone) {
    return c;
  } else {
    if (lod <= 0) return c;  // magnification: level 0
    if constexpr (kMip == MipMode::kNearest) {
      int d = ((lod + 128 + 255) >> 8) - 1;  // ceil(lod + 0.5) - 1
      c.level0 = c.level1 = d > last ? last : d;
    } else {
      int d = lod >> 8;
      if (d >= last) {
        c.level0 = c.level1 = last;
      } else {
        c.level0 = d;
        c.level1 = d + 1;
        c.weight = static_cast<uint32_t>(lod & 255);
      }
    }
    return c;
  }
}

// round(2^16 / n) for n = 1..32: chunk interpolation without a division per chunk.
consteval std::array<uint32_t, 33> make_inverse_table() {
  std::array<uint32_t, 33> t{};
  for (uint32_t n = 1; n <= 32; ++n) t[n] = (65536u + n / 2) / n;
  return t;
}
inline constexpr std::array<uint32_t, 33> kInverse = make_inverse_table();

// Attributes at one pixel: texel coordinates (level-0 Q.8, relative to the triangle's origin)
// and the primary and secondary colours (Q1.15, in c[0..2] and c[3..5]).
struct TexAttrs {
  int32_t s = 0, t = 0;
  int32_t c[6] = {0, 0, 0, 0, 0, 0};
};

// Plane values at one pixel, stepped along a row.
struct PlaneValues {
  uint32_t q, s, t, c[6];
  void load(const ActiveTriangle& tri, int32_t col, int32_t row, bool colors) {
    q = tri.q.at(col, row);
    s = tri.ext->s.at(col, row);
    t = tri.ext->t.at(col, row);
    if (colors) {
      for (int k = 0; k < 3; ++k) {
        c[k] = tri.c[k].at(col, row);
        c[k + 3] = tri.ext->extra.spec[k].at(col, row);
      }
    }
  }
};

// Exact attributes from perspective plane values.
inline TexAttrs exact_attrs(const ActiveTriangle& tri, const PlaneValues& p, bool colors) {
  const PreciseRecip rc(p.q);
  TexAttrs a;
  a.s = rc.div(p.s, tri.ext->m_s);
  a.t = rc.div(p.t, tri.ext->m_t);
  if (colors)
    for (int k = 0; k < 6; ++k) a.c[k] = rc.div(p.c[k], Color15::kFracBits);
  return a;
}

// Level of detail at a pixel whose perspective plane values (q, s, t) are pc: from exact
// differences over one pixel in x and in y.
inline int32_t lod_at(const ActiveTriangle& tri, const PlaneValues& pc) {
  PlaneValues px1 = pc, py1 = pc;
  px1.q += tri.q.gx;
  px1.s += tri.ext->s.gx;
  px1.t += tri.ext->t.gx;
  py1.q += tri.q.gy;
  py1.s += tri.ext->s.gy;
  py1.t += tri.ext->t.gy;
  const TexAttrs b = exact_attrs(tri, pc, false);
  const TexAttrs bx = exact_attrs(tri, px1, false);
  const TexAttrs by = exact_attrs(tri, py1, false);
  return lod_q8(int64_t{bx.s} - b.s, int64_t{bx.t} - b.t, int64_t{by.s} - b.s, int64_t{by.t} - b.t);
}

// a + b modulo 2^32, without signed overflow.
inline int32_t wrap_add(int32_t a, int32_t b) {
  return static_cast<int32_t>(static_cast<uint32_t>(a) + static_cast<uint32_t>(b));
}

// GL_MODULATE with separate specular, to a byte: round(255 (texel/255 x primary + secondary)).
inline uint32_t modulate(uint32_t texel8, uint32_t prim15, uint32_t spec15) {
  const uint32_t v = (texel8 * prim15 + 255u * spec15 + (1u << 14)) >> 15;
  return v > 255u ? 255u : v;
}

}  // namespace detail

template <class PF>
using TexSpanFn = uint32_t (*)(const ActiveTriangle& t, const DrawRecord& d,
                               typename PF::Storage* px, uint16_t* depth, int32_t col, int32_t row,
                               int32_t count);

namespace detail {
// The span body. kConstColors: a modulated triangle whose colours are the same at its three
// vertices (ActiveExtra::const_colors: flat shading, or faces lit alike such as a cube's under
// directional light) modulates every texel by those values: no colour planes to step, no colour
// divisions.
template <class PF, bool kDepth, TexPersp kPersp, TexEnv kEnv, MipMode kMip, bool kConstColors>
uint32_t fill_tex_span_body(const ActiveTriangle& tri, const DrawRecord& d,
                            typename PF::Storage* px, uint16_t* depth, int32_t col, int32_t row,
                            int32_t count) {
  using detail::TexAttrs;
  constexpr bool kColors = kEnv == TexEnv::kModulate && !kConstColors;
  uint32_t prim[3] = {0, 0, 0}, sec[3] = {0, 0, 0};
  if constexpr (kConstColors)
    for (int k = 0; k < 3; ++k) {
      prim[k] = clamp_c15(static_cast<int32_t>(tri.c[k].base));
      sec[k] = clamp_c15(static_cast<int32_t>(tri.ext->extra.spec[k].base));
    }
  constexpr int kMaxChunk = 32;
  const Texture& tex = *d.texture;
  const int last_level = tex.level_count - 1;
  // Exact mode: chunks of 8 pixels (one level of detail each) when mipmapping, else 32.
  const int chunk = kPersp == TexPersp::kSpan    ? d.span_len
                    : kPersp == TexPersp::kExact ? (kMip == MipMode::kNone ? kMaxChunk : 8)
                                                 : kMaxChunk;

  uint32_t z = 0;
  const uint32_t dz = tri.z.gx;
  if constexpr (kDepth) z = detail::depth_start(tri.z, col, row);

  // Plane values at the current pixel (exact, affine) or at the current chunk start (span).
  detail::PlaneValues pv{};
  pv.load(tri, col, row, kColors);
  detail::PlaneValues gx{};
  gx.q = tri.q.gx;
  gx.s = tri.ext->s.gx;
  gx.t = tri.ext->t.gx;
  for (int k = 0; k < 3; ++k) {
    gx.c[k] = tri.c[k].gx;
    gx.c[k + 3] = tri.ext->extra.spec[k].gx;
  }

  int32_t affine_lod = 0;
  if constexpr (kPersp == TexPersp::kAffine && kMip != MipMode::kNone)
    affine_lod = detail::lod_q8(static_cast<int32_t>(tri.ext->s.gx) >> tri.ext->m_s,
                                static_cast<int32_t>(tri.ext->t.gx) >> tri.ext->m_t,
                                static_cast<int32_t>(tri.ext->s.gy) >> tri.ext->m_s,
                                static_cast<int32_t>(tri.ext->t.gy) >> tri.ext->m_t);

  TexAttrs a0;  // span mode: exact attributes at the chunk start
  if constexpr (kPersp == TexPersp::kSpan) a0 = detail::exact_attrs(tri, pv, kColors);

  // Only what the state uses has room on the stack: the texels of one level overwrite the s
  // coordinates (fetch_batch reads s[k] and t[k] before it writes out[k]), unless a second
  // level is fetched at the same coordinates (trilinear); colours only when they vary.
  constexpr bool kTwoLevels = kMip == MipMode::kLinear;
  int16_t idx[kMaxChunk];
  int32_t cs[kMaxChunk], ct[kMaxChunk];
  uint16_t cc[kColors ? kMaxChunk : 1][6];
  Texel own_texels[kTwoLevels ? kMaxChunk : 1], texels1[kTwoLevels ? kMaxChunk : 1];
  // The unsigned view of int32_t storage: an access the aliasing rules allow.
  Texel* const texels = kTwoLevels ? own_texels : reinterpret_cast<Texel*>(cs);
  uint32_t written = 0;

  for (int32_t done = 0; done < count;) {
    const int len = count - done < chunk ? static_cast<int>(count - done) : chunk;

    // Level of detail for the chunk.
    detail::LevelChoice lv;
    if constexpr (kMip != MipMode::kNone) {
      int32_t lod = affine_lod;
      if constexpr (kPersp != TexPersp::kAffine) {
        // At the chunk's centre pixel: the level of detail changes along a row on faces seen at
        // a grazing angle, and the centre halves the error of taking it at one end.
        detail::PlaneValues pc = pv;
        const auto half = static_cast<uint32_t>(len / 2);
        pc.q += gx.q * half;
        pc.s += gx.s * half;
        pc.t += gx.t * half;
        lod = detail::lod_at(tri, pc);
      }
      lv = detail::choose_levels<kMip>(lod, last_level);
    }

    // Span mode: exact attributes at the chunk's end, and the steps towards them (Q.8 extra).
    int32_t ds = 0, dt = 0, dc[6] = {0, 0, 0, 0, 0, 0};
    TexAttrs a1;
    detail::PlaneValues pe{};
    if constexpr (kPersp == TexPersp::kSpan) {
      const bool last = done + len >= count;
      const int steps = last ? len - 1 : len;
      pe.load(tri, col + done + steps, row, kColors);
      a1 = detail::exact_attrs(tri, pe, kColors);
      if (steps > 0) {
        const int64_t inv = detail::kInverse[static_cast<size_t>(steps)];
        auto step = [&](int32_t from, int32_t to) {
          int64_t diff = int64_t{to} - from;
          diff = diff > (1 << 22) ? (1 << 22) : diff < -(1 << 22) ? -(1 << 22) : diff;
          return static_cast<int32_t>((diff * 256 * inv) >> 16);
        };
        ds = step(a0.s, a1.s);
        dt = step(a0.t, a1.t);
        if constexpr (kColors)
          for (int k = 0; k < 6; ++k) dc[k] = step(a0.c[k], a1.c[k]);
      }
    }

    // Pass A: depth, then coordinates and colours of the visible pixels only.
    int m = 0;
    int32_t acc_s = 0, acc_t = 0, acc_c[6] = {0, 0, 0, 0, 0, 0};
    for (int i = 0; i < len; ++i) {
      const int k = static_cast<int>(done) + i;
      bool pass = true;
      if constexpr (kDepth) {
        pass = detail::depth_pass(z, depth[k]);
        z += dz;
      }
      if (pass) {
        TexAttrs a;
        if constexpr (kPersp == TexPersp::kExact) {
          a = detail::exact_attrs(tri, pv, kColors);
        } else if constexpr (kPersp == TexPersp::kSpan) {
          a.s = detail::wrap_add(a0.s, acc_s >> 8);
          a.t = detail::wrap_add(a0.t, acc_t >> 8);
          if constexpr (kColors)
            for (int c = 0; c < 6; ++c) a.c[c] = a0.c[c] + (acc_c[c] >> 8);
        } else {
          a.s = static_cast<int32_t>(pv.s) >> tri.ext->m_s;
          a.t = static_cast<int32_t>(pv.t) >> tri.ext->m_t;
          if constexpr (kColors)
            for (int c = 0; c < 6; ++c) a.c[c] = static_cast<int32_t>(pv.c[c]) >> 15;
        }
        idx[m] = static_cast<int16_t>(k);
        // Modular: coordinates only overflow for degenerate inputs, where any texel will do,
        // and repeat wrapping is modular anyway.
        cs[m] = detail::wrap_add(a.s, tri.ext->off_s);
        ct[m] = detail::wrap_add(a.t, tri.ext->off_t);
        if constexpr (kColors)
          for (int c = 0; c < 6; ++c) cc[m][c] = static_cast<uint16_t>(clamp_c15(a.c[c]));
        ++m;
      }
      if constexpr (kPersp == TexPersp::kSpan) {
        acc_s += ds;
        acc_t += dt;
        if constexpr (kColors)
          for (int c = 0; c < 6; ++c) acc_c[c] += dc[c];
      } else {
        pv.q += gx.q;
        pv.s += gx.s;
        pv.t += gx.t;
        if constexpr (kColors)
          for (int c = 0; c < 6; ++c) pv.c[c] += gx.c[c];
      }
    }
    if constexpr (kPersp == TexPersp::kSpan) {
      if (done + len < count) {
        // The next chunk starts where this one ended (steps == len): its plane values and
        // exact attributes are already known.
        pv = pe;
        a0 = a1;
      }
    }

    // Fetch, blend levels, combine, write.
    if (m > 0) {
      d.fetch(tex, lv.level0, cs, ct, m, texels);
      if constexpr (kMip == MipMode::kLinear) {
        if (lv.weight != 0) {
          d.fetch(tex, lv.level1, cs, ct, m, texels1);
          for (int j = 0; j < m; ++j)
            texels[j] = detail::lerp_texel(texels[j], texels1[j], lv.weight);
        }
      }
      for (int j = 0; j < m; ++j) {
        const Texel tx = texels[j];
        Rgb8 out{static_cast<uint8_t>(tx >> 16), static_cast<uint8_t>(tx >> 8),
                 static_cast<uint8_t>(tx)};
        if constexpr (kColors) {
          out.r = static_cast<uint8_t>(detail::modulate(out.r, cc[j][0], cc[j][3]));
          out.g = static_cast<uint8_t>(detail::modulate(out.g, cc[j][1], cc[j][4]));
          out.b = static_cast<uint8_t>(detail::modulate(out.b, cc[j][2], cc[j][5]));
        } else if constexpr (kConstColors) {
          out.r = static_cast<uint8_t>(detail::modulate(out.r, prim[0], sec[0]));
          out.g = static_cast<uint8_t>(detail::modulate(out.g, prim[1], sec[1]));
          out.b = static_cast<uint8_t>(detail::modulate(out.b, prim[2], sec[2]));
        }
        px[idx[j]] = PF::encode(out);
      }
      written += static_cast<uint32_t>(m);
    }
    done += len;
  }
  return written;
}

// Exact perspective without mipmaps on an RGB565 texture (replaced, or modulated by constant
// colours) takes the routine of tex_exact_span.hpp, its fetch inlined per filter and wrap.
template <class PF, bool kDepth, TexEnv kEnv, bool kConstColors>
uint32_t fill_exact_565(const ActiveTriangle& tri, const DrawRecord& d, typename PF::Storage* px,
                        uint16_t* depth, int32_t col, int32_t row, int32_t count) {
  uint32_t prim[3] = {0, 0, 0}, sec[3] = {0, 0, 0};
  if constexpr (kConstColors)
    for (int k = 0; k < 3; ++k) {
      prim[k] = clamp_c15(static_cast<int32_t>(tri.c[k].base));
      sec[k] = clamp_c15(static_cast<int32_t>(tri.ext->extra.spec[k].base));
    }
  auto slow = [&](typename PF::Storage* p, uint16_t* dp, int32_t c, int32_t r) {
    return fill_tex_span_body<PF, kDepth, TexPersp::kExact, kEnv, MipMode::kNone, kConstColors>(
        tri, d, p, dp, c, r, 1);
  };
  const Texture& tex = *d.texture;
  const bool repeat = d.wrap_s == Wrap::kRepeat && d.wrap_t == Wrap::kRepeat;
  const bool clamp = d.wrap_s == Wrap::kClampToEdge && d.wrap_t == Wrap::kClampToEdge;
  auto run = [&]<Filter kF, Wrap kW>() {
    return exact_span_565<PF, kDepth, kEnv, kF, kW, kW>(tri, tex, px, depth, col, row, count, prim,
                                                        sec, slow);
  };
  if (repeat && tex.power_of_two())
    return d.filter == Filter::kNearest
               ? run.template operator()<Filter::kNearest, Wrap::kRepeat>()
               : run.template operator()<Filter::kBilinear, Wrap::kRepeat>();
  if (clamp)
    return d.filter == Filter::kNearest
               ? run.template operator()<Filter::kNearest, Wrap::kClampToEdge>()
               : run.template operator()<Filter::kBilinear, Wrap::kClampToEdge>();
  return fill_tex_span_body<PF, kDepth, TexPersp::kExact, kEnv, MipMode::kNone, kConstColors>(
      tri, d, px, depth, col, row, count);
}

}  // namespace detail

// One routine per (depth, perspective mode, environment, mip mode); a modulated one picks its
// body per span by whether the triangle's colours are constant (a per-span choice, not per pixel).
// kInlineFetch: whether the spans that allow it take fill_exact_565 (SpanSet::inline_fetch).
template <class PF, bool kDepth, TexPersp kPersp, TexEnv kEnv, MipMode kMip,
          bool kInlineFetch = true>
uint32_t fill_tex_span(const ActiveTriangle& tri, const DrawRecord& d, typename PF::Storage* px,
                       uint16_t* depth, int32_t col, int32_t row, int32_t count) {
  if constexpr (kInlineFetch && kPersp == TexPersp::kExact && kMip == MipMode::kNone) {
    if (d.texture->format == TexelFormat::kRgb565) {
      if constexpr (kEnv == TexEnv::kReplace)
        return detail::fill_exact_565<PF, kDepth, kEnv, false>(tri, d, px, depth, col, row, count);
      else if (tri.ext->const_colors)
        return detail::fill_exact_565<PF, kDepth, kEnv, true>(tri, d, px, depth, col, row, count);
    }
  }
  if constexpr (kEnv == TexEnv::kModulate)
    if (tri.ext->const_colors)
      return detail::fill_tex_span_body<PF, kDepth, kPersp, kEnv, kMip, true>(tri, d, px, depth,
                                                                              col, row, count);
  return detail::fill_tex_span_body<PF, kDepth, kPersp, kEnv, kMip, false>(tri, d, px, depth, col,
                                                                           row, count);
}

// The textured family (dispatch.hpp): fill_tex_span per (depth test, perspective mode,
// environment, mip mode); the filter is the fetcher's.
template <class PF, bool kInlineFetch = true>
struct TexturedSpans {
  using Layout = TexturedLayout;
  using Fn = TexSpanFn<PF>;
  static constexpr auto kUsed = &UsedRoutines::textured;
  template <bool kDepth, TexPersp kPersp, TexEnv kEnv, MipMode kMip>
  static constexpr Fn routine() {
    return &fill_tex_span<PF, kDepth, kPersp, kEnv, kMip, kInlineFetch>;
  }
};

template <class PF, SpanSet kSet = kAllSpans>
inline constexpr std::array<TexSpanFn<PF>, kTexturedRoutines> kTexSpanTable =
    make_table<TexturedSpans<PF, detail::has(kSet.inline_fetch, true)>, kSet>();

// The textured span routine for a draw: generated from the template and the state space,
// indexed by its state (nullptr for a state outside kSet, which draw() refuses).
template <class PF, SpanSet kSet = kAllSpans>
constexpr TexSpanFn<PF> tex_span_routine(const DrawRecord& d) {
  return kTexSpanTable<PF, kSet>[textured_index(d.depth, d.persp, d.env, d.mip)];
}

}  // namespace lr
