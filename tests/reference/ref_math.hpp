// Double-precision vector and matrix helpers for the reference renderer (tests and benchmarks
// only, never firmware). GL conventions: matrices are row-major m[row][col] and act on column
// vectors (v' = M * v); perspective() and look_at() are gluPerspective() and gluLookAt().
#pragma once

#include <array>
#include <cmath>

namespace lr::ref {

using Vec3d = std::array<double, 3>;
using Vec4d = std::array<double, 4>;

// Row-major 4x4 matrix for column vectors. A default-constructed matrix is the identity.
struct Mat4d {
  double m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
};

inline constexpr double kPi = 3.14159265358979323846;

// ---- 3-vectors ----

inline Vec3d add(const Vec3d& a, const Vec3d& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline Vec3d sub(const Vec3d& a, const Vec3d& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline Vec3d muls(const Vec3d& a, double s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
// Component-wise product (colour modulation).
inline Vec3d cmul(const Vec3d& a, const Vec3d& b) {
  return {a[0] * b[0], a[1] * b[1], a[2] * b[2]};
}
inline double dot(const Vec3d& a, const Vec3d& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double length(const Vec3d& a) {
  return std::sqrt(dot(a, a));
}
// Unit vector along a; the zero vector (or a non-finite one) stays as it is.
inline Vec3d normalize(const Vec3d& a) {
  const double len = length(a);
  if (!(len > 0.0) || !std::isfinite(len)) return a;
  return muls(a, 1.0 / len);
}

// ---- 4x4 matrices ----

inline Mat4d identity() {
  return Mat4d{};
}

inline Mat4d zero_matrix() {
  Mat4d r;
  for (auto& row : r.m)
    for (double& v : row) v = 0.0;
  return r;
}

inline Mat4d mul(const Mat4d& a, const Mat4d& b) {
  Mat4d r = zero_matrix();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0.0;
      for (int k = 0; k < 4; ++k) s += a.m[i][k] * b.m[k][j];
      r.m[i][j] = s;
    }
  return r;
}

// M * v for a column vector v.
inline Vec4d transform(const Mat4d& a, const Vec4d& v) {
  Vec4d r{};
  for (int i = 0; i < 4; ++i)
    r[static_cast<size_t>(i)] =
        a.m[i][0] * v[0] + a.m[i][1] * v[1] + a.m[i][2] * v[2] + a.m[i][3] * v[3];
  return r;
}

// M * (p, 1), returned as x, y, z (w dropped: for affine matrices it is 1).
inline Vec3d transform_point(const Mat4d& a, const Vec3d& p) {
  const Vec4d r = transform(a, Vec4d{p[0], p[1], p[2], 1.0});
  return {r[0], r[1], r[2]};
}

// Upper 3x3 of M times d (directions: translation ignored).
inline Vec3d transform_dir(const Mat4d& a, const Vec3d& d) {
  const Vec4d r = transform(a, Vec4d{d[0], d[1], d[2], 0.0});
  return {r[0], r[1], r[2]};
}

inline Mat4d transpose(const Mat4d& a) {
  Mat4d r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[j][i];
  return r;
}

// General inverse by cofactors. Returns false (and leaves out unchanged) when a is singular.
inline bool invert(const Mat4d& a, Mat4d& out) {
  const double* m = &a.m[0][0];
  double inv[16];
  inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] +
           m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
  inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] -
           m[8] * m[7] * m[14] - m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
  inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] +
           m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
  inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] -
            m[8] * m[6] * m[13] - m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
  inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] -
           m[9] * m[3] * m[14] - m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
  inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] +
           m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
  inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] -
           m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
  inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] +
            m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
  inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] +
           m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
  inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] -
           m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
  inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] +
            m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
  inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] -
            m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
  inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] -
           m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
  inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] +
           m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
  inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] -
            m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
  inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] +
            m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
  const double det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
  if (det == 0.0 || !std::isfinite(det)) return false;
  const double s = 1.0 / det;
  for (int i = 0; i < 16; ++i) out.m[i / 4][i % 4] = inv[i] * s;
  return true;
}

// Transforms a normal by the inverse transpose of a's upper 3x3 and normalizes it. Uses the
// cofactor matrix times sign(det), which equals the inverse transpose up to a positive factor and
// stays defined for singular matrices.
inline Vec3d transform_normal(const Mat4d& a, const Vec3d& n) {
  const auto& m = a.m;
  // cof[i][j] = cofactor of element (i, j); (A^-1)^T = cof / det.
  const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
  const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
  const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  const double c10 = m[0][2] * m[2][1] - m[0][1] * m[2][2];
  const double c11 = m[0][0] * m[2][2] - m[0][2] * m[2][0];
  const double c12 = m[0][1] * m[2][0] - m[0][0] * m[2][1];
  const double c20 = m[0][1] * m[1][2] - m[0][2] * m[1][1];
  const double c21 = m[0][2] * m[1][0] - m[0][0] * m[1][2];
  const double c22 = m[0][0] * m[1][1] - m[0][1] * m[1][0];
  const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
  const double sgn = det < 0.0 ? -1.0 : 1.0;
  const Vec3d r{c00 * n[0] + c01 * n[1] + c02 * n[2], c10 * n[0] + c11 * n[1] + c12 * n[2],
                c20 * n[0] + c21 * n[1] + c22 * n[2]};
  return normalize(muls(r, sgn));
}

// gluPerspective: fovy in degrees, aspect = width / height, 0 < z_near < z_far.
inline Mat4d perspective(double fovy_deg, double aspect, double z_near, double z_far) {
  const double f = 1.0 / std::tan(fovy_deg * kPi / 360.0);
  Mat4d r = zero_matrix();
  r.m[0][0] = f / aspect;
  r.m[1][1] = f;
  r.m[2][2] = (z_far + z_near) / (z_near - z_far);
  r.m[2][3] = 2.0 * z_far * z_near / (z_near - z_far);
  r.m[3][2] = -1.0;
  return r;
}

// gluLookAt: rows s = normalize(f x up), u = s x f, -f with f = normalize(target - eye), then a
// translation by -eye.
inline Mat4d look_at(Vec3d eye, Vec3d target, Vec3d up) {
  const Vec3d f = normalize(sub(target, eye));
  const Vec3d s = normalize(cross(f, up));
  const Vec3d u = cross(s, f);
  Mat4d r;
  for (int j = 0; j < 3; ++j) {
    const auto c = static_cast<size_t>(j);
    r.m[0][j] = s[c];
    r.m[1][j] = u[c];
    r.m[2][j] = -f[c];
  }
  r.m[0][3] = -dot(s, eye);
  r.m[1][3] = -dot(u, eye);
  r.m[2][3] = dot(f, eye);
  return r;
}

inline Mat4d translate(Vec3d t) {
  Mat4d r;
  r.m[0][3] = t[0];
  r.m[1][3] = t[1];
  r.m[2][3] = t[2];
  return r;
}

inline Mat4d scale(Vec3d s) {
  Mat4d r;
  r.m[0][0] = s[0];
  r.m[1][1] = s[1];
  r.m[2][2] = s[2];
  return r;
}

// glRotate about the x, y or z axis by deg degrees (counter-clockwise looking down the axis).
inline Mat4d rotate_x(double deg) {
  const double c = std::cos(deg * kPi / 180.0), s = std::sin(deg * kPi / 180.0);
  Mat4d r;
  r.m[1][1] = c;
  r.m[1][2] = -s;
  r.m[2][1] = s;
  r.m[2][2] = c;
  return r;
}

inline Mat4d rotate_y(double deg) {
  const double c = std::cos(deg * kPi / 180.0), s = std::sin(deg * kPi / 180.0);
  Mat4d r;
  r.m[0][0] = c;
  r.m[0][2] = s;
  r.m[2][0] = -s;
  r.m[2][2] = c;
  return r;
}

inline Mat4d rotate_z(double deg) {
  const double c = std::cos(deg * kPi / 180.0), s = std::sin(deg * kPi / 180.0);
  Mat4d r;
  r.m[0][0] = c;
  r.m[0][1] = -s;
  r.m[1][0] = s;
  r.m[1][1] = c;
  return r;
}

}  // namespace lr::ref
