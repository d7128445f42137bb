// Tests of the double-precision reference renderer: matrix conventions (gluPerspective,
// gluLookAt), the exact fill rule, GL fixed-function lighting, perspective-correct interpolation,
// near/far clipping, depth test and back-face culling.
#include "tests/reference/ref_renderer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace lr::ref {
namespace {

using host::HostMesh;
using Tri = std::array<uint32_t, 3>;

HostMesh make_mesh(const std::vector<Vec3d>& positions, const std::vector<Tri>& tris,
                   Vec3d normal = {0, 0, 1}) {
  HostMesh m;
  m.positions = positions;
  m.normals.assign(positions.size(), normal);
  m.triangles = tris;
  return m;
}

// Subpixel coordinate of the centre of pixel column/row i.
int64_t centre(int i, int64_t S) {
  return i * S + S / 2;
}

ScreenTri screen_tri(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t x2, int64_t y2) {
  ScreenTri t{};
  t.x[0] = x0;
  t.y[0] = y0;
  t.x[1] = x1;
  t.y[1] = y1;
  t.x[2] = x2;
  t.y[2] = y2;
  return t;
}

ScreenTri reversed(const ScreenTri& t) {
  return screen_tri(t.x[0], t.y[0], t.x[2], t.y[2], t.x[1], t.y[1]);
}

int count_drawn(const RefFrame& f) {
  return static_cast<int>(
      std::count_if(f.owner.begin(), f.owner.end(), [](int32_t o) { return o >= 0; }));
}

// Eye-space direction (z = -1) of the ray through pixel (i, j)'s centre for
// perspective(fovy_deg, aspect, ...) and an identity view.
Vec3d pixel_ray(int i, int j, int w, int h, double fovy_deg, double aspect) {
  const double xn = 2.0 * (i + 0.5) / w - 1.0;
  const double yn = 1.0 - 2.0 * (j + 0.5) / h;
  const double th = std::tan(fovy_deg * kPi / 360.0);
  return {xn * th * aspect, yn * th, -1.0};
}

// Window depth of an eye-space z for gluPerspective(..., n, f), computed from the GL formulas.
double window_depth(double z_eye, double n, double f) {
  const double a = (f + n) / (n - f), b = 2.0 * f * n / (n - f);
  const double z_ndc = (a * z_eye + b) / -z_eye;
  return (z_ndc + 1.0) * 0.5;
}

// Ray (from the origin along d) against triangle abc: hit parameter t and barycentrics.
struct RayHit {
  bool ok = false;
  double t = 0;
  double b[3] = {0, 0, 0};
};

RayHit intersect(const Vec3d& d, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  RayHit h;
  const Vec3d e1 = sub(b, a), e2 = sub(c, a);
  const Vec3d p = cross(d, e2);
  const double det = dot(e1, p);
  if (std::fabs(det) < 1e-300) return h;
  const Vec3d s = sub(Vec3d{0, 0, 0}, a);
  const double u = dot(s, p) / det;
  const Vec3d q = cross(s, e1);
  const double v = dot(d, q) / det;
  h.t = dot(e2, q) / det;
  h.b[0] = 1.0 - u - v;
  h.b[1] = u;
  h.b[2] = v;
  h.ok = true;
  return h;
}

// ---------------------------------------------------------------------------------------------
// Matrices

TEST(RefMath, PerspectiveEqualsGluPerspective) {
  // fovy 90: f = cot(45 deg) = 1.
  const Mat4d p = perspective(90.0, 2.0, 1.0, 10.0);
  const double expect[4][4] = {{0.5, 0, 0, 0},
                               {0, 1.0, 0, 0},
                               {0, 0, -11.0 / 9.0, -20.0 / 9.0},  // (f+n)/(n-f), 2fn/(n-f)
                               {0, 0, -1, 0}};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(p.m[r][c], expect[r][c], 1e-14) << r << "," << c;

  // fovy 60: f = cot(30 deg) = sqrt(3).
  const Mat4d q = perspective(60.0, 4.0 / 3.0, 0.5, 100.0);
  EXPECT_NEAR(q.m[0][0], 1.2990381056766580, 1e-13);
  EXPECT_NEAR(q.m[1][1], 1.7320508075688772, 1e-13);
  EXPECT_NEAR(q.m[2][2], -1.0100502512562815, 1e-14);
  EXPECT_NEAR(q.m[2][3], -1.0050251256281406, 1e-14);
  EXPECT_EQ(q.m[3][2], -1.0);
  EXPECT_EQ(q.m[3][3], 0.0);

  // z = -near maps to NDC -1, z = -far to +1.
  const Vec4d n = transform(q, Vec4d{0, 0, -0.5, 1});
  const Vec4d f = transform(q, Vec4d{0, 0, -100, 1});
  EXPECT_NEAR(n[2] / n[3], -1.0, 1e-12);
  EXPECT_NEAR(f[2] / f[3], 1.0, 1e-12);
}

TEST(RefMath, LookAtEqualsGluLookAt) {
  // Straight down -Z: a pure translation.
  const Mat4d a = look_at({1, 2, 3}, {1, 2, 0}, {0, 1, 0});
  const Mat4d ta = translate({-1, -2, -3});
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(a.m[r][c], ta.m[r][c], 1e-15);

  // From +X: s = (0,0,-1), u = (0,1,0), -f = (1,0,0), translation (0,0,-3).
  const Mat4d b = look_at({3, 0, 0}, {0, 0, 0}, {0, 1, 0});
  const double eb[4][4] = {{0, 0, -1, 0}, {0, 1, 0, 0}, {1, 0, 0, -3}, {0, 0, 0, 1}};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(b.m[r][c], eb[r][c], 1e-15) << r << "," << c;

  // Oblique: eye (1,1,1) -> origin. s = (1,0,-1)/sqrt2, u = (-1,2,-1)/sqrt6, -f = (1,1,1)/sqrt3.
  const Mat4d c = look_at({1, 1, 1}, {0, 0, 0}, {0, 1, 0});
  const double r2 = 0.70710678118654752, r6 = 0.40824829046386302, r3 = 0.57735026918962576;
  const double ec[4][4] = {
      {r2, 0, -r2, 0}, {-r6, 2 * r6, -r6, 0}, {r3, r3, r3, -1.7320508075688772}, {0, 0, 0, 1}};
  for (int r = 0; r < 4; ++r)
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(c.m[r][k], ec[r][k], 1e-14) << r << "," << k;
  // The target lands on the -Z axis at the eye distance.
  const Vec3d o = transform_point(c, {0, 0, 0});
  EXPECT_NEAR(o[0], 0.0, 1e-15);
  EXPECT_NEAR(o[1], 0.0, 1e-15);
  EXPECT_NEAR(o[2], -1.7320508075688772, 1e-14);
}

TEST(RefMath, RotateTranslateScaleFollowGl) {
  const Vec3d x = transform_point(rotate_z(90), {1, 0, 0});  // x -> y
  EXPECT_NEAR(x[0], 0.0, 1e-15);
  EXPECT_NEAR(x[1], 1.0, 1e-15);
  const Vec3d y = transform_point(rotate_x(90), {0, 1, 0});  // y -> z
  EXPECT_NEAR(y[1], 0.0, 1e-15);
  EXPECT_NEAR(y[2], 1.0, 1e-15);
  const Vec3d z = transform_point(rotate_y(90), {0, 0, 1});  // z -> x
  EXPECT_NEAR(z[0], 1.0, 1e-15);
  EXPECT_NEAR(z[2], 0.0, 1e-15);
  // mul(A, B) applies B first: translate(scale(p)).
  const Vec3d p = transform_point(mul(translate({1, 2, 3}), scale({2, 3, 4})), {1, 1, 1});
  EXPECT_EQ(p, (Vec3d{3, 5, 7}));
  // Normals: inverse transpose. Plane x + z = 0 scaled by (1,1,2) has normal (2,0,1)/sqrt5.
  const Vec3d n = transform_normal(scale({1, 1, 2}), normalize({1, 0, 1}));
  EXPECT_NEAR(n[0], 2.0 / std::sqrt(5.0), 1e-15);
  EXPECT_NEAR(n[1], 0.0, 1e-15);
  EXPECT_NEAR(n[2], 1.0 / std::sqrt(5.0), 1e-15);
  Mat4d inv;
  ASSERT_TRUE(invert(look_at({1, 1, 1}, {0, 0, 0}, {0, 1, 0}), inv));
  const Vec3d eye = transform_point(inv, {0, 0, 0});
  EXPECT_NEAR(eye[0], 1.0, 1e-14);
  EXPECT_NEAR(eye[1], 1.0, 1e-14);
  EXPECT_NEAR(eye[2], 1.0, 1e-14);
}

// ---------------------------------------------------------------------------------------------
// Fill rule

TEST(FillRule, TrianglesOwnCentresOnLeftAndBottomEdgesOnly) {
  for (int bits : {4, 8}) {
    const int64_t S = int64_t{1} << bits;
    auto c = [&](int i) { return centre(i, S); };
    // T1: top edge y = 2.5 (not owned), left edge x = 2.5 (owned), hypotenuse x + y = 11 with
    // the interior at smaller x: a right edge (not owned).
    const ScreenTri t1 = screen_tri(c(2), c(2), c(8), c(2), c(2), c(8));
    // T2: bottom edge y = 8.5 (owned), right edge x = 8.5 (not owned), hypotenuse x + y = 11 with
    // the interior at larger x: a left edge (owned).
    const ScreenTri t2 = screen_tri(c(2), c(8), c(8), c(8), c(8), c(2));
    auto expect1 = [](int i, int j) { return i >= 2 && j >= 3 && i + j < 10; };
    auto expect2 = [](int i, int j) { return j <= 8 && i <= 7 && i + j >= 10; };
    for (const ScreenTri& t : {t1, reversed(t1)}) {
      std::vector<int32_t> hits, owner;
      coverage({t}, 12, 12, bits, hits, owner);
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 12; ++i) {
          EXPECT_EQ(hits[static_cast<size_t>(j * 12 + i)], expect1(i, j) ? 1 : 0) << i << "," << j;
          EXPECT_EQ(covers(t, c(i), c(j)), expect1(i, j)) << i << "," << j;
        }
    }
    for (const ScreenTri& t : {t2, reversed(t2)}) {
      std::vector<int32_t> hits, owner;
      coverage({t}, 12, 12, bits, hits, owner);
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 12; ++i) {
          EXPECT_EQ(hits[static_cast<size_t>(j * 12 + i)], expect2(i, j) ? 1 : 0) << i << "," << j;
          EXPECT_EQ(owner[static_cast<size_t>(j * 12 + i)], expect2(i, j) ? 0 : -1);
        }
    }
    // Spot checks with the rule spelled out.
    EXPECT_TRUE(covers(t1, c(2), c(5)));   // on T1's left edge
    EXPECT_FALSE(covers(t1, c(5), c(2)));  // on T1's top edge
    EXPECT_FALSE(covers(t1, c(4), c(6)));  // on T1's right (hypotenuse) edge
    EXPECT_TRUE(covers(t1, c(3), c(3)));   // strictly inside
    EXPECT_FALSE(covers(t1, c(2), c(2)));  // vertex on left + top: top not owned
    EXPECT_TRUE(covers(t2, c(5), c(8)));   // on T2's bottom edge
    EXPECT_FALSE(covers(t2, c(8), c(5)));  // on T2's right edge
    EXPECT_TRUE(covers(t2, c(4), c(6)));   // on T2's left (hypotenuse) edge
    EXPECT_TRUE(covers(t2, c(2), c(8)));   // vertex on bottom + left: both owned
    EXPECT_FALSE(covers(t2, c(8), c(8)));  // vertex on bottom + right: right not owned
    // Degenerate triangles cover nothing, not even their own points.
    EXPECT_FALSE(covers(screen_tri(c(1), c(1), c(5), c(5), c(3), c(3)), c(3), c(3)));
  }
}

TEST(FillRule, SquareSplitByDiagonalCoversEveryCentreOnce) {
  for (int bits : {4, 8}) {
    const int64_t S = int64_t{1} << bits;
    const int64_t l = centre(2, S), r = centre(10, S), t = centre(2, S), b = centre(10, S);
    // Corners at pixel centres: centres lie on all four sides and on the diagonal.
    const std::vector<std::vector<ScreenTri>> splits = {
        {screen_tri(l, t, r, t, r, b), screen_tri(l, t, r, b, l, b)},  // diagonal TL-BR
        {screen_tri(l, t, r, t, l, b), screen_tri(r, t, r, b, l, b)},  // diagonal TR-BL
    };
    for (const auto& split : splits) {
      for (bool flip : {false, true}) {
        std::vector<ScreenTri> tris = split;
        if (flip) tris[1] = reversed(tris[1]);  // mixed windings
        std::vector<int32_t> hits, owner;
        coverage(tris, 14, 14, bits, hits, owner);
        for (int j = 0; j < 14; ++j)
          for (int i = 0; i < 14; ++i) {
            // Closed on the left and bottom sides, open on the top and right sides.
            const bool in = i >= 2 && i <= 9 && j >= 3 && j <= 10;
            EXPECT_EQ(hits[static_cast<size_t>(j * 14 + i)], in ? 1 : 0) << i << "," << j;
          }
      }
    }
  }
}

TEST(FillRule, FanAroundAPixelCentreCoversEveryCentreOnce) {
  const int64_t S = 256;
  const int64_t cx = centre(20, S), cy = centre(20, S);
  // Outer ring (convex, angular order); most vertices at pixel centres so spokes and outer edges
  // pass through many centres, two with odd subpixel offsets.
  const std::vector<std::array<int64_t, 2>> ring = {
      {8 * S, 0},       {8 * S, 5 * S},  {6 * S, 8 * S},       {0, 8 * S},
      {-4 * S, 8 * S},  {-8 * S, 8 * S}, {-8 * S, 37},         {-8 * S, -3 * S},
      {-8 * S, -8 * S}, {0, -8 * S},     {5 * S + 13, -8 * S}, {8 * S, -8 * S}};
  const size_t n = ring.size();
  for (bool reverse : {false, true}) {
    std::vector<ScreenTri> fan;
    for (size_t k = 0; k < n; ++k) {
      const auto& a = ring[k];
      const auto& b = ring[(k + 1) % n];
      ScreenTri t = screen_tri(cx, cy, cx + a[0], cy + a[1], cx + b[0], cy + b[1]);
      fan.push_back(reverse ? reversed(t) : t);
    }
    std::vector<int32_t> hits, owner;
    coverage(fan, 40, 40, 8, hits, owner);
    EXPECT_EQ(hits[20 * 40 + 20], 1);  // the hub, where all triangles meet
    int inside_count = 0;
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 40; ++i) {
        const int64_t px = centre(i, S) - cx, py = centre(j, S) - cy;
        int pos = 0, neg = 0;
        for (size_t k = 0; k < n; ++k) {
          const auto& a = ring[k];
          const auto& b = ring[(k + 1) % n];
          const int64_t e = (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
          pos += e > 0;
          neg += e < 0;
        }
        const int h = hits[static_cast<size_t>(j * 40 + i)];
        if (pos == static_cast<int>(n) || neg == static_cast<int>(n)) {
          EXPECT_EQ(h, 1) << "strictly inside " << i << "," << j;
          ++inside_count;
        } else if (pos > 0 && neg > 0) {
          EXPECT_EQ(h, 0) << "outside " << i << "," << j;
        } else {
          EXPECT_LE(h, 1) << "on the outer boundary " << i << "," << j;
        }
      }
    EXPECT_GT(inside_count, 200);
  }
}

TEST(FillRule, JitteredGridTilingCoversEveryCentreOnce) {
  for (uint32_t seed = 1; seed <= 30; ++seed) {
    std::mt19937 rng(seed);
    const int bits = (seed % 3 == 0) ? 4 : (seed % 3 == 1) ? 6 : 8;
    const int64_t S = int64_t{1} << bits;
    const int n = 12;                              // cells per side
    const int64_t cell = 4 * S, o = centre(4, S);  // grid starts on a pixel centre
    std::uniform_int_distribution<int64_t> uni(-3 * S / 4, 3 * S / 4);
    auto jitter = [&]() -> int64_t {
      if (rng() % 2) return uni(rng);
      const int64_t choice[3] = {-S / 2, 0, S / 2};  // on centres or on pixel borders
      return choice[rng() % 3];
    };
    // Boundary vertices only slide along the boundary, so the union is the rectangle.
    std::vector<int64_t> vx((n + 1) * (n + 1)), vy((n + 1) * (n + 1));
    for (int gy = 0; gy <= n; ++gy)
      for (int gx = 0; gx <= n; ++gx) {
        const size_t k = static_cast<size_t>(gy * (n + 1) + gx);
        vx[k] = o + gx * cell + ((gx == 0 || gx == n) ? 0 : jitter());
        vy[k] = o + gy * cell + ((gy == 0 || gy == n) ? 0 : jitter());
      }
    auto v = [&](int gx, int gy) { return static_cast<size_t>(gy * (n + 1) + gx); };
    auto make = [&](size_t a, size_t b, size_t c) {
      ScreenTri t = screen_tri(vx[a], vy[a], vx[b], vy[b], vx[c], vy[c]);
      return (rng() % 2) ? reversed(t) : t;
    };
    std::vector<ScreenTri> tris;
    for (int gy = 0; gy < n; ++gy)
      for (int gx = 0; gx < n; ++gx) {
        const size_t a = v(gx, gy), b = v(gx + 1, gy), c = v(gx + 1, gy + 1), d = v(gx, gy + 1);
        if (rng() % 2) {
          tris.push_back(make(a, b, c));
          tris.push_back(make(a, c, d));
        } else {
          tris.push_back(make(a, b, d));
          tris.push_back(make(b, c, d));
        }
      }
    std::shuffle(tris.begin(), tris.end(), rng);
    std::vector<int32_t> hits, owner;
    coverage(tris, 64, 64, bits, hits, owner);
    const int64_t x1 = o + n * cell, y1 = o + n * cell;
    int wrong = 0;
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i) {
        const int64_t px = centre(i, S), py = centre(j, S);
        const bool in = px >= o && px < x1 && py > o && py <= y1;
        const int h = hits[static_cast<size_t>(j * 64 + i)];
        if (h != (in ? 1 : 0)) ++wrong;
      }
    EXPECT_EQ(wrong, 0) << "seed " << seed << " bits " << bits;
  }
}

TEST(FillRule, RenderRasterizesTheSnappedVerticesWithTheSameRule) {
  // Identity matrices: clip = position, so the snapped display coordinates are known exactly.
  const int W = 40, H = 30, bits = 8;
  const int64_t S = 256;
  std::mt19937 rng(7);
  std::uniform_int_distribution<int64_t> ux(-5 * S, 45 * S), uy(-5 * S, 35 * S);
  std::uniform_int_distribution<int> pick(0, 2);
  HostMesh mesh;
  std::vector<ScreenTri> expected;
  for (uint32_t t = 0; t < 60; ++t) {
    int64_t sx[3], sy[3];
    for (int k = 0; k < 3; ++k) {
      sx[k] = ux(rng);
      sy[k] = uy(rng);
      if (pick(rng) == 0) {  // land some vertices exactly on pixel centres
        sx[k] = (sx[k] / S) * S + S / 2;
        sy[k] = (sy[k] / S) * S + S / 2;
      }
      const double x_ndc = static_cast<double>(sx[k]) / S / W * 2.0 - 1.0;
      const double y_ndc = 1.0 - static_cast<double>(sy[k]) / S / H * 2.0;
      mesh.positions.push_back({x_ndc, y_ndc, 0.0});
      mesh.normals.push_back({0, 0, 1});
    }
    mesh.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
    expected.push_back(screen_tri(sx[0], sy[0], sx[1], sy[1], sx[2], sy[2]));
  }
  RefParams p;
  p.width = W;
  p.height = H;
  p.depth_test = false;
  p.unlit = true;
  p.subpixel_bits = bits;
  RefFrame f;
  render(mesh, p, f);
  std::vector<int32_t> hits, owner;
  coverage(expected, W, H, bits, hits, owner);
  EXPECT_EQ(f.owner, owner);
  EXPECT_GT(count_drawn(f), 100);
}

TEST(FillRule, SnappingRoundsToNearestSubpixelHalfAwayFromZero) {
  // A triangle whose left edge is vertical at window x = xs / 256 (subpixels), through rows 1..15.
  // Pixel column 5 has its centre at subpixel 1408: covered iff the snapped edge is <= 1408.
  auto column5_covered = [](double xs) {
    const double x = xs / 256.0;
    auto ndc_x = [](double wx) { return wx / 16.0 * 2.0 - 1.0; };
    auto ndc_y = [](double wy) { return 1.0 - wy / 16.0 * 2.0; };
    const HostMesh mesh =
        make_mesh({{ndc_x(x), ndc_y(1), 0}, {ndc_x(x), ndc_y(15), 0}, {ndc_x(x + 8), ndc_y(8), 0}},
                  {{0, 1, 2}});
    RefParams p;
    p.width = p.height = 16;
    p.unlit = true;
    RefFrame f;
    render(mesh, p, f);
    EXPECT_EQ(f.owner[f.index(6, 8)], 0);  // well inside
    return f.owner[f.index(5, 8)] == 0;
  };
  EXPECT_TRUE(column5_covered(1408.0));   // exactly on the centre: left edge owns it
  EXPECT_TRUE(column5_covered(1408.4));   // rounds down to 1408
  EXPECT_FALSE(column5_covered(1408.5));  // half rounds away from zero: 1409
  EXPECT_FALSE(column5_covered(1408.6));  // rounds up to 1409
  EXPECT_TRUE(column5_covered(1407.5));   // 1408
  EXPECT_TRUE(column5_covered(1407.4));   // 1407: the centre is strictly inside
}

// ---------------------------------------------------------------------------------------------
// Culling

TEST(Culling, CounterClockwiseInNdcIsFrontFacing) {
  const HostMesh ccw = make_mesh({{-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0, 0.5, 0}}, {{0, 1, 2}});
  const HostMesh cw = make_mesh({{-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0, 0.5, 0}}, {{0, 2, 1}});
  RefParams p;
  p.width = p.height = 16;
  p.unlit = true;
  RefFrame f;
  p.cull_back = false;
  render(ccw, p, f);
  const int drawn = count_drawn(f);
  EXPECT_GT(drawn, 20);
  render(cw, p, f);
  EXPECT_EQ(count_drawn(f), drawn);
  p.cull_back = true;
  render(ccw, p, f);
  EXPECT_EQ(count_drawn(f), drawn);
  render(cw, p, f);
  EXPECT_EQ(count_drawn(f), 0);
  // Turning the CCW triangle around (seen from behind) makes it a back face.
  p.model = rotate_y(180);
  render(ccw, p, f);
  EXPECT_EQ(count_drawn(f), 0);

  // The same triangle in display coordinates (y down): negative signed area is front.
  // NDC (-0.5,-0.5), (0.5,-0.5), (0,0.5) -> pixels (4,12), (12,12), (8,4).
  const ScreenTri front = screen_tri(4 * 256, 12 * 256, 12 * 256, 12 * 256, 8 * 256, 4 * 256);
  EXPECT_LT(signed_area2(front), 0.0);
  EXPECT_GT(signed_area2(reversed(front)), 0.0);
}

// ---------------------------------------------------------------------------------------------
// Lighting

RefParams camera_params(Vec3d eye, int size = 33) {
  RefParams p;
  p.width = p.height = size;
  p.view = look_at(eye, {0, 0, 0}, {0, 1, 0});
  p.projection = perspective(60, 1, 1, 100);
  return p;
}

TEST(Lighting, TriangleFacingLightAndViewerMatchesGlFormula) {
  const HostMesh mesh = make_mesh({{-3, -3, 0}, {3, -3, 0}, {0, 3, 0}}, {{0, 1, 2}});
  RefParams p = camera_params({0, 0, 5});
  p.lights = {RefLight{{1, 2, 2}, {1.0, 0.5, 0.25}}};  // normalized: (1,2,2)/3
  p.global_ambient = {0.2, 0.2, 0.2};
  p.material.ambient = {0.1, 0.2, 0.3};
  p.material.diffuse = {0.5, 0.4, 0.3};
  p.material.specular = {0.2, 0.2, 0.2};
  p.material.emission = {0.05, 0, 0};
  p.material.shininess = 4;
  // N = (0,0,1), L = (1,2,2)/3: N.L = 2/3. V = (0,0,1): H = (1,2,5)/sqrt30, N.H^4 = (25/30)^2.
  const double ndl = 2.0 / 3.0, spec = 25.0 / 36.0;
  const Vec3d expect{0.05 + 0.2 * 0.1 + 1.0 * 0.1 + ndl * 1.0 * 0.5 + spec * 1.0 * 0.2,
                     0.0 + 0.2 * 0.2 + 0.5 * 0.2 + ndl * 0.5 * 0.4 + spec * 0.5 * 0.2,
                     0.0 + 0.2 * 0.3 + 0.25 * 0.3 + ndl * 0.25 * 0.3 + spec * 0.25 * 0.2};
  for (RefShading shading : {RefShading::Gouraud, RefShading::Flat}) {
    p.shading = shading;
    RefFrame f;
    render(mesh, p, f);
    const size_t c = f.index(16, 16);
    ASSERT_EQ(f.owner[c], 0);
    for (size_t ch = 0; ch < 3; ++ch) EXPECT_NEAR(f.color[c][ch], expect[ch], 1e-12);
    EXPECT_EQ(f.rgb8[c * 3 + 0], 164);  // round(255 * 0.64222)
    EXPECT_EQ(f.rgb8[c * 3 + 1], 87);   // round(255 * 0.34278)
    EXPECT_EQ(f.rgb8[c * 3 + 2], 56);   // round(255 * 0.21972)
    // A plane with one normal and an infinite viewer: every drawn pixel has the same colour.
    for (size_t i = 0; i < f.owner.size(); ++i)
      if (f.owner[i] == 0) {
        EXPECT_NEAR(f.color[i][0], expect[0], 1e-12);
      }
  }
}

TEST(Lighting, SurfaceFacingAwayFromLightGetsOnlyAmbientAndEmission) {
  const HostMesh mesh = make_mesh({{-3, -3, 0}, {3, -3, 0}, {0, 3, 0}}, {{0, 1, 2}});
  RefParams p = camera_params({0, 0, 5});
  p.lights = {RefLight{{0, 0.2, -1}, {1, 1, 1}}};
  p.material.ambient = {0.1, 0.2, 0.3};
  p.material.emission = {0.01, 0.02, 0.03};
  p.material.specular = {1, 1, 1};
  p.material.shininess = 0;  // pow(0, 0) = 1 would show if the N.L > 0 guard were missing
  RefFrame f;
  render(mesh, p, f);
  const size_t c = f.index(16, 16);
  EXPECT_NEAR(f.color[c][0], 0.11, 1e-15);
  EXPECT_NEAR(f.color[c][1], 0.22, 1e-15);
  EXPECT_NEAR(f.color[c][2], 0.33, 1e-15);
}

TEST(Lighting, InfiniteViewerUsesTheViewZAxis) {
  const HostMesh mesh = make_mesh({{-100, -100, 0}, {100, -100, 0}, {0, 100, 0}}, {{0, 1, 2}});
  RefParams p = camera_params({3, 0, 4});  // V = (0.6, 0, 0.8) everywhere
  p.lights = {RefLight{{0, 0, 1}, {1, 1, 1}}};
  p.material.ambient = {0, 0, 0};
  p.material.diffuse = {0, 0, 0};
  p.material.specular = {1, 1, 1};
  p.material.shininess = 8;
  // H = normalize((0.6, 0, 1.8)): (N.H)^2 = 3.24 / 3.6 = 0.9, so (N.H)^8 = 0.9^4 = 0.6561.
  RefFrame f;
  render(mesh, p, f);
  int drawn = 0;
  for (size_t i = 0; i < f.owner.size(); ++i)
    if (f.owner[i] == 0) {
      ++drawn;
      EXPECT_NEAR(f.color[i][1], 0.6561, 1e-12);
      EXPECT_EQ(f.rgb8[i * 3 + 1], 167);
    }
  EXPECT_EQ(drawn, 33 * 33);
}

TEST(Lighting, LocalViewerUsesTheEyeToPointVector) {
  // Flat shading lights the centroid (1, 0, 0) once; the eye is at (0, 0, 5).
  const HostMesh mesh = make_mesh({{-1, -2, 0}, {5, -2, 0}, {-1, 4, 0}}, {{0, 1, 2}});
  RefParams p = camera_params({0, 0, 5});
  p.shading = RefShading::Flat;
  p.lights = {RefLight{{0, 0, 1}, {1, 1, 1}}};
  p.material.ambient = {0, 0, 0};
  p.material.diffuse = {0, 0, 0};
  p.material.specular = {1, 1, 1};
  p.material.shininess = 10;
  const double r26 = std::sqrt(26.0);
  const double hx = -1.0 / r26, hz = 1.0 + 5.0 / r26;  // L + V, V = (-1, 0, 5)/sqrt26
  const double expect = std::pow(hz / std::sqrt(hx * hx + hz * hz), 10.0);
  ASSERT_LT(expect, 0.96);
  RefFrame f;
  p.local_viewer = true;
  render(mesh, p, f);
  const size_t c = f.index(16, 16);
  ASSERT_EQ(f.owner[c], 0);
  EXPECT_NEAR(f.color[c][0], expect, 1e-12);
  p.local_viewer = false;  // infinite viewer: H = N exactly
  render(mesh, p, f);
  EXPECT_NEAR(f.color[c][0], 1.0, 1e-12);
}

TEST(Lighting, NormalsAreTransformedByTheInverseTransposeOfTheModel) {
  // Model-space plane x + z = 0 (normal (1,0,1)/sqrt2), scaled by (1,1,2): world normal is
  // (2,0,1)/sqrt5. Light along (2,0,1): N.L = 1 gives 0.6; transforming the normal by the model
  // matrix itself would give (1,0,2)/sqrt5 and N.L = 0.8 (0.48).
  const HostMesh mesh =
      make_mesh({{1, -1, -1}, {0, 1, 0}, {-1, -1, 1}}, {{0, 1, 2}}, normalize({1, 0, 1}));
  RefParams p = camera_params({8, 0, 4});
  p.model = scale({1, 1, 2});
  p.lights = {RefLight{{2, 0, 1}, {1, 1, 1}}};
  p.material.ambient = {0, 0, 0};
  p.material.diffuse = {0.6, 0.6, 0.6};
  p.material.specular = {0, 0, 0};
  for (RefShading shading : {RefShading::Gouraud, RefShading::Flat}) {
    p.shading = shading;
    RefFrame f;
    render(mesh, p, f);
    const size_t c = f.index(16, 16);
    ASSERT_EQ(f.owner[c], 0);
    EXPECT_NEAR(f.color[c][0], 0.6, 1e-12);
    EXPECT_EQ(f.rgb8[c * 3], 153);
  }
}

// ---------------------------------------------------------------------------------------------
// Unlit colours, depth

TEST(Shading, UnlitFlatTakesTheLastVertexColour) {
  HostMesh mesh = make_mesh({{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {{0, 1, 2}});
  mesh.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  RefParams p;
  p.width = p.height = 16;
  p.unlit = true;
  p.shading = RefShading::Flat;
  RefFrame f;
  render(mesh, p, f);
  int drawn = 0;
  for (size_t i = 0; i < f.owner.size(); ++i)
    if (f.owner[i] == 0) {
      ++drawn;
      EXPECT_EQ(f.color[i], (Vec3d{0, 0, 1}));
      EXPECT_EQ(f.rgb8[i * 3 + 2], 255);
    }
  EXPECT_GT(drawn, 60);
  // Without vertex colours: the material's diffuse colour.
  mesh.colors.clear();
  p.material.diffuse = {0.2, 0.4, 0.6};
  for (RefShading s : {RefShading::Flat, RefShading::Gouraud}) {
    p.shading = s;
    render(mesh, p, f);
    const size_t c = f.index(8, 8);
    ASSERT_EQ(f.owner[c], 0);
    EXPECT_NEAR(f.color[c][1], 0.4, 1e-15);
    EXPECT_EQ(f.rgb8[c * 3 + 0], 51);
    EXPECT_EQ(f.rgb8[c * 3 + 1], 102);
    EXPECT_EQ(f.rgb8[c * 3 + 2], 153);
  }
  // Background where nothing is drawn.
  p.background = {0.5, 0.25, 1.0};
  render(mesh, p, f);
  EXPECT_EQ(f.owner[0], -1);
  EXPECT_EQ(f.depth[0], 1.0);
  EXPECT_EQ(f.rgb8[0], 128);  // round(127.5) = 128
  EXPECT_EQ(f.rgb8[1], 64);   // round(63.75)
  EXPECT_EQ(f.rgb8[2], 255);
}

TEST(Depth, NearerSurfaceWinsWhateverTheOrderAndTiesKeepTheFirst) {
  // Two full-screen quads (identity matrices), z = -0.5 (depth 0.25) and z = 0.5 (depth 0.75).
  auto quad_pair = [](double z_first, double z_second) {
    return make_mesh({{-1, -1, z_first},
                      {1, -1, z_first},
                      {1, 1, z_first},
                      {-1, 1, z_first},
                      {-1, -1, z_second},
                      {1, -1, z_second},
                      {1, 1, z_second},
                      {-1, 1, z_second}},
                     {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}});
  };
  RefParams p;
  p.width = p.height = 8;
  p.unlit = true;
  RefFrame f;
  render(quad_pair(-0.5, 0.5), p, f);
  for (size_t i = 0; i < f.owner.size(); ++i) {
    EXPECT_LT(f.owner[i], 2);
    EXPECT_EQ(f.depth[i], 0.25);
  }
  render(quad_pair(0.5, -0.5), p, f);
  for (size_t i = 0; i < f.owner.size(); ++i) {
    EXPECT_GE(f.owner[i], 2);
    EXPECT_EQ(f.depth[i], 0.25);
  }
  render(quad_pair(0.0, 0.0), p, f);  // LESS: equal depth does not overwrite
  for (size_t i = 0; i < f.owner.size(); ++i) EXPECT_LT(f.owner[i], 2);
  p.depth_test = false;  // no test, no depth writes: the last triangle wins
  render(quad_pair(-0.5, 0.5), p, f);
  for (size_t i = 0; i < f.owner.size(); ++i) {
    EXPECT_GE(f.owner[i], 2);
    EXPECT_EQ(f.depth[i], 1.0);
  }
}

// ---------------------------------------------------------------------------------------------
// Perspective-correct interpolation and clipping

struct FloorCase {
  double z_near_edge, z_far_edge, clip_near;
};

// A floor quad y = -1, x in [-5, 5], from z_near_edge to z_far_edge, colour r linear in z and g
// linear in x (both affine on the plane, so exact for any triangulation). Every pixel whose ray
// hits the quad (with a margin) must show the analytic colour and depth; every pixel whose ray
// misses it must show the background.
void check_floor(const FloorCase& fc) {
  const int W = 64, H = 64;
  const double fovy = 60, n = fc.clip_near, far = 100;
  const double z0 = fc.z_near_edge, z1 = fc.z_far_edge;
  HostMesh mesh = make_mesh({{-5, -1, z0}, {5, -1, z0}, {5, -1, z1}, {-5, -1, z1}},
                            {{0, 1, 2}, {0, 2, 3}}, {0, 1, 0});
  auto r_of = [&](double z) { return (z0 - z) / (z0 - z1); };
  auto g_of = [](double x) { return (x + 5.0) / 10.0; };
  for (const Vec3d& v : mesh.positions) mesh.colors.push_back({r_of(v[2]), g_of(v[0]), 0.25});
  RefParams p;
  p.width = W;
  p.height = H;
  p.projection = perspective(fovy, 1.0, n, far);
  p.unlit = true;
  p.cull_back = true;  // seen from above: front facing
  RefFrame f;
  render(mesh, p, f);

  int checked = 0, clipped_away = 0;
  double max_col_err = 0, max_depth_err = 0;
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const size_t idx = f.index(i, j);
      const Vec3d d = pixel_ray(i, j, W, H, fovy, 1.0);
      if (d[1] >= 0) {  // at or above the horizon: nothing, and no spikes
        EXPECT_EQ(f.owner[idx], -1) << i << "," << j;
        continue;
      }
      const double t = -1.0 / d[1];  // hit y = -1 at eye distance t (z = -t)
      const double x = t * d[0], z = -t;
      const double zmin = std::min(z0, z1), zmax = std::max(z0, z1);
      const bool on_quad_in = std::fabs(x) < 4.9 && z > zmin + 0.3 && z < zmax - 0.3;
      const bool on_quad_out = std::fabs(x) > 5.1 || z < zmin - 0.5 || z > zmax + 0.3;
      if (on_quad_in && t > n * 1.01) {
        ASSERT_NE(f.owner[idx], -1) << "crack at " << i << "," << j;
        const Vec3d expect{r_of(z), g_of(x), 0.25};
        for (size_t ch = 0; ch < 3; ++ch)
          max_col_err = std::max(max_col_err, std::fabs(f.color[idx][ch] - expect[ch]));
        max_depth_err = std::max(max_depth_err, std::fabs(f.depth[idx] - window_depth(z, n, far)));
        ++checked;
      } else if (on_quad_out || t < n * 0.99) {
        EXPECT_EQ(f.owner[idx], -1) << i << "," << j;
        if (on_quad_in) ++clipped_away;
      }
      EXPECT_GE(f.depth[idx], 0.0);
      EXPECT_LE(f.depth[idx], 1.0);
    }
  EXPECT_GT(checked, 500);
  EXPECT_LT(max_col_err, 3e-3);
  EXPECT_LT(max_depth_err, 2e-4);
  if (z0 > -n) {
    EXPECT_GT(clipped_away, 0);  // the near plane cut through the visible floor
  }

  // The test discriminates: along column 32, the analytic r differs from a screen-linear ramp
  // between the projected near and far edges by far more than the tolerance.
  const double th = std::tan(fovy * kPi / 360.0);
  auto screen_y = [&](double z) { return (1.0 - (-1.0 / (-z * th))) * H * 0.5; };
  const double ya = screen_y(std::min(z0, -n)), yb = screen_y(z1);
  double max_affine_gap = 0;
  for (int j = 0; j < H; ++j) {
    const double yc = j + 0.5;
    if (yc >= ya || yc <= yb) continue;
    const Vec3d d = pixel_ray(32, j, W, H, fovy, 1.0);
    const double z = 1.0 / d[1];
    const double linear =
        r_of(std::min(z0, -n)) + (ya - yc) / (ya - yb) * (1.0 - r_of(std::min(z0, -n)));
    max_affine_gap = std::max(max_affine_gap, std::fabs(r_of(z) - linear));
  }
  EXPECT_GT(max_affine_gap, 0.1);
}

TEST(Interpolation, RecedingQuadIsPerspectiveCorrect) {
  check_floor({-2.0, -20.0, 1.0});
}

TEST(Clipping, QuadCrossingTheNearPlaneKeepsExactAttributes) {
  // The near edge is behind the eye (z = +3); the near plane (z = -2.5) cuts the visible floor.
  check_floor({3.0, -20.0, 2.5});
}

TEST(Clipping, TriangleCrossingTheNearPlaneDrawsOnlyTheVisiblePart) {
  // A floor triangle with two vertices behind the eye: projected without clipping they would
  // flip above the horizon (spikes).
  const int W = 64, H = 64;
  const double fovy = 60, n = 2.5, far = 100;
  const Vec3d a{0, -1, -30}, b{6, -1, 4}, c{-6, -1, 4};
  HostMesh mesh = make_mesh({a, b, c}, {{0, 1, 2}}, {0, 1, 0});
  mesh.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  RefParams p;
  p.width = W;
  p.height = H;
  p.projection = perspective(fovy, 1.0, n, far);
  p.unlit = true;
  RefFrame f;
  render(mesh, p, f);
  int inside = 0, clipped = 0;
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const size_t idx = f.index(i, j);
      EXPECT_GE(f.depth[idx], 0.0);
      EXPECT_LE(f.depth[idx], 1.0);
      const Vec3d d = pixel_ray(i, j, W, H, fovy, 1.0);
      if (d[1] >= 0) {
        EXPECT_EQ(f.owner[idx], -1) << "spike at " << i << "," << j;
        continue;
      }
      const RayHit h = intersect(d, a, b, c);
      ASSERT_TRUE(h.ok);
      const double bmin = std::min({h.b[0], h.b[1], h.b[2]});
      if (bmin > 0.01 && h.t > n * 1.01) {
        ASSERT_EQ(f.owner[idx], 0) << i << "," << j;
        EXPECT_NEAR(f.depth[idx], window_depth(-h.t, n, far), 2e-4);
        for (size_t ch = 0; ch < 3; ++ch) EXPECT_NEAR(f.color[idx][ch], h.b[ch], 3e-3);
        ++inside;
      } else if (bmin < -0.01 || h.t < n * 0.99) {
        EXPECT_EQ(f.owner[idx], -1) << i << "," << j;
        if (bmin > 0.01) ++clipped;
      }
    }
  EXPECT_GT(inside, 500);
  EXPECT_GT(clipped, 64);  // the rows below the near-plane cut
}

TEST(Clipping, FarPlaneCutsTheDistantPart) {
  // A wall-like triangle receding from z = -5 to z = -50 with far = 20.
  const int W = 32, H = 32;
  const double fovy = 60, n = 1, far = 20;
  const Vec3d a{-1, -1, -5}, b{1, -1, -5}, c{0, 0.5, -50};
  HostMesh mesh = make_mesh({a, b, c}, {{0, 1, 2}});
  RefParams p;
  p.width = W;
  p.height = H;
  p.projection = perspective(fovy, 1.0, n, far);
  p.unlit = true;
  // Without the depth test nothing else (e.g. depth > 1 failing LESS against 1.0) hides the part
  // beyond the far plane: the clipping must remove it.
  for (bool depth_test : {true, false}) {
    p.depth_test = depth_test;
    RefFrame f;
    render(mesh, p, f);
    int in = 0, cut = 0;
    for (int j = 0; j < H; ++j)
      for (int i = 0; i < W; ++i) {
        const size_t idx = f.index(i, j);
        const RayHit h = intersect(pixel_ray(i, j, W, H, fovy, 1.0), a, b, c);
        const double bmin = std::min({h.b[0], h.b[1], h.b[2]});
        if (h.ok && bmin > 0.01 && h.t < far * 0.99) {
          EXPECT_EQ(f.owner[idx], 0);
          if (depth_test) {
            EXPECT_NEAR(f.depth[idx], window_depth(-h.t, n, far), 2e-4);
          }
          ++in;
        } else if (!h.ok || bmin < -0.01 || h.t > far * 1.01) {
          EXPECT_EQ(f.owner[idx], -1);
          if (h.ok && bmin > 0.01) ++cut;
        }
      }
    EXPECT_GT(in, 20);
    EXPECT_GT(cut, 0);
  }
}

TEST(Clipping, SharedEdgesStayWatertightAfterNearClipping) {
  // A jittered floor grid from z = +6 (behind the eye) to z = -30, every triangle rendered alone:
  // no pixel centre may be covered twice, and the whole visible floor must be covered.
  const int W = 48, H = 48, n_cells = 6;
  const double fovy = 70, n = 1.5, far = 100;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jit(-0.9, 0.9);
  HostMesh mesh;
  for (int gz = 0; gz <= n_cells; ++gz)
    for (int gx = 0; gx <= n_cells; ++gx) {
      const bool edge = gx == 0 || gx == n_cells || gz == 0 || gz == n_cells;
      mesh.positions.push_back(
          {-12.0 + 4.0 * gx + (edge ? 0 : jit(rng)), -1.0, 6.0 - 6.0 * gz + (edge ? 0 : jit(rng))});
      mesh.normals.push_back({0, 1, 0});
    }
  auto v = [&](int gx, int gz) { return static_cast<uint32_t>(gz * (n_cells + 1) + gx); };
  for (int gz = 0; gz < n_cells; ++gz)
    for (int gx = 0; gx < n_cells; ++gx) {
      if ((gx + gz) % 2) {
        mesh.triangles.push_back({v(gx, gz), v(gx + 1, gz), v(gx + 1, gz + 1)});
        mesh.triangles.push_back({v(gx, gz), v(gx + 1, gz + 1), v(gx, gz + 1)});
      } else {
        mesh.triangles.push_back({v(gx, gz), v(gx + 1, gz), v(gx, gz + 1)});
        mesh.triangles.push_back({v(gx + 1, gz), v(gx + 1, gz + 1), v(gx, gz + 1)});
      }
    }
  RefParams p;
  p.width = W;
  p.height = H;
  p.projection = perspective(fovy, 1.0, n, far);
  p.unlit = true;
  p.depth_test = false;
  std::vector<int> hits(static_cast<size_t>(W * H), 0);
  HostMesh single = mesh;
  RefFrame f;
  for (const auto& t : mesh.triangles) {
    single.triangles = {t};
    render(single, p, f);
    for (size_t i = 0; i < hits.size(); ++i) hits[i] += f.owner[i] == 0;
  }
  int visible = 0;
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const int h = hits[static_cast<size_t>(j * W + i)];
      EXPECT_LE(h, 1) << i << "," << j;
      const Vec3d d = pixel_ray(i, j, W, H, fovy, 1.0);
      if (d[1] >= 0) {
        EXPECT_EQ(h, 0);
        continue;
      }
      const double t = -1.0 / d[1], x = t * d[0], z = -t;
      if (std::fabs(x) < 11.9 && z > -29.9 && t > n * 1.01) {
        EXPECT_EQ(h, 1) << "crack at " << i << "," << j;
        ++visible;
      } else if (t < n * 0.99) {
        EXPECT_EQ(h, 0) << i << "," << j;
      }
    }
  EXPECT_GT(visible, 500);
}

TEST(Clipping, HugeXOverWIsRasterizedWithoutTrouble) {
  // perspective(90, 1): x_ndc = x / -z. The third vertex sits on the near plane at x/w = 1e6.
  const int W = 32, H = 32;
  const HostMesh mesh = make_mesh({{0, 0, -5}, {0, 1, -5}, {1e6, 0, -1}}, {{0, 1, 2}});
  RefParams p;
  p.width = W;
  p.height = H;
  p.projection = perspective(90, 1.0, 1.0, 100);
  p.unlit = true;
  RefFrame f;
  render(mesh, p, f);
  // On screen the triangle is the band x_ndc in [0, 1e6], y_ndc in [0, ~0.2]: columns 16..31,
  // rows 13..15 (centres at y_ndc 0.156, 0.094, 0.031).
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const size_t idx = f.index(i, j);
      const bool in = i >= 16 && j >= 13 && j <= 15;
      EXPECT_EQ(f.owner[idx], in ? 0 : -1) << i << "," << j;
      EXPECT_GE(f.depth[idx], 0.0);
      EXPECT_LE(f.depth[idx], 1.0);
    }
}

}  // namespace
}  // namespace lr::ref
