// The exact-perspective textured span without mipmaps: one 32-bit division per coordinate and
// pixel (on cores without a divider one table reciprocal per pixel, shared by both), the texel
// fetch inlined.
//
// A span is cut into chunks of up to 32 pixels. Per chunk, each coordinate s (and t) gets a base
// b (an integer in the output unit: texels for nearest, Q.8 texels for bilinear) a little below
// its smallest value in the chunk, and the plane D = (S 2^m - (b - off) q) / 2^(sh + fb) of the
// remainder u = s - b, which is >= 0 and fits in 32 bits over the chunk; per pixel
// u = D / qn with qn = round(q / 2^sh), the 24 top bits of q for nearest and 16 for bilinear.
// So a pixel costs two divisions and no 64-bit arithmetic, and the division is exact: the only
// errors are qn's rounding and D's rounded step (docs/numerics.md#exact-perspective-chunks). A
// chunk where a bound fails (a huge minification, a degenerate q) is halved, down to one pixel, and
// then drawn with the precise reciprocal of the general routine.
#pragma once

#include <cstdint>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/reciprocal.hpp"
#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/span/sampler.hpp"
#include "lineraster/core/span/span.hpp"
#include "lineraster/core/texture/texture.hpp"

namespace lr {

namespace detail {

// v / 2^k rounded down, for k of either sign (|k| < 63, no overflow for the callers' ranges).
constexpr int64_t shift_down(int64_t v, int k) {
  return k >= 0 ? v >> k : static_cast<int64_t>(static_cast<uint64_t>(v) << -k);
}

// One coordinate's remainder plane over a chunk (see the file comment). d, gd: D at the chunk's
// first pixel and its step, both in [0, 2^32) at every pixel of the chunk; base: b.
// No member initialisers: the chunk is made per 32 pixels and zeroing it cost a memset call;
// chunk_coord() writes every member before it returns true, and nothing reads it otherwise.
struct ChunkCoord {
  uint32_t d, gd;
  int32_t base;
};

// The largest remainder of a chunk, in Q.8 texels: u < 2^kMaxRemainderBits bounds the error
// of qn's rounding (relative 2^-15 at most) to one Q.8 unit.
inline constexpr int kMaxRemainderBits = 15;

// The bits of the per-pixel divisor qn = round(q / 2^sh): D = u qn < 2^32 with u below
// 2^(kMaxRemainderBits - fb) output units leaves 24 bits for nearest (whole texels) and 16 for
// bilinear (Q.8 texels); the more bits, the smaller qn's rounding.
constexpr int divisor_bits(int fb) {
  return fb == 8 ? 24 : 16;
}

// The chunk plane of one coordinate from its plane value S0 at the first pixel, its step gs,
// m (S = s q / 2^m), the origin off (Q.8), q at both ends (q0, q1 >= 1), the chunk length,
// se (r0, r1 ~ 2^(32 + se) / q at both ends: estimates of s only), sh (qn = q / 2^sh) and fb
// (output unit 2^fb Q.8).
inline bool chunk_coord(uint32_t s0_plane, uint32_t gs_plane, int m, int32_t off, int32_t q0,
                        int32_t q1, uint32_t gq, int len, int se, int sh, int fb, uint32_t r0,
                        uint32_t r1, ChunkCoord& out) {
  const auto s0 = static_cast<int32_t>(s0_plane);
  const auto s1 = static_cast<int32_t>(s0_plane + gs_plane * static_cast<uint32_t>(len - 1));
  // s (Q.8, relative to off) at both ends to about 2^-13 relative: s is monotonic in a chunk
  // (a ratio of two linear functions, q > 0), so the ends bound it.
  const int64_t e0 = shift_down(int64_t{s0} * r0, 32 + se - m);
  const int64_t e1 = shift_down(int64_t{s1} * r1, 32 + se - m);
  const int64_t lo = e0 < e1 ? e0 : e1;
  const int64_t mag =
      (e0 < 0 ? -e0 : e0) > (e1 < 0 ? -e1 : e1) ? (e0 < 0 ? -e0 : e0) : (e1 < 0 ? -e1 : e1);
  const int64_t b = (lo + off - (mag >> 11) - 512) >> fb;  // below the smallest s, in 2^fb units
  const int64_t b_rel = b * (int64_t{1} << fb) - off;      // Q.8, relative to off
  if (b_rel < -(int64_t{1} << 30) || b_rel > (int64_t{1} << 30)) return false;
  // |s0 2^m| < 2^62 and |b_rel q| < 2^61: no overflow.
  const int64_t d0 = int64_t{s0} * (int64_t{1} << m) - b_rel * q0;
  const int64_t gd = int64_t{static_cast<int32_t>(gs_plane)} * (int64_t{1} << m) -
                     b_rel * static_cast<int32_t>(gq);
  const int k = sh + fb;
  const int64_t dn0 = shift_down(d0, k);
  const int64_t gdn = k > 0 ? shift_down(gd + (int64_t{1} << (k - 1)), k) : gd;
  const int64_t dn1 = dn0 + gdn * (len - 1);
  // u = D / qn below 2^kMaxRemainderBits Q.8 units: D below that times the smallest qn
  // (< 2^31: qn < 2^divisor_bits(fb)).
  const int32_t qmin = q0 < q1 ? q0 : q1;
  const int64_t limit = int64_t{qmin >> sh} << (kMaxRemainderBits - fb);
  if (dn0 < 0 || dn1 < 0 || dn0 > limit || dn1 > limit || dn0 > 0xFFFFFFFFll || dn1 > 0xFFFFFFFFll)
    return false;
  out.d = static_cast<uint32_t>(dn0);
  out.gd = static_cast<uint32_t>(gdn);
  out.base = static_cast<int32_t>(b);
  return true;
}

// The chunk of an exact span: q (biased by half of 2^sh, so that >> sh rounds), its step, sh,
// j (qn / 2^j in [2^14, 2^16]: small_divisor's shift) and the planes of s and t.
struct ExactChunk {  // no member initialisers, as ChunkCoord; setup() writes what it returns
  uint32_t q, gq;
  int sh, j;
  ChunkCoord s, t;

  // From the plane values (q, s, t) at the chunk's first pixel; false when a bound fails.
  bool setup(const ActiveTriangle& tri, uint32_t q_plane, uint32_t s_plane, uint32_t t_plane,
             int len, int fb) {
    gq = tri.q.gx;
    const auto q0 = static_cast<int32_t>(q_plane);
    const auto q1 = static_cast<int32_t>(q_plane + gq * static_cast<uint32_t>(len - 1));
    if (q0 < (1 << 15) || q1 < (1 << 15)) return false;
    const int32_t qmax = q0 > q1 ? q0 : q1, qmin = q0 > q1 ? q1 : q0;
    const int bits = 32 - clz32(static_cast<uint32_t>(qmax));
    const int se = bits > 16 ? bits - 16 : 0;  // q / 2^se < 2^16: the estimates' scale
    const int extra = divisor_bits(fb) - 16;
    sh = se > extra ? se - extra : 0;  // qmax / 2^sh < 2^divisor_bits(fb)
    j = se - sh;
    const uint32_t half = sh > 0 ? 1u << (sh - 1) : 0u;
    // qn / 2^j in [2^14, 2^16] over the chunk: qn's rounding is below 2^-15 of it.
    if (((static_cast<uint32_t>(qmin) + half) >> se) < (1u << 14)) return false;
    q = static_cast<uint32_t>(q0) + half;
    const uint32_t half_e = se > 0 ? 1u << (se - 1) : 0u;
    const uint32_t r0 = 0xFFFFFFFFu / ((static_cast<uint32_t>(q0) + half_e) >> se);
    const uint32_t r1 = 0xFFFFFFFFu / ((static_cast<uint32_t>(q1) + half_e) >> se);
    return chunk_coord(s_plane, tri.ext->s.gx, tri.ext->m_s, tri.ext->off_s, q0, q1, gq, len, se,
                       sh, fb, r0, r1, s) &&
           chunk_coord(t_plane, tri.ext->t.gx, tri.ext->m_t, tri.ext->off_t, q0, q1, gq, len, se,
                       sh, fb, r0, r1, t);
  }
};

// Texel access of one level-0 RGB565 texture for the inlined fetch: the index of an absolute
// texel (x, y) after wrapping, masks for power-of-two repeat.
template <Wrap kWs, Wrap kWt>
struct Texels565 {
  const uint16_t* p;
  int32_t w, h, mask_w, mask_h;
  int shift_w;
  bool pow2;
  explicit Texels565(const Texture& tex)
      : p(tex.levels[0].rgb565.data()),
        w(tex.levels[0].width),
        h(tex.levels[0].height),
        mask_w(w - 1),
        mask_h(h - 1),
        shift_w(__builtin_ctz(static_cast<unsigned>(w))),
        pow2(tex.power_of_two()) {}
  template <Wrap kW>
  [[gnu::always_inline]] static int32_t wrap(int32_t i, int32_t size, int32_t mask) {
    if constexpr (kW == Wrap::kRepeat) {
      return i & mask;
    } else {
      return i < 0 ? 0 : i >= size ? size - 1 : i;
    }
  }
  // Power-of-two sizes (repeat) or any size (clamp).
  [[gnu::always_inline]] uint32_t at(int32_t x, int32_t y) const {
    const int32_t xi = wrap<kWs>(x, w, mask_w), yi = wrap<kWt>(y, h, mask_h);
    if constexpr (kWs == Wrap::kRepeat && kWt == Wrap::kRepeat) {
      return p[static_cast<uint32_t>(xi) + (static_cast<uint32_t>(yi) << shift_w)];
    } else {
      return p[static_cast<uint32_t>(xi) + static_cast<uint32_t>(yi) * static_cast<uint32_t>(w)];
    }
  }
  // GL_LINEAR at absolute Q.8 coordinates, as fetch_batch computes it.
  [[gnu::always_inline]] uint32_t bilinear(int32_t s, int32_t t) const {
    const int32_t xs = s - 128, ys = t - 128;
    const int32_t xi = xs >> 8, yi = ys >> 8;
    const uint32_t wx = ((static_cast<uint32_t>(xs) & 255u) + 4) >> 3;
    const uint32_t wy = ((static_cast<uint32_t>(ys) & 255u) + 4) >> 3;
    const uint32_t a = spread565(at(xi, yi)), b = spread565(at(xi + 1, yi));
    const uint32_t c = spread565(at(xi, yi + 1)), d = spread565(at(xi + 1, yi + 1));
    return unspread565(lerp_spread(lerp_spread(a, b, wx), lerp_spread(c, d, wx), wy));
  }
};

// Whether a PF stores an RGB565 value v as PF::encode(expand565(v)) would: then a replaced
// texel is stored as it is. Checked for every value of each field with the other two fields all
// zeros and all ones (256 values: every field and every pair's interaction; a loop over all
// 65,536 values exceeds clang's constant-evaluation step limit).
template <class PF>
consteval bool stores_565() {
  if constexpr (requires { PF::from_value(0u); } && sizeof(typename PF::Storage) == 2) {
    constexpr uint32_t kFields[3][2] = {{11, 31}, {5, 63}, {0, 31}};  // shift, largest value
    for (int f = 0; f < 3; ++f)
      for (uint32_t others : {0u, 0xFFFFu}) {
        const uint32_t rest = others & ~(kFields[f][1] << kFields[f][0]);
        for (uint32_t x = 0; x <= kFields[f][1]; ++x) {
          const uint32_t v = rest | (x << kFields[f][0]);
          if (PF::encode(Rgb8{static_cast<uint8_t>(expand565(v) >> 16),
                              static_cast<uint8_t>(expand565(v) >> 8),
                              static_cast<uint8_t>(expand565(v))}) != PF::from_value(v))
            return false;
        }
      }
    return true;
  } else {
    return false;
  }
}

// The modulated or replaced colour of a texel (0x00RRGGBB), encoded (as fill_tex_span_body).
template <class PF, TexEnv kEnv>
[[gnu::always_inline]] inline typename PF::Storage shade_texel(Texel tx, const uint32_t* prim,
                                                               const uint32_t* sec) {
  Rgb8 out{static_cast<uint8_t>(tx >> 16), static_cast<uint8_t>(tx >> 8), static_cast<uint8_t>(tx)};
  if constexpr (kEnv == TexEnv::kModulate) {
    auto mod = [](uint32_t texel8, uint32_t p15, uint32_t s15) {
      const uint32_t v = (texel8 * p15 + 255u * s15 + (1u << 14)) >> 15;
      return static_cast<uint8_t>(v > 255u ? 255u : v);
    };
    out.r = mod(out.r, prim[0], sec[0]);
    out.g = mod(out.g, prim[1], sec[1]);
    out.b = mod(out.b, prim[2], sec[2]);
  }
  return PF::encode(out);
}

// The span: kEnv replace, or modulate by the triangle's constant colours (prim, sec: Q1.15).
template <class PF, bool kDepth, TexEnv kEnv, Filter kFilter, Wrap kWs, Wrap kWt, class SlowFn>
uint32_t exact_span_565(const ActiveTriangle& tri, const Texture& tex, typename PF::Storage* px,
                        uint16_t* depth, int32_t col, int32_t row, int32_t count,
                        const uint32_t* prim, const uint32_t* sec, SlowFn&& slow) {
  constexpr int kFb = kFilter == Filter::kNearest ? 8 : 0;
  constexpr bool kStoreRaw = kEnv == TexEnv::kReplace && stores_565<PF>();
  const Texels565<kWs, kWt> tx(tex);
  uint32_t z = 0;
  const uint32_t dz = tri.z.gx;
  if constexpr (kDepth) z = depth_start(tri.z, col, row);
  uint32_t qp = tri.q.at(col, row), sp = tri.ext->s.at(col, row), tp = tri.ext->t.at(col, row);
  const uint32_t gq = tri.q.gx, gs = tri.ext->s.gx, gt = tri.ext->t.gx;
  uint32_t written = 0;
  for (int32_t done = 0; done < count;) {
    int len = count - done < 32 ? static_cast<int>(count - done) : 32;
    ExactChunk ch;
    bool ok = ch.setup(tri, qp, sp, tp, len, kFb);
    while (!ok && len > 1) {
      len = (len + 1) / 2;
      ok = ch.setup(tri, qp, sp, tp, len, kFb);
    }
    typename PF::Storage* out = px + done;
    uint16_t* dp = depth + done;
    if (ok) {
      uint32_t q = ch.q, ds = ch.s.d, dt = ch.t.d;
      const int sh = ch.sh, j = ch.j;
      const int32_t bs = ch.s.base, bt = ch.t.base;
      const uint32_t gds = ch.s.gd, gdt = ch.t.gd;
      for (int i = 0; i < len; ++i) {
        bool pass = true;
        if constexpr (kDepth) {
          pass = depth_pass(z, dp[i]);
          z += dz;
        }
        if (pass) {
          // The pixel's two divisions (exact on every core; a table reciprocal without UDIV).
          const SmallDivisor qn = small_divisor(q >> sh, j);
          const auto u = static_cast<int32_t>(divide_small(ds, qn));
          const auto v = static_cast<int32_t>(divide_small(dt, qn));
          uint32_t raw;
          if constexpr (kFilter == Filter::kNearest)
            raw = tx.at(bs + u, bt + v);
          else
            raw = tx.bilinear(bs + u, bt + v);
          if constexpr (kStoreRaw)
            out[i] = PF::from_value(raw);
          else
            out[i] = shade_texel<PF, kEnv>(expand565(raw), prim, sec);
          ++written;
        }
        q += gq;
        ds += gds;
        dt += gdt;
      }
    } else {
      // One pixel the bounds refuse: the general routine's precise reciprocal.
      written += slow(out, dp, col + done, row);
      if constexpr (kDepth) z += dz;
    }
    const auto n = static_cast<uint32_t>(len);
    qp += gq * n;
    sp += gs * n;
    tp += gt * n;
    done += len;
  }
  return written;
}

}  // namespace detail

}  // namespace lr
