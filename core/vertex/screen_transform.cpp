#include "lineraster/core/vertex/screen_transform.hpp"

namespace lr {
namespace {

// An unsigned 128-bit sum, for the per-draw bounds (products of up to 2^62 and 2^32).
struct Wide {
  uint64_t hi = 0, lo = 0;
  void add(uint64_t v) {
    lo += v;
    if (lo < v) ++hi;
  }
  // += u b, u < 2^64, b < 2^32: u = u1 2^32 + u0, u0 b < 2^64, u1 b < 2^64.
  void add_mul(uint64_t u, uint32_t b) {
    const uint64_t l = (u & 0xFFFFFFFFu) * b, h = (u >> 32) * b;
    add(l);
    add(h << 32);
    hi += h >> 32;
  }
  int bit_length() const { return hi != 0 ? 128 - clz64(hi) : lo != 0 ? 64 - clz64(lo) : 0; }
};

// c 2^sh as int32, rounded to nearest (|c| 2^sh < 2^31 by the caller's bound; the rounding may
// reach 2^31, which saturates).
int32_t scaled(int64_t c, int sh) {
  const uint64_t m = abs64(c);
  uint64_t v;
  if (sh >= 0)
    v = m << sh;
  else if (sh > -63)
    v = (m + (uint64_t{1} << (-sh - 1))) >> -sh;
  else
    v = 0;
  if (v > 0x7FFFFFFFu) v = 0x7FFFFFFFu;
  return c < 0 ? -static_cast<int32_t>(v) : static_cast<int32_t>(v);
}

}  // namespace

uint32_t position_bound(const Vec3* positions, size_t n) {
  uint32_t b = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec3& p = positions[i];
    b |= static_cast<uint32_t>(p.x.raw ^ (p.x.raw >> 31)) |
         static_cast<uint32_t>(p.y.raw ^ (p.y.raw >> 31)) |
         static_cast<uint32_t>(p.z.raw ^ (p.z.raw >> 31));
  }
  return b;
}

bool ScreenTransform::is_perspective(const Mat4& p) {
  return p.m[2][0].raw == 0 && p.m[2][1].raw == 0 && p.m[3][0].raw == 0 && p.m[3][1].raw == 0 &&
         p.m[3][2].raw == -Fixed::kOne && p.m[3][3].raw == 0;
}

ScreenTransform::ScreenTransform(const Mat4& mvp, const Mat4* projection, uint32_t bound, int width,
                                 int height, GuardBand guard) {
  // Coordinates lie in [-(bound + 1), bound]; with bound < 2^(31 - ps) they stay in int32 when
  // shifted by ps, and bound 2^ps >= 2^30 (so a row's factors fit int32, below).
  if (bound > 0x7FFFFFFFu) bound = 0x7FFFFFFFu;  // no int32 coordinate is beyond
  ps_ = bound == 0 ? 30 : clz32(bound) - 1;
  const uint32_t b = bound + 1;  // the largest magnitude, <= 2^31
  const int32_t sx = width * kHalfPixel, sy = height * kHalfPixel;
  const int32_t lx = guard.gx * sx, ly = guard.gy * sy;  // <= 2^20 (G W <= 8192)
  // Row factors: the row's value times K is what the quotient by w must give (subpixels from the
  // centre, window depth from the middle of the range).
  const int64_t k[4] = {sx, -int64_t{sy}, kHalfDepth, 1};
  int exponent[4];
  for (int i = 0; i < 4; ++i) {
    // |value| 2^32 <= sum_j |K m_j| b + |K t| 2^16 < 2^L (the row times K, in Q32.32); and the
    // same without K, whose bound the exact path's range (|clip| < 2^19) must hold.
    Wide with_k, plain;
    for (int j = 0; j < 3; ++j) {
      const int64_t m = mvp.m[i][j].raw;
      with_k.add_mul(abs64(k[i] * m), b);
      plain.add_mul(abs64(m), b);
    }
    with_k.add_mul(abs64(k[i] * mvp.m[i][3].raw), 1u << 16);
    plain.add_mul(abs64(mvp.m[i][3].raw), 1u << 16);
    if (plain.bit_length() > 50) return;  // the exact path for every vertex (enabled_ false)
    // V 2^32 < 2^L, E = 61 - L: every row sum |V| 2^E below 2^29.
    exponent[i] = 61 - with_k.bit_length();
  }
  const int ew = exponent[3];
  int exy = exponent[0] < exponent[1] ? exponent[0] : exponent[1];
  // n = clz(W) is at least 2 (W < 2^30). r = recip >> (n_max - n) is 2^(61 - n_max) / W, so
  // mul_hi(X, r) = (x - sx) 2^f with f = sxy - n_max, sxy = 29 + exy - ew. n_max: at most 9
  // (W >= 2^22: its own rounding moves x by 2^-20 of x - sx at most) and sxy - 5 (f >= 5).
  int n_max = 9;
  if (n_max > 29 + exy - ew - kShortPathFractionBits)
    n_max = 29 + exy - ew - kShortPathFractionBits;
  // The z row (not GL's perspective): mul_hi(Z, r) = (z_ndc D) 2^-kz, kz = n_max - cz with
  // cz = 29 + ez - ew; ez lowered so that kz >= 0, n_max so that kz <= 10 (z in units of 2^10,
  // 1/64 of a 16-bit depth step).
  // GL's perspective: window z from D B / w = mul_hi(c1, r) 2^kz (below), kz the least that keeps
  // c1 = D B 2^(ew - 45 + n_max - kz) in int32; at most 15 (else the z row).
  bool affine = projection != nullptr && is_perspective(*projection);
  const int64_t db = affine ? int64_t{kHalfDepth} * projection->m[2][3].raw : 0;  // < 2^62
  int kz_affine = 0;
  if (affine) {
    const uint64_t mag = abs64(db);
    const int len = mag == 0 ? 0 : 64 - clz64(mag);
    kz_affine = len + (ew - 45 + n_max) - 31;
    if (kz_affine < 0) kz_affine = 0;
    if (kz_affine > 15) affine = false;
  }
  int ez = exponent[2];
  if (!affine && n_max > ez - ew + 39) n_max = ez - ew + 39;
  if (n_max < 2) return;
  if (!affine && ez > ew - 29 + n_max) ez = ew - 29 + n_max;
  // f at most 10 (x - sx and y - sy below 2^21, times 2^f below 2^31): exy lowered if need be.
  if (29 + exy - ew - n_max > 10) exy = n_max + 10 - 29 + ew;
  f_ = 29 + exy - ew - n_max;
  const int e[4] = {exy, exy, ez, ew};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 3; ++j) a_[i][j] = scaled(k[i] * mvp.m[i][j].raw, e[i] - ps_);
    t_[i] = scaled(k[i] * mvp.m[i][3].raw, e[i] - 16);
  }
  n_max_ = n_max;
  w_min_ = int32_t{1} << (31 - n_max);
  w_range_ = static_cast<uint32_t>(kMaxW - w_min_);
  acc_x_ = (sx << f_) + (1 << (f_ - 1));
  acc_y_ = (sy << f_) + (1 << (f_ - 1));
  x_lo_ = sx - lx;
  x_span_ = static_cast<uint32_t>(2 * lx);
  y_lo_ = sy - ly;
  y_span_ = static_cast<uint32_t>(2 * ly);
  int64_t c0;  // z = c0 + m 2^kz
  if (affine) {
    // z_ndc = -A + B / w, window z = D (1 - A) + D B / w (D = kHalfDepth; A, B Q16.16): with
    // 1 / w = 2^ew / W and r = 2^(61 - n_max) / W, D B / w = mul_hi(c1, r) 2^kz.
    kz_ = kz_affine;
    c1_ = scaled(db, ew - 45 + n_max - kz_);
    c0 = int64_t{kHalfDepth} - ((int64_t{kHalfDepth} * projection->m[2][2].raw + 32768) >> 16);
    affine_z_ = true;
  } else {
    kz_ = n_max - (29 + ez - ew);
    c0 = kHalfDepth;
  }
  c0_ = static_cast<uint32_t>(c0);
  // Inside the depth range: 0 <= c0 + m 2^kz <= 2 D, m in [ceil(-c0 / 2^kz), floor((2D - c0) /
  // 2^kz)] (c0 within a few times D: both ends far inside int32).
  const int64_t unit = int64_t{1} << kz_;
  const auto clamp30 = [](int64_t v) {
    return v < -(int64_t{1} << 30)  ? -(int64_t{1} << 30)
           : v > (int64_t{1} << 30) ? int64_t{1} << 30
                                    : v;
  };  // |m| < 2^27 + 1: the clamped ends decide as the exact ones
  const int64_t lo = clamp30(-floor_div(c0, unit)),
                hi = clamp30(floor_div(2 * int64_t{kHalfDepth} - c0, unit));
  m_lo_ = static_cast<int32_t>(lo);
  m_span_ = hi >= lo ? static_cast<uint32_t>(hi - lo) : 0;
  // W = w 2^ew: w's Q16.16 is W 2^(16 - ew). ew >= 11: the plain bound keeps w below 2^18.
  w_shift_ = ew - 16;
  enabled_ = true;
}

// The planes a short-path vertex is outside of: x and y (subpixels, y down) against the guard
// band, m (z = c0 + m 2^kz) against the depth range.
uint8_t ScreenTransform::outside(int32_t x, int32_t y, int32_t m) const {
  uint32_t code = 0;
  if (m < m_lo_) code |= kClipNear;
  if (static_cast<int64_t>(m) > int64_t{m_lo_} + m_span_) code |= kClipFar;
  if (x < x_lo_) code |= kClipLeft;
  if (static_cast<int64_t>(x) > int64_t{x_lo_} + x_span_) code |= kClipRight;
  if (static_cast<int64_t>(y) > int64_t{y_lo_} + y_span_) code |= kClipBottom;  // y is down
  if (y < y_lo_) code |= kClipTop;
  return static_cast<uint8_t>(code);
}

}  // namespace lr
