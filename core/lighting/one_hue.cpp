#include "lineraster/core/lighting/one_hue.hpp"

namespace lr {
namespace {
// |x_c Kd_g - x_g Kd_c| <= kHueSlack Kd_g for c = red, blue (x below 2^15: products below 2^30),
// as one unsigned compare each.
bool near_hue(int32_t r, int32_t g, int32_t b, const Color15& kd) {
  const uint32_t slack = kHueSlack * kd.g;
  return static_cast<uint32_t>(r * kd.g - g * kd.r) + slack <= 2 * slack &&
         static_cast<uint32_t>(b * kd.g - g * kd.b) + slack <= 2 * slack;
}
}  // namespace

void one_hue(const PreparedLighting& pl, OneHue& out) {
  out.valid = false;  // (the ratios are read only when valid)
  const Color15 kd = pl.material.diffuse;
  if (pl.count != 1 || pl.any_point || kd.g == 0) return;
  // The ratios to 15 bits: below 2 (a quotient below 2^16) or no hue.
  const uint32_t qr = (uint32_t{kd.r} << 15) / kd.g, qb = (uint32_t{kd.b} << 15) / kd.g;
  if ((qr | qb) >> 16 != 0) return;
  const PreparedLighting::Light& li = pl.lights[0];
  // object_lights.hpp's add_diffuse adds at most kd + kd / 2^10 + 1 <= kd + 33,
  // light_directional_split at most kd + 1: no channel may reach above 1 (which also bounds
  // every value by 2^15).
  for (int c = 0; c < 3; ++c)
    if (li.ks[c] != 0 || pl.base[c] + li.kd[c] + 33 > int32_t{Color15::kOne}) return;
  if (!near_hue(pl.base[0], pl.base[1], pl.base[2], kd) ||
      !near_hue(li.kd[0], li.kd[1], li.kd[2], kd))
    return;
  out.red = static_cast<int32_t>(qr << 15);
  out.blue = static_cast<int32_t>(qb << 15);
  out.valid = true;
}

}  // namespace lr
