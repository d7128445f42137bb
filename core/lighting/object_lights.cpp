#include "lineraster/core/lighting/object_lights.hpp"

namespace lr {
namespace {

// R^T u, Q1.30 rows and vector (products below 2^60, sums below 2^62), rounded to Q1.(60 - sh).
[[gnu::always_inline]] inline void to_model(const NormalRotation& r, const Unit30& u, int sh,
                                            int32_t (&out)[3]) {
  for (int j = 0; j < 3; ++j) {
    const int64_t s =
        int64_t{r.r[0][j]} * u.x + int64_t{r.r[1][j]} * u.y + int64_t{r.r[2][j]} * u.z;
    out[j] = static_cast<int32_t>((s + (int64_t{1} << (sh - 1))) >> sh);
  }
}

int64_t dot30(const int32_t (&a)[3], const int32_t (&b)[3]) {
  return (int64_t{a[0]} * b[0] + int64_t{a[1]} * b[1] + int64_t{a[2]} * b[2]) >> 30;
}

// Row v minus its projection on the unit row u (Q1.30), in place; not normalised.
[[gnu::always_inline]] inline void remove_along(int64_t (&v)[3], const int32_t (&u)[3]) {
  int32_t v32[3] = {static_cast<int32_t>(v[0]), static_cast<int32_t>(v[1]),
                    static_cast<int32_t>(v[2])};
  const int64_t d = dot30(v32, u);
  for (int i = 0; i < 3; ++i) v[i] -= (d * u[i]) >> 30;
}

// The rows made orthonormal (Gram-Schmidt, Q1.30): a rotation whose rows are orthogonal only to
// the Q16.16 rounding of the model matrix (about 2^-16) changes a normal's length by as much,
// which the specular power would multiply; the world-space path renormalises instead.
[[gnu::always_inline]] inline NormalRotation orthonormal(const NormalRotation& r) {
  NormalRotation o = r;  // row 0 is unit already
  for (int k = 1; k < 3; ++k) {
    int64_t v[3] = {r.r[k][0], r.r[k][1], r.r[k][2]};
    for (int j = 0; j < k; ++j) remove_along(v, o.r[j]);
    Unit30 u{o.r[k][0], o.r[k][1], o.r[k][2]};
    normalize_unit30(v[0], v[1], v[2], u);  // unchanged if v vanished (not for a rigid matrix)
    o.r[k][0] = u.x;
    o.r[k][1] = u.y;
    o.r[k][2] = u.z;
  }
  return o;
}

// prepare_object_lights (kHalfVectors) or prepare_diffuse_object_lights.
template <bool kHalfVectors>
[[gnu::always_inline]] inline void prepare(const PreparedLighting& pl, const NormalRotation& rows,
                                           ObjectLights& out) {
  out = ObjectLights{};
  const NormalRotation r = orthonormal(rows);
  out.count = pl.count;
  for (int i = 0; i < pl.count; ++i) {
    const PreparedLighting::Light& li = pl.lights[static_cast<size_t>(i)];
    to_model(r, li.l, 44, out.l[i]);                    // Q1.16
    if (kHalfVectors) to_model(r, li.h, 30, out.h[i]);  // Q1.30
    if ((li.ks[0] | li.ks[1] | li.ks[2]) != 0) out.specular = true;
  }
}

}  // namespace

void prepare_object_lights(const PreparedLighting& pl, const NormalRotation& rows,
                           ObjectLights& out) {
  prepare<true>(pl, rows, out);
}

void prepare_diffuse_object_lights(const PreparedLighting& pl, const NormalRotation& rows,
                                   ObjectLights& out) {
  prepare<false>(pl, rows, out);
}

}  // namespace lr
