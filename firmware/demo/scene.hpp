// What a demo scene is made of, and the values lineraster-sim uses by default, so that a
// firmware scene can be rendered by lineraster-sim from its command line and the two frames
// compared byte for byte (scripts/ci_firmware.sh).
//
// Every Fixed here comes from a consteval conversion of the number the CLI parses: the CLI
// rounds v * 65536 to the nearest integer at run time (host_sim/scene/scene.cpp to_fixed), and
// so does Fixed::from_double at compile time. The doubles exist only in the compiler: nothing in
// the firmware image computes with floating point.
#pragma once

#include <cstdint>

#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/vec.hpp"
#include "lineraster/core/scene/camera.hpp"

namespace lr::fw::demo {

// The camera of a scene (world units, degrees).
struct SceneView {
  Fixed fovy, near, far;
  Vec3 eye, target, up;
};

consteval Vec3 vec(double x, double y, double z) {
  return {Fixed::from_double(x), Fixed::from_double(y), Fixed::from_double(z)};
}

// lineraster-sim's defaults: --fovy 60 --near 0.1 --far 100 --eye 0,0,3 --target 0,0,0 --up 0,1,0.
inline constexpr SceneView kSimDefaultView{Fixed::from_double(60.0),
                                           Fixed::from_double(0.1),
                                           Fixed::from_double(100.0),
                                           vec(0, 0, 3),
                                           vec(0, 0, 0),
                                           vec(0, 1, 0)};

// sqrt by Newton's method for compile-time normalisation (std::sqrt is not constexpr in C++20).
// Converges to the correctly rounded value or next to it; a last-bit difference could only
// change the Q16.16 result on an exact rounding tie, and the byte comparison with lineraster-sim
// would say so.
consteval double sqrt_ct(double v) {
  double x = v > 1 ? v : 1;
  for (int i = 0; i < 64; ++i) x = 0.5 * (x + v / x);
  return x;
}

// A white directional light towards (x, y, z), normalised as the CLI's --light-dir does.
consteval Light white_directional(double x, double y, double z) {
  const double len = sqrt_ct(x * x + y * y + z * z);
  return Light::directional(vec(x / len, y / len, z / len),
                            Color15{Color15::kOne, Color15::kOne, Color15::kOne});
}

// The CLI's default lighting: one white light along (1, 1, 1), no global ambient.
consteval LightSet sim_default_lights() {
  LightSet s;
  s.lights[0] = white_directional(1, 1, 1);
  s.count = 1;
  return s;
}

// A camera for a viewport, as the CLI builds it. False if the view is degenerate.
inline bool make_camera(const SceneView& v, int width, int height, Camera& out) {
  out.eye = v.eye;
  return perspective(v.fovy, Fixed::ratio(width, height), v.near, v.far, out.projection) &&
         look_at(v.eye, v.target, v.up, out.view);
}

}  // namespace lr::fw::demo
