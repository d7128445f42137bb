// Normals under a rigid model matrix (a rotation times a uniform scale): detected once per draw,
// then each normal is rotated by a unit-row matrix and renormalised by one Newton step instead
// of a square root and three divisions (docs/numerics.md#normals-under-a-rigid-model-matrix).
#pragma once

#include <cstdint>

#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/math/vec.hpp"

namespace lr {

// The rows of a normal matrix, each a Q1.30 unit vector (int32: every entry is within
// [-2^30, 2^30]). Valid only when rigid_normal_rows() returned true.
struct NormalRotation {
  int32_t r[3][3] = {{1 << 30, 0, 0}, {0, 1 << 30, 0}, {0, 0, 1 << 30}};
};

// Relative tolerance of the rigidity test: rows of equal length and pairwise orthogonal within
// 2^-kRigidToleranceBits of their squared length.
inline constexpr int kRigidToleranceBits = 12;

// True when the upper 3x3 of nm (a normal matrix, core/math/mat4.hpp) has rows of equal length
// that are pairwise orthogonal, within the tolerance above; then out holds its rows normalised.
bool rigid_normal_rows(const Mat4& nm, NormalRotation& out);

// rot times the Q1.14 normal n, renormalised by one Newton step of 1/sqrt, into out (Q1.30):
// its length is within 2^-19 of 1. False (out unchanged) when |rot n| is not within about
// 2^-10 of 1 (a normal that is not unit: the caller normalises it exactly instead).
// Products: |entry| <= 2^30 times |n_i| <= 2^14 is <= 2^44, a row's sum below 2^46 (int64);
// >> 14 gives Q1.30 (|v_i| < 2^31 since |n| < 2); each square is below 2^62 and the sum, the
// squared length of a vector shorter than 2, below 2^62. Accepted, |v| < 1 + 2^-10: the Newton
// factor k is below 2^31 and each product v_i k below 2^62.
inline bool rotate_unit_normal(const NormalRotation& rot, const Normal16& n, Unit30& out) {
  int32_t v[3];
  for (int i = 0; i < 3; ++i)
    v[i] = static_cast<int32_t>(
        (int64_t{rot.r[i][0]} * n.x + int64_t{rot.r[i][1]} * n.y + int64_t{rot.r[i][2]} * n.z) >>
        14);
  const int64_t len2 = int64_t{v[0]} * v[0] + int64_t{v[1]} * v[1] + int64_t{v[2]} * v[2];
  constexpr int64_t kOne = int64_t{1} << 60, kBand = int64_t{1} << 51;  // 1 +- 2^-9 in Q2.60
  if (len2 < kOne - kBand || len2 > kOne + kBand) return false;
  // 1/|v| ~ (3 - |v|^2) / 2, Q1.30: (3 * 2^60 - len2) >> 31, near 2^30.
  const int64_t k = ((int64_t{3} << 60) - len2) >> 31;
  out = {static_cast<int32_t>((int64_t{v[0]} * k) >> 30),
         static_cast<int32_t>((int64_t{v[1]} * k) >> 30),
         static_cast<int32_t>((int64_t{v[2]} * k) >> 30)};
  return true;
}

}  // namespace lr
