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

ScreenTransform::ScreenTransform(const Mat4& mvp, uint32_t bound, int width, int height,
                                 GuardBand guard) {
  // Coordinates lie in [-(bound + 1), bound]; with bound < 2^(31 - ps) they stay in int32 when
  // shifted by ps, and bound 2^ps >= 2^30 (so a row's factors fit int32, below).
  if (bound > 0x7FFFFFFFu) bound = 0x7FFFFFFFu;  // no int32 coordinate is beyond
  ps_ = bound == 0 ? 30 : clz32(bound) - 1;
  const uint32_t b = bound + 1;  // the largest magnitude, <= 2^31
  sx_ = width * kHalfPixel;
  sy_ = height * kHalfPixel;
  lx_ = guard.gx * sx_;
  ly_ = guard.gy * sy_;
  // Row factors: the row's value times K is what the quotient by w must give (subpixels from the
  // centre, window depth from the middle of the range), scaled by 2^E.
  const int64_t k[4] = {sx_, -int64_t{sy_}, kHalfDepth, 1};
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
  if (exy > ew + 3) exy = ew + 3;  // s = 29 + exy - ew - n stays below 31
  int ez = exponent[2];
  if (ez > ew - 27) ez = ew - 27;  // k = n - cz >= 0 for every n >= 2
  const int e[4] = {exy, exy, ez, ew};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 3; ++j) a_[i][j] = scaled(k[i] * mvp.m[i][j].raw, e[i] - ps_);
    t_[i] = scaled(k[i] * mvp.m[i][3].raw, e[i] - 16);
  }
  sxy_ = 29 + exy - ew;
  cz_ = 29 + ez - ew;
  // n = clz(W) is at least 2 (W < 2^30); at most 9 (W >= 2^22: W's own rounding moves x / w by
  // 2^-20 of itself at most), sxy - kShortPathFractionBits (x / w's fraction bits) and cz + 10
  // (z / w's unit, 2^k, at most 1/64 of a 16-bit depth step).
  int n_max = 9;
  if (n_max > sxy_ - kShortPathFractionBits) n_max = sxy_ - kShortPathFractionBits;
  if (n_max > cz_ + 10) n_max = cz_ + 10;
  if (n_max < 2) return;
  w_min_ = int32_t{1} << (31 - n_max);
  w_range_ = static_cast<uint32_t>(kMaxW - w_min_);
  // W = w 2^ew: w's Q16.16 is W 2^(16 - ew). ew >= 11: the plain bound keeps w below 2^18.
  w_shift_ = ew - 16;
  enabled_ = true;
}

// The planes a short-path vertex is outside of, from its quotients: x / w and y / w (qx, qy:
// subpixels from the centre, y down) against the guard band, z / w (mz 2^k, dz = 2^31 / 2^k
// rounded down) against the depth range.
uint8_t ScreenTransform::outside(int32_t qx, int32_t qy, int32_t mz, int32_t dz) const {
  uint32_t code = 0;
  if (mz < -dz) code |= kClipNear;
  if (mz > dz) code |= kClipFar;
  if (qx < -lx_) code |= kClipLeft;
  if (qx > lx_) code |= kClipRight;
  if (qy > ly_) code |= kClipBottom;  // y_ndc below -G: y is down on the display
  if (qy < -ly_) code |= kClipTop;
  return static_cast<uint8_t>(code);
}

}  // namespace lr
