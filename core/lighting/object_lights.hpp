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

struct ObjectLights {
  // Towards each light (Q1.16) and its half vector (Q1.30: the specular power magnifies its
  // error by the shininess), model space, unit within 2^-12 (the rotation's rigidity tolerance).
  int32_t l[kMaxLights][3] = {};
  int32_t h[kMaxLights][3] = {};
  bool specular = false;  // a light whose specular product (Ls Ks) is not zero
};

// pl's directional lights into model space by the rotation rows of a rigid model
// (rigid_normal_rows): l_model = R^T l.
void prepare_object_lights(const PreparedLighting& pl, const NormalRotation& r, ObjectLights& out);

// |n|^2 of a Normal16, Q2.28 (each square below 2^30: no wrap).
constexpr uint32_t normal_len2(const Normal16& n) {
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

// The lit colours of normal n (Normal16, len2 = normal_len2(n) and unit_len2(len2)), negated when
// back: light_directional_split's model for the model-space directions. n's length is corrected
// by one Newton step of 1 / |n|, k = (3 - |n|^2) / 2 (Q1.30, within 2^-24 of 1 / |n|), applied to
// the dot products rather than the normal: N.L = (n . l) k, where n . l is a sum of three
// products below 2^30 (|n| |l| <= 1 + 2^-11 in Q2.30).
inline LitColor light_object(const PreparedLighting& pl, const ObjectLights& ol, const Normal16& n,
                             uint32_t len2, bool back) {
  uint32_t prim[3] = {static_cast<uint32_t>(pl.base[0]), static_cast<uint32_t>(pl.base[1]),
                      static_cast<uint32_t>(pl.base[2])};
  uint32_t spec[3] = {0, 0, 0};
  const int32_t nx = back ? -n.x : n.x, ny = back ? -n.y : n.y, nz = back ? -n.z : n.z;
  const auto k = static_cast<int32_t>(((3u << 28) - len2) << 1);  // 2^30 +- 2^17
  for (int i = 0; i < pl.count; ++i) {
    const PreparedLighting::Light& li = pl.lights[static_cast<size_t>(i)];
    const int32_t* l = ol.l[i];
    int32_t ndl = nx * l[0] + ny * l[1] + nz * l[2];  // Q2.30
    if (ndl <= 0) continue;  // no diffuse, and GL gives no specular where N.L <= 0
    ndl = mul_hi(ndl, k) * 4;  // Q2.30 again, below 2^30 + 2^20
    const auto d16 = static_cast<uint32_t>(ndl) >> 14;  // Q1.16, <= 2^16 + 64
    // Kd <= 2^15: the product is below 2^31 + 2^22.
    for (int c = 0; c < 3; ++c) prim[c] += (d16 * li.kd[c] + (1u << 15)) >> 16;
    if (!ol.specular) continue;
    // n . h in 64 bits (products below 2^45), Q2.44, then Q2.30.
    const int32_t* h = ol.h[i];
    const int64_t ndh44 = mul_wide(nx, h[0]) + mul_wide(ny, h[1]) + mul_wide(nz, h[2]);
    if (ndh44 <= 0) continue;
    int32_t ndh = mul_hi(static_cast<int32_t>(ndh44 >> 14), k) * 4;  // below 2^30 + 2^20
    if (ndh > (1 << 30)) ndh = 1 << 30;
    const uint32_t sp = DefaultPowTable::pow_q15(static_cast<uint32_t>(ndh), pl.shininess_q8);
    for (int c = 0; c < 3; ++c) spec[c] += (sp * uint32_t{li.ks[c]} + (1u << 14)) >> 15;
  }
  auto clamp = [](uint32_t x) {
    return static_cast<uint16_t>(x > Color15::kOne ? Color15::kOne : x);
  };
  return {{clamp(prim[0]), clamp(prim[1]), clamp(prim[2])},
          {clamp(spec[0]), clamp(spec[1]), clamp(spec[2])}};
}

}  // namespace lr
