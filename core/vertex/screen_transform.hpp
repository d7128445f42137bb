// The short path of the vertex stage: a draw's model-view-projection in 32-bit rows, taking a
// model position straight to display subpixels, window depth and clip w with high-word products
// (mla_hi: SMMLA on cores with the DSP extension) and one reciprocal of w (recip_q61), the same
// integers on every core.
//
// Per draw, each row of the model-view-projection is multiplied by its viewport factor (x: the
// half width in subpixels, y: minus the half height, z: half the depth range kDepthMax / 2, w: 1)
// and scaled by a power of two chosen from the row and the draw's position bound, so that no sum
// can leave int32; positions are shifted up to use 31 bits. Per vertex:
//   X, Y, W = rows . (P, 1)                 sums of three mla_hi each
//   n = clz(W), r = recip_q61(W << n) >> (n_max - n)      about 2^(61 - n_max) / W
//   x = mla_hi(X, r, (sx << f) + 2^(f - 1)) >> f          display subpixels, rounded
//   y = mla_hi(Y, r, (sy << f) + 2^(f - 1)) >> f
//   z = c0 + mul_hi(Z, r) 2^kz                            Z: the z row, or a constant when the
//                                                         projection is GL's perspective (window
//                                                         z is affine in 1 / w there)
// and the outcode from those: x, y against the guard band, z against the depth range. Vertices
// whose w is below 2^-n_max of the draw's scale (near the eye or behind it), and draws whose clip
// coordinates may reach the exact path's range limit, return false: the caller projects them
// exactly (VertexStage::project on 64-bit clip coordinates) and counts them
// (FrameStats::vertices_wide). Derivation and bounds: docs/numerics.md#the-short-path.
#pragma once

#include <cstddef>
#include <cstdint>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/math/reciprocal.hpp"
#include "lineraster/core/math/vec.hpp"
#include "lineraster/core/math/wide_mul.hpp"
#include "lineraster/core/vertex/clip.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr {

// Fraction bits of a subpixel the short path keeps in x / w and y / w before rounding (at least):
// x and y are within 2^-kShortPathFractionBits subpixels plus 2^-19 of their distance from the
// centre of the quotients of the draw's clip coordinates (before rounding; tests/core/vertex_test).
inline constexpr int kShortPathFractionBits = 5;

// A bound of a draw's position coordinates (Q16.16 raw): every coordinate c lies in
// [-bound - 1, bound]. One pass over the positions: the OR of c ^ (c >> 31) (c, or -c - 1), less
// than twice the largest magnitude, which is all the short path's scaling needs.
uint32_t position_bound(const Vec3* positions, size_t n);

class ScreenTransform {
 public:
  // mvp: the draw's model-view-projection (Q16.16); projection: its projection, when it is GL's
  // perspective (z affine in 1 / w: is_perspective()), else nullptr; bound: every coordinate of
  // the positions it will be given lies in [-bound - 1, bound] (position_bound); the viewport
  // (1..kMaxViewport) and its guard band.
  ScreenTransform(const Mat4& mvp, const Mat4* projection, uint32_t bound, int width, int height,
                  GuardBand guard);

  // Whether any vertex can take the short path (false: the draw's clip coordinates may reach the
  // exact path's range limit, or its rows leave no precision for it).
  bool enabled() const { return enabled_; }

  // p into v's x, y, z, w and outcode (nothing else of v); false (v unchanged) when the vertex
  // needs the exact path (always when !enabled()). A position outside the bound gives a wrong
  // vertex (never undefined behaviour, never one outside the coordinate budget).
  [[gnu::always_inline]] bool project(const Vec3& p, ScreenVertex& v) const;

  // GL's perspective (glFrustum, gluPerspective): z_clip = A z_eye + B, w_clip = -z_eye.
  static bool is_perspective(const Mat4& projection);

 private:
  static constexpr int32_t kMaxW = (int32_t{1} << 30) - 1;  // row sums are below 2^29 + 5
  static constexpr uint32_t kHalfDepth = kDepthMax / 2;     // 65535 * 2^15

  [[gnu::noinline]] uint8_t outside(int32_t x, int32_t y, int32_t m) const;

  // Rows x, y, z, w: a_[i][j] = K_i m_ij 2^(E_i - ps), |a| < 2^31; t_[i] = K_i t_i 2^(E_i - 16),
  // with m, t the Q16.16 entries, K_i the row's viewport factor and E_i its exponent (x and y
  // share one): every row sum is below 2^29 + 5 in magnitude (docs/numerics.md#the-short-path).
  int32_t a_[4][3] = {};
  int32_t t_[4] = {};
  int ps_ = 0;  // position shift: |p << ps| <= 2^31
  // Short path when W is in [w_min, kMaxW]: w_min = 2^(31 - n_max), w_range = kMaxW - w_min.
  // Disabled: only W = INT32_MIN, which no row sum reaches (nor the zero rows).
  int32_t w_min_ = INT32_MIN;
  uint32_t w_range_ = 0;
  int n_max_ = 0;      // in [2, 9]
  int f_ = 0;          // fraction bits of x and y before the rounding shift, in [5, 10]
  int32_t acc_x_ = 0;  // (sx << f) + 2^(f - 1): sx the viewport's centre, subpixels
  int32_t acc_y_ = 0;  // (sy << f) + 2^(f - 1)
  int32_t x_lo_ = 0;   // the guard band: x in [x_lo, x_lo + x_span], subpixels
  uint32_t x_span_ = 0;
  int32_t y_lo_ = 0;
  uint32_t y_span_ = 0;
  bool affine_z_ = false;  // z from c1 (GL's perspective), not from the z row
  int32_t c1_ = 0;         // affine z: m = mul_hi(c1, r) is B / w in units of 2^kz
  uint32_t c0_ = 0;        // z = c0 + m 2^kz (wrapping: exact inside the depth range)
  int kz_ = 0;             // in [0, 15]
  int32_t m_lo_ = 0;       // the depth range: m in [m_lo, m_lo + m_span]
  uint32_t m_span_ = 0;
  int w_shift_ = 0;  // clip w in Q16.16: W >> w_shift (w_shift >= 0) or W << -w_shift
  bool enabled_ = false;
};

inline bool ScreenTransform::project(const Vec3& p, ScreenVertex& v) const {
  // C++20 shifts are modular: a position beyond the bound gives a wrong vertex, never UB.
  const int32_t px = p.x.raw << ps_, py = p.y.raw << ps_, pz = p.z.raw << ps_;
  auto row = [&](int i) {
    return mla_hi(a_[i][0], px, mla_hi(a_[i][1], py, mla_hi(a_[i][2], pz, t_[i])));
  };
  const int32_t w = row(3);
  // w in [w_min, kMaxW]: n = clz(w) in [2, n_max] (one compare; the upper end holds for
  // positions within the bound and keeps every shift below defined for any others).
  if (static_cast<uint32_t>(w) - static_cast<uint32_t>(w_min_) > w_range_) return false;
  const int32_t x = row(0), y = row(1);
  const int32_t zs = affine_z_ ? c1_ : row(2);
  const int n = clz32(static_cast<uint32_t>(w));
  const auto r = static_cast<int32_t>(recip_q61(static_cast<uint32_t>(w) << n) >> (n_max_ - n));
  const int32_t xs = mla_hi(x, r, acc_x_) >> f_;
  const int32_t ys = mla_hi(y, r, acc_y_) >> f_;
  const int32_t m = mul_hi(zs, r);
  if (static_cast<uint32_t>(xs - x_lo_) > x_span_ || static_cast<uint32_t>(ys - y_lo_) > y_span_ ||
      static_cast<uint32_t>(m - m_lo_) > m_span_) [[unlikely]] {
    v.outcode = outside(xs, ys, m);
    return true;
  }
  v.x = xs;
  v.y = ys;
  v.z = c0_ + (static_cast<uint32_t>(m) << kz_);
  v.w = w_shift_ >= 0 ? static_cast<uint32_t>(w) >> w_shift_
        : static_cast<uint32_t>(w) >= (0xFFFFFFFFu >> -w_shift_)
            ? 0xFFFFFFFFu
            : static_cast<uint32_t>(w) << -w_shift_;
  v.outcode = 0;
  return true;
}

}  // namespace lr
