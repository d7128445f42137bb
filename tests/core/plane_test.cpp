// make_plane against the exact plane through the three vertex values.
//
// Short path (PlaneBasis::fast): every pixel centre of the triangle's bounding box is within
// 9 x 2^(2 bm + sh - 30) + 0.5 (|Dx| + |Dy| + 1) units of the exact value (modulo 2^32), Dx, Dy
// the pixel's distance from vertex 0 (docs/numerics.md#attribute-plane-equations). Exact path:
// bit for bit the two-division formula 256 q + round(256 r / area) with q, r the truncated
// quotient and remainder of n / area, including the needle limit (|q| >= 2^30: constant
// attributes). Random triangles from tiny to guard-band size, attribute differences up to 32
// bits. Also the perspective factors q = w_min / w against the rounded 64-bit quotient.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/setup/triangle_setup.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"
#include "tests/support/plane_error.hpp"

namespace lr {
namespace {

using test::plane_error;
using test::sample_bounding_box;

// The previous implementation, kept as the reference of the exact path.
bool reference_gradient(int64_t n, int64_t area, int64_t& g) {
  const int64_t q = n / area, r = n % area;
  if (q >= (int64_t{1} << 30) || q <= -(int64_t{1} << 30)) return false;
  g = q * kSubpixel + round_div(r * kSubpixel, area);
  return true;
}

Plane reference_plane(const ScreenVertex* const v[3], const uint32_t a[3]) {
  const int64_t x0 = v[0]->x, y0 = v[0]->y;
  const int64_t ex1 = v[1]->x - x0, ey1 = v[1]->y - y0, ex2 = v[2]->x - x0, ey2 = v[2]->y - y0;
  int64_t area = ex1 * ey2 - ex2 * ey1;
  const int64_t da1 = int64_t{a[1]} - a[0], da2 = int64_t{a[2]} - a[0];
  int64_t nx = da1 * ey2 - da2 * ey1, ny = da2 * ex1 - da1 * ex2;
  if (area < 0) {
    area = -area;
    nx = -nx;
    ny = -ny;
  }
  Plane p;
  int64_t gx = 0, gy = 0;
  if (area == 0 || !reference_gradient(nx, area, gx) || !reference_gradient(ny, area, gy)) {
    p.base = static_cast<uint32_t>((int64_t{a[0]} + a[1] + a[2]) / 3);
    return p;
  }
  const int64_t off = gx * (kHalfPixel - x0) + gy * (kHalfPixel - y0);
  p.base = static_cast<uint32_t>(static_cast<uint64_t>(int64_t{a[0]} + round_div(off, kSubpixel)));
  p.gx = static_cast<uint32_t>(static_cast<uint64_t>(gx));
  p.gy = static_cast<uint32_t>(static_cast<uint64_t>(gy));
  return p;
}

// The short path's documented error term 9 x 2^(2 bm + sh - 30) for this triangle.
double fast_term(const ScreenVertex* const v[3]) {
  auto mag = [](int64_t e) { return static_cast<uint32_t>(e < 0 ? -e : e); };
  const int64_t e1x = v[1]->x - v[0]->x, e1y = v[1]->y - v[0]->y;
  const int64_t e2x = v[2]->x - v[0]->x, e2y = v[2]->y - v[0]->y;
  const int bm = 32 - clz32(mag(e1x) | mag(e1y) | mag(e2x) | mag(e2y));
  const auto d = static_cast<uint32_t>(abs64(e1x * e2y - e2x * e1y));
  return 9.0 * std::ldexp(1.0, 2 * bm + clz32(d) - 30);
}

struct Errors {
  long long samples = 0, over = 0;
  double max_ratio = 0;  // largest error / bound
  double max_abs = 0;
};

// Checks the plane at the corners and a few random pixel centres of the triangle's bounding box.
void check_bound(const ScreenVertex* const v[3], const uint32_t a[3], bool fast,
                 std::mt19937_64& rng, Errors& e) {
  const Plane p = make_plane(v, a);
  const double term = fast ? fast_term(v) : 0.0;
  sample_bounding_box(v, rng, [&](int32_t c, int32_t r, double distance) {
    const double err = std::fabs(plane_error(v, a, p, c, r));
    const double bound = term + 0.5 * (distance + 1) + 1e-6;
    ++e.samples;
    e.max_abs = std::max(e.max_abs, err);
    e.max_ratio = std::max(e.max_ratio, err / bound);
    if (err > bound && e.over++ < 5)
      ADD_FAILURE() << "error " << err << " > bound " << bound << " at (" << c << "," << r << ")";
  });
}

TEST(PlaneGradient, WithinTheDocumentedBoundOnBothPathsAndExactOnTheExactPath) {
  std::mt19937_64 rng(20261122);
  int fast = 0, exact = 0, needles = 0;
  Errors ef, ee;
  for (int i = 0; i < 300000; ++i) {
    // Extent: 2^2 .. 2^22 subpixels (1/64 pixel .. the guard band), so |n| spans 2^3 .. 2^57.
    const int bits = 2 + static_cast<int>(rng() % 21);
    const int32_t span = int32_t{1} << bits;
    auto coord = [&] {
      return static_cast<int32_t>(rng() % static_cast<uint64_t>(2 * span)) - span;
    };
    ScreenVertex s[3];
    // Half of them near a random place on the screen (the base's pixel split).
    const int32_t ox = i % 2 ? static_cast<int32_t>(rng() % (1u << 20)) - (1 << 19) : 0;
    const int32_t oy = i % 2 ? static_cast<int32_t>(rng() % (1u << 20)) - (1 << 19) : 0;
    for (auto& sv : s) {
      sv.x = ox + coord();
      sv.y = oy + coord();
    }
    uint32_t a[3];
    const int abits = 1 + static_cast<int>(rng() % 32);
    for (auto& x : a) x = static_cast<uint32_t>(rng() >> (64 - abits));
    const ScreenVertex* v[3] = {&s[0], &s[1], &s[2]};
    const PlaneBasis pb(v);
    if (signed_area2(s[0], s[1], s[2]) == 0) continue;
    if (pb.fast) {
      ++fast;
      check_bound(v, a, true, rng, ef);
    } else {
      ++exact;
      const Plane want = reference_plane(v, a), got = make_plane(pb, a);
      EXPECT_EQ(got.base, want.base) << i;
      EXPECT_EQ(got.gx, want.gx) << i;
      EXPECT_EQ(got.gy, want.gy) << i;
      if (want.gx == 0 && want.gy == 0 && a[0] != a[1]) {
        ++needles;
      } else {
        check_bound(v, a, false, rng, ee);
      }
    }
  }
  std::printf(
      "[ plane ] short path: %d triangles, %lld samples, max error %.1f units, %.3f of the bound; "
      "exact path: %d (%d needles), max error %.1f, %.3f of the bound\n",
      fast, ef.samples, ef.max_abs, ef.max_ratio, exact, needles, ee.max_abs, ee.max_ratio);
  EXPECT_EQ(ef.over, 0);
  EXPECT_EQ(ee.over, 0);
  // Both paths and the needle fallback were exercised, and the bound is not loose by orders of
  // magnitude.
  EXPECT_GT(fast, 50000);
  EXPECT_GT(exact, 20000);
  EXPECT_GT(needles, 100);
  EXPECT_GT(ef.max_ratio, 0.1);
}

// The exact path's numerators at 2^55 and above (gradient()'s second way: quotient and remainder
// from the reciprocal, no 64-bit division), which only coordinates beyond the budget reach
// (edges up to 2^25 subpixels): bit for bit the two-division formula.
TEST(PlaneGradient, LargeNumeratorsEqualTheTwoDivisions) {
  std::mt19937_64 rng(20261206);
  int large = 0;
  for (int i = 0; i < 200000; ++i) {
    const int32_t span = int32_t{1} << (21 + static_cast<int>(rng() % 4));  // 2^21 .. 2^24
    auto coord = [&] {
      return static_cast<int32_t>(rng() % static_cast<uint64_t>(2 * span)) - span;
    };
    ScreenVertex s[3];
    for (auto& sv : s) {
      sv.x = coord();
      sv.y = coord();
    }
    uint32_t a[3];
    for (auto& x : a) x = static_cast<uint32_t>(rng());
    const ScreenVertex* v[3] = {&s[0], &s[1], &s[2]};
    const PlaneBasis pb(v);
    if (pb.fast || signed_area2(s[0], s[1], s[2]) == 0) continue;
    const int64_t da1 = int64_t{a[1]} - a[0], da2 = int64_t{a[2]} - a[0];
    const uint64_t nx = abs64(da1 * pb.ey2 - da2 * pb.ey1), ny = abs64(da2 * pb.ex1 - da1 * pb.ex2);
    const auto area = static_cast<uint64_t>(pb.area);
    if ((nx >= (uint64_t{1} << 55) && (nx >> 30) < area) ||
        (ny >= (uint64_t{1} << 55) && (ny >> 30) < area))
      ++large;
    const Plane want = reference_plane(v, a), got = make_plane(pb, a);
    ASSERT_EQ(got.base, want.base) << i;
    ASSERT_EQ(got.gx, want.gx) << i;
    ASSERT_EQ(got.gy, want.gy) << i;
  }
  EXPECT_GT(large, 10000);
}

// Typical mesh triangles (a few pixels, aspect below 16) all take the short path, and depth
// differs from the exact plane by far less than one 16-bit depth step (2^16 units).
TEST(PlaneGradient, SmallWellShapedTrianglesTakeTheShortPath) {
  std::mt19937_64 rng(7);
  Errors e;
  for (int i = 0; i < 100000; ++i) {
    const int32_t size = 64 + static_cast<int32_t>(rng() % (16 * 256));  // 1/4 .. 16 pixels
    ScreenVertex s[3];
    s[0].x = static_cast<int32_t>(rng() % (320 * 256));
    s[0].y = static_cast<int32_t>(rng() % (240 * 256));
    const double ang = static_cast<double>(rng() % 6283) / 1000;
    const double ang2 = ang + 0.4 + static_cast<double>(rng() % 2300) / 1000;  // 23 .. 155 deg
    s[1].x = s[0].x + static_cast<int32_t>(size * std::cos(ang));
    s[1].y = s[0].y + static_cast<int32_t>(size * std::sin(ang));
    const double len2 = size * (0.5 + static_cast<double>(rng() % 1000) / 1000);
    s[2].x = s[0].x + static_cast<int32_t>(len2 * std::cos(ang2));
    s[2].y = s[0].y + static_cast<int32_t>(len2 * std::sin(ang2));
    const ScreenVertex* v[3] = {&s[0], &s[1], &s[2]};
    if (signed_area2(s[0], s[1], s[2]) == 0) continue;
    ASSERT_TRUE(PlaneBasis(v).fast) << i;
    const uint32_t z[3] = {static_cast<uint32_t>(rng() % (uint64_t{65535} << 16)),
                           static_cast<uint32_t>(rng() % (uint64_t{65535} << 16)),
                           static_cast<uint32_t>(rng() % (uint64_t{65535} << 16))};
    check_bound(v, z, true, rng, e);
  }
  EXPECT_EQ(e.over, 0);
  EXPECT_LT(e.max_abs, 1024.0);  // 1/64 of a depth step
}

TEST(PerspectiveFactor, EqualsTheRoundedQuotient) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 300000; ++i) {
    const int wb = 1 + static_cast<int>(rng() % 32);
    auto w = static_cast<uint32_t>(rng() >> (64 - wb));
    w = w == 0 ? 1 : w;
    const uint32_t wmin = i % 4 == 0 ? w : 1 + static_cast<uint32_t>(rng() % w);
    const uint64_t want = ((uint64_t{wmin} << 30) + w / 2) / w;
    ASSERT_EQ(perspective_factor(wmin, w), want == 0 ? 1u : want) << wmin << " / " << w;
  }
  EXPECT_EQ(perspective_factor(0xFFFFFFFFu, 0xFFFFFFFFu), 1u << 30);
  EXPECT_EQ(perspective_factor(1, 0xFFFFFFFFu), 1u);
  EXPECT_EQ(perspective_factor(1u << 15, 1u << 16), 1u << 29);
  EXPECT_EQ(perspective_factor(1, 3), 357913941u);  // 2^30 / 3 = 357913941.33
}

}  // namespace
}  // namespace lr
