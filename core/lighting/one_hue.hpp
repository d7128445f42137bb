// One hue: lit colours that are one colour times a scalar per vertex.
//
// With one grey directional light, no specular term and a material whose ambient and emission
// have the hue of its diffuse colour Kd, every lit colour is Kd times a scalar: red =
// (Kd_r / Kd_g) green and blue = (Kd_b / Kd_g) green at every vertex, so at every point of a
// Gouraud triangle too (interpolation is linear). The small lanes setup then makes red's and
// blue's planes from green's vertex differences (docs/numerics.md#one-hue), sharing its numerators.
//
// The colours are sums of rounded Q1.15 products, so they are proportional to within a few
// units: one_hue accepts a PreparedLighting whose base and Ld Kd lie within kHueSlack units of
// the proportional value, that never clamps (a channel that stops at 1 while green goes on is no
// longer the hue), and whose ratios are below 2. (One light: the common lit draw; more lights
// are not tested, to keep the renderer's code small.)
#pragma once

#include <cstdint>

#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/output/color.hpp"

namespace lr {

// The ratios Kd_r / Kd_g and Kd_b / Kd_g in Q1.30, to 15 bits (below 2^31), valid when the
// draw's lit colours are one hue. (A hue off by 2^-15 moves a derived channel by at most 2
// units of Q1.15: kHueSlack's scale.)
struct OneHue {
  bool valid = false;
  int32_t red = 0, blue = 0;
};

// Units of Q1.15 by which base and Ld Kd may differ from the proportional value: the rounding
// of the material's ambient and diffuse colours (half a unit each, times a ratio up to 2) and of
// the light products (the same again).
inline constexpr int32_t kHueSlack = 4;

// Whether the colours pl lights are one hue: out.valid, and its ratios when valid (written in
// place: no copy of a returned one in the front end's code).
void one_hue(const PreparedLighting& pl, OneHue& out);

}  // namespace lr
