// Fixed-point math against double: trig, normalisation, camera matrices, specular power table,
// the material table as published, colour conversions.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdio>
#include <vector>

#include "lineraster/core/binning/edge_table.hpp"
#include "lineraster/core/math/divide.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/math/pow_table.hpp"
#include "lineraster/core/math/reciprocal.hpp"
#include "lineraster/core/math/saturate.hpp"
#include "lineraster/core/math/trig.hpp"
#include "lineraster/core/math/vec.hpp"
#include "lineraster/core/math/wide_divide.hpp"
#include "lineraster/core/math/wide_mul.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/raster/strip_fill.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/setup/row_edge.hpp"
#include "lineraster/core/setup/triangle_rows.hpp"

namespace lr {
namespace {

double d(Fixed f) {
  return f.raw / 65536.0;
}
Fixed fx(double v) {
  return Fixed::from_raw(static_cast<int32_t>(std::lround(v * 65536.0)));
}
constexpr double kPi = 3.14159265358979323846;

TEST(Trig, SinCosWithinHalfAUnitOfQ16Everywhere) {
  double worst = 0;
  for (int i = -720 * 16; i <= 720 * 16; ++i) {
    Fixed a = Fixed::from_raw(i * 4096);  // 1/16 degree steps over two turns each way
    double rad = i / 16.0 * kPi / 180.0;
    worst = std::max(worst, std::fabs(d(sin_deg(a)) - std::sin(rad)));
    worst = std::max(worst, std::fabs(d(cos_deg(a)) - std::cos(rad)));
  }
  EXPECT_LT(worst, 1.0 / 65536.0);  // under one Q16.16 unit
  EXPECT_EQ(sin_deg(Fixed::from_int(90)).raw, 65536);
  EXPECT_EQ(sin_deg(Fixed::from_int(180)).raw, 0);
  EXPECT_EQ(cos_deg(Fixed::from_int(0)).raw, 65536);
  EXPECT_EQ(sin_deg(Fixed::from_int(-90)).raw, -65536);
}

TEST(Vec, NormalizeIsUnitWithinTwoQ30Units) {
  uint32_t seed = 12345;
  auto rnd = [&]() {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<int32_t>(seed >> 1) - (1 << 30);
  };
  for (int i = 0; i < 2000; ++i) {
    int64_t x = rnd() >> (i % 30), y = rnd() >> (i % 17), z = rnd() >> (i % 5);
    Unit30 u;
    ASSERT_TRUE(normalize_unit30(x, y, z, u));
    double len = std::sqrt(double(u.x) * u.x + double(u.y) * u.y + double(u.z) * u.z) / (1 << 30);
    EXPECT_NEAR(len, 1.0, 4.0 / (1 << 30));
    const double dx = double(x), dy = double(y), dz = double(z);
    double n = std::sqrt(dx * dx + dy * dy + dz * dz);
    EXPECT_NEAR(u.x / double(1 << 30), dx / n, 3e-9);
  }
  Unit30 u;
  EXPECT_FALSE(normalize_unit30(0, 0, 0, u));
}

// The previous sin_deg and perspective, with C's 64-bit divisions: the references of the
// current ones (64-by-32 divisions, no C library 64-bit division), which give the same integers.
int32_t reference_sin_deg(int32_t raw) {
  constexpr int64_t kQuarter = int64_t{90} << Fixed::kFracBits;
  int64_t a = raw % (4 * kQuarter);
  if (a < 0) a += 4 * kQuarter;
  int32_t sign = 1;
  if (a >= 2 * kQuarter) {
    a -= 2 * kQuarter;
    sign = -1;
  }
  if (a > kQuarter) a = 2 * kQuarter - a;
  const int64_t pos = a * detail::kTrigSteps * Fixed::kOne / kQuarter;
  const auto i = static_cast<size_t>(pos >> Fixed::kFracBits);
  const int64_t frac = pos & (Fixed::kOne - 1);
  const int64_t s0 = detail::kSinTable[i];
  const int64_t s1 =
      i + 1 <= static_cast<size_t>(detail::kTrigSteps) ? detail::kSinTable[i + 1] : s0;
  const int64_t v = s0 + (((s1 - s0) * frac) >> Fixed::kFracBits);
  return sign * static_cast<int32_t>(round_shift(v, 30 - Fixed::kFracBits));
}

bool reference_perspective(Fixed fovy, Fixed aspect, Fixed near, Fixed far, Mat4& out) {
  if (fovy.raw <= 0 || fovy >= Fixed::from_int(180)) return false;
  if (aspect.raw <= 0 || near.raw <= 0 || far <= near) return false;
  const Fixed half{fovy.raw / 2};
  const int64_t s = sin_deg(half).raw, c = cos_deg(half).raw;
  if (s <= 0) return false;
  const int64_t f = round_div(c * Fixed::kOne, s);
  Mat4 m{};
  m.m[0][0] = Fixed::from_raw(saturate32(round_div(f * Fixed::kOne, aspect.raw)));
  m.m[1][1] = Fixed::from_raw(saturate32(f));
  const int64_t n = near.raw, fa = far.raw, dd = n - fa;
  m.m[2][2] = Fixed::from_raw(saturate32(round_div(-(fa + n) * Fixed::kOne, -dd)));
  m.m[2][3] = Fixed::from_raw(saturate32(round_div(-2 * fa * n, -dd)));
  m.m[3][2] = Fixed::from_int(-1);
  out = m;
  return true;
}

TEST(Trig, SinEqualsTheSixtyFourBitDivisionForm) {
  // Every raw angle in [-2^20, 2^20] (16 degrees each way), random ones and the extremes.
  for (int32_t raw = -(1 << 20); raw <= (1 << 20); ++raw)
    ASSERT_EQ(sin_deg(Fixed::from_raw(raw)).raw, reference_sin_deg(raw)) << raw;
  uint64_t x = 0x3C6EF372FE94F82Bu;
  for (int i = 0; i < 1000000; ++i) {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    const auto raw = static_cast<int32_t>(static_cast<uint32_t>(x));
    ASSERT_EQ(sin_deg(Fixed::from_raw(raw)).raw, reference_sin_deg(raw)) << raw;
  }
  for (int32_t raw : {INT32_MIN, INT32_MIN + 1, INT32_MAX, INT32_MAX - 1})
    EXPECT_EQ(sin_deg(Fixed::from_raw(raw)).raw, reference_sin_deg(raw)) << raw;
}

// Every matrix entry of the previous form, for every combination of arguments at the ends of
// their ranges (fields of view down to a few units, which saturate f and the x scale; near and
// far close together or 2^31 apart, which saturate the depth terms) and for random ones.
TEST(Camera, PerspectiveEqualsTheSixtyFourBitDivisionForm) {
  const int32_t fovs[] = {
      1, 2, 3, 4, 7, 64, 100, 114, 120, 200, 1000, 65536, 30 << 16, 45 << 16, (180 << 16) - 1};
  const int32_t aspects[] = {1, 2, 3, 255, 65536, 87381, 1 << 24, INT32_MAX};
  const int32_t depths[] = {1, 2, 3, 6554, 65536, 1 << 20, 1 << 30, INT32_MAX - 1, INT32_MAX};
  int compared = 0;
  auto check = [&compared](int32_t fov_raw, int32_t aspect_raw, int32_t a, int32_t b) {
    const Fixed fov = Fixed::from_raw(fov_raw), asp = Fixed::from_raw(aspect_raw);
    const Fixed nr = Fixed::from_raw(std::min(a, b)), fr = Fixed::from_raw(std::max(a, b));
    Mat4 got{}, want{};
    const bool ok = perspective(fov, asp, nr, fr, got);
    ASSERT_EQ(ok, reference_perspective(fov, asp, nr, fr, want));
    if (!ok) return;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(got.m[r][c].raw, want.m[r][c].raw)
            << fov_raw << " " << aspect_raw << " " << nr.raw << " " << fr.raw << " [" << r << "]["
            << c << "]";
    ++compared;
  };
  for (int32_t fov : fovs)
    for (int32_t aspect : aspects)
      for (int32_t a : depths)
        for (int32_t b : depths)
          if (a < b) check(fov, aspect, a, b);
  uint64_t x = 0xA54FF53A5F1D36F1u;
  auto next = [&x] {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  };
  for (int i = 0; i < 100000; ++i) {
    const auto fov = static_cast<int32_t>(next() % (180u << 16));
    const auto aspect = static_cast<int32_t>(next() >> (33 + next() % 31));
    const auto a = static_cast<int32_t>(next() >> (33 + next() % 31));
    const auto b = static_cast<int32_t>(next() >> (33 + next() % 31));
    if (a != b) check(fov, aspect, a, b);
  }
  EXPECT_GT(compared, 90000);
}

// gluPerspective, written out.
TEST(Camera, PerspectiveMatchesGluPerspective) {
  Mat4 m;
  ASSERT_TRUE(
      perspective(Fixed::from_int(60), Fixed::ratio(320, 240), fx(0.1), Fixed::from_int(100), m));
  double f = 1.0 / std::tan(30.0 * kPi / 180.0);
  double n = d(fx(0.1)), fa = 100;
  EXPECT_NEAR(d(m.m[0][0]), f / (4.0 / 3.0), 2e-5);
  EXPECT_NEAR(d(m.m[1][1]), f, 2e-5);
  EXPECT_NEAR(d(m.m[2][2]), (fa + n) / (n - fa), 2e-5);
  EXPECT_NEAR(d(m.m[2][3]), 2 * fa * n / (n - fa), 2e-5);
  EXPECT_EQ(m.m[3][2].raw, -65536);
  EXPECT_EQ(m.m[3][3].raw, 0);
  EXPECT_EQ(m.m[0][1].raw, 0);
  EXPECT_FALSE(
      perspective(Fixed::from_int(0), Fixed::from_int(1), fx(0.1), Fixed::from_int(10), m));
  EXPECT_FALSE(perspective(Fixed::from_int(60), Fixed::from_int(1), Fixed::from_int(10),
                           Fixed::from_int(1), m));
  EXPECT_FALSE(
      perspective(Fixed::from_int(180), Fixed::from_int(1), fx(0.1), Fixed::from_int(10), m));
}

TEST(Camera, LookAtMatchesGluLookAt) {
  Vec3 eye{fx(1), fx(2), fx(3)}, target{fx(0), fx(0.5), fx(0)}, up{fx(0), fx(1), fx(0)};
  Mat4 m;
  ASSERT_TRUE(look_at(eye, target, up, m));
  // gluLookAt: f = normalize(target - eye), s = normalize(f x up), u = s x f.
  double F[3] = {-1, -1.5, -3}, fl = std::sqrt(1 + 2.25 + 9);
  for (double& v : F) v /= fl;
  double S[3] = {F[1] * 0 - F[2] * 1, F[2] * 0 - F[0] * 0, F[0] * 1 - F[1] * 0};
  double sl = std::sqrt(S[0] * S[0] + S[1] * S[1] + S[2] * S[2]);
  for (double& v : S) v /= sl;
  double U[3] = {S[1] * F[2] - S[2] * F[1], S[2] * F[0] - S[0] * F[2], S[0] * F[1] - S[1] * F[0]};
  const double* rows[3] = {S, U, F};
  double E[3] = {1, 2, 3};
  for (int i = 0; i < 3; ++i) {
    double sign = i == 2 ? -1 : 1;
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(d(m.m[i][j]), sign * rows[i][j], 3e-5) << i << "," << j;
    double t = -sign * (rows[i][0] * E[0] + rows[i][1] * E[1] + rows[i][2] * E[2]);
    EXPECT_NEAR(d(m.m[i][3]), t, 1e-4);
  }
  EXPECT_FALSE(look_at(eye, eye, up, m));
  EXPECT_FALSE(look_at(Vec3{}, Vec3{fx(0), fx(5), fx(0)}, up, m));  // up parallel to view
}

TEST(Camera, TransformPointAgreesWithDouble) {
  Mat4 p, v;
  ASSERT_TRUE(
      perspective(Fixed::from_int(45), Fixed::from_int(1), fx(0.5), Fixed::from_int(50), p));
  ASSERT_TRUE(look_at({fx(0), fx(0), fx(5)}, {}, {fx(0), fx(1), fx(0)}, v));
  Mat4 mvp = p * v * rotate_y(Fixed::from_int(30));
  Vec3 pt{fx(0.5), fx(-0.25), fx(1.0)};
  ClipCoord c = transform_point(mvp, pt);
  // Same in double.
  double a = 30 * kPi / 180, x = 0.5 * std::cos(a) + 1.0 * std::sin(a), y = -0.25,
         z = -0.5 * std::sin(a) + 1.0 * std::cos(a) - 5;
  double f = 1 / std::tan(22.5 * kPi / 180), n = 0.5, fa = 50;
  double cx = f * x, cy = f * y, cz = (fa + n) / (n - fa) * z + 2 * fa * n / (n - fa), cw = -z;
  double s = 1.0 / (1 << 28);
  EXPECT_NEAR(double(c.x) * s, cx, 1e-4);
  EXPECT_NEAR(double(c.y) * s, cy, 1e-4);
  EXPECT_NEAR(double(c.z) * s, cz, 2e-4);
  EXPECT_NEAR(double(c.w) * s, cw, 1e-4);
}

// ---- Fine transforms (docs/numerics.md#fine-transforms) --------------------------------------

// sin_cos_q30 within 3 units of 2^-30 of the exact values over two turns either way (the
// Q16.16 sin_deg is within half a unit of 2^-16), and exact at the quarter turns.
TEST(FineMath, SinCosQ30WithinThreeUnitsOfTwoToTheMinus30) {
  double worst = 0;
  for (int32_t raw = -720 * 65536; raw <= 720 * 65536; raw += 24571) {
    const SinCos30 sc = sin_cos_q30(Fixed::from_raw(raw));
    const double a = raw / 65536.0 * kPi / 180;
    worst = std::max({worst, std::abs(sc.sin - std::ldexp(std::sin(a), 30)),
                      std::abs(sc.cos - std::ldexp(std::cos(a), 30))});
  }
  for (const int deg : {20, 30, 45, 60, -20, 135, 359}) {
    const SinCos30 sc = sin_cos_q30(Fixed::from_int(deg));
    const double a = deg * kPi / 180;
    worst = std::max({worst, std::abs(sc.sin - std::ldexp(std::sin(a), 30)),
                      std::abs(sc.cos - std::ldexp(std::cos(a), 30))});
  }
  std::printf("sin_cos_q30: worst %.2f units of 2^-30\n", worst);
  EXPECT_LE(worst, 3.0);
  const int32_t one = 1 << 30;
  for (const auto& [deg, s, c] :
       {std::array{0, 0, one}, std::array{90, one, 0}, std::array{180, 0, -one},
        std::array{270, -one, 0}, std::array{-90, -one, 0}}) {
    const SinCos30 sc = sin_cos_q30(Fixed::from_int(deg));
    EXPECT_EQ(sc.sin, s) << deg;
    EXPECT_EQ(sc.cos, c) << deg;
  }
}

// FineMat4 products: rounded once to the finest count the entries allow, within a unit of it of
// the exact product; Q16.16 matrices through the fine forms give the Q16.16 integers back.
TEST(FineMath, ProductKeepsTheFinestFractionCount) {
  const int32_t tz = static_cast<int32_t>(std::llround(-2.45 * (1 << 28)));
  const FineMat4 t = translate_fine(0, 0, tz, 28);
  const FineMat4 r = rotate_x_fine(Fixed::from_int(10)) * rotate_y_fine(Fixed::from_int(20));
  EXPECT_EQ(r.frac, 30);  // rotations: every entry below 1
  const FineMat4 m = t * r;
  EXPECT_EQ(m.frac, 29);  // -2.45: two integer bits and the sign (Q3.29 holds [-4, 4))
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double e = 0;
      for (int k = 0; k < 4; ++k)
        e += std::ldexp(t.m[i][k], -t.frac) * std::ldexp(r.m[k][j], -r.frac);
      EXPECT_LE(std::abs(m.m[i][j] - std::ldexp(e, 29)), 0.5 + 1e-6) << i << "," << j;
    }
  EXPECT_EQ(m.m[2][3], 2 * tz);  // exact
  // Entries beyond 2^15 cannot be finer than 16 bits: saturated there, as Mat4's product.
  FineMat4 big = translate_fine(0, 0, 0, 16);
  big.m[0][0] = 30000 << 16;
  EXPECT_EQ((big * big).frac, 16);
  EXPECT_EQ((big * big).m[0][0], INT32_MAX);
  // Q16.16 in, Q16.16 out.
  Mat4 p;
  ASSERT_TRUE(
      perspective(Fixed::from_int(45), Fixed::from_int(1), fx(0.5), Fixed::from_int(50), p));
  EXPECT_EQ(to_mat4(to_fine(p)), p);
  const Vec3 pt{fx(0.5), fx(-0.25), fx(1.0)};
  const ClipCoord a = transform_point(p, pt), b = transform_point(to_fine(p), pt, 16);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.z, b.z);
  EXPECT_EQ(a.w, b.w);
}

// perspective_fine: the aspect the viewport's ratio (exactly 4/3 here); the depth entries within
// a unit and a half of their fraction count of gluPerspective's (exact divisions, one rounding),
// f = cos / sin within 16 units of 2^-30 (sin_cos_q30's 3 units each, over sin(30) = 1/2); the
// same refusals as perspective().
TEST(Camera, PerspectiveFineMatchesGluPerspectiveWithTheViewportsRatio) {
  FineMat4 m{};
  ASSERT_TRUE(
      perspective_fine(Fixed::from_int(60), 320, 240, Fixed::from_int(1), Fixed::from_int(10), m));
  EXPECT_EQ(m.frac, 29);  // 2 far near / (far - near) = 2.22: two integer bits
  const double f = 1.0 / std::tan(30.0 * kPi / 180.0), n = 1, fa = 10;
  auto e = [&](int i, int j) { return std::ldexp(m.m[i][j], -m.frac); };
  const double unit = std::ldexp(1.0, -m.frac);
  EXPECT_NEAR(e(0, 0), f * 240 / 320, std::ldexp(16.0, -30));
  EXPECT_NEAR(e(1, 1), f, std::ldexp(16.0, -30));
  EXPECT_NEAR(e(2, 2), (fa + n) / (n - fa), 1.5 * unit);
  EXPECT_NEAR(e(2, 3), 2 * fa * n / (n - fa), 1.5 * unit);
  EXPECT_EQ(m.m[3][2], -(1 << 29));
  EXPECT_EQ(m.m[3][3], 0);
  EXPECT_EQ(m.m[0][1], 0);
  // The Q16.16 form of the ratio (4/3 rounded) is further off than this one.
  Mat4 q;
  ASSERT_TRUE(perspective(Fixed::from_int(60), Fixed::ratio(320, 240), Fixed::from_int(1),
                          Fixed::from_int(10), q));
  EXPECT_GT(std::abs(d(q.m[0][0]) - f * 0.75), std::abs(e(0, 0) - f * 0.75));
  // Larger entries, fewer bits: far 300, near 0.5 (the ground plane's).
  ASSERT_TRUE(perspective_fine(Fixed::from_int(60), 320, 240, fx(0.5), Fixed::from_int(300), m));
  EXPECT_EQ(m.frac, 30);
  EXPECT_FALSE(perspective_fine(Fixed::from_int(0), 320, 240, fx(0.1), Fixed::from_int(10), m));
  EXPECT_FALSE(perspective_fine(Fixed::from_int(180), 320, 240, fx(0.1), Fixed::from_int(10), m));
  EXPECT_FALSE(perspective_fine(Fixed::from_int(60), 0, 240, fx(0.1), Fixed::from_int(10), m));
  EXPECT_FALSE(
      perspective_fine(Fixed::from_int(60), 320, 240, Fixed::from_int(10), Fixed::from_int(1), m));
}

TEST(PowTable, DefaultTablesWithinTwoAndAQuarterQ15UnitsOfStdPow) {
  double worst = 0;
  for (int si = 0; si <= 128 * 4; ++si) {
    uint32_t s_q8 = static_cast<uint32_t>(si * 64);  // shininess in quarter steps
    double s = s_q8 / 256.0;
    for (int xi = 0; xi <= 4096; ++xi) {
      uint32_t x = static_cast<uint32_t>((static_cast<uint64_t>(xi) << 30) / 4096);
      double ref = std::pow(x / double(1 << 30), s) * 32768.0;
      double got = DefaultPowTable::pow_q15(x, s_q8);
      worst = std::max(worst, std::fabs(got - ref));
    }
  }
  EXPECT_LE(worst, 2.25);  // docs/numerics.md#specular-power-xs
  EXPECT_GT(worst, 0.5);   // the bound is tight: a broken table would not be this close
  EXPECT_EQ(DefaultPowTable::pow_q15(0, 0), 32768u);  // pow(0, 0) = 1
  EXPECT_EQ(DefaultPowTable::pow_q15(0, 256), 0u);
  EXPECT_EQ(DefaultPowTable::pow_q15(1u << 30, 128 * 256), 32768u);
}

TEST(Materials, TableHoldsThePublishedValues) {
  EXPECT_EQ(material_table().size(), 24u);
  const NamedMaterial* gold = find_material("gold");
  ASSERT_NE(gold, nullptr);
  EXPECT_EQ(gold->ambient[0], 24725000u);   // 0.24725
  EXPECT_EQ(gold->diffuse[1], 60648000u);   // 0.60648
  EXPECT_EQ(gold->specular[2], 36606500u);  // 0.366065
  Material m = to_material(*gold);
  EXPECT_EQ(m.shininess_q8, std::lround(51.2 * 256));  // 0.4 x 128 = 51.2
  EXPECT_EQ(m.diffuse.r, static_cast<uint16_t>(std::lround(0.75164 * 32768)));
  const NamedMaterial* brass = find_material("brass");
  ASSERT_NE(brass, nullptr);
  EXPECT_EQ(to_material(*brass).shininess_q8, std::lround(0.21794872 * 128 * 256));  // 27.9 x 256
  ASSERT_NE(find_material("black-plastic"), nullptr);
  EXPECT_EQ(find_material("black plastic"), find_material("black_plastic"));
  EXPECT_EQ(find_material("unobtainium"), nullptr);
  EXPECT_EQ(to_material(*find_material("yellow_rubber")).shininess_q8, 10 * 256);  // .078125 x 128
}

TEST(Color, ByteRoundingAndRgb565) {
  for (uint32_t v = 0; v <= 255; ++v) {
    EXPECT_EQ(to_byte(from_byte(static_cast<uint8_t>(v))), v);
    Rgb8 c{static_cast<uint8_t>(v), static_cast<uint8_t>(v), static_cast<uint8_t>(v)};
    uint16_t s = Rgb565Be::encode(c);
    const auto* bytes = reinterpret_cast<const uint8_t*>(&s);
    unsigned value = (unsigned{bytes[0]} << 8) | bytes[1];  // big-endian in memory
    EXPECT_EQ(value >> 11, (31 * v + 127) / 255);
    EXPECT_EQ((value >> 5) & 63, (63 * v + 127) / 255);
    EXPECT_EQ(value & 31, (31 * v + 127) / 255);
  }
  EXPECT_EQ(to_byte(16384), 128);  // round(127.5) = 128
  EXPECT_EQ(to_byte(32768), 255);
  Rgb8 red = Rgb565Be::decode(Rgb565Be::encode({255, 0, 0}));
  EXPECT_EQ(red, (Rgb8{255, 0, 0}));
}

// encode15 (one table address, the green offset folded into the rounding) stores what encode
// of the rounded bytes stores, for every Q1.15 value of each channel with the others at 0 and 1.
TEST(Color, Encode15IsEncodeOfTheBytes) {
  int mismatches = 0;
  for (uint32_t v = 0; v <= Color15::kOne; ++v) {
    const uint8_t b = to_byte(v);
    for (uint32_t o : {0u, uint32_t{Color15::kOne}}) {
      const uint8_t ob = to_byte(o);
      mismatches += Rgb565Be::encode15(v, o, o) != Rgb565Be::encode({b, ob, ob});
      mismatches += Rgb565Be::encode15(o, v, o) != Rgb565Be::encode({ob, b, ob});
      mismatches += Rgb565Be::encode15(o, o, v) != Rgb565Be::encode({ob, ob, b});
      mismatches += Rgb888::encode15(v, o, v) != (Rgb8{b, ob, b});
    }
  }
  EXPECT_EQ(mismatches, 0);
}

// usat_asr against the clamp it stands for, at the bounds and on a sweep of int32.
TEST(Saturate, UsatAsrIsTheClampOfTheShift) {
  auto clamp = [](int32_t v) {
    const int32_t x = v >> 15;
    return static_cast<uint32_t>(std::clamp(x, 0, 32767));
  };
  const int32_t edges[] = {INT32_MIN,         -1,          0,        1, 32767 << 15,
                           (32768 << 15) - 1, 32768 << 15, INT32_MAX};
  for (int32_t v : edges) EXPECT_EQ((usat_asr<15, 15>(v)), clamp(v)) << v;
  int mismatches = 0;
  for (int64_t v = INT32_MIN; v <= INT32_MAX; v += 65521)
    mismatches += usat_asr<15, 15>(static_cast<int32_t>(v)) != clamp(static_cast<int32_t>(v));
  EXPECT_EQ(mismatches, 0);
  static_assert(usat_asr<15, 15>(-5) == 0 && usat_asr<15, 15>(INT32_MAX) == 32767);
}

}  // namespace
}  // namespace lr

namespace lr {
namespace {

// Marsaglia's xorshift64: reproducible operands for the division tests.
struct XorShift64 {
  uint64_t s;
  uint64_t operator()() {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return s;
  }
};

// The reciprocal divider gives the quotient of a division, bit for bit: divisors of every bit
// length, numerators near 0, near multiples of d and up to 2^63 - 1.
TEST(Divide, QuotientEqualsDivisionForEveryRange) {
  XorShift64 next{0x9E3779B97F4A7C15u};
  uint64_t checked = 0;
  for (int bits = 1; bits <= 63; ++bits) {
    for (int k = 0; k < 2000; ++k) {
      uint64_t d = next() >> (64 - bits);
      if (d == 0) d = 1;
      const Divider div(d);
      const uint64_t n[] = {next() >> 1,
                            next() >> (1 + next() % 62),
                            (next() >> 1) / d * d,
                            (next() >> 1) / d * d - 1,
                            d - 1,
                            d,
                            0,
                            (uint64_t{1} << 63) - 1};
      for (uint64_t v : n) {
        if (v >= (uint64_t{1} << 63)) continue;
        ASSERT_EQ(div.quotient(v), v / d) << v << " / " << d;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 900000u);
}

// The normalised reciprocals equal the divisions they stand for, on the table path that cores
// without a divider take (every 16-bit divisor) as on the path this host takes.
TEST(Reciprocal, Recip16EqualsTheDivisionForEveryDivisor) {
  for (uint32_t d = 1u << 15; d < (1u << 16); ++d) {
    ASSERT_EQ(detail::recip16_table(d), 0xFFFFFFFFu / d) << d;
    ASSERT_EQ(recip16(d), 0xFFFFFFFFu / d) << d;
  }
}

TEST(Reciprocal, Recip32AndTheTwoByOneDivisionEqualTheDivisions) {
  XorShift64 next{0x2545F4914F6CDD1Du};
  auto check = [&](uint32_t d) {
    const uint32_t v = static_cast<uint32_t>(~uint64_t{0} / d - (uint64_t{1} << 32));
    ASSERT_EQ(detail::recip32_newton(d), v) << d;
    ASSERT_EQ(recip32(d), v) << d;
    const uint64_t n[] = {
        next() % (uint64_t{d} << 32),          (uint64_t{d} << 32) - 1, 0, d - 1u, d,
        (next() % (uint64_t{d} << 32)) / d * d};
    for (uint64_t x : n) {
      const Quotient32 qr = divide_2by1(x, d, v);
      ASSERT_EQ(qr.q, x / d) << x << " / " << d;
      ASSERT_EQ(qr.r, x % d) << x << " % " << d;
    }
  };
  for (uint32_t k = 0; k < 70000; ++k) {
    check((1u << 31) + k);   // the smallest divisors
    check(0xFFFFFFFFu - k);  // the largest
    check(static_cast<uint32_t>(next()) | (1u << 31));
    check(((0x8000u + (k % 0x8000u)) << 16) | (k & 1 ? 0xFFFFu : 0u));  // top-half boundaries
  }
}

// The 64-bit divisions in 32-bit pieces (core/math/wide_divide.hpp) equal C's: the 64-by-32
// division on the path 32-bit Arm takes (normalised 2-by-1 division, recip32_newton) for
// divisors of every bit length with numerators at the ends of its range (0, d - 1, d, d 2^32 - 1)
// and random below d 2^32; the 64-bit reciprocal for divisors of every bit length, both sides of
// 2^32 (its two ways) and the extremes.
TEST(WideDivide, SixtyFourBy32EqualsTheDivisionOnTheArmPath) {
  XorShift64 next{0x6A09E667F3BCC909u};
  uint64_t checked = 0;
  for (int bits = 1; bits <= 32; ++bits) {
    for (int k = 0; k < 3000; ++k) {
      auto d = static_cast<uint32_t>(next() >> (64 - bits));
      if (d == 0) d = 1;
      const uint64_t top = (uint64_t{d} << 32) - 1;  // the largest numerator allowed
      const uint64_t n[] = {0,
                            d - 1u,
                            d,
                            top,
                            next() % top,
                            (next() % top) / d * d,
                            next() >> (64 - bits - 1 - static_cast<int>(next() % 32))};
      for (uint64_t x : n) {
        if (x > top) continue;
        const Quotient32 arm = detail::divide_64by32_2by1(x, d), here = divide_64by32(x, d);
        ASSERT_EQ(arm.q, x / d) << x << " / " << d;
        ASSERT_EQ(arm.r, x % d) << x << " % " << d;
        ASSERT_EQ(here.q, arm.q) << x << " / " << d;
        ASSERT_EQ(here.r, arm.r) << x << " % " << d;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 600000u);
}

TEST(WideDivide, Reciprocal64EqualsTheDivision) {
  XorShift64 next{0xBB67AE8584CAA73Bu};
  auto check = [](uint64_t d) { ASSERT_EQ(reciprocal64(d), ~uint64_t{0} / d) << d; };
  for (uint64_t d :
       {uint64_t{1}, uint64_t{2}, uint64_t{3}, (uint64_t{1} << 31) - 1, uint64_t{1} << 31,
        (uint64_t{1} << 32) - 1, uint64_t{1} << 32, (uint64_t{1} << 32) + 1,
        (uint64_t{1} << 47) - 1, uint64_t{1} << 63, ~uint64_t{0} - 1, ~uint64_t{0}})
    check(d);
  for (int bits = 1; bits <= 64; ++bits) {
    for (int k = 0; k < 20000; ++k) {
      const uint64_t d = next() >> (64 - bits);
      if (d != 0) check(d);
      // Exactly `bits` long.
      check((uint64_t{1} << (bits - 1)) | (bits > 1 ? next() >> (65 - bits) : 0));
    }
  }
}

// The vertex stage's reciprocal of w: within two units of 2^61 / d for every top half of the
// divisor (what its recip16 seed sees), each with its smallest, largest and a random low half, and
// for random divisors; its 32-bit-product form (Armv6-M) the same integer. Its parts (recip16,
// the high-word products) are exact on every core.
TEST(Reciprocal, RecipQ61IsWithinTwoUnitsOfTheQuotient) {
  XorShift64 next{0x2545F4914F6CDD1Du};
  int64_t worst = 0;
  auto check = [&](uint32_t d) {
    const auto y = static_cast<int64_t>((uint64_t{1} << 61) / d);  // floor(2^61 / d)
    const auto x = static_cast<int64_t>(recip_q61(d));
    // x in [2^61 / d - 2, 2^61 / d + 2): between floor - 2 and floor + 2.
    ASSERT_GE(x, y - 2) << d;
    ASSERT_LE(x, y + 2) << d;
    // The form for cores without a 64-bit product: the same integer.
    ASSERT_EQ(detail::recip_q61_split(d), recip_q61(d)) << d;
    worst = std::max(worst, x > y ? x - y : y - x);
  };
  for (uint32_t top = 1u << 15; top < (1u << 16); ++top) {
    check(top << 16);
    check((top << 16) | 0xFFFFu);
    check((top << 16) | (static_cast<uint32_t>(next()) & 0xFFFFu));
  }
  for (int i = 0; i < 300000; ++i) check(static_cast<uint32_t>(next()) | (1u << 31));
  std::printf("recip_q61: worst distance from floor(2^61 / d): %lld\n",
              static_cast<long long>(worst));
}

// The edge table's strip of a row without a division: (r ceil(2^17 / h)) >> 17 = r / h for every
// row of the largest viewport and every strip height.
TEST(EdgeTable, StripOfRowIsTheQuotientForEveryRowAndStripHeight) {
  for (int h = 1; h <= 32; ++h) {
    EdgeTable table;
    std::vector<BinnedTriangle> tris(4);
    std::vector<uint16_t> buckets(kMaxViewport);
    ASSERT_TRUE(table.configure(tris, {}, buckets, {}, kMaxViewport, kMaxViewport, h));
    for (int32_t r = 0; r < kMaxViewport; ++r)
      ASSERT_EQ(table.strip_of_row(r), static_cast<size_t>(r / h)) << r << " / " << h;
  }
}

// The Armv6-M high words (four 16 x 16 products) equal the 64-bit products' for the operands
// at every boundary of the split (0, +-1, +-2^15, +-2^16, the extremes) and for random ones:
// what makes a Cortex-M0+ frame the same integers as a Cortex-M4F frame.
TEST(WideMul, SplitHighWordsEqualTheSixtyFourBitProducts) {
  XorShift64 next{0x9E3779B97F4A7C15u};
  std::vector<int32_t> edge;
  for (int64_t base :
       {int64_t{0}, int64_t{1} << 15, int64_t{1} << 16, int64_t{1} << 30, int64_t{INT32_MAX}})
    for (int64_t dv : {-1, 0, 1})
      for (int64_t sign : {-1, 1}) {
        const int64_t v = sign * (base + dv);
        if (v >= INT32_MIN && v <= INT32_MAX) edge.push_back(static_cast<int32_t>(v));
      }
  edge.push_back(INT32_MIN);
  auto check = [](int32_t a, int32_t b) {
    const int64_t p = int64_t{a} * b;
    ASSERT_EQ(detail::mul_hi_split(a, b), static_cast<int32_t>(p >> 32)) << a << " * " << b;
    ASSERT_EQ(mul_hi_halves(halves(a), halves(b)), static_cast<int32_t>(p >> 32))
        << a << " * " << b;
    ASSERT_EQ(mul_hi(a, b), static_cast<int32_t>(p >> 32)) << a << " * " << b;
    ASSERT_EQ(detail::mul_wide_split(a, b), p) << a << " * " << b;
    ASSERT_EQ(mla_hi(a, b, 12345), static_cast<int32_t>((p >> 32) + 12345)) << a << " * " << b;
    const auto ua = static_cast<uint32_t>(a), ub = static_cast<uint32_t>(b);
    const auto up = static_cast<uint32_t>((uint64_t{ua} * ub) >> 32);
    ASSERT_EQ(detail::mul_hi_u_split(ua, ub), up) << ua << " * " << ub;
    ASSERT_EQ(mul_hi_u(ua, ub), up) << ua << " * " << ub;
  };
  for (int32_t a : edge)
    for (int32_t b : edge) check(a, b);
  for (int i = 0; i < 2000000; ++i) {
    const uint64_t r = next();
    // Every magnitude: a random number of significant bits for each operand.
    const int sa = static_cast<int>(r & 31), sb = static_cast<int>((r >> 5) & 31);
    check(static_cast<int32_t>(static_cast<uint32_t>(r >> 10)) >> sa,
          static_cast<int32_t>(static_cast<uint32_t>(r >> 32)) >> sb);
  }
}

// The textured span's per-pixel division on the table path, over the range it is used on
// (d in [2^14, 2^24] with the chunk's shift j, n <= 2^31, n < 2^15 d): every divisor up to 2^17,
// each power-of-two boundary, random ones, and for each the ends of its dividends and random ones.
TEST(Reciprocal, SmallDivisionEqualsTheDivision) {
  XorShift64 next{0x9E3779B97F4A7C15u};
  auto check = [&](uint32_t d, int j) {
    const SmallDivisor table = detail::small_divisor_table(d, j), here = small_divisor(d, j);
    const uint64_t top64 = std::min<uint64_t>(uint64_t{1} << 31, (uint64_t{d} << 15) - 1);
    const auto top = static_cast<uint32_t>(top64);  // the largest dividend
    const uint32_t n[] = {0,
                          1,
                          d - 1,
                          d,
                          top,
                          top - d + 1,
                          top - d,
                          static_cast<uint32_t>(next() % (top64 + 1)),
                          static_cast<uint32_t>(next() % (top64 + 1)) / d * d,
                          static_cast<uint32_t>(next() % top64) / d * d + d - 1};
    for (uint32_t x : n) {
      ASSERT_EQ(detail::divide_small_table(x, table), x / d) << x << " / " << d << ", j " << j;
      ASSERT_EQ(divide_small(x, here), x / d) << x << " / " << d << ", j " << j;
    }
  };
  // Every shift the span can pass: floor(d / 2^j) in [2^14, 2^16].
  auto check_all_shifts = [&](uint32_t d) {
    for (int j = 0; j <= 10; ++j) {
      const uint32_t dh = d >> j;
      if (dh >= (1u << 14) && dh <= (1u << 16)) check(d, j);
    }
  };
  for (uint32_t d = 1u << 14; d <= (1u << 17); ++d) check_all_shifts(d);
  for (int b = 17; b <= 24; ++b)
    for (uint32_t k = 0; k < 64; ++k) {
      check_all_shifts((1u << b) - k);
      check_all_shifts((1u << b) + k);
    }
  for (int i = 0; i < 200000; ++i)
    check_all_shifts((1u << 14) + static_cast<uint32_t>(next() % ((1u << 24) - (1u << 14) + 1)));
}

// Edge records (core/setup/row_edge.hpp): the column of a row picked up from a record equals
// ceil(((xa - 128) dy + dx (yc - ya)) / (256 dy)), checked against a direct 64-bit evaluation for
// short edges (one record at the edge's first row, relative to the column base of its bounding
// box: the record fits) and guard-band-long ones (picked up from the vertices for a visit of 32
// rows, wide_edge), with both walkers and the step to the next row; a sixth of the short edges
// have |dx| within one of dy, where the DDA's step is found without a division.
TEST(RowEdge, PickUpMatchesTheExactFormulaOnBothPaths) {
  uint64_t s = 12345;
  auto next = [&s]() {
    s = s * 6364136223846793005u + 1442695040888963407u;
    return static_cast<int64_t>(s >> 33);
  };
  auto exact = [](int64_t xa, int64_t ya, int64_t xb, int64_t yb, int64_t row) {
    const int64_t dy = yb - ya, dx = xb - xa;
    const int64_t n = (xa - kHalfPixel) * dy + dx * (row * kSubpixel + kHalfPixel - ya);
    return ceil_div(n, dy * kSubpixel);
  };
  int records = 0, wide = 0;
  for (int i = 0; i < 200000; ++i) {
    const int32_t range = i % 2 ? (1 << 14) : (1 << 22) - 1;  // short edges, then long ones
    const auto xa = static_cast<int32_t>(next() % (2 * range) - range);
    const auto ya = static_cast<int32_t>(next() % (2 * range) - range);
    auto xb = static_cast<int32_t>(next() % (2 * range) - range);
    auto yb = static_cast<int32_t>(next() % (2 * range) - range);
    if (yb <= ya) yb = ya + 1 + static_cast<int32_t>(next() % 1000);
    if (i % 6 == 5) {  // short edges with |dx| within one of dy: DdaEdge's steep-edge shortcut
      const int32_t dx = yb - ya + static_cast<int32_t>(next() % 3) - 1;
      xb = xa + (next() % 2 ? dx : -dx);
    }
    // A row whose centre is on the edge (the rows a triangle asks for).
    const int32_t r0 = first_row_below(ya), r1 = last_row_at_or_above(yb);
    if (r1 < r0) continue;
    const int32_t row = r0 + static_cast<int32_t>(next() % (r1 - r0 + 1));
    const int32_t last = std::min(r1, row + 31);
    const ScreenVertex a{xa, ya, 0, 0, {}, 0, 0}, b{xb, yb, 0, 0, {}, 0, 0};
    const ScreenVertex* v[3] = {&a, &a, &b};
    const PickedEdge p = wide_edge(v, ActiveTriangle::kLong, row, last);
    DivideEdge d(p.e, p.cb, 0);
    DdaEdge e(p.e, p.cb, 0);
    for (int32_t r = row; r <= last; ++r) {
      ASSERT_EQ(d.column(), exact(xa, ya, xb, yb, r));
      ASSERT_EQ(e.column(), exact(xa, ya, xb, yb, r));
      d.step();
      e.step();
    }
    ++wide;
    const int32_t cb = (std::min(xa, xb) - kHalfPixel) >> kSubpixelBits;
    const int32_t cmax = (std::max(xa, xb) - kHalfPixel + kSubpixel - 1) >> kSubpixelBits;
    if (int64_t{cmax - cb + 1} * (int64_t{yb} - ya) >= (int64_t{1} << 32)) continue;
    const RowEdge rec = make_row_edge(xa, ya, xb, yb, cb, r0);
    DivideEdge dr(rec, cb, row - r0);
    DdaEdge er(rec, cb, row - r0);
    for (int32_t r = row; r <= last; ++r) {
      ASSERT_EQ(dr.column(), exact(xa, ya, xb, yb, r));
      ASSERT_EQ(er.column(), exact(xa, ya, xb, yb, r));
      dr.step();
      er.step();
    }
    ++records;
  }
  EXPECT_GT(records, 50000);  // the short edges
  EXPECT_GT(wide, 100000);
}

// Strip fills: every length from 0 to 300 and values with equal and unequal bytes, the pixels
// after the end untouched.
TEST(StripFill, FillsExactlyNPixelsWithTheValue) {
  for (uint16_t v : {uint16_t{0}, uint16_t{0xFFFF}, uint16_t{0x1234}, uint16_t{0x00FF}}) {
    for (size_t n = 0; n <= 300; ++n) {
      std::vector<uint16_t> buf(n + 3, 0xABCD);
      fill_pixels(buf.data(), n, v);
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(buf[i], v) << n << " " << i;
      for (size_t i = n; i < n + 3; ++i) ASSERT_EQ(buf[i], 0xABCD) << n;
    }
  }
  for (Rgb8 v : {Rgb8{7, 7, 7}, Rgb8{1, 2, 3}}) {
    std::vector<Rgb8> buf(260, Rgb8{9, 9, 9});
    fill_pixels(buf.data(), 257, v);
    for (size_t i = 0; i < 257; ++i) ASSERT_EQ(buf[i], v);
    for (size_t i = 257; i < 260; ++i) ASSERT_EQ(buf[i], (Rgb8{9, 9, 9}));
  }
}

}  // namespace
}  // namespace lr
