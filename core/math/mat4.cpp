#include "lineraster/core/math/mat4.hpp"

#include "lineraster/core/math/trig.hpp"

namespace lr {

Mat4 translate(Vec3 t) {
  Mat4 r = Mat4::identity();
  r.m[0][3] = t.x;
  r.m[1][3] = t.y;
  r.m[2][3] = t.z;
  return r;
}

Mat4 scale(Vec3 s) {
  Mat4 r = Mat4::identity();
  r.m[0][0] = s.x;
  r.m[1][1] = s.y;
  r.m[2][2] = s.z;
  return r;
}

Mat4 scale(Fixed s) {
  return scale(Vec3{s, s, s});
}

namespace {
// Rotation in the plane of axes (a, b): the standard GL matrices.
Mat4 rotation(int a, int b, Fixed degrees) {
  Fixed c = cos_deg(degrees), s = sin_deg(degrees);
  Mat4 r = Mat4::identity();
  r.m[a][a] = c;
  r.m[a][b] = -s;
  r.m[b][a] = s;
  r.m[b][b] = c;
  return r;
}
}  // namespace

Mat4 rotate_x(Fixed degrees) {
  return rotation(1, 2, degrees);
}
Mat4 rotate_y(Fixed degrees) {
  return rotation(2, 0, degrees);
}
Mat4 rotate_z(Fixed degrees) {
  return rotation(0, 1, degrees);
}

Mat4 normal_matrix(const Mat4& model) {
  // Cofactors in Q32.32 (int64): each a difference of two products of Q16.16 entries.
  int64_t c[3][3];
  auto e = [&](int r, int k) { return int64_t{model.m[r][k].raw}; };
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      int r0 = (i + 1) % 3, r1 = (i + 2) % 3, k0 = (j + 1) % 3, k1 = (j + 2) % 3;
      c[i][j] = e(r0, k0) * e(r1, k1) - e(r0, k1) * e(r1, k0);
    }
  }
  // The cofactor matrix itself is the inverse transpose times det; rescale to Q16.16.
  uint64_t mag = 0;
  for (auto& row : c)
    for (int64_t v : row) mag |= abs64(v);
  Mat4 r{};
  if (mag == 0) return r;
  int top = 63 - clz64(mag);
  int shift = top - 16;  // largest entry lands in [2^16, 2^17): about 1.0 to 2.0 in Q16.16
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r.m[i][j] = Fixed::from_raw(static_cast<int32_t>(
          shift >= 0 ? (c[i][j] >> shift) : (c[i][j] * (int64_t{1} << -shift))));
  return r;
}

}  // namespace lr
