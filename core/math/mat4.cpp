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

namespace {
FineMat4 rotation_fine(int a, int b, Fixed degrees) {
  const SinCos30 sc = sin_cos_q30(degrees);
  FineMat4 r{};
  r.frac = 30;
  for (int i = 0; i < 4; ++i) r.m[i][i] = int32_t{1} << 30;
  r.m[a][a] = sc.cos;
  r.m[a][b] = -sc.sin;
  r.m[b][a] = sc.sin;
  r.m[b][b] = sc.cos;
  return r;
}

// The bit length of the largest magnitude of a's entries.
int entry_bits(const FineMat4& a) {
  uint32_t m = 0;
  for (const auto& row : a.m)
    for (const int32_t v : row)
      m |= v < 0 ? 0u - static_cast<uint32_t>(v) : static_cast<uint32_t>(v);
  return m == 0 ? 0 : 32 - clz32(m);
}
}  // namespace

FineMat4 rotate_x_fine(Fixed degrees) {
  return rotation_fine(1, 2, degrees);
}
FineMat4 rotate_y_fine(Fixed degrees) {
  return rotation_fine(2, 0, degrees);
}
FineMat4 rotate_z_fine(Fixed degrees) {
  return rotation_fine(0, 1, degrees);
}

Mat4 to_mat4(const FineMat4& a) {
  Mat4 r{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      r.m[i][j] = Fixed::from_raw(saturate32(shift_rounded(a.m[i][j], a.frac - 16)));
  return r;
}

FineMat4 operator*(const FineMat4& a, const FineMat4& b) {
  int sh = entry_bits(a) + entry_bits(b) - 60;
  if (sh < 0) sh = 0;
  int64_t s[4][4];
  uint64_t mag = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      int64_t v = 0;
      for (int k = 0; k < 4; ++k) v += (int64_t{a.m[i][k]} * b.m[k][j]) >> sh;
      s[i][j] = v;
      if (abs64(v) > mag) mag = abs64(v);
    }
  // The sums have fs = a.frac + b.frac - sh >= 30 fraction bits; the result keeps frac <= fs
  // with every rounded entry below 2^31: mag < 2^bits, so mag 2^-(fs - frac) < 2^31 at frac =
  // fs - (bits - 31), and one bit less where the largest rounds up to 2^31.
  const int fs = a.frac + b.frac - sh;
  const int bits = mag == 0 ? 0 : 64 - clz64(mag);
  int frac = fs - (bits > 31 ? bits - 31 : 0);
  if (frac > FineMat4::kMaxFrac) frac = FineMat4::kMaxFrac;
  if (shift_rounded(static_cast<int64_t>(mag), fs - frac) > INT32_MAX) --frac;
  if (frac < FineMat4::kMinFrac) frac = FineMat4::kMinFrac;  // saturates below
  FineMat4 r{};
  r.frac = frac;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = saturate32(shift_rounded(s[i][j], fs - frac));
  return r;
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
