// One hue: lit colours that are one colour times a scalar per vertex.
//
// With white (grey) lights, no specular term, no point light and a material whose ambient and
// emission are proportional to its diffuse colour Kd, every lit colour is Kd times a scalar:
// red = (Kd_r / Kd_g) green and blue = (Kd_b / Kd_g) green at every vertex, so at every point of
// a Gouraud triangle too (interpolation is linear). The setup then makes green's plane and
// derives red's and blue's from it (core/setup/small_plane.hpp, docs/numerics.md#one-hue)
// instead of making three.
//
// The colours are sums of rounded Q1.15 products, so they are proportional to within a few
// units: one_hue accepts a PreparedLighting whose base and every light's Ld Kd lie within
// kHueSlack units of the proportional value, never clamp (so that a channel at 1 does not stop
// while the others go on), and whose ratios are at most 2.
#pragma once

#include <cstdint>

#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/output/color.hpp"

namespace lr {

// The ratios Kd_r / Kd_g and Kd_b / Kd_g in Q1.30 (at most 2^31: ratios up to 2), valid when
// the draw's lit colours are one hue.
struct OneHue {
  bool valid = false;
  uint32_t red = 0, blue = 0;
  friend constexpr bool operator==(const OneHue&, const OneHue&) = default;
};

// Units of Q1.15 by which base and Ld Kd may differ from the proportional value: the rounding
// of the material's ambient and diffuse colours (half a unit each, times a ratio up to 2) and of
// the light products (the same again).
inline constexpr int32_t kHueSlack = 4;

// Whether the colours pl lights are one hue (directional lights, diffuse and ambient only).
constexpr OneHue one_hue(const PreparedLighting& pl) {
  const Color15 kd = pl.material.diffuse;
  const int64_t g = kd.g;
  if (pl.any_point || g == 0 || kd.r > 2 * g || kd.b > 2 * g) return {};
  // x (channels) within kHueSlack units of x_g Kd_c / Kd_g: |x_c Kd_g - x_g Kd_c| <= slack Kd_g.
  auto proportional = [&](int64_t r, int64_t gr, int64_t b) {
    const int64_t dr = r * g - gr * kd.r, db = b * g - gr * kd.b;
    return (dr < 0 ? -dr : dr) <= kHueSlack * g && (db < 0 ? -db : db) <= kHueSlack * g;
  };
  if (!proportional(pl.base[0], pl.base[1], pl.base[2])) return {};
  // The largest sum per channel: object_lights.hpp's add_diffuse adds at most kd + kd / 2^10 + 1
  // per light, light_directional_split at most kd + 1.
  int64_t most[3] = {pl.base[0], pl.base[1], pl.base[2]};
  for (int i = 0; i < pl.count; ++i) {
    const PreparedLighting::Light& li = pl.lights[static_cast<unsigned>(i)];
    if ((li.ks[0] | li.ks[1] | li.ks[2]) != 0) return {};
    if (!proportional(li.kd[0], li.kd[1], li.kd[2])) return {};
    for (int c = 0; c < 3; ++c) most[c] += li.kd[c] + (li.kd[c] >> 10) + 1;
  }
  for (const int64_t m : most)
    if (m < 0 || m > Color15::kOne) return {};
  return {true, static_cast<uint32_t>((int64_t{kd.r} << 30) / g),
          static_cast<uint32_t>((int64_t{kd.b} << 30) / g)};
}

}  // namespace lr
