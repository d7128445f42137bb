// Directional lights in a draw's model space: under a rigid model matrix (a rotation times a
// uniform scale, R the rotation) a world normal is R n, so N.L = n . (R^T L). Turning L and H
// into model space once per draw leaves a dot product of the mesh's normal per light and vertex:
// no rotation and no renormalisation (docs/numerics.md#lights-in-model-space). Only for
// directional lights and the infinite viewer (PreparedLighting::needs_position() false), and only
// for normals of unit length within kUnitNormalTolerance (the others take the world-space path).
#pragma once

#include <cstdint>

#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/math/rigid.hpp"
#include "lineraster/core/math/vec.hpp"
#include "lineraster/core/math/wide_mul.hpp"

namespace lr {

// The directions only: the colours (base, Ld Kd, Ls Ks) are read from the PreparedLighting they
// were made from (no copy in the renderer object, whose every byte counts in 16 KB of RAM).
struct ObjectLights {
  // Towards each light (Q1.16) and its half vector (Q1.30: the specular power magnifies its
  // error by the shininess), model space, unit within 2^-12 (the rotation's rigidity tolerance).
  int32_t l[kMaxLights][3] = {};
  int32_t h[kMaxLights][3] = {};
  uint8_t count = 0;
  bool specular = false;  // a light whose specular product (Ls Ks) is not zero
};

// pl's directional lights into model space by the rotation rows of a rigid model
// (rigid_normal_rows): l_model = R^T l.
void prepare_object_lights(const PreparedLighting& pl, const NormalRotation& r, ObjectLights& out);
// The same without the half vectors (h stays zero), for lighting prepared by
// prepare_diffuse_lighting (no specular product: light_object never reads them).
void prepare_diffuse_object_lights(const PreparedLighting& pl, const NormalRotation& r,
                                   ObjectLights& out);
using PrepareObjectLightsFn = void (*)(const PreparedLighting&, const NormalRotation&,
                                       ObjectLights&);

// |n|^2 of a Normal16, Q2.28 (each square below 2^30: no wrap).
[[gnu::always_inline]] constexpr uint32_t normal_len2(const Normal16& n) {
  return static_cast<uint32_t>(n.x * n.x) + static_cast<uint32_t>(n.y * n.y) +
         static_cast<uint32_t>(n.z * n.z);
}
// A Normal16 of unit length: |n|^2 within 2^-12 of 1 (a unit vector rounded to Q1.14 is within
// 2^-13.2).
constexpr bool unit_len2(uint32_t len2) {
  return len2 - ((1u << 28) - (1u << 16)) <= (1u << 17);
}
constexpr bool unit_normal(const Normal16& n) {
  return unit_len2(normal_len2(n));
}

// 1 / |n| by one Newton step from 1, k = (3 - |n|^2) / 2 in Q1.30 (within 2^-24 of 1 / |n| for
// unit_len2(len2)): 2^30 +- 2^17.
constexpr int32_t inverse_length(uint32_t len2) {
  return static_cast<int32_t>(((3u << 28) - len2) << 1);
}

// One light's diffuse term for normal (nx, ny, nz) (Q1.14, negated for a back face) with
// 1 / |n| = k: max(N.L, 0) Ld Kd added to prim (Q1.15 sums). N.L = (n . l) k, where n . l is a sum
// of three products below 2^30 (|n| |l| <= 1 + 2^-11 in Q2.30); N.L / 2^14 (Q1.16, at most 2^16
// + 64) times Kd (<= 2^15) is below 2^31 + 2^22. Returns N.L (Q2.30; 0 where not positive), for
// the specular term. The one home of the formula: object_diffuse() and OneDiffuseLight use it.
[[gnu::always_inline]] inline int32_t add_diffuse(const int32_t (&l)[3], const uint16_t (&kd)[3],
                                                  int32_t nx, int32_t ny, int32_t nz, int32_t k,
                                                  uint32_t (&prim)[3]) {
  int32_t d = nx * l[0] + ny * l[1] + nz * l[2];  // Q2.30
  if (d <= 0) return 0;  // no diffuse, and GL gives no specular where N.L <= 0
  d = mul_hi(d, k) * 4;  // Q2.30 again, below 2^30 + 2^20
  const auto d16 = static_cast<uint32_t>(d) >> 14;
  for (int c = 0; c < 3; ++c) prim[c] += (d16 * kd[c] + (1u << 15)) >> 16;
  return d;
}

// The diffuse sums of normal (nx, ny, nz) with 1 / |n| = k: prim[c] = pl.base[c] + sum over
// lights of add_diffuse(). The lights' N.L in ndl (Q2.30; 0 where not positive).
[[gnu::always_inline]] inline void object_diffuse(const PreparedLighting& pl,
                                                  const ObjectLights& ol, int32_t nx, int32_t ny,
                                                  int32_t nz, int32_t k, uint32_t (&prim)[3],
                                                  int32_t (&ndl)[kMaxLights]) {
  prim[0] = static_cast<uint32_t>(pl.base[0]);
  prim[1] = static_cast<uint32_t>(pl.base[1]);
  prim[2] = static_cast<uint32_t>(pl.base[2]);
  for (int i = 0; i < ol.count; ++i)
    ndl[i] = add_diffuse(ol.l[i], pl.lights[static_cast<size_t>(i)].kd, nx, ny, nz, k, prim);
}

constexpr uint16_t clamp_one(uint32_t x) {
  return static_cast<uint16_t>(x > Color15::kOne ? Color15::kOne : x);
}

// The lit colours of normal n (Normal16, len2 = normal_len2(n) and unit_len2(len2)), negated when
// back: light_directional_split's model for the model-space directions, n's length corrected by
// inverse_length() on the dot products rather than on the normal. kSpecular false: without the
// specular term (RendererFeatures::specular), the same colours where ol.specular is false.
template <bool kSpecular = true>
inline LitColor light_object(const PreparedLighting& pl, const ObjectLights& ol, const Normal16& n,
                             uint32_t len2, bool back) {
  const int32_t nx = back ? -n.x : n.x, ny = back ? -n.y : n.y, nz = back ? -n.z : n.z;
  const int32_t k = inverse_length(len2);
  uint32_t prim[3];
  int32_t ndl[kMaxLights];
  object_diffuse(pl, ol, nx, ny, nz, k, prim, ndl);
  uint32_t spec[3] = {0, 0, 0};
  if (kSpecular && ol.specular) {
    for (int i = 0; i < ol.count; ++i) {
      if (ndl[i] <= 0) continue;
      // n . h in 64 bits (products below 2^45), Q2.44, then Q2.30.
      const int32_t* h = ol.h[i];
      const int64_t ndh44 = mul_wide(nx, h[0]) + mul_wide(ny, h[1]) + mul_wide(nz, h[2]);
      if (ndh44 <= 0) continue;
      int32_t ndh = mul_hi(static_cast<int32_t>(ndh44 >> 14), k) * 4;  // below 2^30 + 2^20
      if (ndh > (1 << 30)) ndh = 1 << 30;
      const uint32_t sp = DefaultPowTable::pow_q15(static_cast<uint32_t>(ndh), pl.shininess_q8);
      const PreparedLighting::Light& li = pl.lights[static_cast<size_t>(i)];
      for (int c = 0; c < 3; ++c) spec[c] += (sp * uint32_t{li.ks[c]} + (1u << 14)) >> 15;
    }
  }
  return {{clamp_one(prim[0]), clamp_one(prim[1]), clamp_one(prim[2])},
          {clamp_one(spec[0]), clamp_one(spec[1]), clamp_one(spec[2])}};
}

// The diffuse-only colour (no light with a specular product: !ol.specular) of a unit normal n
// (unit_len2(len2)), front side: light_object's primary colour (its secondary is 0).
[[gnu::always_inline]] inline Color15 light_object_diffuse(const PreparedLighting& pl,
                                                           const ObjectLights& ol,
                                                           const Normal16& n, uint32_t len2) {
  uint32_t prim[3];
  int32_t ndl[kMaxLights];
  object_diffuse(pl, ol, n.x, n.y, n.z, inverse_length(len2), prim, ndl);
  return {clamp_one(prim[0]), clamp_one(prim[1]), clamp_one(prim[2])};
}

// The common draw's one diffuse directional light (ol.count == 1, !ol.specular), copied out of
// its PreparedLighting and ObjectLights so that a loop over many vertices holds it in registers
// (light_object_diffuse() reloads the light and walks the light count per vertex): the same
// integers as light_object_diffuse().
struct OneDiffuseLight {
  int32_t l[3];
  uint16_t kd[3];
  int32_t base[3];
  [[gnu::always_inline]] OneDiffuseLight(const PreparedLighting& pl, const ObjectLights& ol)
      : l{ol.l[0][0], ol.l[0][1], ol.l[0][2]},
        kd{pl.lights[0].kd[0], pl.lights[0].kd[1], pl.lights[0].kd[2]},
        base{pl.base[0], pl.base[1], pl.base[2]} {}

  // No channel's sum can pass 1, so the clamps change nothing and a loop may leave them out
  // (operator()<false>). add_diffuse adds at most kd + (kd >> 10) + 1 to the base: its N.L times
  // 1 / |n| is below 2^30 + 2^20, so d16 < 2^16 + 2^6 and (d16 kd + 2^15) >> 16 stays below
  // kd + kd / 2^10 + 1/2. The usual material (ambient plus diffuse below 1) never clamps.
  // (A function, not a member: light_corners() makes one of these per vertex.)
  bool never_clamps() const { return sum_within(0) && sum_within(1) && sum_within(2); }

  // A unit normal's colour (unit_len2(len2)), front side. kClamp false: only where
  // never_clamps().
  template <bool kClamp = true>
  [[gnu::always_inline]] Color15 operator()(const Normal16& n, uint32_t len2) const {
    uint32_t prim[3] = {static_cast<uint32_t>(base[0]), static_cast<uint32_t>(base[1]),
                        static_cast<uint32_t>(base[2])};
    add_diffuse(l, kd, n.x, n.y, n.z, inverse_length(len2), prim);
    if constexpr (!kClamp)
      return {static_cast<uint16_t>(prim[0]), static_cast<uint16_t>(prim[1]),
              static_cast<uint16_t>(prim[2])};
    else
      return {clamp_one(prim[0]), clamp_one(prim[1]), clamp_one(prim[2])};
  }

 private:
  [[gnu::always_inline]] bool sum_within(int c) const {
    return base[c] >= 0 && base[c] <= int32_t{Color15::kOne} &&
           base[c] + kd[c] + (kd[c] >> 10) + 1 <= int32_t{Color15::kOne};
  }
};

}  // namespace lr
