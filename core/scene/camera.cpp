#include "lineraster/core/scene/camera.hpp"

#include "lineraster/core/math/trig.hpp"

namespace lr {

bool perspective(Fixed fovy_degrees, Fixed aspect, Fixed near, Fixed far, Mat4& out) {
  if (fovy_degrees.raw <= 0 || fovy_degrees >= Fixed::from_int(180)) return false;
  if (aspect.raw <= 0 || near.raw <= 0 || far <= near) return false;
  Fixed half{fovy_degrees.raw / 2};
  // f = cot(fovy / 2) = cos / sin, computed in 64 bits for the full Q16.16 precision.
  int64_t s = sin_deg(half).raw, c = cos_deg(half).raw;
  if (s <= 0) return false;
  int64_t f = round_div(c * Fixed::kOne, s);
  Mat4 m{};
  m.m[0][0] = Fixed::from_raw(saturate32(round_div(f * Fixed::kOne, aspect.raw)));
  m.m[1][1] = Fixed::from_raw(saturate32(f));
  int64_t n = near.raw, fa = far.raw, d = n - fa;  // d < 0
  m.m[2][2] = Fixed::from_raw(saturate32(round_div(-(fa + n) * Fixed::kOne, -d)));
  m.m[2][3] = Fixed::from_raw(saturate32(round_div(-2 * fa * n, -d)));
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
