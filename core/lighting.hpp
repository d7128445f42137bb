// Per-vertex (and per-face) lighting: OpenGL's fixed-function model (DESIGN.md §4) in fixed point.
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

#include "core/color.hpp"
#include "core/material.hpp"
#include "core/pow_table.hpp"
#include "core/vec.hpp"

namespace lr {

inline constexpr int kMaxLights = 4;

// A directional light: direction in world space from the surface towards the light (any
// non-zero length), and its ambient, diffuse and specular colours.
struct DirectionalLight {
  Vec3 direction{Fixed::from_int(1), Fixed::from_int(1), Fixed::from_int(1)};
  Color15 ambient{0, 0, 0};
  Color15 diffuse{Color15::kOne, Color15::kOne, Color15::kOne};
  Color15 specular{Color15::kOne, Color15::kOne, Color15::kOne};

  // The project's convention for "a light of colour c": ambient, diffuse and specular all c.
  static constexpr DirectionalLight of_color(Vec3 dir, Color15 c) { return {dir, c, c, c}; }
};

// The lights of a frame.
struct LightSet {
  std::array<DirectionalLight, kMaxLights> lights{};
  uint8_t count = 0;
  Color15 global_ambient{0, 0, 0};
  bool local_viewer = false;
};

// Lighting prepared for one material, one light set and one camera: unit directions, half
// vectors (infinite viewer) and the products of light and material colours. Made per draw.
struct PreparedLighting {
  struct Light {
    Unit30 l;        // towards the light
    Unit30 h;        // half vector for the infinite viewer
    uint16_t kd[3];  // Ld * Kd, Q1.15
    uint16_t ks[3];  // Ls * Ks, Q1.15
  };
  std::array<Light, kMaxLights> lights{};
  uint8_t count = 0;
  int32_t base[3] = {0, 0, 0};  // emission + global ambient * Ka + sum La * Ka, Q1.15
  uint16_t shininess_q8 = 0;
  bool local_viewer = false;
  Vec3 eye{};     // world-space eye position (local viewer)
  Unit30 view{};  // world-space direction towards the viewer (infinite viewer)
};

// view_dir: world-space direction from the scene towards the eye (the view's +Z axis).
PreparedLighting prepare_lighting(const LightSet& lights, const Material& material, Vec3 view_dir,
                                  Vec3 eye);

// Lit colour of a surface point with unit normal n (world) at world position p.
Color15 light_point(const PreparedLighting& pl, const Unit30& n, Vec3 p);

// The same split as GL_SEPARATE_SPECULAR_COLOR does it: primary = emission + ambient + diffuse,
// secondary = specular, each clamped to [0, 1]. Textures modulate the primary only.
struct LitColor {
  Color15 primary, secondary;
};
LitColor light_point_split(const PreparedLighting& pl, const Unit30& n, Vec3 p);

}  // namespace lr
