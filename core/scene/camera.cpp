#include "lineraster/core/scene/camera.hpp"

#include "lineraster/core/math/trig.hpp"
#include "lineraster/core/math/wide_divide.hpp"

namespace lr {
namespace {

// round_div(n, d) for n >= 0 (n < 2^63) and d in (0, 2^32), but 2^32 for any quotient from 2^32
// on: the callers saturate it to 32 bits (or its negation), so the value they get is the same.
// One 64-by-32 division, no C library 64-bit division.
uint64_t rounded_quotient(uint64_t n, uint32_t d) {
  const uint64_t m = n + d / 2;
  if ((m >> 32) >= d) return uint64_t{1} << 32;  // m >= d 2^32
  return divide_64by32(m, d).q;
}

// floor(n / d) and n mod d for any n and d in (0, 2^32): two 64-by-32 divisions (no C library
// 64-bit division).
struct Quotient64 {
  uint64_t q;
  uint32_t r;
};
Quotient64 divide_wide(uint64_t n, uint32_t d) {
  const Quotient32 hi = divide_64by32(n >> 32, d);
  const Quotient32 lo = divide_64by32((uint64_t{hi.r} << 32) | (n & 0xFFFFFFFFu), d);
  return {uint64_t{hi.q} << 32 | lo.q, lo.r};
}

// n / d rounded (half up), n < 2^63, d in (0, 2^32).
uint64_t rounded_wide(uint64_t n, uint32_t d) {
  return divide_wide(n + d / 2, d).q;
}

}  // namespace

bool perspective_fine(Fixed fovy_degrees, int width, int height, Fixed near, Fixed far,
                      FineMat4& out) {
  if (fovy_degrees.raw <= 0 || fovy_degrees >= Fixed::from_int(180)) return false;
  if (width < 1 || height < 1 || width > 32768 || height > 32768) return false;
  if (near.raw <= 0 || far <= near) return false;
  // The half angle in (0, 90) degrees: s and c in Q1.30, s > 0 but for the least angles.
  const SinCos30 sc = sin_cos_q30(Fixed::from_raw(fovy_degrees.raw / 2));
  if (sc.sin <= 0) return false;
  // The entries in Q2.30 (int64): f = c / s (c 2^30 < 2^61); f below 2^46 (f < 2^16, Q16.16's
  // range), so f height < 2^61.
  const uint64_t f =
      rounded_wide(static_cast<uint64_t>(sc.cos) << 30, static_cast<uint32_t>(sc.sin));
  if (f >= (uint64_t{1} << 46)) return false;
  const uint64_t fx = rounded_wide(f * static_cast<uint32_t>(height), static_cast<uint32_t>(width));
  // (far + near) / (far - near): (far + near) 2^30 < 2^62. 2 far near / (far - near): 2 far near
  // < 2^63 in Q32.32, its quotient by (far - near) a Q16.16 value, its 14 more bits from the
  // remainder; below 2^46 (Q16.16's range) or refused.
  const uint64_t n = static_cast<uint32_t>(near.raw), fa = static_cast<uint32_t>(far.raw);
  const auto depth = static_cast<uint32_t>(fa - n);
  const uint64_t zz = rounded_wide((fa + n) << 30, depth);
  const Quotient64 zw = divide_wide(2 * fa * n, depth);
  if (zz >= (uint64_t{1} << 46) || zw.q >= (uint64_t{1} << 32)) return false;
  const uint64_t zt = (zw.q << 14) + rounded_wide(uint64_t{zw.r} << 14, depth);
  uint64_t mag = fx | f | zz | zt | (uint64_t{1} << 30);
  const int bits = 64 - clz64(mag);
  const int drop = bits > 31 ? bits - 31 : 0;  // every entry below 2^31 after the rounding
  const int frac = 30 - drop;
  if (frac < FineMat4::kMinFrac) return false;
  auto entry = [&](uint64_t v) { return saturate32(shift_rounded(static_cast<int64_t>(v), drop)); };
  FineMat4 m{};
  m.frac = frac;
  m.m[0][0] = entry(fx);
  m.m[1][1] = entry(f);
  m.m[2][2] = -entry(zz);
  m.m[2][3] = -entry(zt);
  m.m[3][2] = -entry(uint64_t{1} << 30);
  out = m;
  return true;
}

bool perspective(Fixed fovy_degrees, Fixed aspect, Fixed near, Fixed far, Mat4& out) {
  if (fovy_degrees.raw <= 0 || fovy_degrees >= Fixed::from_int(180)) return false;
  if (aspect.raw <= 0 || near.raw <= 0 || far <= near) return false;
  Fixed half{fovy_degrees.raw / 2};
  // f = cot(fovy / 2) = cos / sin, computed in 64 bits for the full Q16.16 precision.
  // half in (0, 90) degrees: s in (0, 1], c in [0, 1] (Q16.16), so f <= 2^32, and exact: the
  // quotient reaches 2^32 only for s = 1 unit, c = 1, where it is 2^32.
  const int32_t s = sin_deg(half).raw, c = cos_deg(half).raw;
  if (s <= 0) return false;
  const auto f = static_cast<int64_t>(
      rounded_quotient(static_cast<uint64_t>(c) * Fixed::kOne, static_cast<uint32_t>(s)));
  Mat4 m{};
  m.m[0][0] = Fixed::from_raw(saturate32(static_cast<int64_t>(rounded_quotient(
      static_cast<uint64_t>(f) * Fixed::kOne, static_cast<uint32_t>(aspect.raw)))));
  m.m[1][1] = Fixed::from_raw(saturate32(f));
  // 0 < near < far < 2^31: the numerators are negative (round_div rounds their magnitudes),
  // (far + near) 2^16 < 2^48 and 2 far near < 2^63.
  const uint64_t n = static_cast<uint32_t>(near.raw), fa = static_cast<uint32_t>(far.raw);
  const auto depth = static_cast<uint32_t>(fa - n);
  m.m[2][2] = Fixed::from_raw(
      saturate32(-static_cast<int64_t>(rounded_quotient((fa + n) * Fixed::kOne, depth))));
  m.m[2][3] =
      Fixed::from_raw(saturate32(-static_cast<int64_t>(rounded_quotient(2 * fa * n, depth))));
  m.m[3][2] = Fixed::from_int(-1);
  out = m;
  return true;
}

bool look_at(Vec3 eye, Vec3 target, Vec3 up, Mat4& out) {
  // The difference of two Q16.16 values needs 33 bits: normalised straight from int64.
  Unit30 fu;
  if (!normalize_unit30(int64_t{target.x.raw} - eye.x.raw, int64_t{target.y.raw} - eye.y.raw,
                        int64_t{target.z.raw} - eye.z.raw, fu))
    return false;
  Vec3 f = to_vec3(fu);
  Vec3 u0 = normalize(up);
  Vec3 side = cross(f, u0);
  // Parallel up: the cross product of two unit vectors is (near) zero.
  if (dot_q30(side, side) < (int64_t{1} << 10)) return false;
  Vec3 s = normalize(side);
  Vec3 u = cross(s, f);
  Mat4 m = Mat4::identity();
  const Vec3 rows[3] = {s, u, Vec3{-f.x, -f.y, -f.z}};
  for (int i = 0; i < 3; ++i) {
    m.m[i][0] = rows[i].x;
    m.m[i][1] = rows[i].y;
    m.m[i][2] = rows[i].z;
    m.m[i][3] = Fixed::from_raw(saturate32(-round_shift(dot_q30(rows[i], eye), 14)));
  }
  out = m;
  return true;
}

}  // namespace lr
