// The untextured family's setup (core/setup/untextured_setup.{hpp,cpp}) against exact values:
//
// - the 32-bit short path's planes (fast_basis, fast_plane, and the int32 setup of small
//   triangles) at pixel centres of random triangles' bounding boxes, within the error the
//   documentation derives (docs/numerics.md#untextured-planes): per pixel from vertex 0,
//   5 x 2^s units from the coefficients (half a unit more where the gradient is rounded), plus
//   the base's rounding;
// - long needles take the exact wide path and FrameStats::triangles_wide counts them;
// - the affine colour test of each pixel format: wherever it accepts a triangle, its
//   screen-linear colours are within half an output step of the perspective-correct ones
//   (docs/numerics.md#when-screen-linear-colours-are-close-enough), and the test is tight.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/setup/triangle_rows.hpp"
#include "lineraster/core/setup/triangle_setup.hpp"
#include "lineraster/core/setup/untextured_setup.hpp"
#include "tests/support/core_harness.hpp"
#include "tests/support/plane_error.hpp"

namespace lr {
namespace {

using test::plane_error;
using test::sample_bounding_box;

int bit_length(uint32_t v) {
  return v == 0 ? 0 : 32 - clz32(v);
}
uint32_t mag(int64_t v) {
  return static_cast<uint32_t>(v < 0 ? -v : v);
}

// The triangle's bm and L (docs/numerics.md#untextured-planes).
void bm_and_l(const ScreenVertex* const v[3], int& bm, int& l) {
  const int64_t e1x = v[1]->x - v[0]->x, e1y = v[1]->y - v[0]->y;
  const int64_t e2x = v[2]->x - v[0]->x, e2y = v[2]->y - v[0]->y;
  bm = bit_length(mag(e1x) | mag(e1y) | mag(e2x) | mag(e2y));
  const int64_t d = e1x * e2y - e2x * e1y;
  const auto ad = static_cast<uint64_t>(d < 0 ? -d : d);
  l = 64 - clz64(ad);
}

struct Errors {
  long long samples = 0, over = 0;
  double max_ratio = 0;     // largest error / bound
  double max_relative = 0;  // largest error / the attribute's largest difference
  double max_abs = 0;       // in units
};

// Checks plane p (gradient scale 2^s) at the corners and random pixel centres of the bounding
// box against the derived bound.
void check(const ScreenVertex* const v[3], const uint32_t a[3], const Plane& p, int s,
           std::mt19937_64& rng, Errors& e) {
  const uint32_t range = std::max({mag(int64_t{a[1]} - a[0]), mag(int64_t{a[2]} - a[0]), 1u});
  const double unit = std::ldexp(1.0, s);
  sample_bounding_box(v, rng, [&](int32_t c, int32_t r, double distance) {
    const double err = std::fabs(plane_error(v, a, p, c, r));
    const double bound = (5 * unit + (s < 0 ? 0.5 : 0.0)) * (distance + 1) + 8 * unit + 1;
    ++e.samples;
    e.max_ratio = std::max(e.max_ratio, err / bound);
    e.max_relative = std::max(e.max_relative, err / range);
    e.max_abs = std::max(e.max_abs, err);
    if (err > bound && e.over++ < 5)
      ADD_FAILURE() << "error " << err << " > bound " << bound << " at (" << c << "," << r
                    << "), s " << s;
  });
}

TEST(UntexturedPlanes, ShortPathWithinTheDocumentedBound) {
  std::mt19937_64 rng(36);
  int taken = 0, refused = 0;
  Errors e;
  for (int i = 0; i < 200000; ++i) {
    // Extent 2^2 .. 2^20 subpixels, anywhere in the guard band.
    const int bits = 2 + static_cast<int>(rng() % 19);
    const int32_t span = int32_t{1} << bits;
    auto coord = [&] {
      return static_cast<int32_t>(rng() % static_cast<uint64_t>(2 * span)) - span;
    };
    const int32_t ox = static_cast<int32_t>(rng() % (1u << 21)) - (1 << 20);
    const int32_t oy = static_cast<int32_t>(rng() % (1u << 21)) - (1 << 20);
    ScreenVertex sv[3];
    for (auto& x : sv) {
      x.x = ox + coord();
      x.y = oy + coord();
    }
    if (signed_area2(sv[0], sv[1], sv[2]) == 0) continue;
    const ScreenVertex* v[3] = {&sv[0], &sv[1], &sv[2]};
    FastBasis b;
    if (!fast_basis(v, kFastMaxSpread, b)) {
      ++refused;
      continue;
    }
    ++taken;
    // Values in [0, 2^31) whose differences have abits bits: u = 30 - abits.
    const int abits = 1 + static_cast<int>(rng() % 31);
    const uint32_t lo = static_cast<uint32_t>(rng() % (1u << 30));
    int32_t a[3];
    uint32_t ua[3];
    for (int k = 0; k < 3; ++k) {
      a[k] = static_cast<int32_t>(lo + static_cast<uint32_t>(rng() >> (64 - abits)) / 2);
      ua[k] = static_cast<uint32_t>(a[k]);
    }
    const int dbits = bit_length(std::max(mag(int64_t{a[1]} - a[0]), mag(int64_t{a[2]} - a[0])));
    const int u = 30 - dbits;
    const Plane p = fast_plane(b, a, u);
    check(v, ua, p, b.p - u, rng, e);
  }
  std::printf("[ planes ] short path: %d triangles (%d refused), %lld samples, %.3f of the bound\n",
              taken, refused, e.samples, e.max_ratio);
  EXPECT_EQ(e.over, 0);
  EXPECT_GT(taken, 100000);
  EXPECT_GT(refused, 5000);
  EXPECT_GT(e.max_ratio, 0.05);  // not loose by orders of magnitude
}

// The small path's bound (docs/numerics.md#untextured-planes): the reciprocal's relative error
// (2^-27 plus that of its shift right by rshift) times the exact plane's change from vertex 0,
// the floored gradients' 2^left per pixel from the reference pixel, the offset's two floors, the
// dropped low bits of the depth differences (2^zsh times the barycentric weights) and a unit.
void check_small(const ScreenVertex* const v[3], const uint32_t a[3], const Plane& p, int left,
                 int rshift, int zsh, std::mt19937_64& rng, Errors& e) {
  const double x0 = v[0]->x, y0 = v[0]->y;
  const double ex1 = v[1]->x - x0, ey1 = v[1]->y - y0, ex2 = v[2]->x - x0, ey2 = v[2]->y - y0;
  const double d = ex1 * ey2 - ex2 * ey1;
  const double rel = std::ldexp(1.0, -27) + std::ldexp(1.0, rshift - 30);
  const double da1 = static_cast<double>(a[1]) - a[0], da2 = static_cast<double>(a[2]) - a[0];
  sample_bounding_box(v, rng, [&](int32_t c, int32_t r, double /*distance*/) {
    const double err = std::fabs(plane_error(v, a, p, c, r));
    const double px = c * 256.0 + 128 - x0, py = r * 256.0 + 128 - y0;
    const double l1 = (px * ey2 - py * ex2) / d, l2 = (py * ex1 - px * ey1) / d;
    const double change = std::fabs(l1 * da1 + l2 * da2);
    const double unit = std::ldexp(1.0, left);
    const double bound = rel * change + unit * (std::fabs(px) / 256 + std::fabs(py) / 256 + 4) +
                         std::ldexp(1.0, zsh) * (std::fabs(l1) + std::fabs(l2)) + 1;
    ++e.samples;
    e.max_ratio = std::max(e.max_ratio, err / bound);
    if (l1 >= 0 && l2 >= 0 && l1 + l2 <= 1) e.max_abs = std::max(e.max_abs, err);  // inside
    if (err > bound && e.over++ < 5)
      ADD_FAILURE() << "error " << err << " > bound " << bound << " at (" << c << "," << r
                    << "), left " << left << " rshift " << rshift << " zsh " << zsh;
  });
}

// Small triangles (edge components below 2^14 subpixels) are set up in int32 throughout, from
// exact numerators and one reciprocal; their depth and colour planes are within its bound.
TEST(UntexturedPlanes, SmallTrianglesInInt32WithinTheBound) {
  std::mt19937_64 rng(37);
  UntexturedInput in;
  in.colors = ColorPlanes::kAffine;
  in.depth = true;
  Errors ez, ec, eo;
  int small = 0, flat = 0, deep = 0;
  for (int i = 0; i < 100000; ++i) {
    ScreenVertex sv[3];
    const int32_t ox = static_cast<int32_t>(rng() % (300 * 256)),
                  oy = static_cast<int32_t>(rng() % (200 * 256));
    const int32_t reach = 1 + static_cast<int32_t>(rng() % (i % 2 ? 16383 : 2048));
    // One triangle in four at (nearly) one depth, at the range's ends among others; one in four
    // with depth differences below 2^26 half units (the small path's), the rest anywhere.
    const bool flat_depth = i % 4 == 3;
    const bool near_depth = i % 4 == 1;
    const uint32_t zbase = i % 8 == 3   ? kDepthMax - 3
                           : i % 8 == 7 ? static_cast<uint32_t>(rng() % 4)
                                        : static_cast<uint32_t>(rng() % (kDepthMax - (1u << 28)));
    const uint32_t zreach = near_depth ? static_cast<uint32_t>(1u << (rng() % 28)) : 0;
    for (auto& x : sv) {
      x.x = ox + static_cast<int32_t>(rng() % static_cast<uint64_t>(reach));
      x.y = oy + static_cast<int32_t>(rng() % static_cast<uint64_t>(reach));
      x.z = flat_depth   ? zbase + static_cast<uint32_t>(rng() % (i % 16 == 3 ? 1 : 4))
            : near_depth ? zbase + static_cast<uint32_t>(rng() % zreach)
                         : static_cast<uint32_t>(rng() % (uint64_t{kDepthMax} + 1));
      x.w = 1u << 16;
      x.color = Color15{static_cast<uint16_t>(rng() % 32769), static_cast<uint16_t>(rng() % 32769),
                        static_cast<uint16_t>(rng() % 32769)};
    }
    if (signed_area2(sv[0], sv[1], sv[2]) == 0) continue;
    const ScreenVertex* v[3] = {&sv[0], &sv[1], &sv[2]};
    sort_by_y(v);
    int bm = 0, l = 0;
    bm_and_l(v, bm, l);
    if (2 * bm - l > kFastMaxSpread) continue;
    uint32_t z[3];
    for (int k = 0; k < 3; ++k) z[k] = (v[k]->z >> 1) + (1u << 14);
    const uint32_t zd = std::max(mag(int64_t{z[1]} - z[0]), mag(int64_t{z[2]} - z[0]));
    const int zbits = bit_length(zd);
    if (2 * bm - l + zbits > kFastMaxDepthSpread) continue;
    ActiveTriangle t;
    const UntexturedTriangle got = setup_untextured_triangle(v, RowWindow{0, 240, 320}, in, t);
    if (!got.pixels()) continue;
    ASSERT_FALSE(got.wide());
    ASSERT_EQ(got.kind(), UntexturedKind::kAffine);
    if (zbits > kSmallMaxDepthBits) {
      // setup_untextured's short path (fast_plane): its own bound.
      const int p = 11 + bm - l;
      ++deep;
      check(v, z, t.z, p - (30 - zbits), rng, eo);
      for (int ch = 0; ch < 3; ++ch) {
        uint32_t c[3];
        for (int k = 0; k < 3; ++k) c[k] = uint32_t{channel(v[k]->color, ch)} << 15;
        check(v, c, t.c[ch], p, rng, eo);
      }
      continue;
    }
    ++small;
    flat += flat_depth ? 1 : 0;
    const int tg = l - bm + 4;  // the products' exponent
    auto split = [](int s, int& left, int& rshift) {
      left = s > 0 ? s : 0;
      rshift = s < 0 ? std::min(-s, 31) : 0;
    };
    int left = 0, rshift = 0;
    const int zsh = zbits > 16 ? zbits - 16 : 0;
    split(zsh - tg, left, rshift);
    check_small(v, z, t.z, left, rshift, zsh, rng, ez);
    split(15 - tg, left, rshift);
    for (int ch = 0; ch < 3; ++ch) {
      uint32_t c[3];
      for (int k = 0; k < 3; ++k) c[k] = uint32_t{channel(v[k]->color, ch)} << 15;
      check_small(v, c, t.c[ch], left, rshift, 0, rng, ec);
    }
  }
  std::printf(
      "[ planes ] small path: %d triangles (%d at nearly one depth, %d deeper on the short "
      "path), depth %.3f, colours %.3f of the bound, depth %.0f half units at most\n",
      small, flat, deep, ez.max_ratio, ec.max_ratio, ez.max_abs);
  EXPECT_EQ(ez.over, 0);
  EXPECT_EQ(ec.over, 0);
  EXPECT_EQ(eo.over, 0);
  EXPECT_GT(small, 40000);
  EXPECT_GT(flat, 10000);
  EXPECT_GT(deep, 1000);
  EXPECT_GT(ec.max_ratio, 0.05);  // not loose by orders of magnitude
  // Depth within 0.08 of a 16-bit step (2^15 units of half depth) inside these triangles.
  EXPECT_LT(ez.max_abs, 2560.0);
}

// A needle whose spread exceeds the short path's limit is set up on the exact wide path and
// counted; a small triangle beside it is not.
TEST(UntexturedPlanes, NeedlesTakeTheWidePathAndAreCounted) {
  test::ScreenScene scene;
  constexpr int64_t S = kSubpixel;
  // 1,800 pixels long, a quarter pixel thick, crossing the row centre 30.5 (spread 13).
  scene.add(-800 * S, 30 * S, 1000 * S, 31 * S, 1000 * S, 31 * S + S / 4);
  scene.add(10 * S, 10 * S, 20 * S, 12 * S, 12 * S, 20 * S);
  DrawState st = test::coverage_state();
  st.depth_test = true;
  st.shading = Shading::kGouraud;
  test::CoreHarness<8> h(320, 64);
  h.begin();
  ASSERT_EQ(h.renderer().draw_screen(scene.vertices, scene.triangles, st), Status::kOk);
  Status status = Status::kInvalidArgument;
  h.render(&status);
  EXPECT_EQ(status, Status::kOk);
  EXPECT_EQ(h.renderer().stats().triangles_wide, 1u);
  EXPECT_GT(h.renderer().stats().pixels_written, 100u);

  const ScreenVertex* v[3] = {&scene.vertices[0], &scene.vertices[1], &scene.vertices[2]};
  sort_by_y(v);
  UntexturedInput in;
  in.colors = ColorPlanes::kAffine;
  ActiveTriangle t;
  EXPECT_TRUE(setup_untextured(v, in, t).wide);
  const ScreenVertex* w[3] = {&scene.vertices[3], &scene.vertices[4], &scene.vertices[5]};
  sort_by_y(w);
  EXPECT_FALSE(setup_untextured(w, in, t).wide);
}

// Barycentric mixes of the vertex colours: screen-linear and perspective-correct (weights
// l_i / w_i), channel ch in [0, 1].
double mix(const ScreenVertex* const v[3], const double l[3], int ch, bool perspective) {
  double num = 0, den = 0;
  for (int k = 0; k < 3; ++k) {
    const double wt = perspective ? l[k] / v[k]->w : l[k];
    num += wt * channel(v[k]->color, ch);
    den += wt;
  }
  return num / den / Color15::kOne;
}

TEST(AffineBound, AcceptedTrianglesAreWithinHalfAnOutputStep) {
  std::mt19937_64 rng(38);
  struct Format {
    AffineBound bound;
    double half_step[3];  // of red, green, blue, in [0, 1]
    int accepted = 0, refused = 0;
    double worst = 0;  // largest error / half a step, over accepted triangles
  };
  Format formats[2] = {{kAffineBound8, {0.5 / 255, 0.5 / 255, 0.5 / 255}},
                       {kAffineBound565, {0.5 / 31, 0.5 / 63, 0.5 / 31}}};
  for (int i = 0; i < 40000; ++i) {
    ScreenVertex sv[3];
    const uint32_t w0 = 1u << (10 + rng() % 16);
    const uint32_t dw = static_cast<uint32_t>(rng() % (w0 >> (1 + rng() % 9)) + 1);
    for (auto& x : sv) {
      x.w = w0 + static_cast<uint32_t>(rng() % dw);
      // Colour ranges from a few levels to full scale.
      const uint32_t cr = 1u << (6 + rng() % 10);
      const uint32_t c0 = static_cast<uint32_t>(rng() % (32769 - cr));
      x.color =
          Color15{static_cast<uint16_t>(c0 + rng() % cr), static_cast<uint16_t>(c0 + rng() % cr),
                  static_cast<uint16_t>(c0 + rng() % cr)};
    }
    // The worst pixel lies at an edge: sample barycentrics on the edges and inside.
    const ScreenVertex* v[3] = {&sv[0], &sv[1], &sv[2]};
    for (Format& f : formats) {
      if (!affine_within(v, f.bound)) {
        ++f.refused;
        continue;
      }
      ++f.accepted;
      for (int k = 0; k <= 64; ++k) {
        for (int e = 0; e < 4; ++e) {
          double l[3] = {0, 0, 0};
          const double s = k / 64.0;
          if (e < 3) {
            l[e] = s;
            l[(e + 1) % 3] = 1 - s;
          } else {
            const double r1 = static_cast<double>(rng() % 1000) / 1000, r2 = (1 - r1) * s;
            l[0] = r1;
            l[1] = r2;
            l[2] = 1 - r1 - r2;
          }
          for (int ch = 0; ch < 3; ++ch) {
            const double d = std::fabs(mix(v, l, ch, false) - mix(v, l, ch, true));
            f.worst = std::max(f.worst, d / f.half_step[ch]);
          }
        }
      }
    }
  }
  for (const Format& f : formats)
    std::printf("[ affine ] bound %u: %d accepted, %d refused, worst %.3f of half a step\n",
                f.bound.bound, f.accepted, f.refused, f.worst);
  for (const Format& f : formats) {
    EXPECT_LE(f.worst, 1.0);
    EXPECT_GT(f.worst, 0.25);  // the test is not far stricter than it needs to be
    EXPECT_GT(f.accepted, 1000);
    EXPECT_GT(f.refused, 1000);
  }
  // The RGB565 bound accepts more triangles than the 8-bit one.
  EXPECT_GT(formats[1].accepted, formats[0].accepted);
}

// The bound itself, at its edge: (w_max - w_min) D = bound x w_min is accepted, one more is not.
TEST(AffineBound, ExactlyAtTheBound) {
  ScreenVertex sv[3];
  const uint32_t wmin = 1u << 20;
  // Red range D = 2^12: (w_max - w_min) = 2080 x 2^20 / 2^12 = 2080 x 2^8 for RGB565.
  sv[0].color = Color15{0, 0, 0};
  sv[1].color = Color15{1u << 12, 0, 0};
  sv[2].color = Color15{0, 0, 0};
  sv[0].w = wmin;
  sv[2].w = wmin;
  const ScreenVertex* v[3] = {&sv[0], &sv[1], &sv[2]};
  sv[1].w = wmin + 2080 * 256;
  EXPECT_TRUE(affine_within(v, kAffineBound565));
  EXPECT_FALSE(affine_within(v, kAffineBound8));
  sv[1].w = wmin + 2080 * 256 + 1;
  EXPECT_FALSE(affine_within(v, kAffineBound565));
  // Green counts twice for RGB565: the same range in green needs half the w spread.
  sv[1].color = Color15{0, 1u << 12, 0};
  sv[1].w = wmin + 1040 * 256;
  EXPECT_TRUE(affine_within(v, kAffineBound565));
  sv[1].w = wmin + 1040 * 256 + 1;
  EXPECT_FALSE(affine_within(v, kAffineBound565));
  // The colour-free quick test: w_max - w_min <= w_min / 2^5 is accepted whatever the colours.
  sv[1].color = Color15{Color15::kOne, Color15::kOne, Color15::kOne};
  sv[1].w = wmin + (wmin >> 5);
  EXPECT_TRUE(affine_within(v, kAffineBound565));
  sv[1].w = wmin + (wmin >> 5) + 1024;
  EXPECT_FALSE(affine_within(v, kAffineBound565));
}

// Small thin triangles in windows that cut their first rows: setup_untextured_triangle finds
// pixels exactly where setup_rows does (its small path checks one row first, then the later
// ones: later_rows_have_pixels), with the same rows.
TEST(UntexturedRows, SliversAsSetupRowsFindsThem) {
  std::mt19937_64 rng(53);
  UntexturedInput in;
  in.colors = ColorPlanes::kAffine;
  in.depth = true;
  int slivers = 0, drawn = 0, untested_slivers = 0;
  for (int i = 0; i < 200000; ++i) {
    ScreenVertex sv[3];
    const int32_t ox = static_cast<int32_t>(rng() % (40 * 256)) - 4 * 256,
                  oy = static_cast<int32_t>(rng() % (40 * 256));
    // A needle from (ox, oy) along a random direction, its third vertex a little off the line.
    const int32_t dx = static_cast<int32_t>(rng() % (16 * 256)) - 8 * 256,
                  dy = static_cast<int32_t>(rng() % (16 * 256));
    const int32_t off = static_cast<int32_t>(rng() % 257) - 128;
    const int32_t f = static_cast<int32_t>(rng() % 256);
    sv[0].x = ox;
    sv[0].y = oy;
    sv[1].x = ox + dx;
    sv[1].y = oy + dy;
    sv[2].x = ox + dx * f / 256 + off;
    sv[2].y = oy + dy * f / 256 + static_cast<int32_t>(rng() % 65) - 32;
    for (auto& x : sv) {
      x.z = 1u << 20;
      x.w = 1u << 16;
      x.color = Color15{1000, 2000, 3000};
    }
    if (signed_area2(sv[0], sv[1], sv[2]) == 0) continue;
    const ScreenVertex* v[3] = {&sv[0], &sv[1], &sv[2]};
    sort_by_y(v);
    const int32_t first_min = static_cast<int32_t>(rng() % 40);
    const RowWindow w{first_min, first_min + static_cast<int32_t>(rng() % 16),
                      1 + static_cast<int32_t>(rng() % 32)};
    ActiveTriangle t, r;
    const UntexturedTriangle got = setup_untextured_triangle(v, w, in, t);
    const int32_t first = std::max(first_row_below(v[0]->y), w.first_min);
    const int32_t last = std::min(last_row_at_or_above(v[2]->y), w.last_max);
    const bool want = first <= last && setup_rows(v, first, last, w.width, r);
    // Untested from kSurelyPixelsArea2 on: such a triangle without pixels may still get planes.
    const auto d = static_cast<int32_t>(signed_area2(*v[0], *v[1], *v[2]));
    if (first <= last && surely_pixels(d) && !want) {
      ++untested_slivers;
      continue;
    }
    ASSERT_EQ(got.pixels(), want) << "triangle " << i;
    if (!want) {
      ++slivers;
      continue;
    }
    ++drawn;
    EXPECT_EQ(t.first_row, r.first_row);
    EXPECT_EQ(t.mid_row, r.mid_row);
    EXPECT_EQ(t.last_row, r.last_row);
  }
  std::printf("[ rows ] %d slivers, %d with pixels, %d without but untested\n", slivers, drawn,
              untested_slivers);
  EXPECT_GT(slivers, 100000);
  EXPECT_GT(drawn, 5000);
}

// The active store is zero-initialised storage (.bss on the targets, no flash image of it):
// a default ActiveTriangle is all zero bytes.
TEST(ActiveRecord, DefaultIsAllZeroBytes) {
  static const ActiveTriangle t{};
  const auto* bytes = reinterpret_cast<const unsigned char*>(&t);
  for (size_t i = 0; i < sizeof t; ++i) EXPECT_EQ(bytes[i], 0u) << "byte " << i;
}

}  // namespace
}  // namespace lr
