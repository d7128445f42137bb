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

}  // namespace

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
