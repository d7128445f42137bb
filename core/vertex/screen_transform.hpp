// The short path of the vertex stage: a draw's model-view-projection in 32-bit rows, taking a
// model position straight to display subpixels, window depth and clip w with high-word products
// (mla_hi: SMMLA on Armv7-M) and one reciprocal of w (recip_q61), the same integers on every core.
//
// Per draw, each row of the model-view-projection is multiplied by its viewport factor (x: the
// half width in subpixels, y: minus the half height, z: half the depth range kDepthMax / 2, w: 1)
// and scaled by a power of two chosen from the row and the draw's position bound, so that no sum
// can leave int32; positions are shifted up to use 31 bits. Per vertex:
//   X, Y, Z, W = rows . (P, 1)                 four sums of three mla_hi each
//   n = clz(W), r = recip_q61(W << n)           about 2^(61 - n) / W
//   x = sx + round(mul_hi(X, r) / 2^s)          s = the draw's base - n, at least
//   y = sy + round(mul_hi(Y, r) / 2^s)            kShortPathFractionBits
//   z = kDepthMax / 2 + mul_hi(Z, r) 2^k        k = n - the draw's z exponent, at most 10
// and the outcode from the quotients: x, y against the guard band, z against the depth range.
// Vertices whose w is too small for that precision (near the eye, behind it, or a draw whose
// clip coordinates reach the exact path's range limit) return false: the caller takes the exact
// path (VertexStage::project on 64-bit clip coordinates) and counts them
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

// Fraction bits of a subpixel the short path keeps in x / w and y / w before rounding: its x and y
// are within 2^-kShortPathFractionBits subpixels (plus the rounding) of the quotients of its
// own clip coordinates.
inline constexpr int kShortPathFractionBits = 5;

// A bound of a draw's position coordinates (Q16.16 raw): every coordinate c lies in
// [-bound - 1, bound]. One pass over the positions: the OR of c ^ (c >> 31) (c, or -c - 1), less
// than twice the largest magnitude, which is all the short path's scaling needs.
uint32_t position_bound(const Vec3* positions, size_t n);

class ScreenTransform {
 public:
  // mvp: the draw's model-view-projection (Q16.16); bound: every coordinate of the positions it
  // will be given lies in [-bound - 1, bound] (position_bound); the viewport (1..kMaxViewport)
  // and its guard band.
  ScreenTransform(const Mat4& mvp, uint32_t bound, int width, int height, GuardBand guard);

  // Whether any vertex can take the short path (false: the draw's clip coordinates may reach the
  // exact path's range limit, or its rows leave no precision for it).
  bool enabled() const { return enabled_; }

  // p into v's x, y, z, w and outcode (nothing else of v); false (v unchanged) when the vertex
  // needs the exact path. Only when enabled(). A position outside the bound gives a wrong vertex
  // (never undefined behaviour).
  [[gnu::always_inline]] bool project(const Vec3& p, ScreenVertex& v) const;

 private:
  static constexpr int32_t kMaxW = (int32_t{1} << 30) - 1;  // row sums are below 2^29 + 5
  static constexpr int32_t kHalfDepth = static_cast<int32_t>(kDepthMax / 2);  // 65535 * 2^15

  [[gnu::noinline]] uint8_t outside(int32_t qx, int32_t qy, int32_t mz, int32_t dz) const;

  // Rows x, y, z, w: a_[i][j] = K_i m_ij 2^(E_i - ps), |a| < 2^31; t_[i] = K_i t_i 2^(E_i - 16),
  // with m, t the Q16.16 entries, K_i the row's viewport factor and E_i its exponent (x and y
  // share one): every row sum is below 2^29 + 4 in magnitude (docs/numerics.md#the-short-path).
  int32_t a_[4][3] = {};
  int32_t t_[4] = {};
  int ps_ = 0;              // position shift: |p << ps| <= 2^31
  // Short path when W is in [w_min, kMaxW]: w_min a power of two in [2^22, 2^29], w_range
  // kMaxW - w_min. Disabled: only W = INT32_MIN, which no row sum reaches (nor the zero rows).
  int32_t w_min_ = INT32_MIN;
  uint32_t w_range_ = 0;
  int sxy_ = 0;             // s = sxy - clz(W): x, y quotient shift, >= kShortPathFractionBits
  int cz_ = 0;              // k = clz(W) - cz: z quotient shift, in [0, 10]
  int w_shift_ = 0;         // clip w in Q16.16: W >> w_shift (w_shift >= 0) or W << -w_shift
  int32_t sx_ = 0, sy_ = 0;  // the viewport's centre, subpixels
  int32_t lx_ = 0, ly_ = 0;  // the guard band's half extents, subpixels (<= 2^20)
  bool enabled_ = false;
};

inline bool ScreenTransform::project(const Vec3& p, ScreenVertex& v) const {
  // C++20 shifts are modular: a position beyond the bound gives a wrong vertex, never UB.
  const int32_t px = p.x.raw << ps_, py = p.y.raw << ps_, pz = p.z.raw << ps_;
  auto row = [&](int i) {
    return mla_hi(a_[i][0], px, mla_hi(a_[i][1], py, mla_hi(a_[i][2], pz, t_[i])));
  };
  const int32_t w = row(3);
  // w in [w_min, kMaxW]: n = clz(w) in [2, 9] (one compare; the upper end holds for positions
  // within the bound and keeps every shift below defined for any others).
  if (static_cast<uint32_t>(w) - static_cast<uint32_t>(w_min_) > w_range_) return false;
  const int32_t x = row(0), y = row(1), z = row(2);
  const int n = clz32(static_cast<uint32_t>(w));  // in [2, 9]
  const auto r = static_cast<int32_t>(recip_q61(static_cast<uint32_t>(w) << n));
  const int s = sxy_ - n;
  const int32_t half = int32_t{1} << (s - 1);
  const int32_t qx = (mul_hi(x, r) + half) >> s;
  const int32_t qy = (mul_hi(y, r) + half) >> s;
  const int k = n - cz_;
  const int32_t mz = mul_hi(z, r);
  const int32_t dz = kHalfDepth >> k;
  // Inside the guard band and the depth range: |qx| <= lx, |qy| <= ly, |mz| <= dz.
  if (static_cast<uint32_t>(qx + lx_) > static_cast<uint32_t>(2 * lx_) ||
      static_cast<uint32_t>(qy + ly_) > static_cast<uint32_t>(2 * ly_) ||
      static_cast<uint32_t>(mz + dz) > static_cast<uint32_t>(2 * dz)) [[unlikely]] {
    v.outcode = outside(qx, qy, mz, dz);
    return true;
  }
  v.x = qx + sx_;
  v.y = qy + sy_;
  v.z = (static_cast<uint32_t>(mz) << k) + static_cast<uint32_t>(kHalfDepth);
  v.w = w_shift_ >= 0 ? static_cast<uint32_t>(w) >> w_shift_
        : static_cast<uint32_t>(w) >= (0xFFFFFFFFu >> -w_shift_)
            ? 0xFFFFFFFFu
            : static_cast<uint32_t>(w) << -w_shift_;
  v.outcode = 0;
  return true;
}

}  // namespace lr
