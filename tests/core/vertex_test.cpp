// The vertex stage's fast paths against their exact forms: normals under a rigid model matrix
// against exact normalisation, the projection's 2-by-1 divisions against round_div, the 32-bit
// short path against the quotients of its clip coordinates, lights in model space against
// lighting in world space.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "lineraster/core/lighting/object_lights.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/math/rigid.hpp"
#include "lineraster/core/math/trig.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/core/vertex/screen_transform.hpp"
#include "lineraster/core/vertex/vertex_stage.hpp"

namespace lr {
namespace {

// (x, y, z) normalised, times `length` (1: a unit normal rounded to Q1.14).
Normal16 unit_normal16(double x, double y, double z, double length = 1.0) {
  const double l = std::sqrt(x * x + y * y + z * z) / length;
  auto q = [l](double v) { return static_cast<int16_t>(std::lround(v / l * 16384.0)); };
  return {q(x), q(y), q(z)};
}

TEST(RigidNormals, RotationsAndUniformScalesAreRigidOthersAreNot) {
  NormalRotation r;
  const Mat4 rot = rotate_y(Fixed::from_int(35)) * rotate_x(Fixed::from_int(-20));
  EXPECT_TRUE(rigid_normal_rows(normal_matrix(rot), r));
  EXPECT_TRUE(rigid_normal_rows(normal_matrix(rot * scale(Fixed::from_int(3))), r));
  EXPECT_TRUE(rigid_normal_rows(normal_matrix(translate({Fixed::from_int(5), {}, {}}) * rot), r));
  EXPECT_FALSE(rigid_normal_rows(
      normal_matrix(rot * scale(Vec3{Fixed::from_int(1), Fixed::from_int(2), Fixed::from_int(1)})),
      r));
  // A shear of 1/100: the rows are no longer orthogonal within the tolerance.
  Mat4 shear = Mat4::identity();
  shear.m[0][1] = Fixed::from_raw(655);
  EXPECT_FALSE(rigid_normal_rows(normal_matrix(shear), r));
  EXPECT_FALSE(rigid_normal_rows(Mat4{}, r));
}

TEST(RigidNormals, RotatedNormalsMatchExactNormalisationWithinTwoToTheMinus16) {
  const Mat4 model = rotate_z(Fixed::from_int(71)) * rotate_y(Fixed::from_int(35)) *
                     scale(Fixed::from_double(0.75));
  const Mat4 nm = normal_matrix(model);
  NormalRotation r;
  ASSERT_TRUE(rigid_normal_rows(nm, r));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int64_t worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const Normal16 n = unit_normal16(u(rng), u(rng), u(rng) + 1e-3);
    Unit30 fast;
    ASSERT_TRUE(rotate_unit_normal(r, n, fast));
    const Unit30 exact = transform_normal(nm, n.x, n.y, n.z);
    for (int64_t e :
         {int64_t{fast.x} - exact.x, int64_t{fast.y} - exact.y, int64_t{fast.z} - exact.z})
      worst = std::max(worst, e < 0 ? -e : e);
  }
  // Q1.30 units: the rows' own Q16.16 rounding (about 2^-17) dominates.
  EXPECT_LE(worst, int64_t{1} << 14);
  std::printf("rigid normals: worst component difference %lld / 2^30\n",
              static_cast<long long>(worst));
}

TEST(RigidNormals, ANormalThatIsNotUnitIsRefused) {
  NormalRotation r;
  ASSERT_TRUE(rigid_normal_rows(normal_matrix(Mat4::identity()), r));
  Unit30 out{1, 2, 3};
  EXPECT_FALSE(rotate_unit_normal(r, Normal16{8192, 0, 0}, out));
  EXPECT_FALSE(rotate_unit_normal(r, Normal16{0, 0, 0}, out));
  EXPECT_EQ(out.x, 1);
  EXPECT_TRUE(rotate_unit_normal(r, Normal16{0, 16384, 0}, out));
  EXPECT_EQ(out.x, 0);
  EXPECT_EQ(out.y, 1 << 30);
}

TEST(Projection, EqualsRoundDivOnRandomClipCoordinates) {
  const Camera camera;
  const Mat4 model = Mat4::identity();
  const GuardBand g{25, 34};
  const VertexStage stage(camera, model, g, 320, 240);
  std::mt19937_64 rng(11);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    // w from 2^-16 to 2^19 units (Q28.28), both below and above the 2^31 normalisation.
    const int bits = 12 + static_cast<int>(rng() % 36);
    int64_t w = static_cast<int64_t>(rng() >> (64 - bits)) | (int64_t{1} << (bits - 1));
    auto within = [&](int64_t lim) {
      return static_cast<int64_t>(rng() % static_cast<uint64_t>(2 * lim + 1)) - lim;
    };
    const int64_t x = within(g.gx * w), y = within(g.gy * w), z = within(w);
    const ClipCoord c{x, y, z, w};
    if (outcode(c, g) != 0) continue;
    ScreenVertex v;
    ASSERT_TRUE(stage.project(c, v));
    int64_t xs = x, ys = y, zs = z, ws = w;
    while (ws >= (int64_t{1} << 31)) {
      xs >>= 1;
      ys >>= 1;
      zs >>= 1;
      ws >>= 1;
    }
    ASSERT_EQ(v.x, round_div((xs + ws) * (320 * kHalfPixel), ws)) << x << " " << w;
    ASSERT_EQ(v.y, round_div((ws - ys) * (240 * kHalfPixel), ws)) << y << " " << w;
    const int64_t zz = round_div((zs + ws) * (int64_t{65535} << 15), ws);
    ASSERT_EQ(v.z, static_cast<uint32_t>(zz > kDepthMax ? kDepthMax : zz)) << z << " " << w;
    ++checked;
  }
  EXPECT_GT(checked, 150000);
}

// A random draw for the short path: a perspective camera looking at a mesh of random extent
// under a random model matrix (rotated, scaled, maybe unevenly, translated), its positions.
struct RandomDraw {
  Mat4 mvp;
  std::vector<Vec3> positions;
};

RandomDraw random_draw(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  auto fx = [](double v) { return Fixed::from_raw(static_cast<int32_t>(std::lround(v * 65536))); };
  Camera cam;
  const double near = std::exp2(-4 + 5 * pos(rng));  // 1/16 .. 2
  const double far = near * std::exp2(3 + 8 * pos(rng));
  EXPECT_TRUE(perspective(fx(20 + 90 * pos(rng)), fx(4.0 / 3), fx(near), fx(far), cam.projection));
  const double dist = near + (far - near) * pos(rng) * 0.5;
  EXPECT_TRUE(look_at({fx(u(rng)), fx(u(rng)), fx(dist)}, {fx(u(rng)), fx(u(rng)), {}},
                      {{}, Fixed::from_int(1), {}}, cam.view));
  const double extent = std::exp2(-4 + 12 * pos(rng)) * (0.2 + pos(rng));  // 1/16 .. 4096
  Mat4 model = translate({fx(u(rng) * extent), fx(u(rng) * extent), fx(u(rng) * extent)}) *
               rotate_y(fx(180 * u(rng))) * rotate_x(fx(180 * u(rng)));
  if (rng() % 3 == 0) model = model * scale(Vec3{fx(0.5 + pos(rng)), fx(1), fx(0.5 + pos(rng))});
  RandomDraw d;
  d.mvp = cam.projection * cam.view * model;
  const double r = std::min(extent, 30000.0);
  for (int i = 0; i < 400; ++i)
    d.positions.push_back({fx(r * u(rng)), fx(r * u(rng)), fx(r * u(rng))});
  return d;
}

// The short path's vertices against the exact quotients of the same Q16.16 model-view-projection
// (evaluated in double: every product is exact, each sum within 2^-50 of itself): only vertices
// inside every plane, with outcode 0; x and y within half a subpixel plus 2^-kShortPathFractionBits
// plus 2^-19 of their distance from the centre, z within 2^12 of 2^32 (1/16 of a 16-bit step), w
// within 2^-19 of itself. It hands the exact path the vertices outside a plane and those of small
// w, and almost never one inside every plane in the draw's far half. Its split-product form
// (project_halves: the Cortex-M0+'s) gives the same integers.
TEST(ShortPath, AgreesWithTheQuotientsOfItsClipCoordinates) {
  std::mt19937_64 rng(36);
  const int width = 320, height = 240;
  const GuardBand g{8192 / width, 8192 / height};
  const double sx = width * 128.0, sy = height * 128.0, dz = 65535.0 * 32768.0;
  double worst_xy = 0, worst_guard = 0, worst_z = 0, worst_w = 0;
  int short_path = 0, exact_path = 0, exact_far = 0, disabled = 0, guard_free = 0;
  for (int draw = 0; draw < 3000; ++draw) {
    const RandomDraw d = random_draw(rng);
    const ScreenTransform st(d.mvp, position_bound(d.positions.data(), d.positions.size()), width,
                             height, g);
    if (!st.enabled()) {
      ++disabled;
      continue;
    }
    double max_w = 0;
    std::vector<std::array<double, 4>> clip;
    for (const Vec3& p : d.positions) {
      std::array<double, 4> c{};
      for (int i = 0; i < 4; ++i)
        c[static_cast<size_t>(i)] =
            (double(d.mvp.m[i][0].raw) * p.x.raw + double(d.mvp.m[i][1].raw) * p.y.raw +
             double(d.mvp.m[i][2].raw) * p.z.raw) /
                4294967296.0 +
            d.mvp.m[i][3].raw / 65536.0;
      clip.push_back(c);
      max_w = std::max(max_w, std::abs(c[3]));
    }
    for (size_t k = 0; k < d.positions.size(); ++k) {
      const auto [x, y, z, w] = clip[k];
      const double qz = dz * z / w;
      const double qx = sx * x / w, qy = -sy * y / w;
      const double lx = g.gx * sx, ly = g.gy * sy;
      // Inside every plane by a margin of 2^-10 of its extent (and in front of the eye).
      const bool inside = w > 0 && std::abs(qx) < lx * (1 - 1.0 / 1024) &&
                          std::abs(qy) < ly * (1 - 1.0 / 1024) &&
                          std::abs(qz) < dz * (1 - 1.0 / 1024);
      ScreenVertex v;
      v.outcode = 0xEE;
      // The split-product form (Armv6-M's) gives the same integers.
      ScreenVertex vh;
      vh.outcode = 0xEE;
      const bool taken = st.project(d.positions[k], v);
      ASSERT_EQ(st.project_halves(d.positions[k], vh), taken) << draw << " " << k;
      ASSERT_EQ(vh.x, v.x);
      ASSERT_EQ(vh.y, v.y);
      ASSERT_EQ(vh.z, v.z);
      ASSERT_EQ(vh.w, v.w);
      ASSERT_EQ(vh.outcode, v.outcode);
      if (!taken) {
        ++exact_path;
        EXPECT_EQ(v.outcode, 0xEE);
        if (inside && w > max_w / 2) ++exact_far;
        continue;
      }
      ++short_path;
      ASSERT_GT(w, 0.0);
      ASSERT_GE(v.w, 1u);  // (setup divides by it)
      ASSERT_EQ(v.outcode, 0);
      // Rounding, then a unit or so of the draw's 2^-f (the product's floor, a row sum's error
      // over W), never more than 2^-5, and 2^-19 of the distance from the centre (r's and W's
      // own errors).
      const double unit = std::min(1.0 / 32, std::ldexp(1.25, -st.fraction_bits()));
      const double tx = 0.5 + unit + std::abs(qx) / 524288, ty = 0.5 + unit + std::abs(qy) / 524288;
      const double tz = 4096 + std::abs(qz) / 524288;
      const double ex = std::abs(v.x - (sx + qx)), ey = std::abs(v.y - (sy + qy));
      ASSERT_LE(ex, tx) << draw << " " << k;
      ASSERT_LE(ey, ty) << draw << " " << k;
      ASSERT_LE(std::abs(double(v.z) - (dz + qz)), tz) << draw << " " << k;
      ASSERT_LE(std::abs(double(v.w) - w * 65536), 1 + w * 65536 / 524288) << draw << " " << k;
      // Inside every plane, up to the tolerances.
      ASSERT_LE(std::abs(qx), lx + tx) << draw << " " << k;
      ASSERT_LE(std::abs(qy), ly + ty) << draw << " " << k;
      ASSERT_LE(std::abs(qz), dz + tz) << draw << " " << k;
      if (std::abs(qx) < sx && std::abs(qy) < sy)  // on the display
        worst_xy = std::max({worst_xy, ex - 0.5, ey - 0.5});
      else
        worst_guard = std::max({worst_guard, ex - 0.5, ey - 0.5});
      worst_z = std::max(worst_z, std::abs(double(v.z) - (dz + qz)));
      worst_w = std::max(worst_w, std::abs(double(v.w) - w * 65536) / (w * 65536));
      if (st.guard_free()) ++guard_free;
    }
  }
  std::printf(
      "short path: %d vertices (%d of draws with no guard test), %d exact (%d inside every "
      "plane and in the far half of w), %d draws disabled; worst x/y beyond half a subpixel %.4f "
      "on the display, %.4f in the guard band; z %.0f / 2^32, w %.2e relative\n",
      short_path, guard_free, exact_path, exact_far, disabled, worst_xy, worst_guard, worst_z,
      worst_w);
  EXPECT_GT(short_path, 2 * exact_path);  // (random cameras: many vertices near or behind the eye)
  EXPECT_LT(exact_far, short_path / 1000);
  EXPECT_GT(guard_free, 10000);
  EXPECT_LT(disabled, 100);  // (w beyond 2^13 or the range limit: the exact path whole)
}

// Peer scene S1's draw (docs/measurements/peer_scenes.md): every vertex of a mesh in [-1, 1]^3
// in front of a 60-degree camera takes the short path, and as the draw's cube lies inside the
// guard band with w in a factor of two, with ten fraction bits (docs/numerics.md#the-short-path):
// x and y within 2^-9 subpixel of the exact quotients of their clip coordinates before rounding
// (five fraction bits, the bound for every draw, would allow 2^-5), so each is the quotient
// rounded to nearest unless that lies within 2^-9 of a half. Checked on random positions and on
// positions whose quotient lies within 2^-8 of a half (chosen from many random ones).
TEST(ShortPath, TakesEveryVertexOfThePeerSceneWithTenFractionBits) {
  Camera cam;
  ASSERT_TRUE(perspective(Fixed::from_int(60), Fixed::ratio(4, 3), Fixed::from_int(1),
                          Fixed::from_int(10), cam.projection));
  const Mat4 model = translate({{}, {}, Fixed::from_double(-2.45)}) * rotate_y(Fixed::from_int(20));
  const Mat4 mvp = cam.projection * cam.view * model;
  const double sx = 320 * 128.0, sy = 240 * 128.0;
  // The exact quotients (display subpixels) of p's clip coordinates (products below 2^53: exact).
  auto exact = [&](const Vec3& p) {
    double c[4];
    for (int i = 0; i < 4; ++i)
      c[i] = (double(mvp.m[i][0].raw) * p.x.raw + double(mvp.m[i][1].raw) * p.y.raw +
              double(mvp.m[i][2].raw) * p.z.raw) /
                 4294967296.0 +
             mvp.m[i][3].raw / 65536.0;
    return std::array<double, 2>{sx + sx * c[0] / c[3], sy - sy * c[1] / c[3]};
  };
  auto near_half = [](double q, double d) { return std::abs(q - std::floor(q) - 0.5) < d; };
  std::mt19937_64 rng(1);
  auto coordinate = [&] { return Fixed::from_raw(static_cast<int32_t>(rng() % 131073) - 65536); };
  std::vector<Vec3> p;
  for (int i = 0; i < 5000; ++i) p.push_back({coordinate(), coordinate(), coordinate()});
  size_t constructed = 0;
  for (int i = 0; i < 400000; ++i) {
    const Vec3 q{coordinate(), coordinate(), coordinate()};
    const auto e = exact(q);
    if (near_half(e[0], 1.0 / 256) || near_half(e[1], 1.0 / 256)) {
      p.push_back(q);
      ++constructed;
    }
  }
  const ScreenTransform st(mvp, position_bound(p.data(), p.size()), 320, 240, GuardBand{25, 34});
  ASSERT_TRUE(st.enabled());
  ASSERT_TRUE(st.guard_free());
  EXPECT_EQ(st.fraction_bits(), 10);
  double worst = 0;
  size_t off = 0;
  for (const Vec3& q : p) {
    ScreenVertex v;
    ASSERT_TRUE(st.project(q, v));
    EXPECT_EQ(v.outcode, 0);
    const auto e = exact(q);
    const double ex = std::abs(v.x - e[0]), ey = std::abs(v.y - e[1]);
    worst = std::max({worst, ex - 0.5, ey - 0.5});
    ASSERT_LE(ex, 0.5 + 1.0 / 512) << e[0];
    ASSERT_LE(ey, 0.5 + 1.0 / 512) << e[1];
    off += v.x != std::llround(e[0]) || v.y != std::llround(e[1]);
  }
  std::printf(
      "peer draw: %zu vertices (%zu within 2^-8 of a half), worst x/y beyond half a subpixel "
      "%.5f (2^-9 = %.5f); %zu not the rounded quotient\n",
      p.size(), constructed, worst, 1.0 / 512, off);
  EXPECT_GT(constructed, 2000u);
}

// A draw whose clip coordinates can reach 2^19 (the exact path's range limit: kClipOutOfRange
// there) takes the exact path whole.
TEST(ShortPath, DrawsNearTheExactPathsRangeAreLeftToIt) {
  // w = z, coordinates up to 4000: the short path.
  Mat4 mvp = Mat4::identity();
  mvp.m[3][3] = Fixed{};
  mvp.m[3][2] = Fixed::from_int(1);
  const uint32_t bound = 4000u << 16;
  EXPECT_TRUE(ScreenTransform(mvp, bound, 320, 240, GuardBand{25, 34}).enabled());
  mvp.m[3][2] = Fixed::from_int(256);  // w up to 1024000 > 2^19
  EXPECT_FALSE(ScreenTransform(mvp, bound, 320, 240, GuardBand{25, 34}).enabled());
}

// A draw whose w row is tiny (w = z 2^-16: W's scale 2^44, w in Q16.16 is W >> 28): a vertex
// whose Q16.16 w would be 0 is left to the exact path (which clamps it to 1: setup divides by
// it); one unit and above take the short path. (Found by the pipeline fuzzer.)
TEST(ShortPath, NeverGivesAZeroW) {
  Mat4 mvp = Mat4::identity();
  mvp.m[0][0] = Fixed::from_raw(1);
  mvp.m[1][1] = Fixed::from_raw(1);
  mvp.m[2][2] = Fixed{};
  mvp.m[3][3] = Fixed{};
  mvp.m[3][2] = Fixed::from_raw(1);
  const ScreenTransform st(mvp, 1u << 16, 320, 240, GuardBand{25, 34});
  ASSERT_TRUE(st.enabled());
  ScreenVertex v;
  EXPECT_FALSE(st.project({Fixed::ratio(1, 10), Fixed::ratio(1, 10), Fixed::ratio(1, 2)}, v));
  EXPECT_FALSE(
      st.project_halves({Fixed::ratio(1, 10), Fixed::ratio(1, 10), Fixed::ratio(1, 2)}, v));
  ASSERT_TRUE(st.project({Fixed::ratio(1, 10), Fixed::ratio(1, 10), Fixed::from_int(1)}, v));
  EXPECT_EQ(v.w, 1u);
  EXPECT_EQ(v.x, 320 * 128 + 4096);  // x / w = 0.1: a tenth of the half width right of centre
}

// A draw beyond the short path's range (rows of 2^50 and more in Q32.32) with a tiny viewport's
// wide guard band: the exact path whole, and no overflow on the way (the guard-band test of the
// cube's corners multiplied clip coordinates of up to 2^60 by the band's factor: UBSan in the
// random call-order tests).
TEST(ShortPath, HugeRowsAndAWideBandAreLeftToTheExactPath) {
  Mat4 mvp{};  // w = -32768 x: about 2^58 in Q28.28 at the corner x = -2^31
  mvp.m[3][0] = Fixed::from_raw(-0x7FFFFFFF);
  const ScreenTransform st(mvp, 0x7FFFFFFFu, 24, 24, GuardBand{341, 341});
  EXPECT_FALSE(st.enabled());
}

// Lights in model space: a rigid model's lit colours against GL's model evaluated in double
// (the normal through the inverse transpose of the Q16.16 model matrix, normalised), diffuse and
// specular (gold: shininess 51.2), both sides: within 4 Q1.15 units (1/32 of an 8-bit level),
// about as close as lighting in world space (a rotated and renormalised normal) is. A normal
// that is not unit is refused (unit_normal), the vertex stage then lights it in world space.
TEST(ObjectLights, MatchGlLightingAsCloselyAsWorldSpaceLighting) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto fx = [](double v) { return Fixed::from_raw(static_cast<int32_t>(std::lround(v * 65536))); };
  LightSet set;
  set.count = 3;
  set.lights[0] = Light::directional({fx(-0.6), fx(0.8), fx(1.0)}, {26000, 24000, 20000});
  set.lights[1] = Light::directional({fx(0.3), fx(-0.2), fx(0.9)}, {9000, 12000, 16000});
  set.lights[2] = Light::directional({fx(0.0), fx(1.0), fx(0.1)}, {7000, 7000, 7000});
  const Material m = to_material(*find_material("gold"));
  const PreparedLighting pl = prepare_lighting(set, m, {{}, {}, Fixed::from_int(1)}, {});
  double worst_fast = 0, worst_world = 0;
  for (int model_i = 0; model_i < 40; ++model_i) {
    const Mat4 model = translate({fx(3 * u(rng)), {}, fx(-5)}) * rotate_z(fx(180 * u(rng))) *
                       rotate_y(fx(180 * u(rng))) * rotate_x(fx(180 * u(rng))) *
                       scale(fx(0.25 + std::abs(u(rng)) * 4));
    const Camera cam;
    const VertexStage stage(cam, model, GuardBand{1, 1}, 64, 64);
    ObjectLights ol;
    ASSERT_TRUE(stage.object_lights(pl, ol));
    EXPECT_TRUE(ol.specular);
    // The inverse transpose of the upper 3x3, in double: the cofactor matrix (its scale does not
    // matter, the normal is normalised).
    double a[3][3], cof[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) a[i][j] = model.m[i][j].raw / 65536.0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        cof[i][j] = a[(i + 1) % 3][(j + 1) % 3] * a[(i + 2) % 3][(j + 2) % 3] -
                    a[(i + 1) % 3][(j + 2) % 3] * a[(i + 2) % 3][(j + 1) % 3];
    for (int i = 0; i < 2000; ++i) {
      // Unit normals, and normals near the ends of unit_normal()'s band (|n| up to 1 +- 2^-13),
      // which 1 / |n| corrects (the specular power would multiply their length's error).
      const double x = u(rng), y = u(rng), z = u(rng) + 1e-3;
      double off = (i % 3 == 0 ? 0.0 : i % 3 == 1 ? 1.0 : -1.0) / 8192;
      Normal16 n = unit_normal16(x, y, z, 1.0 + off);
      while (!unit_normal(n)) n = unit_normal16(x, y, z, 1.0 + (off *= 0.9));
      if (off != 0) {
        ASSERT_GT(std::abs(off), 0.5 / 8192);
      }
      const bool back = (i & 1) != 0;
      const LitColor fast = light_object(pl, ol, n, normal_len2(n), back);
      Unit30 nw = stage.world_normal(n);
      if (back) nw = negate(nw);
      const LitColor world = light_directional_split(pl, nw);
      double nd[3], len = 0;
      for (int r = 0; r < 3; ++r) {
        nd[r] = (cof[r][0] * n.x + cof[r][1] * n.y + cof[r][2] * n.z) * (back ? -1 : 1);
        len += nd[r] * nd[r];
      }
      len = std::sqrt(len);
      double prim[3] = {double(pl.base[0]), double(pl.base[1]), double(pl.base[2])};
      double spec[3] = {0, 0, 0};
      for (int li = 0; li < pl.count; ++li) {
        const PreparedLighting::Light& L = pl.lights[static_cast<size_t>(li)];
        const double ndl = (nd[0] * L.l.x + nd[1] * L.l.y + nd[2] * L.l.z) / len / 1073741824.0;
        if (ndl <= 0) continue;
        const double ndh = (nd[0] * L.h.x + nd[1] * L.h.y + nd[2] * L.h.z) / len / 1073741824.0;
        const double sp = ndh > 0 ? std::pow(ndh, pl.shininess_q8 / 256.0) : 0.0;
        for (int c = 0; c < 3; ++c) {
          prim[c] += ndl * L.kd[c];
          spec[c] += sp * L.ks[c];
        }
      }
      for (int c = 0; c < 3; ++c) {
        const double p = std::min(prim[c], 32768.0), q = std::min(spec[c], 32768.0);
        worst_fast = std::max({worst_fast, std::abs(channel(fast.primary, c) - p),
                               std::abs(channel(fast.secondary, c) - q)});
        worst_world = std::max({worst_world, std::abs(channel(world.primary, c) - p),
                                std::abs(channel(world.secondary, c) - q)});
      }
    }
  }
  std::printf("lights in model space: worst channel error %.2f / 2^15 (world space: %.2f)\n",
              worst_fast, worst_world);
  EXPECT_LE(worst_fast, 4.0);
  EXPECT_LE(worst_fast, worst_world + 1.0);
  EXPECT_FALSE(unit_normal(Normal16{8192, 0, 0}));
  EXPECT_FALSE(unit_normal(Normal16{16384, 16384, 0}));
  EXPECT_FALSE(unit_normal(Normal16{-32768, -32768, -32768}));
  EXPECT_TRUE(unit_normal(Normal16{0, -16384, 0}));
  // A non-uniform scale is not rigid: no model-space lights.
  const Camera cam;
  const Mat4 squash = scale(Vec3{fx(1), fx(2), fx(1)});
  ObjectLights ol;
  EXPECT_FALSE(VertexStage(cam, squash, GuardBand{1, 1}, 64, 64)
                   .object_lights(prepare_lighting(set, m, {{}, {}, Fixed::from_int(1)}, {}), ol));
}

// The one-light loop's copy of the light (OneDiffuseLight, FrontEnd::light_list) against the
// general diffuse path (light_object_diffuse), exactly: random directions, light and material
// colours (sums past 1, clamped, included) and unit normals, lit and unlit sides.
TEST(ObjectLights, OneDiffuseLightEqualsTheGeneralPath) {
  std::mt19937 rng(36);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> c15(0, Color15::kOne);
  auto fx = [](double v) { return Fixed::from_raw(static_cast<int32_t>(std::lround(v * 65536))); };
  auto color = [&] {
    return Color15{static_cast<uint16_t>(c15(rng)), static_cast<uint16_t>(c15(rng)),
                   static_cast<uint16_t>(c15(rng))};
  };
  int lit = 0, unlit = 0, clamped = 0, never_clamps = 0;
  for (int set_i = 0; set_i < 200; ++set_i) {
    LightSet set;
    set.count = 1;
    set.lights[0] = Light::directional({fx(u(rng)), fx(u(rng)), fx(u(rng) + 1e-3)}, color());
    set.global_ambient = color();
    Material m;
    m.ambient = color();
    m.diffuse = color();
    m.emission = set_i % 4 == 0 ? color() : Color15{0, 0, 0};
    const PreparedLighting pl = prepare_lighting(set, m, {{}, {}, Fixed::from_int(1)}, {});
    const Mat4 model = rotate_z(fx(180 * u(rng))) * rotate_y(fx(180 * u(rng))) *
                       rotate_x(fx(180 * u(rng))) * scale(fx(0.5 + std::abs(u(rng)) * 2));
    const VertexStage stage(Camera{}, model, GuardBand{1, 1}, 64, 64);
    ObjectLights ol;
    ASSERT_TRUE(stage.object_lights(pl, ol));
    ASSERT_EQ(ol.count, 1);
    ASSERT_FALSE(ol.specular);
    const OneDiffuseLight one(pl, ol);
    for (int i = 0; i < 200; ++i) {
      const double off = (i % 3 == 0 ? 0.0 : i % 3 == 1 ? 0.9 : -0.9) / 8192;
      const Normal16 n = unit_normal16(u(rng), u(rng), u(rng) + 1e-3, 1.0 + off);
      const uint32_t len2 = normal_len2(n);
      if (!unit_len2(len2)) continue;
      const Color15 general = light_object_diffuse(pl, ol, n, len2);
      const Color15 fast = one(n, len2);
      ASSERT_EQ(fast.r, general.r) << set_i << " " << i;
      ASSERT_EQ(fast.g, general.g) << set_i << " " << i;
      ASSERT_EQ(fast.b, general.b) << set_i << " " << i;
      if (one.never_clamps()) {
        const Color15 unclamped = one.operator()<false>(n, len2);
        ASSERT_EQ(unclamped, general) << set_i << " " << i;
        ++never_clamps;
      }
      uint32_t prim[3];
      int32_t ndl[kMaxLights];
      object_diffuse(pl, ol, n.x, n.y, n.z, inverse_length(len2), prim, ndl);
      (ndl[0] > 0 ? lit : unlit) += 1;
      clamped += (prim[0] > Color15::kOne || prim[1] > Color15::kOne || prim[2] > Color15::kOne);
    }
  }
  // Every case taken: lit and unlit sides, sums past 1, lights that never clamp.
  EXPECT_GT(lit, 1000);
  EXPECT_GT(unlit, 1000);
  EXPECT_GT(clamped, 1000);
  EXPECT_GT(never_clamps, 1000);
}

// OneDiffuseLight::never_clamps at its edge: materials whose ambient plus diffuse lies within a
// few hundred units of 1 either side, normals along the light rounded every way to Q1.14 at
// lengths across the unit range (the largest N.L). Where never_clamps holds, the loop without the
// clamps gives the general path's colour; it holds for most materials below 1, none past it.
TEST(ObjectLights, OneDiffuseLightLeavesOutTheClampsOnlyWhereNoSumPassesOne) {
  std::mt19937 rng(3601);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto fx = [](double v) { return Fixed::from_raw(static_cast<int32_t>(std::lround(v * 65536))); };
  const auto gray = [](int v) {
    const auto c = static_cast<uint16_t>(v);
    return Color15{c, c, c};
  };
  int unclamped_cases = 0, refused_cases = 0, max_excess = -1;
  for (const int ambient : {0, 1000, 8000})
    for (int delta = -8; delta <= 200; ++delta) {
      const int diffuse = std::clamp(Color15::kOne - ambient - delta, 0, int{Color15::kOne});
      const double lx = 0.3 * u(rng), ly = 0.3 * u(rng), lz = 1.0;
      LightSet set;
      set.count = 1;
      set.lights[0] = Light::directional({fx(lx), fx(ly), fx(lz)}, gray(Color15::kOne));
      set.global_ambient = gray(Color15::kOne);
      Material m;
      m.ambient = gray(ambient);
      m.diffuse = gray(diffuse);
      const PreparedLighting pl = prepare_lighting(set, m, {{}, {}, Fixed::from_int(1)}, {});
      const VertexStage stage(Camera{}, Mat4::identity(), GuardBand{1, 1}, 64, 64);
      ObjectLights ol;
      ASSERT_TRUE(stage.object_lights(pl, ol));
      const OneDiffuseLight one(pl, ol);
      if (!one.never_clamps()) {
        ++refused_cases;
        continue;
      }
      ++unclamped_cases;
      const double norm = std::sqrt(lx * lx + ly * ly + lz * lz);
      for (int i = 0; i < 8 * 9; ++i) {
        const double s = 16384.0 / norm * (1.0 + (i / 8 - 4) * 0.25 / 8192);
        auto q = [&](double v, int bit) {
          return static_cast<int16_t>(i >> bit & 1 ? std::ceil(v * s) : std::floor(v * s));
        };
        const Normal16 n{q(lx, 0), q(ly, 1), q(lz, 2)};
        const uint32_t len2 = normal_len2(n);
        if (!unit_len2(len2)) continue;
        const Color15 general = light_object_diffuse(pl, ol, n, len2);
        const Color15 unclamped = one.operator()<false>(n, len2);
        ASSERT_EQ(unclamped, general) << ambient << " " << delta << " " << i;
        max_excess = std::max(max_excess, unclamped.r - (one.base[0] + one.kd[0]));
      }
    }
  EXPECT_GT(unclamped_cases, 100);
  EXPECT_GT(refused_cases, 30);
  // The sums reach base + kd (N.L times 1 / |n| reaches 1 here, not the bound's 1 + 2^-10).
  EXPECT_GE(max_excess, 0);
}

// A vertex lit by a point light reads its world position: the point routine (light_point_at)
// lights model * p, so a moved model changes the colour as moving the mesh would; a face (its
// world centroid given) is lit where it is.
TEST(VertexLighting, PointLitVertexIsLitAtItsWorldPosition) {
  Camera camera;
  ASSERT_TRUE(perspective(Fixed::from_int(60), Fixed::from_int(1), Fixed::from_double(0.5),
                          Fixed::from_int(50), camera.projection));
  const Mat4 model = translate({Fixed::from_int(3), Fixed::from_int(-1), Fixed::from_int(-6)});
  const std::vector<Vec3> positions = {{Fixed::from_double(0.5), Fixed{}, Fixed{}}};
  const std::vector<Normal16> normals = {{0, 0, 16384}};
  Mesh mesh{};
  mesh.positions = positions;
  mesh.normals = normals;
  LightSet set;
  set.lights[0] = Light::point({Fixed::from_int(2), Fixed::from_int(0), Fixed::from_int(-4)},
                               {30000, 26000, 20000}, Fixed::from_int(1), Fixed::from_double(0.5));
  set.count = 1;
  Material m;
  m.diffuse = {26000, 24000, 22000};
  m.specular = {12000, 12000, 12000};
  m.shininess_q8 = 16 * 256;
  const PreparedLighting pl = prepare_lighting(set, m, {Fixed{}, Fixed{}, Fixed::from_int(1)}, {});
  ASSERT_TRUE(pl.needs_position());
  const VertexStage stage(camera, model, GuardBand{}, 64, 64);
  VertexColors colors;
  colors.lit = true;
  colors.pending = true;
  colors.split = true;
  colors.need_position = true;
  colors.lighting = &pl;
  colors.point = &light_point_at;
  const Unit30 n = stage.world_normal(normals[0]);
  const Vec3 world = transform_affine(model, positions[0]);
  const LitColor want = light_point_split(pl, n, world);
  const LitColor got = VertexStage::light(stage, mesh, colors, 0, false);
  EXPECT_EQ(got.primary, want.primary);
  EXPECT_EQ(got.secondary, want.secondary);
  // Not the colour at the model-space position: the test tells the two apart.
  EXPECT_NE(light_point_split(pl, n, positions[0]).primary, want.primary);
  EXPECT_EQ(light_point_at(pl, n, nullptr, world).primary, want.primary);
  EXPECT_EQ(light_point_at(pl, n, &model, positions[0]).secondary, want.secondary);
}

// ---- Fine transforms (Mesh::position_frac, FineMat4: docs/numerics.md#fine-transforms) ------

// The projected vertices of a draw: out[i] for positions[i] (frac fraction bits).
std::vector<ScreenVertex> transform_all(const Camera& cam, const Mat4& model,
                                        const FineMat4* fine_model,
                                        const std::vector<Vec3>& positions, int frac) {
  Mesh mesh;
  mesh.positions = positions;
  mesh.position_frac = static_cast<uint8_t>(frac);
  const VertexStage stage(cam, model, GuardBand{25, 34}, 320, 240,
                          position_bound(positions.data(), positions.size()), frac, fine_model,
                          &fine_model_view_projection);
  std::vector<ScreenVertex> out(positions.size());
  stage.transform(mesh, VertexColors{}, out.data(), nullptr, nullptr);
  return out;
}

// A mesh's fraction count is an exponent: the same positions in Q16.16 and, 14 bits finer, in
// Q2.30 (position_frac 30) project to the same vertices on both paths (the short path's factors
// take the exponent, the exact path's clip coordinates the shift): x, y, z, w and outcode.
// Positions from behind the eye to beyond the far plane, so that both paths and every plane
// are taken.
TEST(FineTransforms, PositionFracIsAnExponentOfTheSameVertices) {
  Camera cam;
  ASSERT_TRUE(perspective(Fixed::from_int(60), Fixed::ratio(4, 3), Fixed::from_int(1),
                          Fixed::from_int(10), cam.projection));
  std::mt19937_64 rng(30);
  for (const double tz : {-2.45, -1.2, -9.5}) {
    const Mat4 model =
        translate({{}, {}, Fixed::from_raw(static_cast<int32_t>(std::llround(tz * 65536)))}) *
        rotate_y(Fixed::from_int(20));
    std::vector<Vec3> q16, q30;
    for (int i = 0; i < 4000; ++i) {
      auto c = [&] { return static_cast<int32_t>(rng() % 131073) - 65536; };  // [-1, 1]
      const int32_t x = c(), y = c(), z = c();
      q16.push_back({Fixed::from_raw(x), Fixed::from_raw(y), Fixed::from_raw(z)});
      q30.push_back(
          {Fixed::from_raw(x * 16384), Fixed::from_raw(y * 16384), Fixed::from_raw(z * 16384)});
    }
    const std::vector<ScreenVertex> a = transform_all(cam, model, nullptr, q16, 16);
    const std::vector<ScreenVertex> b = transform_all(cam, model, nullptr, q30, 30);
    size_t outside = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(a[i].outcode, b[i].outcode) << tz << " " << i;
      outside += a[i].outcode != 0;
      if (a[i].outcode != 0) continue;
      ASSERT_EQ(a[i].x, b[i].x) << tz << " " << i;
      ASSERT_EQ(a[i].y, b[i].y) << tz << " " << i;
      ASSERT_EQ(a[i].z, b[i].z) << tz << " " << i;
      ASSERT_EQ(a[i].w, b[i].w) << tz << " " << i;
    }
    if (tz == -1.2) {
      EXPECT_GT(outside, 100u);  // (near the eye: the near plane cuts the cube)
    }
  }
}

// Fine transforms snap the peer draw's vertices as the double scene does: the bunny's
// matrices (perspective_fine with the viewport's ratio, the model of rotate_y_fine and a Q4.28
// translation) and positions in Q1.30 give every vertex within 2^-8 subpixel beyond half a
// subpixel of the double scene's exact quotient; the Q16.16 draw (perspective with the Q16.16
// aspect, rotate_y, Q16.16 positions) is up to about a third of a subpixel beyond it.
TEST(FineTransforms, PeerDrawSnapsAsTheDoubleScene) {
  const double kPi = 3.14159265358979323846;
  const double tz = -2.45, ry = 20.0 * kPi / 180, f = 1 / std::tan(30.0 * kPi / 180);
  auto exact = [&](const std::array<double, 3>& p) {
    const double x = std::cos(ry) * p[0] + std::sin(ry) * p[2];
    const double z = -std::sin(ry) * p[0] + std::cos(ry) * p[2] + tz;
    const double w = -z;
    return std::array<double, 2>{320 * 128.0 * (1 + f * 0.75 * x / w),
                                 240 * 128.0 * (1 - f * p[1] / w)};
  };
  std::mt19937_64 rng(36);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::array<double, 3>> pd;
  std::vector<Vec3> q16, q30;
  for (int i = 0; i < 5000; ++i) {
    const std::array<double, 3> p{u(rng), u(rng), u(rng)};
    pd.push_back(p);
    auto r = [](double v, int frac) {
      return Fixed::from_raw(static_cast<int32_t>(std::llround(std::ldexp(v, frac))));
    };
    q16.push_back({r(p[0], 16), r(p[1], 16), r(p[2], 16)});
    q30.push_back({r(p[0], 30), r(p[1], 30), r(p[2], 30)});
  }
  Camera coarse;
  ASSERT_TRUE(perspective(Fixed::from_int(60), Fixed::ratio(320, 240), Fixed::from_int(1),
                          Fixed::from_int(10), coarse.projection));
  const Mat4 model =
      translate({{}, {}, Fixed::from_raw(static_cast<int32_t>(std::llround(tz * 65536)))}) *
      rotate_y(Fixed::from_int(20));
  Camera fine;
  FineMat4 fine_projection{};
  ASSERT_TRUE(perspective_fine(Fixed::from_int(60), 320, 240, Fixed::from_int(1),
                               Fixed::from_int(10), fine_projection));
  fine.fine_projection = &fine_projection;
  fine.projection = to_mat4(fine_projection);
  const FineMat4 fine_model =
      translate_fine(0, 0, static_cast<int32_t>(std::llround(tz * (1 << 28))), 28) *
      rotate_y_fine(Fixed::from_int(20));
  const std::vector<ScreenVertex> a = transform_all(coarse, model, nullptr, q16, 16);
  const std::vector<ScreenVertex> b =
      transform_all(fine, to_mat4(fine_model), &fine_model, q30, 30);
  double worst_coarse = 0, worst_fine = 0;
  for (size_t i = 0; i < pd.size(); ++i) {
    ASSERT_EQ(a[i].outcode, 0);
    ASSERT_EQ(b[i].outcode, 0);
    const auto e = exact(pd[i]);
    worst_coarse =
        std::max({worst_coarse, std::abs(a[i].x - e[0]) - 0.5, std::abs(a[i].y - e[1]) - 0.5});
    worst_fine =
        std::max({worst_fine, std::abs(b[i].x - e[0]) - 0.5, std::abs(b[i].y - e[1]) - 0.5});
  }
  std::printf("peer draw, beyond half a subpixel of the double scene: Q16.16 %.4f, fine %.5f\n",
              worst_coarse, worst_fine);
  EXPECT_LE(worst_fine, 1.0 / 256);
  EXPECT_GT(worst_coarse, 0.1);
}

// The model-view-projection is today's Q16.16 product unless the draw's model is a FineMat4
// (a camera's fine_projection alone changes nothing); with one, P (V M) in FineMat4 products, P
// the fine projection when the camera has one.
TEST(FineTransforms, ModelViewProjectionIsQ16UnlessTheModelIsFine) {
  Camera cam;
  FineMat4 fine_projection{};
  ASSERT_TRUE(perspective(Fixed::from_int(60), Fixed::ratio(4, 3), Fixed::from_int(1),
                          Fixed::from_int(10), cam.projection));
  ASSERT_TRUE(perspective_fine(Fixed::from_int(60), 4, 3, Fixed::from_int(1), Fixed::from_int(10),
                               fine_projection));
  cam.fine_projection = &fine_projection;
  const Mat4 model = translate({{}, {}, Fixed::from_raw(-160563)}) * rotate_y(Fixed::from_int(20));
  EXPECT_EQ(VertexStage::model_view_projection(cam, model, nullptr),
            to_fine(cam.projection * cam.view * model));
  const FineMat4 fm = to_fine(model);
  const FineMat4 fine = VertexStage::model_view_projection(cam, model, &fm);
  EXPECT_EQ(fine, fine_projection * (to_fine(cam.view) * fm));
  EXPECT_GT(fine.frac, 16);
  Camera coarse = cam;
  coarse.fine_projection = nullptr;
  EXPECT_EQ(VertexStage::model_view_projection(coarse, model, &fm),
            to_fine(cam.projection) * (to_fine(cam.view) * fm));
}

}  // namespace
}  // namespace lr
