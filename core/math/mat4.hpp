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

// A transform with more fraction bits than Mat4, for draws that ask for a projection finer than
// Q16.16 (opt-in: Camera::fine_projection, Renderer::draw with a FineMat4 model,
// Mesh::position_frac; docs/numerics.md#fine-transforms): entry = raw / 2^frac, frac in [16, 30],
// so |entry| < 2^(31 - frac) (at 30 below 2, at 28 below 8, at 16 Mat4's range). frac 0: no matrix
// given.
struct FineMat4 {
  static constexpr int kMinFrac = 16, kMaxFrac = 30;
  int32_t m[4][4];
  int32_t frac;
  constexpr bool valid() const { return frac >= kMinFrac && frac <= kMaxFrac; }
  friend constexpr bool operator==(const FineMat4&, const FineMat4&) = default;
};

// A Mat4 as a FineMat4 (frac 16: the same entries).
constexpr FineMat4 to_fine(const Mat4& a) {
  FineMat4 r;  // every member assigned below (no zeroing first: a memset per Q16.16 draw)
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[i][j].raw;
  r.frac = 16;
  return r;
}

// v 2^-s rounded to nearest (ties towards +infinity) for s > 0, v 2^-s exactly for s <= 0
// (|v| 2^-s < 2^63 by the caller's bound).
constexpr int64_t shift_rounded(int64_t v, int s) {
  return s > 0 ? (v + (int64_t{1} << (s - 1))) >> s : v * (int64_t{1} << -s);
}

// A FineMat4 rounded to Q16.16 (saturated): for the lighting, which reads Mat4.
Mat4 to_mat4(const FineMat4& a);

// a * b with as many fraction bits as the largest entry of the product leaves (at most 30, at
// least 16: entries beyond 2^15 saturate, as Mat4's product does). Each product of entries is
// below 2^(la + lb) (la, lb: the bit lengths of the largest magnitudes, <= 32), shifted right
// by max(0, la + lb - 60) so that the sum of four stays below 2^62; then rounded once to the
// result's fraction count. Both must be valid().
FineMat4 operator*(const FineMat4& a, const FineMat4& b);

// M * (p, 1) in clip coordinates (Q28.28) for a point of p_frac fraction bits (in [16, 30]):
// each product of an entry and a coordinate is below 2^62 and has frac + p_frac >= 32 fraction
// bits, shifted right by frac + p_frac - 28 >= 4 (below 2^58, the sum of three and the
// translation below 2^60). At frac = p_frac = 16 the integers of transform_point(Mat4, p).
constexpr ClipCoord transform_point(const FineMat4& m, Vec3 p, int p_frac) {
  const int s = m.frac + p_frac - 28;
  auto row = [&](int i) {
    return ((int64_t{m.m[i][0]} * p.x.raw) >> s) + ((int64_t{m.m[i][1]} * p.y.raw) >> s) +
           ((int64_t{m.m[i][2]} * p.z.raw) >> s) + shift_rounded(m.m[i][3], m.frac - 28);
  };
  return {row(0), row(1), row(2), row(3)};
}

// A translation by (x, y, z) 2^-frac (raw values of frac fraction bits, frac in [16, 30]).
constexpr FineMat4 translate_fine(int32_t x, int32_t y, int32_t z, int frac) {
  FineMat4 r{};
  r.frac = frac;
  for (int i = 0; i < 4; ++i) r.m[i][i] = int32_t{1} << frac;
  r.m[0][3] = x;
  r.m[1][3] = y;
  r.m[2][3] = z;
  return r;
}

// Rotations as FineMat4 of frac 30 (sine and cosine in Q1.30: sin_cos_q30, trig.hpp).
FineMat4 rotate_x_fine(Fixed degrees);
FineMat4 rotate_y_fine(Fixed degrees);
FineMat4 rotate_z_fine(Fixed degrees);

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
