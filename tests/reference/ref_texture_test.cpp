// Tests of the reference renderer's texturing, against OpenGL's rules worked out by hand:
// nearest texel per pixel, row order, GL_REPEAT and GL_CLAMP_TO_EDGE far from [0, 1], GL_LINEAR
// weights, the level of detail (exact screen-space derivatives) and mip level choice and blend,
// GL_MODULATE with separate specular and GL_REPLACE, and the bridge from core textures.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "tests/reference/ref_renderer.hpp"
#include "tests/reference/ref_texture_core.hpp"

namespace lr::ref {
namespace {

using host::HostMesh;

// A level whose texels are all different: r encodes the column, g the row.
RefLevel distinct_level(int w, int h) {
  RefLevel l;
  l.width = w;
  l.height = h;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      l.texels.push_back(
          {(i + 1.0) / (w + 1.0), (j + 1.0) / (h + 1.0), ((i * 7 + j * 3) % 5) / 4.0});
  return l;
}

RefLevel flat_level(int w, int h, Vec3d c) {
  RefLevel l;
  l.width = w;
  l.height = h;
  l.texels.assign(static_cast<size_t>(w) * static_cast<size_t>(h), c);
  return l;
}

// A distinct flat colour for each mip level.
Vec3d level_colour(int d) {
  return {d / 8.0, 1.0 - d / 8.0, (d % 2) ? 0.75 : 0.25};
}

// A full GL chain from w0 x h0 down to 1 x 1 (or the first `levels` of it), level d flat in
// level_colour(d).
RefTexture mip_chain(int w0, int h0, int levels = 100) {
  RefTexture t;
  int w = w0, h = h0;
  for (int d = 0; d < levels; ++d) {
    t.levels.push_back(flat_level(w, h, level_colour(d)));
    if (w == 1 && h == 1) break;
    w = std::max(1, w / 2);
    h = std::max(1, h / 2);
  }
  return t;
}

// An axis-aligned quad at z = 0 from NDC (x0, y0) to (x1, y1), (u, v) = (u0, v0) at the first
// corner and (u1, v1) at the opposite one, linear in between. Counter-clockwise, normal +z.
HostMesh quad(double x0, double y0, double x1, double y1, double u0, double v0, double u1,
              double v1) {
  HostMesh m;
  m.positions = {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
  m.normals.assign(4, {0, 0, 1});
  m.uvs = {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// Identity matrices (NDC = positions), unlit, GL_REPLACE, nearest, no mipmaps.
RefParams tex_params(const RefTexture& t, int w, int h) {
  RefParams p;
  p.width = w;
  p.height = h;
  p.unlit = true;
  p.texture = &t;
  p.filter = RefFilter::Nearest;
  p.tex_env = RefTexEnv::Replace;
  p.mip = RefMipMode::None;
  return p;
}

void expect_colour(const Vec3d& got, const Vec3d& want, double tol, const char* what, int i,
                   int j) {
  for (size_t c = 0; c < 3; ++c)
    EXPECT_NEAR(got[c], want[c], tol) << what << " at pixel " << i << "," << j << " channel " << c;
}

Vec3d clamp_sum(const Vec3d& a, const Vec3d& b) {
  Vec3d r{};
  for (size_t c = 0; c < 3; ++c) r[c] = std::clamp(a[c] + b[c], 0.0, 1.0);
  return r;
}

int64_t floor_mod(int64_t a, int64_t n) {
  return ((a % n) + n) % n;
}

// ---------------------------------------------------------------------------------------------
// Nearest, row order, wrap

TEST(TextureNearest, ScreenFillingQuadShowsEachTexelInItsOwnBlock) {
  // 4x4 texture on a quad of exactly 64x64 pixels: pixel (x, y) shows texel column x / 16 and
  // storage row 3 - y / 16 (storage row 0 = bottom of the screen).
  RefTexture t;
  t.levels.push_back(distinct_level(4, 4));
  const RefParams p = tex_params(t, 64, 64);
  RefFrame f;
  render(quad(-1, -1, 1, 1, 0, 0, 1, 1), p, f);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const size_t idx = f.index(x, y);
      ASSERT_NE(f.owner[idx], -1);
      EXPECT_EQ(f.color[idx], t.levels[0].at(x / 16, 3 - y / 16)) << x << "," << y;
      EXPECT_NEAR(f.lod[idx], std::log2(4.0 / 64.0), 1e-9);  // magnification
    }
}

TEST(TextureNearest, StorageRowZeroShowsAtTheBottomOfTheScreen) {
  // 1x2 texture: storage row 0 red, row 1 blue. v = 0 at the bottom of the quad.
  RefTexture t;
  RefLevel l;
  l.width = 1;
  l.height = 2;
  l.texels = {{1, 0, 0}, {0, 0, 1}};
  t.levels.push_back(l);
  RefFrame f;
  render(quad(-1, -1, 1, 1, 0, 0, 1, 1), tex_params(t, 8, 8), f);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_EQ(f.color[f.index(x, y)], (y < 4 ? Vec3d{0, 0, 1} : Vec3d{1, 0, 0})) << x << "," << y;
  // Display row 7 (the bottom row) is storage row 0: red.
  EXPECT_EQ(f.rgb8[f.index(0, 7) * 3 + 0], 255);
  EXPECT_EQ(f.rgb8[f.index(0, 0) * 3 + 2], 255);
}

TEST(TextureNearest, MeshWithoutUvsSamplesTheOrigin) {
  RefTexture t;
  t.levels.push_back(distinct_level(3, 2));
  HostMesh m = quad(-1, -1, 1, 1, 0, 0, 1, 1);
  m.uvs.clear();
  RefFrame f;
  render(m, tex_params(t, 16, 16), f);
  for (size_t idx = 0; idx < f.color.size(); ++idx) {
    EXPECT_EQ(f.color[idx], t.levels[0].at(0, 0));
    EXPECT_EQ(f.lod[idx], -std::numeric_limits<double>::infinity());
  }
}

// u and v from -1000 to 1000 across 64 pixels on a 3x5 texture (not a power of two): the pixel
// centre has u = -1000 + 2000 (x + 0.5) / 64 (never within 1/8 texel of a texel edge) and
// v likewise from the bottom. Expected texel: floor(u W) wrapped per mode.
size_t check_wrap(RefWrap ws, RefWrap wt, double lo, double hi) {
  RefTexture t;
  t.levels.push_back(distinct_level(3, 5));
  RefParams p = tex_params(t, 64, 64);
  p.wrap_s = ws;
  p.wrap_t = wt;
  RefFrame f;
  render(quad(-1, -1, 1, 1, lo, lo, hi, hi), p, f);
  auto wrap = [](double s, int n, RefWrap w) {
    const auto i = static_cast<int64_t>(std::floor(s));
    return static_cast<int>(w == RefWrap::Repeat ? floor_mod(i, n)
                                                 : std::clamp<int64_t>(i, 0, n - 1));
  };
  std::set<std::pair<int, int>> seen;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const double u = lo + (hi - lo) * (x + 0.5) / 64.0;
      const double v = lo + (hi - lo) * (64 - y - 0.5) / 64.0;  // window y counts up
      const double s = 3 * u, tt = 5 * v;
      // The case is well posed: no pixel centre within 1/200 texel of a texel edge.
      EXPECT_GT(std::fabs(s - std::round(s)), 0.005);
      EXPECT_GT(std::fabs(tt - std::round(tt)), 0.005);
      const int i = wrap(s, 3, ws), j = wrap(tt, 5, wt);
      seen.insert({i, j});
      EXPECT_EQ(f.color[f.index(x, y)], t.levels[0].at(i, j)) << x << "," << y;
    }
  return seen.size();  // how many different texels showed
}

TEST(TextureWrap, RepeatIsExactForCoordinatesAroundPlusMinus1000) {
  // Steps of 93.75 and 156.25 texels per pixel: t mod 5 runs 1.875, 0.625, 4.375, 3.125, ...
  // so row 2 never shows; 12 of the 15 texels do.
  EXPECT_EQ(check_wrap(RefWrap::Repeat, RefWrap::Repeat, -1000, 1000), 12u);
  EXPECT_EQ(check_wrap(RefWrap::Repeat, RefWrap::Repeat, 999.03, 1000.97), 15u);
  EXPECT_EQ(check_wrap(RefWrap::Repeat, RefWrap::Repeat, -1000.97, -999.03), 15u);
}

TEST(TextureWrap, ClampToEdgeHoldsTheEdgeTexelsFarOutside) {
  EXPECT_EQ(check_wrap(RefWrap::ClampToEdge, RefWrap::ClampToEdge, -1000, 1000), 4u);
  EXPECT_EQ(check_wrap(RefWrap::ClampToEdge, RefWrap::ClampToEdge, -2, 3), 15u);
  EXPECT_EQ(check_wrap(RefWrap::ClampToEdge, RefWrap::Repeat, -2, 3), 15u);
  EXPECT_EQ(check_wrap(RefWrap::Repeat, RefWrap::ClampToEdge, -1000, 1000), 6u);
}

// ---------------------------------------------------------------------------------------------
// Bilinear

Vec3d mean_of(const RefLevel& l, const std::vector<int>& is, const std::vector<int>& js) {
  Vec3d m{0, 0, 0};
  for (int i : is)
    for (int j : js) m = add(m, l.at(i, j));
  return muls(m, 1.0 / static_cast<double>(is.size() * js.size()));
}

TEST(TextureBilinear, TexelCentresGiveTheTexelAndHalfwayGivesTheAverage) {
  const RefLevel l = distinct_level(4, 3);
  for (RefWrap w : {RefWrap::Repeat, RefWrap::ClampToEdge})
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) {
        const double uc = (i + 0.5) / 4, vc = (j + 0.5) / 3;
        expect_colour(sample_level(l, uc, vc, RefFilter::Bilinear, w, w), l.at(i, j), 1e-15,
                      "centre", i, j);
        // Halfway to the right neighbour, halfway up, and both.
        const int ir = w == RefWrap::Repeat ? (i + 1) % 4 : std::min(i + 1, 3);
        const int ju = w == RefWrap::Repeat ? (j + 1) % 3 : std::min(j + 1, 2);
        const double uh = (i + 1.0) / 4, vh = (j + 1.0) / 3;
        expect_colour(sample_level(l, uh, vc, RefFilter::Bilinear, w, w), mean_of(l, {i, ir}, {j}),
                      1e-15, "halfway in u", i, j);
        expect_colour(sample_level(l, uc, vh, RefFilter::Bilinear, w, w), mean_of(l, {i}, {j, ju}),
                      1e-15, "halfway in v", i, j);
        expect_colour(sample_level(l, uh, vh, RefFilter::Bilinear, w, w),
                      mean_of(l, {i, ir}, {j, ju}), 1e-15, "halfway in both", i, j);
      }
  // A quarter of the way: weights 3/4 and 1/4.
  const Vec3d q =
      sample_level(l, 0.75 / 4, 0.5 / 3, RefFilter::Bilinear, RefWrap::Repeat, RefWrap::Repeat);
  expect_colour(q, add(muls(l.at(0, 0), 0.75), muls(l.at(1, 0), 0.25)), 1e-15, "quarter", 0, 0);
  // Far outside [0, 1] with clamp: the corner texel; with repeat: as at the wrapped position.
  expect_colour(sample_level(l, -1000.3, 1000.7, RefFilter::Bilinear, RefWrap::ClampToEdge,
                             RefWrap::ClampToEdge),
                l.at(0, 2), 0, "clamped corner", 0, 2);
  expect_colour(sample_level(l, 1000 + 1.0 / 4, 1000 + 0.5 / 3, RefFilter::Bilinear,
                             RefWrap::Repeat, RefWrap::Repeat),
                mean_of(l, {0, 1}, {0}), 1e-12, "repeat far away", 0, 0);
}

TEST(TextureBilinear, RenderedQuadHitsCentresAndHalfwaysAsGlLinear) {
  // 8x8 pixels, 4x4 texels, u from -1/16 to 15/16: pixel column x has s = x / 2, so odd columns
  // sit on texel centres ((x - 1) / 2) and even ones halfway (x / 2 - 1 and x / 2, repeat wraps
  // -1 to 3). Likewise t = (7 - y) / 2 for display row y.
  RefTexture t;
  t.levels.push_back(distinct_level(4, 4));
  RefParams p = tex_params(t, 8, 8);
  p.filter = RefFilter::Bilinear;
  RefFrame f;
  render(quad(-1, -1, 1, 1, -1.0 / 16, -1.0 / 16, 15.0 / 16, 15.0 / 16), p, f);
  auto taps = [](int k) {  // k = 2 s
    return k % 2 ? std::vector<int>{(k - 1) / 2}
                 : std::vector<int>{static_cast<int>(floor_mod(k / 2 - 1, 4)), (k / 2) % 4};
  };
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      expect_colour(f.color[f.index(x, y)], mean_of(t.levels[0], taps(x), taps(7 - y)), 1e-12,
                    "bilinear", x, y);
}

// ---------------------------------------------------------------------------------------------
// Level of detail and mipmaps

// A screen-filling 64x64 quad over a 64x64 level 0 with u from 0 to ku and v from 0 to kv:
// ds/dx = ku, dt/dy = kv (texels per pixel), so lambda = log2(max(ku, kv)).
RefFrame render_ratio(const RefTexture& t, RefMipMode mip, RefFilter filter, double ku, double kv) {
  RefParams p = tex_params(t, 64, 64);
  p.mip = mip;
  p.filter = filter;
  RefFrame f;
  render(quad(-1, -1, 1, 1, 0, 0, ku, kv), p, f);
  return f;
}

TEST(TextureLod, ScreenAlignedRatiosGiveLog2OfTheTexelsPerPixel) {
  const RefTexture t = mip_chain(64, 64);
  const struct {
    double ku, kv, lambda;
  } cases[] = {{1, 1, 0}, {2, 2, 1}, {4, 4, 2},    {0.5, 0.5, -1},
               {4, 1, 2}, {1, 8, 3}, {2, 0.25, 1}, {std::exp2(1.5), 1, 1.5}};
  for (const auto& c : cases) {
    const RefFrame f = render_ratio(t, RefMipMode::None, RefFilter::Nearest, c.ku, c.kv);
    for (size_t idx = 0; idx < f.lod.size(); ++idx)
      ASSERT_NEAR(f.lod[idx], c.lambda, 1e-9) << c.ku << "x" << c.kv << " pixel " << idx;
  }
  // The public helper agrees: rho is the larger of the two derivative lengths.
  EXPECT_NEAR(texture_lod(3.0 / 64, 4.0 / 64, 0, 0, 64, 64), std::log2(5.0), 1e-12);
  EXPECT_NEAR(texture_lod(0, 0, 1.0 / 64, 0, 64, 32), 0.0, 1e-12);
  EXPECT_EQ(texture_lod(0, 0, 0, 0, 64, 64), -std::numeric_limits<double>::infinity());
}

TEST(TextureLod, NearestMipPicksCeilOfLambdaPlusHalfMinusOne) {
  const RefTexture t = mip_chain(64, 64);  // levels 0..6
  const struct {
    double lambda;
    int level;
  } cases[] = {{-2, 0},   {0, 0}, {0.4, 0}, {0.6, 1}, {1, 1}, {1.49, 1},
               {1.51, 2}, {2, 2}, {3.7, 4}, {6, 6},   {10, 6}};
  for (RefFilter filter : {RefFilter::Nearest, RefFilter::Bilinear})
    for (const auto& c : cases) {
      const double k = std::exp2(c.lambda);
      const RefFrame f = render_ratio(t, RefMipMode::Nearest, filter, k, 1);
      for (int y = 0; y < 64; y += 9)
        for (int x = 0; x < 64; x += 7)
          expect_colour(f.color[f.index(x, y)], level_colour(c.level), 1e-12, "nearest mip", x, y);
    }
  // Without mipmaps: level 0 whatever lambda.
  const RefFrame f = render_ratio(t, RefMipMode::None, RefFilter::Nearest, 16, 16);
  EXPECT_EQ(f.color[f.index(5, 5)], level_colour(0));
}

TEST(TextureLod, LinearMipBlendsTheTwoLevelsAroundLambda) {
  const RefTexture t = mip_chain(64, 64);  // levels 0..6
  auto mix = [](int a, int b, double w) {
    return add(muls(level_colour(a), 1 - w), muls(level_colour(b), w));
  };
  const struct {
    double lambda;
    Vec3d want;
  } cases[] = {{-1, level_colour(0)}, {0, level_colour(0)},    {0.5, mix(0, 1, 0.5)},
               {1, level_colour(1)},  {1.25, mix(1, 2, 0.25)}, {2.75, mix(2, 3, 0.75)},
               {5.5, mix(5, 6, 0.5)}, {6, level_colour(6)},    {7.5, level_colour(6)}};
  for (const auto& c : cases) {
    const double k = std::exp2(c.lambda);
    const RefFrame f = render_ratio(t, RefMipMode::Linear, RefFilter::Bilinear, k, 1);
    for (int y = 0; y < 64; y += 9)
      for (int x = 0; x < 64; x += 7)
        expect_colour(f.color[f.index(x, y)], c.want, 1e-9, "linear mip", x, y);
  }
}

TEST(TextureLod, ShortChainStopsAtItsLastLevel) {
  const RefTexture t = mip_chain(64, 64, 3);  // levels 0..2: q = 2
  RefFrame f = render_ratio(t, RefMipMode::Nearest, RefFilter::Nearest, 32, 32);  // lambda 5
  EXPECT_EQ(f.color[f.index(10, 10)], level_colour(2));
  f = render_ratio(t, RefMipMode::Linear, RefFilter::Nearest, std::exp2(2.5), 1);
  EXPECT_EQ(f.color[f.index(10, 10)], level_colour(2));
  f = render_ratio(t, RefMipMode::Linear, RefFilter::Nearest, std::exp2(1.5), 1);
  expect_colour(f.color[f.index(10, 10)],
                add(muls(level_colour(1), 0.5), muls(level_colour(2), 0.5)), 1e-9, "blend", 10, 10);
}

TEST(TextureLod, NonSquareLevelsUseTheirOwnSizes) {
  // 8x2 -> 4x1 -> 2x1 -> 1x1 with distinct texels: level 1 sampled with s = 4 u, t = 1 v.
  RefTexture t;
  for (auto [w, h] : {std::pair{8, 2}, {4, 1}, {2, 1}, {1, 1}})
    t.levels.push_back(distinct_level(w, h));
  RefParams p;
  p.texture = &t;
  p.filter = RefFilter::Nearest;
  p.mip = RefMipMode::Nearest;
  for (int i = 0; i < 4; ++i)
    EXPECT_EQ(sample_texture(t, p, (i + 0.5) / 4, 0.3, 1.0), t.levels[1].at(i, 0));
  EXPECT_EQ(sample_texture(t, p, 0.7, 0.9, 2.0), t.levels[2].at(1, 0));
  EXPECT_EQ(sample_texture(t, p, 0.7, 0.9, 3.0), t.levels[3].at(0, 0));
}

TEST(TextureLod, PerspectiveLambdaIsTheExactDerivativeAtThePixelCentre) {
  // A floor y = -1 from z = -1 to -32 seen by gluPerspective(90, 1): u = (x + 4) / 8 and
  // v = (z + 1) / -31 are affine on the plane. lambda at each pixel is checked against central
  // differences of (u, v) obtained by casting rays through points around the pixel centre.
  // The corners project to whole pixels (X = 32 +- 32 x / -z, Y = 32 + 32 / -z), so snapping
  // leaves them in place and the analytic and the ray-cast mappings are the same function (the
  // far edge lies one pixel below the horizon, where a 1/512-pixel snap would shift lambda by
  // ~1e-3).
  const int W = 64, H = 64;
  const double fovy = 90;
  RefTexture t;
  t.levels.push_back(flat_level(256, 128, {1, 1, 1}));
  HostMesh m;
  m.positions = {{-4, -1, -1}, {4, -1, -1}, {4, -1, -32}, {-4, -1, -32}};
  m.normals.assign(4, {0, 1, 0});
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  RefParams p = tex_params(t, W, H);
  p.projection = perspective(fovy, 1.0, 0.5, 100);
  RefFrame f;
  render(m, p, f);

  const double th = std::tan(fovy * kPi / 360.0);
  auto uv_at = [&](double X, double Y) {  // window X, display Y in pixels
    const Vec3d d{(2 * X / W - 1) * th, (1 - 2 * Y / H) * th, -1};
    const double s = -1.0 / d[1];
    return std::array<double, 2>{(s * d[0] + 4) / 8, (-s + 1) / -31};
  };
  int checked = 0;
  double lo = 1e9, hi = -1e9;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t idx = f.index(x, y);
      if (f.owner[idx] < 0) continue;
      const double X = x + 0.5, Y = y + 0.5, h = 1e-4;
      if ((1 - 2 * (Y - 1) / H) >= 0) continue;  // too close to the horizon for differences
      const auto px = uv_at(X + h, Y), mx = uv_at(X - h, Y);
      const auto py = uv_at(X, Y + h), my = uv_at(X, Y - h);
      const double lambda =
          texture_lod((px[0] - mx[0]) / (2 * h), (px[1] - mx[1]) / (2 * h),
                      (py[0] - my[0]) / (2 * h), (py[1] - my[1]) / (2 * h), 256, 128);
      EXPECT_NEAR(f.lod[idx], lambda, 1e-6) << x << "," << y;
      lo = std::min(lo, lambda);
      hi = std::max(hi, lambda);
      ++checked;
    }
  EXPECT_GT(checked, 500);
  EXPECT_GT(hi - lo, 2.0);  // the case spans several levels
}

TEST(TextureLod, UvsStayPerspectiveCorrectAcrossTheNearPlane) {
  // The floor from z = +3 (behind the eye) to -21, 16 texel columns along x: every pixel shows
  // the texel of the analytic u (pixels within 2% of a texel edge skipped).
  const int W = 64, H = 64;
  const double fovy = 60, n = 1.5;
  RefTexture t;
  t.levels.push_back(distinct_level(16, 1));
  HostMesh m;
  m.positions = {{-4, -1, 3}, {4, -1, 3}, {4, -1, -21}, {-4, -1, -21}};
  m.normals.assign(4, {0, 1, 0});
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  RefParams p = tex_params(t, W, H);
  p.projection = perspective(fovy, 1.0, n, 100);
  RefFrame f;
  render(m, p, f);
  const double th = std::tan(fovy * kPi / 360.0);
  int checked = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const Vec3d d{(2 * (x + 0.5) / W - 1) * th, (1 - 2 * (y + 0.5) / H) * th, -1};
      if (d[1] >= 0) continue;
      const double s = -1.0 / d[1];
      if (s < n * 1.01 || s > 20.5) continue;
      const double wx = s * d[0];
      if (std::fabs(wx) > 3.95) continue;
      const double st = 16 * (wx + 4) / 8;
      if (std::fabs(st - std::round(st)) < 0.02) continue;
      const size_t idx = f.index(x, y);
      ASSERT_NE(f.owner[idx], -1) << x << "," << y;
      EXPECT_EQ(f.color[idx], t.levels[0].at(static_cast<int>(std::floor(st)), 0)) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 300);
}

// ---------------------------------------------------------------------------------------------
// Texture environment

RefParams lit_params(const RefTexture& t) {
  RefParams p = tex_params(t, 16, 16);
  p.unlit = false;
  p.tex_env = RefTexEnv::Modulate;
  p.material.ambient = {0.1, 0.2, 0.3};
  p.material.diffuse = {0.5, 0.4, 0.3};
  p.material.specular = {0.3, 0.2, 0.1};
  p.material.emission = {0.05, 0, 0};
  p.material.shininess = 20;
  p.global_ambient = {0.2, 0.2, 0.2};
  p.lights = {RefLight{{0, 0, 1}, {1, 1, 1}}};  // N.L = 1, infinite viewer: N.H = 1
  return p;
}

TEST(TextureEnv, ModulateMultipliesThePrimaryColourAndAddsSpecularAfter) {
  RefTexture t;
  t.levels.push_back(flat_level(2, 2, {0.5, 1.0, 0.25}));
  // primary = Ke + Ga Ka + La Ka + Ld Kd = (0.05+0.02+0.1+0.5, 0.04+0.2+0.4, 0.06+0.3+0.3)
  //         = (0.67, 0.64, 0.66); secondary = Ks (N.H = 1) = (0.3, 0.2, 0.1).
  // texel * primary + secondary = (0.335 + 0.3, 0.64 + 0.2, 0.165 + 0.1).
  const Vec3d want{0.635, 0.84, 0.265};
  for (RefShading sh : {RefShading::Gouraud, RefShading::Flat}) {
    RefParams p = lit_params(t);
    p.shading = sh;
    const RefLitColor lc = light_point_separate(p, {0, 0, 1}, {0, 0, 0});
    expect_colour(lc.primary, {0.67, 0.64, 0.66}, 1e-15, "primary", 0, 0);
    expect_colour(lc.secondary, {0.3, 0.2, 0.1}, 1e-15, "secondary", 0, 0);
    RefFrame f;
    render(quad(-1, -1, 1, 1, 0, 0, 1, 1), p, f);
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) expect_colour(f.color[f.index(x, y)], want, 1e-12, "lit", x, y);
  }
}

TEST(TextureEnv, PrimaryAndSecondaryAreClampedBeforeTheTexelAndTheSumAfter) {
  RefTexture t;
  t.levels.push_back(flat_level(1, 1, {0.5, 0.5, 0.5}));
  RefParams p = lit_params(t);
  p.lights[0].color = {2, 2, 2};  // primary (1.27, 1.24, 1.26) -> 1; secondary (0.6, 0.4, 0.2)
  RefFrame f;
  render(quad(-1, -1, 1, 1, 0, 0, 1, 1), p, f);
  expect_colour(f.color[f.index(3, 3)], {1.0, 0.9, 0.7}, 1e-12, "clamped primary", 3, 3);
  p.lights[0].color = {4, 4, 4};  // secondary (1.2, 0.8, 0.4) -> (1, 0.8, 0.4); sum clamped
  render(quad(-1, -1, 1, 1, 0, 0, 1, 1), p, f);
  expect_colour(f.color[f.index(3, 3)], {1.0, 1.0, 0.9}, 1e-12, "clamped sum", 3, 3);
}

TEST(TextureEnv, GouraudInterpolatesClampedPrimaryAndSecondarySeparately) {
  // Left vertices face the light (primary clamps to 1 with light colour 2), right vertices face
  // away (primary = emission + ambient terms, secondary 0). Identity projection: weights are
  // linear in x, alpha = (x + 0.5) / 16 towards the right.
  RefTexture t;
  t.levels.push_back(flat_level(1, 1, {0.5, 0.25, 1.0}));
  RefParams p = lit_params(t);
  p.lights[0].color = {2, 2, 2};
  HostMesh m = quad(-1, -1, 1, 1, 0, 0, 1, 1);
  m.normals = {{0, 0, 1}, {0, 0, -1}, {0, 0, -1}, {0, 0, 1}};
  const RefLitColor left = light_point_separate(p, {0, 0, 1}, {0, 0, 0});
  const RefLitColor right = light_point_separate(p, {0, 0, -1}, {0, 0, 0});
  expect_colour(left.primary, {1, 1, 1}, 0, "left primary", 0, 0);
  expect_colour(left.secondary, {0.6, 0.4, 0.2}, 1e-15, "left secondary", 0, 0);
  // Ke + Ga Ka + La Ka = (0.05 + 0.02 + 0.2, 0.04 + 0.4, 0.06 + 0.6)
  expect_colour(right.primary, {0.27, 0.44, 0.66}, 1e-15, "right primary", 0, 0);
  expect_colour(right.secondary, {0, 0, 0}, 0, "right secondary", 0, 0);
  RefFrame f;
  render(m, p, f);
  for (int x = 0; x < 16; ++x) {
    const double a = (x + 0.5) / 16;
    const Vec3d prim = add(muls(left.primary, 1 - a), muls(right.primary, a));
    const Vec3d sec = add(muls(left.secondary, 1 - a), muls(right.secondary, a));
    const Vec3d want = clamp_sum(cmul({0.5, 0.25, 1.0}, prim), sec);
    for (int y = 0; y < 16; y += 5) expect_colour(f.color[f.index(x, y)], want, 1e-12, "", x, y);
  }
}

TEST(TextureEnv, ReplaceIgnoresLighting) {
  RefTexture t;
  t.levels.push_back(distinct_level(4, 4));
  for (RefShading sh : {RefShading::Gouraud, RefShading::Flat})
    for (bool unlit : {false, true}) {
      RefParams p = lit_params(t);
      p.lights[0].color = {3, 3, 3};
      p.tex_env = RefTexEnv::Replace;
      p.shading = sh;
      p.unlit = unlit;
      RefFrame f;
      render(quad(-1, -1, 1, 1, 0, 0, 1, 1), p, f);
      for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
          EXPECT_EQ(f.color[f.index(x, y)], t.levels[0].at(x / 4, 3 - y / 4)) << x << "," << y;
    }
}

TEST(TextureEnv, UnlitModulateUsesVertexColoursOrTheDiffuseMaterial) {
  RefTexture t;
  t.levels.push_back(flat_level(1, 1, {0.5, 0.8, 1.0}));
  RefParams p = tex_params(t, 16, 16);
  p.tex_env = RefTexEnv::Modulate;
  p.material.diffuse = {0.2, 0.5, 0.6};
  HostMesh m = quad(-1, -1, 1, 1, 0, 0, 1, 1);
  RefFrame f;
  render(m, p, f);  // no colours: material diffuse
  expect_colour(f.color[f.index(4, 4)], {0.1, 0.4, 0.6}, 1e-15, "diffuse", 4, 4);

  m.colors.assign(4, {1.0, 0.5, 0.25});
  render(m, p, f);
  expect_colour(f.color[f.index(4, 4)], {0.5, 0.4, 0.25}, 1e-12, "vertex colour", 4, 4);

  // Flat: the last vertex's colour (GL's provoking vertex); triangles (0,1,2) and (0,2,3).
  m.colors = {{1, 1, 1}, {1, 1, 1}, {0.5, 0.5, 0.5}, {1, 0, 0}};
  p.shading = RefShading::Flat;
  render(m, p, f);
  expect_colour(f.color[f.index(14, 8)], {0.25, 0.4, 0.5}, 1e-15, "flat, lower right", 14, 8);
  expect_colour(f.color[f.index(1, 8)], {0.5, 0, 0}, 1e-15, "flat, upper left", 1, 8);
}

TEST(TextureEnv, IncompleteTextureSamplesBlack) {
  RefTexture t;
  RefParams p = tex_params(t, 8, 8);
  RefFrame f;
  render(quad(-1, -1, 1, 1, 0, 0, 1, 1), p, f);
  EXPECT_EQ(f.color[f.index(3, 3)], (Vec3d{0, 0, 0}));
  EXPECT_NE(f.owner[f.index(3, 3)], -1);
}

TEST(TextureEnv, UntexturedFramesHaveNoLod) {
  RefParams p;
  p.width = 8;
  p.height = 8;
  p.unlit = true;
  RefFrame f;
  render(quad(-1, -1, 1, 1, 0, 0, 1, 1), p, f);
  EXPECT_NE(f.owner[f.index(3, 3)], -1);
  for (double l : f.lod) EXPECT_TRUE(std::isnan(l));
}

// ---------------------------------------------------------------------------------------------
// The bridge from core textures

TEST(TextureFromCore, Rgb565ExpandsByBitReplication) {
  const uint16_t texels[] = {0xF800, 0x07E0, 0x001F, 0x8410, 0x0000, 0xFFFF};  // 3x2
  Texture c;
  c.format = TexelFormat::kRgb565;
  c.levels[0] = {texels, {}, 3, 2};
  c.level_count = 1;
  const RefTexture r = from_core(c);
  ASSERT_EQ(r.levels.size(), 1u);
  EXPECT_EQ(r.levels[0].width, 3);
  EXPECT_EQ(r.levels[0].height, 2);
  EXPECT_EQ(r.levels[0].at(0, 0), (Vec3d{1, 0, 0}));
  EXPECT_EQ(r.levels[0].at(1, 0), (Vec3d{0, 1, 0}));
  EXPECT_EQ(r.levels[0].at(2, 0), (Vec3d{0, 0, 1}));
  // 0x8410: r5 = 16 -> 132, g6 = 32 -> 130, b5 = 16 -> 132.
  EXPECT_EQ(r.levels[0].at(0, 1), (Vec3d{132 / 255.0, 130 / 255.0, 132 / 255.0}));
  EXPECT_EQ(r.levels[0].at(1, 1), (Vec3d{0, 0, 0}));
  EXPECT_EQ(r.levels[0].at(2, 1), (Vec3d{1, 1, 1}));
  EXPECT_EQ(rgb565_to_unit(0x0821), (Vec3d{8 / 255.0, 4 / 255.0, 8 / 255.0}));
}

TEST(TextureFromCore, ByteFormatsPaletteAndMipLevels) {
  const uint8_t rgb[] = {10, 20, 30, 255, 0, 128, 1, 2, 3, 4, 5, 6,  // level 0: 2x2
                         7,  8,  9};                                 // level 1: 1x1
  Texture c;
  c.format = TexelFormat::kRgb888;
  c.levels[0] = {{}, std::span<const uint8_t>(rgb, 12), 2, 2};
  c.levels[1] = {{}, std::span<const uint8_t>(rgb + 12, 3), 1, 1};
  c.level_count = 2;
  RefTexture r = from_core(c);
  ASSERT_EQ(r.levels.size(), 2u);
  EXPECT_EQ(r.levels[0].at(1, 0), (Vec3d{255 / 255.0, 0, 128 / 255.0}));
  EXPECT_EQ(r.levels[0].at(0, 1), (Vec3d{1 / 255.0, 2 / 255.0, 3 / 255.0}));
  EXPECT_EQ(r.levels[1].at(0, 0), (Vec3d{7 / 255.0, 8 / 255.0, 9 / 255.0}));

  const uint8_t lum[] = {0, 51, 255};
  c = Texture{};
  c.format = TexelFormat::kL8;
  c.levels[0] = {{}, lum, 3, 1};
  c.level_count = 1;
  r = from_core(c);
  EXPECT_EQ(r.levels[0].at(1, 0), (Vec3d{0.2, 0.2, 0.2}));

  const uint16_t pal[] = {0x001F, 0xF800};
  const uint8_t idx[] = {1, 0, 0, 1};
  c = Texture{};
  c.format = TexelFormat::kPalette8;
  c.palette = pal;
  c.levels[0] = {{}, idx, 2, 2};
  c.level_count = 1;
  r = from_core(c);
  EXPECT_EQ(r.levels[0].at(0, 0), (Vec3d{1, 0, 0}));
  EXPECT_EQ(r.levels[0].at(1, 0), (Vec3d{0, 0, 1}));
  EXPECT_EQ(r.levels[0].at(1, 1), (Vec3d{1, 0, 0}));
}

TEST(TextureFromCore, StorageRowZeroOfACoreTextureShowsAtTheBottom) {
  const uint16_t texels[] = {0xF800, 0x001F};  // 1x2: row 0 red, row 1 blue
  Texture c;
  c.format = TexelFormat::kRgb565;
  c.levels[0] = {texels, {}, 1, 2};
  c.level_count = 1;
  const RefTexture r = from_core(c);
  RefParams p = tex_params(r, 4, 4);
  set_sampler(p, Sampler{Filter::kNearest, Wrap::kClampToEdge, Wrap::kRepeat, MipMode::kNone,
                         TexEnv::kReplace});
  EXPECT_EQ(p.filter, RefFilter::Nearest);
  EXPECT_EQ(p.wrap_s, RefWrap::ClampToEdge);
  EXPECT_EQ(p.wrap_t, RefWrap::Repeat);
  EXPECT_EQ(p.mip, RefMipMode::None);
  EXPECT_EQ(p.tex_env, RefTexEnv::Replace);
  RefFrame f;
  render(quad(-1, -1, 1, 1, 0, 0, 1, 1), p, f);
  EXPECT_EQ(f.color[f.index(0, 3)], (Vec3d{1, 0, 0}));
  EXPECT_EQ(f.color[f.index(0, 0)], (Vec3d{0, 0, 1}));

  set_sampler(p, Sampler{Filter::kBilinear, Wrap::kRepeat, Wrap::kClampToEdge, MipMode::kLinear,
                         TexEnv::kModulate});
  EXPECT_EQ(p.filter, RefFilter::Bilinear);
  EXPECT_EQ(p.wrap_t, RefWrap::ClampToEdge);
  EXPECT_EQ(p.mip, RefMipMode::Linear);
  EXPECT_EQ(p.tex_env, RefTexEnv::Modulate);
  set_sampler(p, Sampler{Filter::kBilinear, Wrap::kRepeat, Wrap::kRepeat, MipMode::kNearest,
                         TexEnv::kModulate});
  EXPECT_EQ(p.mip, RefMipMode::Nearest);
}

}  // namespace
}  // namespace lr::ref
