#include "lineraster/core/math/rigid.hpp"

namespace lr {

bool rigid_normal_rows(const Mat4& nm, NormalRotation& out) {
  // Entries are Q16.16 below 2^17 in magnitude (normal_matrix's scaling; anything larger is
  // refused): products below 2^34, a dot product of two rows below 2^36.
  int64_t g[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      if (nm.m[i][k].raw >= (1 << 17) || nm.m[i][k].raw <= -(1 << 17)) return false;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      g[i][j] = int64_t{nm.m[i][0].raw} * nm.m[j][0].raw +
                int64_t{nm.m[i][1].raw} * nm.m[j][1].raw + int64_t{nm.m[i][2].raw} * nm.m[j][2].raw;
  const int64_t len2 = g[0][0];
  if (len2 <= 0) return false;
  const int64_t tol = len2 >> kRigidToleranceBits;
  auto within = [tol](int64_t v) { return v <= tol && v >= -tol; };
  if (!within(g[1][1] - len2) || !within(g[2][2] - len2) || !within(g[0][1]) || !within(g[0][2]) ||
      !within(g[1][2]))
    return false;
  for (int i = 0; i < 3; ++i) {
    Unit30 u;
    if (!normalize_unit30(nm.m[i][0].raw, nm.m[i][1].raw, nm.m[i][2].raw, u)) return false;
    out.r[i][0] = u.x;
    out.r[i][1] = u.y;
    out.r[i][2] = u.z;
  }
  return true;
}

}  // namespace lr
