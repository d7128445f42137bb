// 4x4 transforms in fixed point, OpenGL conventions: column vectors (v' = M v), m[row][col].
//
// Entries are Fixed (Q16.16, |entry| < 32768). Products of two matrices accumulate in 64 bits
// with each Q32.32 product pre-shifted by 2 (each term < 2^60, the sum of four < 2^62), so no
// intermediate overflows; the result is rounded and saturated to Q16.16.
#pragma once

#include <cstdint>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/vec.hpp"

namespace lr {

struct Mat4 {
  Fixed m[4][4];

  static constexpr Mat4 identity() {
    Mat4 r{};
    for (int i = 0; i < 4; ++i) r.m[i][i] = Fixed::from_int(1);
    return r;
  }
  friend constexpr bool operator==(const Mat4&, const Mat4&) = default;
};

// Clip-space coordinates: Q28.28 in int64 (2^28 = 1.0). A Q16.16 matrix times a Q16.16 point
// gives four Q32.32 products of magnitude < 2^62; each is shifted right by 4 before the sum,
// so every term is < 2^58 and the sum < 2^60: no overflow for any representable input, and
// 2^-28 resolution keeps the projected positions far finer than a subpixel.
struct ClipCoord {
  static constexpr int kFracBits = 28;
  int64_t x, y, z, w;
};

constexpr Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      int64_t s = 0;
      for (int k = 0; k < 4; ++k) s += (int64_t{a.m[i][k].raw} * b.m[k][j].raw) >> 2;
      r.m[i][j] = Fixed::from_raw(saturate32(round_shift(s, 14)));
    }
  }
  return r;
}

// M * (p, 1) in clip coordinates.
constexpr ClipCoord transform_point(const Mat4& m, Vec3 p) {
  auto row = [&](int i) {
    return ((int64_t{m.m[i][0].raw} * p.x.raw) >> 4) + ((int64_t{m.m[i][1].raw} * p.y.raw) >> 4) +
           ((int64_t{m.m[i][2].raw} * p.z.raw) >> 4) + (int64_t{m.m[i][3].raw} << 12);
  };
  return {row(0), row(1), row(2), row(3)};
}

// M * (p, 1) dropping w, back in Q16.16 (saturated): world positions for lighting.
constexpr Vec3 transform_affine(const Mat4& m, Vec3 p) {
  ClipCoord c = transform_point(m, p);
  return {Fixed::from_raw(saturate32(round_shift(c.x, 12))),
          Fixed::from_raw(saturate32(round_shift(c.y, 12))),
          Fixed::from_raw(saturate32(round_shift(c.z, 12)))};
}

Mat4 translate(Vec3 t);
Mat4 scale(Vec3 s);
Mat4 scale(Fixed s);
Mat4 rotate_x(Fixed degrees);
Mat4 rotate_y(Fixed degrees);
Mat4 rotate_z(Fixed degrees);

// The transpose of the cofactor matrix of m's upper 3x3 — proportional to its inverse
// transpose, which is what normals need — scaled so that its largest entry is a Q16.16 value
// near 1 (normals are renormalised afterwards, so only the direction matters). Rows 3 and
// column 3 are zero.
Mat4 normal_matrix(const Mat4& model);

}  // namespace lr
