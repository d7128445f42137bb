// make_plane's gradients against the two-division formula they replaced: 256 q + round(256 r /
// area) with q, r the truncated quotient and remainder of n / area, which never forms 256 n.
// The one-division path (|n| < 2^55) must give the same value bit for bit, and the needle limit
// (|q| >= 2^30: constant attributes) must fall at the same place, over random triangles from
// tiny to guard-band size and attribute differences up to the full 32 bits.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "core/math/fixed.hpp"
#include "core/setup/triangle_setup.hpp"
#include "core/vertex/screen_vertex.hpp"

namespace lr {
namespace {

// The previous implementation, kept as the reference.
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

// True when a numerator of the plane's gradients is 2^55 or more in magnitude: the general path.
bool takes_general_path(const ScreenVertex s[3], const uint32_t a[3]) {
  const int64_t ex1 = int64_t{s[1].x} - s[0].x, ey1 = int64_t{s[1].y} - s[0].y;
  const int64_t ex2 = int64_t{s[2].x} - s[0].x, ey2 = int64_t{s[2].y} - s[0].y;
  const int64_t da1 = int64_t{a[1]} - a[0], da2 = int64_t{a[2]} - a[0];
  const int64_t nx = da1 * ey2 - da2 * ey1, ny = da2 * ex1 - da1 * ex2;
  auto big = [](int64_t n) { return n >= (int64_t{1} << 55) || n <= -(int64_t{1} << 55); };
  return big(nx) || big(ny);
}

// make_plane against the reference for one triangle; the reference plane.
Plane expect_same_plane(const ScreenVertex s[3], const uint32_t a[3], int i) {
  const ScreenVertex* v[3] = {&s[0], &s[1], &s[2]};
  const Plane want = reference_plane(v, a);
  const Plane got = make_plane(v, a);
  EXPECT_EQ(got.base, want.base) << i;
  EXPECT_EQ(got.gx, want.gx) << i;
  EXPECT_EQ(got.gy, want.gy) << i;
  return want;
}

TEST(PlaneGradient, OneDivisionEqualsTheTwoDivisionFormula) {
  std::mt19937_64 rng(20261122);
  int fast = 0, general = 0, needles = 0;
  for (int i = 0; i < 400000; ++i) {
    // Extent: 2^2 .. 2^22 subpixels (1/64 pixel .. the guard band), so |n| spans 2^3 .. 2^57.
    const int bits = 2 + static_cast<int>(rng() % 21);
    const int32_t span = int32_t{1} << bits;
    auto coord = [&] {
      return static_cast<int32_t>(rng() % static_cast<uint64_t>(2 * span)) - span;
    };
    ScreenVertex s[3];
    for (auto& sv : s) {
      sv.x = coord();
      sv.y = coord();
    }
    uint32_t a[3];
    const int abits = 1 + static_cast<int>(rng() % 32);
    for (auto& x : a) x = static_cast<uint32_t>(rng() >> (64 - abits));
    const Plane want = expect_same_plane(s, a, i);
    takes_general_path(s, a) ? ++general : ++fast;
    if (want.gx == 0 && want.gy == 0 && a[0] != a[1]) ++needles;
  }
  // Inside the guard band (|x|, |y| < 2^22) with 32-bit attributes |n| stays below 2^55, so
  // the one-division path always applies in the renderer; the general path is a fallback. It is
  // reached here with coordinates twice the guard band's and attributes from 0 to 2^32 - 1.
  for (int i = 0; i < 20000; ++i) {
    constexpr int32_t kEdge = int32_t{1} << 23;
    auto jitter = [&] { return static_cast<int32_t>(rng() % 4096); };
    ScreenVertex s[3];
    s[0].x = -kEdge + jitter();
    s[0].y = jitter();
    s[1].x = jitter();
    s[1].y = kEdge - 1 - jitter();
    s[2].x = jitter();
    s[2].y = -kEdge + jitter();
    const uint32_t a[3] = {static_cast<uint32_t>(rng() % 65536),
                           0xFFFFFFFFu - static_cast<uint32_t>(rng() % 65536),
                           static_cast<uint32_t>(rng())};
    expect_same_plane(s, a, i);
    if (takes_general_path(s, a)) ++general;
  }
  // Both paths and the needle fallback were exercised.
  EXPECT_GT(fast, 100000);
  EXPECT_GT(general, 1000);  // from the second loop
  EXPECT_GT(needles, 100);
}

}  // namespace
}  // namespace lr
