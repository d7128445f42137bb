// Per-vertex (and per-face) lighting: OpenGL's fixed-function model in fixed point
// (docs/conventions.md#lighting).
//
// colour = emission + global_ambient * Ka
//        + sum over lights of  La * Ka + max(N.L, 0) * Ld * Kd
//                              + (N.L > 0 ? max(N.H, 0)^shininess : 0) * Ls * Ks
// each channel clamped to [0, 1]. H = normalize(L + V): V is the direction to the viewer,
// constant (infinite viewer, the default) or per vertex (local viewer).
// Directions are Q1.30 unit vectors; products of two are Q2.60 in int64 (< 2^61) and are
// brought back to Q1.30 before any sum; colour terms are Q1.15 and sum in int32.
#pragma once

#include <array>
#include <cstdint>

#include "lineraster/core/math/pow_table.hpp"
#include "lineraster/core/math/vec.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/scene/material.hpp"

namespace lr {

inline constexpr int kMaxLights = 4;

// A light (GL's fixed-function light). Directional: `position` is the direction from the
// surface towards the light (world space, any non-zero length). Point: `position` is the
// light's world position, and its three terms are scaled by GL's attenuation
// 1 / (constant + linear d + quadratic d^2), d the distance to the lit point in world units.
// Coefficients are Q16.16 (>= 0, their sum at d > 0 must be > 0); the attenuation is kept in
// Q4.15 and saturates at 16 (GL does not clamp it; a value above 16 only matters where the lit
// colour saturates anyway unless the light's colours are below 1/16).
enum class LightKind : uint8_t { kDirectional, kPoint };
struct Light {
  LightKind kind = LightKind::kDirectional;
  Vec3 position{Fixed::from_int(1), Fixed::from_int(1), Fixed::from_int(1)};
  Color15 ambient{0, 0, 0};
  Color15 diffuse{Color15::kOne, Color15::kOne, Color15::kOne};
  Color15 specular{Color15::kOne, Color15::kOne, Color15::kOne};
  Fixed constant = Fixed::from_int(1), linear{}, quadratic{};

  // The project's convention for "a light of colour c": ambient, diffuse and specular all c.
  static constexpr Light directional(Vec3 dir, Color15 c) {
    return {LightKind::kDirectional, dir, c, c, c, Fixed::from_int(1), {}, {}};
  }
  static constexpr Light point(Vec3 pos, Color15 c, Fixed kc = Fixed::from_int(1), Fixed kl = {},
                               Fixed kq = {}) {
    return {LightKind::kPoint, pos, c, c, c, kc, kl, kq};
  }
};

// The lights of a frame.
struct LightSet {
  std::array<Light, kMaxLights> lights{};
  uint8_t count = 0;
  Color15 global_ambient{0, 0, 0};
  bool local_viewer = false;  // V = direction to the eye per point (GL_LIGHT_MODEL_LOCAL_VIEWER)
  bool two_sided = false;  // back faces are lit with the negated normal (GL_LIGHT_MODEL_TWO_SIDE)
  // True when the lit colour depends on the normal only: directional lights, infinite viewer.
  constexpr bool normal_only() const {
    for (int i = 0; i < count; ++i)
      if (lights[static_cast<size_t>(i)].kind != LightKind::kDirectional) return false;
    return !local_viewer;
  }
};

// Lighting prepared for one material, one light set and one camera: unit directions, half
// vectors (infinite viewer) and the products of light and material colours. Made per draw.
struct PreparedLighting {
  struct Light {
    Unit30 l;        // towards the light (directional lights)
    Unit30 h;        // half vector for the infinite viewer (directional lights)
    uint16_t ka[3];  // La * Ka, Q1.15 (point lights: attenuated per point)
    uint16_t kd[3];  // Ld * Kd, Q1.15
    uint16_t ks[3];  // Ls * Ks, Q1.15
    bool point = false;
    Vec3 position{};                 // point lights, world
    int64_t kc = 0, kl = 0, kq = 0;  // attenuation coefficients, Q16.16
  };
  std::array<Light, kMaxLights> lights{};
  uint8_t count = 0;
  bool any_point = false;
  int32_t base[3] = {0, 0, 0};  // emission + global ambient * Ka + sum of directional La * Ka
  uint16_t shininess_q8 = 0;
  bool local_viewer = false;
  Vec3 eye{};     // world-space eye position (local viewer)
  Unit30 view{};  // world-space direction towards the viewer (infinite viewer)
  // What it was prepared for: draws of equal materials share it. Zero by default (not GL's
  // default material), so that a static store of prepared lighting stays in .bss.
  Material material{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, 0};
  // Whether lighting needs the surface position (a point light or the local viewer).
  bool needs_position() const { return any_point || local_viewer; }
};

// view_dir: world-space direction from the scene towards the eye (the view's +Z axis).
PreparedLighting prepare_lighting(const LightSet& set, const Material& m, Vec3 view_dir, Vec3 eye);
// The same into `pl` (no temporary on the caller's stack: the front end keeps one for its draws).
void prepare_lighting(const LightSet& set, const Material& m, Vec3 view_dir, Vec3 eye,
                      PreparedLighting& pl);
// prepare_lighting for lighting that reads only the directional lights' diffuse and ambient
// terms (RendererFeatures::specular off, no point light or local viewer admitted, no Phong: the
// front end refuses the draws that need more before it prepares their lighting): the same count,
// material, base, l, ka and kd; no half vector, view direction or specular product (zero), and
// every light taken as directional.
void prepare_diffuse_lighting(const LightSet& set, const Material& m, Vec3 view_dir, Vec3 eye,
                              PreparedLighting& pl);
// Either of the two (the front end's FrontEndRoutines::prepare).
using PrepareLightingFn = void (*)(const LightSet&, const Material&, Vec3, Vec3, PreparedLighting&);

// Lit colour of a surface point with unit normal n (world) at world position p (read only for
// point lights and the local viewer).
Color15 light_point(const PreparedLighting& pl, const Unit30& n, Vec3 p);

// The same split as GL_SEPARATE_SPECULAR_COLOR does it: primary = emission + ambient + diffuse,
// secondary = specular, each clamped to [0, 1]. Textures modulate the primary only.
struct LitColor {
  Color15 primary, secondary;
};
LitColor light_point_split(const PreparedLighting& pl, const Unit30& n, Vec3 p);

// light_point_split for directional lights and the infinite viewer only (!pl.needs_position()),
// bit for bit: the per-vertex path of most lit draws, inline and without the general case's
// branches. Products as in light_point_split (docs/numerics.md#lighting-arithmetic).
// kSpecular false: without the specular term, for renderers that refuse materials with one
// (RendererFeatures::specular): the same colours where every light's Ls Ks is zero.
template <bool kSpecular = true>
inline LitColor light_directional_split(const PreparedLighting& pl, const Unit30& n) {
  uint32_t prim[3] = {static_cast<uint32_t>(pl.base[0]), static_cast<uint32_t>(pl.base[1]),
                      static_cast<uint32_t>(pl.base[2])};
  uint32_t spec[3] = {0, 0, 0};
  auto dot = [&n](const Unit30& u) {
    return (int64_t{n.x} * u.x + int64_t{n.y} * u.y + int64_t{n.z} * u.z) >> 30;
  };
  for (int i = 0; i < pl.count; ++i) {
    const PreparedLighting::Light& li = pl.lights[static_cast<size_t>(i)];
    const int64_t ndl = dot(li.l);
    if (ndl <= 0) continue;  // no diffuse, and GL gives no specular where N.L <= 0
    // 0 < ndl <= 2^30 + a few units: times a Q1.15 colour below 2^47, a term below 2^16.
    const auto ndl_u = static_cast<uint64_t>(ndl);
    for (int c = 0; c < 3; ++c)
      prim[c] += static_cast<uint32_t>((ndl_u * li.kd[c] + (1u << 29)) >> 30);
    if constexpr (!kSpecular) continue;
    int64_t ndh = dot(li.h);
    if (ndh <= 0) continue;
    if (ndh > (int64_t{1} << 30)) ndh = int64_t{1} << 30;
    const uint32_t sp = DefaultPowTable::pow_q15(static_cast<uint32_t>(ndh), pl.shininess_q8);
    for (int c = 0; c < 3; ++c) spec[c] += (sp * uint32_t{li.ks[c]} + (1u << 14)) >> 15;
  }
  // Every term is non-negative (base too: sums of products of Q1.15 colours).
  auto clamp = [](uint32_t x) {
    return static_cast<uint16_t>(x > Color15::kOne ? Color15::kOne : x);
  };
  return {{clamp(prim[0]), clamp(prim[1]), clamp(prim[2])},
          {clamp(spec[0]), clamp(spec[1]), clamp(spec[2])}};
}

// Primary plus secondary colour, each channel clamped to 1: one colour of a split one.
constexpr Color15 sum_clamped(Color15 a, Color15 b) {
  auto sum = [](uint16_t x, uint16_t y) {
    const uint32_t v = uint32_t{x} + y;
    return static_cast<uint16_t>(v > Color15::kOne ? Color15::kOne : v);
  };
  return {sum(a.r, b.r), sum(a.g, b.g), sum(a.b, b.b)};
}

// The same summed into one colour (light_point for directional lights and the infinite viewer).
template <bool kSpecular = true>
inline Color15 light_directional(const PreparedLighting& pl, const Unit30& n) {
  const LitColor c = light_directional_split<kSpecular>(pl, n);
  return sum_clamped(c.primary, c.secondary);
}

}  // namespace lr
