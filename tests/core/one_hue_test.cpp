// one_hue (core/lighting/one_hue.hpp): which lit draws are one colour times a scalar, and how
// close their vertex colours are to it (docs/numerics.md#one-hue).
#include "lineraster/core/lighting/one_hue.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>

#include "lineraster/core/lighting/lighting.hpp"

namespace lr {
namespace {

constexpr uint16_t c15(double v) {
  return static_cast<uint16_t>(v * Color15::kOne + 0.5);
}
constexpr Color15 grey(double v) {
  return {c15(v), c15(v), c15(v)};
}
constexpr Color15 scaled(double k, const double (&c)[3]) {
  return {c15(k * c[0]), c15(k * c[1]), c15(k * c[2])};
}

// The peer scenes' lit material: ambient 0.2 and diffuse 0.8 of one colour, each rounded.
constexpr double kPeerColor[3] = {0.95, 0.78, 0.55};
Material peer_material() {
  Material m;
  m.ambient = scaled(0.2, kPeerColor);
  m.diffuse = scaled(0.8, kPeerColor);
  return m;
}
LightSet white_light() {
  LightSet s;
  s.lights[0] = Light::directional(
      {Fixed::from_double(-0.6), Fixed::from_double(0.8), Fixed::from_double(1.0)}, grey(1.0));
  s.count = 1;
  return s;
}
OneHue hue_of(const LightSet& s, const Material& m) {
  const PreparedLighting pl =
      prepare_lighting(s, m, {Fixed{}, Fixed{}, Fixed::from_int(1)}, Vec3{});
  OneHue h;
  one_hue(pl, h);
  return h;
}

TEST(OneHue, PeerMaterialUnderAWhiteLight) {
  const Material m = peer_material();
  const OneHue h = hue_of(white_light(), m);
  ASSERT_TRUE(h.valid);
  EXPECT_EQ(h.red, static_cast<int32_t>(((int64_t{m.diffuse.r} << 15) / m.diffuse.g) << 15));
  EXPECT_EQ(h.blue, static_cast<int32_t>(((int64_t{m.diffuse.b} << 15) / m.diffuse.g) << 15));
  // 0.95 / 0.78 and 0.55 / 0.78 in Q1.30.
  EXPECT_NEAR(h.red / double(1 << 30), 0.95 / 0.78, 1e-4);
  EXPECT_NEAR(h.blue / double(1 << 30), 0.55 / 0.78, 1e-4);
}

TEST(OneHue, GlDefaultMaterialIsGrey) {
  // GL's defaults: global ambient 0.2, a light with diffuse 1 and no ambient.
  LightSet l = white_light();
  l.lights[0].ambient = Color15{};
  l.global_ambient = grey(0.2);
  const OneHue h = hue_of(l, Material{});
  ASSERT_TRUE(h.valid);
  EXPECT_EQ(h.red, 1 << 30);
  EXPECT_EQ(h.blue, 1 << 30);
}

TEST(OneHue, RefusedWhereTheColoursAreNotOneHue) {
  const Material m = peer_material();
  {  // a specular term
    Material s = m;
    s.specular = grey(0.5);
    s.shininess_q8 = 32 * 256;
    EXPECT_FALSE(hue_of(white_light(), s).valid);
  }
  {  // a coloured light
    LightSet l = white_light();
    l.lights[0].diffuse = Color15{Color15::kOne, c15(0.5), c15(0.5)};
    EXPECT_FALSE(hue_of(l, m).valid);
  }
  {  // a coloured global ambient
    LightSet l = white_light();
    l.global_ambient = Color15{c15(0.3), 0, 0};
    EXPECT_FALSE(hue_of(l, m).valid);
  }
  {  // an ambient of another hue
    Material a = m;
    a.ambient = Color15{c15(0.2), 0, 0};
    EXPECT_FALSE(hue_of(white_light(), a).valid);
  }
  {  // a point light (attenuated colours may clamp)
    LightSet l = white_light();
    l.lights[0] = Light::point({Fixed{}, Fixed::from_int(2), Fixed{}}, grey(1.0));
    EXPECT_FALSE(hue_of(l, m).valid);
  }
  {  // red more than twice green, and no green
    Material r = m;
    r.diffuse = Color15{c15(0.9), c15(0.4), c15(0.1)};
    r.ambient = Color15{c15(0.18), c15(0.08), c15(0.02)};
    EXPECT_FALSE(hue_of(white_light(), r).valid);
    r.diffuse = Color15{c15(0.9), 0, c15(0.1)};
    r.ambient = Color15{};
    EXPECT_FALSE(hue_of(white_light(), r).valid);
  }
  {  // two lights (not tested: one_hue takes the common draw's one light only)
    LightSet l = white_light();
    l.lights[1] = l.lights[0];
    l.lights[1].diffuse = grey(0.1);
    l.count = 2;
    EXPECT_FALSE(hue_of(l, m).valid);
  }
  {  // ambient plus diffuse above 1: a channel may clamp while the others go on
    Material c = m;
    c.ambient = scaled(0.5, kPeerColor);
    c.diffuse = scaled(0.9, kPeerColor);
    EXPECT_FALSE(hue_of(white_light(), c).valid);
  }
}

// The lit colours of random normals are the hue times green to within kHueSlack units and the
// rounding of the light's term (4 + 4 + 1.5 units of Q1.15 at most).
TEST(OneHue, VertexColoursAreTheHueTimesGreen) {
  LightSet l = white_light();
  l.lights[0].ambient = grey(0.7);
  Material m;
  m.ambient = scaled(0.1, kPeerColor);
  m.diffuse = scaled(0.55, kPeerColor);
  const PreparedLighting pl =
      prepare_lighting(l, m, {Fixed{}, Fixed{}, Fixed::from_int(1)}, Vec3{});
  OneHue h;
  one_hue(pl, h);
  ASSERT_TRUE(h.valid);
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  double worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const double x = g(rng), y = g(rng), z = g(rng);
    const double k = (1 << 30) / std::sqrt(x * x + y * y + z * z);
    const Unit30 n{static_cast<int32_t>(x * k), static_cast<int32_t>(y * k),
                   static_cast<int32_t>(z * k)};
    const Color15 c = light_directional_split<false>(pl, n).primary;
    const double scale = 1.0 / double(1 << 30);
    worst = std::max(
        {worst, std::abs(c.r - h.red * scale * c.g), std::abs(c.b - h.blue * scale * c.g)});
  }
  std::printf("[ one hue ] largest distance from the hue %.2f units of Q1.15\n", worst);
  const double bound = kHueSlack + kHueSlack + 1.5;
  EXPECT_LE(worst, bound);
  EXPECT_GT(worst, 0.0);  // not trivially proportional: the roundings are there
}

}  // namespace
}  // namespace lr
