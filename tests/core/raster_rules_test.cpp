// The fill rule and watertightness: the core's coverage, read back pixel by pixel, must equal the
// reference's exact evaluation on the same snapped vertices, with no pixel written twice.
#include <gtest/gtest.h>

#include <random>

#include "lineraster/core/vertex/vertex_stage.hpp"
#include "tests/support/core_harness.hpp"

namespace lr {
namespace {

using test::CoreHarness;
using test::ScreenScene;

constexpr int64_t S = kSubpixel;
constexpr int64_t H = kHalfPixel;

struct Compare {
  size_t mismatches = 0;
  uint64_t ref_hits = 0;
  int max_hits = 0;
};

// Renders the scene with the core (painter's order, no depth) and compares ownership with the
// reference for every pixel, and the number of writes with the reference's hit count.
template <int K = 8>
Compare run(const ScreenScene& scene, int w, int h, FrameStats* stats_out = nullptr) {
  CoreHarness<K> core(w, h);
  EXPECT_EQ(core.configured(), Status::kOk);
  core.begin();
  EXPECT_EQ(core.renderer().draw_screen(scene.vertices, scene.triangles, test::coverage_state()),
            Status::kOk);
  Status st;
  host::ImageRgb8 img = core.render(&st);
  EXPECT_EQ(st, Status::kOk);
  std::vector<int32_t> hits, owner;
  ref::coverage(scene.ref, w, h, kSubpixelBits, hits, owner);
  Compare c;
  for (size_t p = 0; p < hits.size(); ++p) {
    c.ref_hits += static_cast<uint64_t>(hits[p]);
    c.max_hits = std::max(c.max_hits, hits[p]);
    if (test::id_of(img, p) != owner[p]) ++c.mismatches;
  }
  const FrameStats& s = core.renderer().stats();
  EXPECT_EQ(s.pixels_written, c.ref_hits) << "writes differ from the reference's hit count";
  if (stats_out) *stats_out = s;
  return c;
}

// A region tiled by a jittered grid, each cell split along a random diagonal, random windings.
ScreenScene jittered_grid(std::mt19937& rng, int nx, int ny, int64_t x0, int64_t y0, int64_t cell,
                          int64_t jitter, bool on_centres) {
  std::uniform_int_distribution<int64_t> j(-jitter, jitter);
  std::vector<int64_t> gx((size_t(nx) + 1) * (size_t(ny) + 1)), gy(gx.size());
  for (int y = 0; y <= ny; ++y) {
    for (int x = 0; x <= nx; ++x) {
      size_t i = size_t(y) * size_t(nx + 1) + size_t(x);
      bool border = x == 0 || y == 0 || x == nx || y == ny;
      gx[i] = x0 + x * cell + (border || on_centres ? 0 : j(rng));
      gy[i] = y0 + y * cell + (border || on_centres ? 0 : j(rng));
    }
  }
  ScreenScene s;
  std::bernoulli_distribution coin(0.5);
  for (int y = 0; y < ny; ++y) {
    for (int x = 0; x < nx; ++x) {
      size_t a = size_t(y) * size_t(nx + 1) + size_t(x), b = a + 1, c = a + size_t(nx + 1),
             d = c + 1;
      size_t t[2][3];
      if (coin(rng)) {
        size_t t0[3] = {a, b, d}, t1[3] = {a, d, c};
        std::copy(t0, t0 + 3, t[0]);
        std::copy(t1, t1 + 3, t[1]);
      } else {
        size_t t0[3] = {a, b, c}, t1[3] = {b, d, c};
        std::copy(t0, t0 + 3, t[0]);
        std::copy(t1, t1 + 3, t[1]);
      }
      for (auto& tri : t) {
        if (coin(rng)) std::swap(tri[1], tri[2]);
        s.add(gx[tri[0]], gy[tri[0]], gx[tri[1]], gy[tri[1]], gx[tri[2]], gy[tri[2]]);
      }
    }
  }
  return s;
}

TEST(FillRule, JitteredGridMatchesReferenceExactlyAndIsWatertight) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 6; ++trial) {
    ScreenScene s = jittered_grid(rng, 16, 12, 8 * S + 37, 5 * S + 91, 17 * S + 13, 6 * S, false);
    Compare c = run(s, 320, 240);
    EXPECT_EQ(c.mismatches, 0u) << "trial " << trial;
    EXPECT_EQ(c.max_hits, 1) << "the reference itself must see one hit per pixel";
  }
}

TEST(FillRule, VerticesOnPixelCentresFollowTheRule) {
  // Every vertex on a pixel centre: every shared edge passes through centres.
  std::mt19937 rng(11);
  ScreenScene s = jittered_grid(rng, 12, 9, 4 * S + H, 3 * S + H, 20 * S, 0, true);
  FrameStats st;
  Compare c = run(s, 320, 240, &st);
  EXPECT_EQ(c.mismatches, 0u);
  EXPECT_EQ(c.max_hits, 1);
  // The tiled rectangle spans centres x in [4.5, 244.5), y in [3.5, 183.5): left and bottom
  // edges own their centres, right and top do not: 240 x 180 pixels... shifted by the rule.
  EXPECT_EQ(st.pixels_written, 240u * 180u);
}

TEST(FillRule, FanAroundAPixelCentre) {
  ScreenScene s;
  const int64_t cx = 50 * S + H, cy = 40 * S + H;
  const int n = 16;
  std::vector<std::pair<int64_t, int64_t>> ring;
  for (int i = 0; i < n; ++i) {
    double a = 2 * 3.14159265358979 * i / n;
    ring.emplace_back(cx + std::llround(30 * S * std::cos(a)),
                      cy + std::llround(30 * S * std::sin(a)));
  }
  for (int i = 0; i < n; ++i) {
    auto [x1, y1] = ring[size_t(i)];
    auto [x2, y2] = ring[size_t((i + 1) % n)];
    s.add(cx, cy, x1, y1, x2, y2);
  }
  Compare c = run(s, 100, 80);
  EXPECT_EQ(c.mismatches, 0u);
  EXPECT_EQ(c.max_hits, 1);
}

TEST(FillRule, SingleTrianglesWithCentresOnEveryKindOfEdge) {
  // A right triangle with a horizontal top edge, a vertical left edge and a diagonal, all
  // through pixel centres; and its mirror images. Left and bottom edges own their centres.
  ScreenScene s;
  s.add(2 * S + H, 2 * S + H, 8 * S + H, 2 * S + H, 2 * S + H, 8 * S + H);     // top + left edges
  s.add(20 * S + H, 8 * S + H, 14 * S + H, 8 * S + H, 20 * S + H, 2 * S + H);  // bottom + right
  s.add(30 * S + H, 2 * S + H, 30 * S + H, 8 * S + H, 36 * S + H, 8 * S + H);  // left + bottom
  s.add(50 * S + H, 2 * S + H, 44 * S + H, 2 * S + H, 50 * S + H, 8 * S + H);  // top + right
  FrameStats st;
  Compare c = run(s, 64, 16, &st);
  EXPECT_EQ(c.mismatches, 0u);
  // Counted by hand: the first owns its left column, not its top row or diagonal: rows 3..7
  // (5 rows) with 1..5 pixels = 15... the reference computes these; check the total exactly.
  EXPECT_EQ(st.pixels_written, c.ref_hits);
  EXPECT_GT(c.ref_hits, 40u);
}

TEST(FillRule, RandomTrianglesIncludingSliversAndGuardBandGiants) {
  std::mt19937 rng(99);
  std::uniform_int_distribution<int64_t> small(-4 * S, 4 * S), pos(-20 * S, 180 * S),
      huge(-3000 * S, 3000 * S);
  ScreenScene s;
  for (int i = 0; i < 400; ++i) {
    int64_t x = pos(rng), y = pos(rng);
    if (i % 4 == 0) {
      s.add(x, y, x + small(rng), y + small(rng), x + small(rng), y + small(rng));  // tiny
    } else if (i % 4 == 1) {
      s.add(x, y, x + 150 * S, y + small(rng) / 4, x + 2, y + 1);  // needle
    } else if (i % 4 == 2) {
      s.add(huge(rng), huge(rng), huge(rng), huge(rng), huge(rng), huge(rng));  // giant
    } else {
      s.add(x, y, pos(rng), pos(rng), pos(rng), pos(rng));
    }
  }
  Compare c = run(s, 160, 120);
  EXPECT_EQ(c.mismatches, 0u);
}

TEST(FillRule, StripHeightDoesNotChangeCoverage) {
  std::mt19937 rng(5);
  ScreenScene s = jittered_grid(rng, 10, 8, 3 * S + 5, 2 * S + 77, 13 * S + 101, 5 * S, false);
  EXPECT_EQ(run<1>(s, 150, 110).mismatches, 0u);
  EXPECT_EQ(run<8>(s, 150, 110).mismatches, 0u);
  EXPECT_EQ(run<32>(s, 150, 110).mismatches, 0u);
}

TEST(Culling, FrontFacesAreCounterClockwiseInNdc) {
  // Seen on the display, down then right is counter-clockwise: counter-clockwise in NDC too
  // (the picture is the same), which in display coordinates (y down) is a negative signed area.
  ScreenScene ccw_ndc, cw_ndc;
  ccw_ndc.add(10 * S, 10 * S, 10 * S, 30 * S, 30 * S, 10 * S);
  cw_ndc.add(10 * S, 10 * S, 30 * S, 10 * S, 10 * S, 30 * S);
  DrawState st = test::coverage_state();
  st.cull = Cull::kBack;
  for (int front = 0; front < 2; ++front) {
    const ScreenScene& s = front ? ccw_ndc : cw_ndc;
    CoreHarness<8> core(40, 40);
    core.begin();
    core.renderer().draw_screen(s.vertices, s.triangles, st);
    core.render();
    EXPECT_EQ(core.renderer().stats().culled_backface, front ? 0u : 1u);
    EXPECT_EQ(core.renderer().stats().pixels_written > 0, front == 1);
  }
}

TEST(Snapping, RoundsToTheNearestSubpixelHalfAwayFromZero) {
  // With w = 2 * width * 128 (resp. height), the subpixel x is (x + w) / 2 and y is (w - y) / 2:
  // odd numerators land exactly on a half subpixel, negative ones left of and below the viewport
  // (inside the guard band).
  const Camera camera;
  const Mat4 model = Mat4::identity();
  const VertexStage stage(camera, model, GuardBand{8, 8}, 320, 240);
  struct Case {
    int64_t n;
    int32_t expected;
  };
  const Case cases[] = {{1, 1}, {3, 2}, {2, 1}, {-1, -1}, {-3, -2}, {-2, -1}, {0, 0}, {5, 3}};
  for (const Case& c : cases) {
    const int64_t wx = 2 * 320 * kHalfPixel, wy = 2 * 240 * kHalfPixel;
    ScreenVertex vx{}, vy{};
    ASSERT_TRUE(stage.project(ClipCoord{c.n - wx, 0, 0, wx}, vx));
    ASSERT_TRUE(stage.project(ClipCoord{0, wy - c.n, 0, wy}, vy));
    EXPECT_EQ(vx.x, c.expected) << "x numerator " << c.n << " / 2";
    EXPECT_EQ(vy.y, c.expected) << "y numerator " << c.n << " / 2";
  }
}

TEST(FillRule, DegenerateTrianglesDrawNothingAndAreCountedAsZeroArea) {
  ScreenScene s;
  s.add(10 * S, 10 * S, 20 * S, 20 * S, 30 * S, 30 * S);                    // collinear, diagonal
  s.add(10 * S + H, 5 * S + H, 30 * S + H, 5 * S + H, 50 * S, 5 * S + H);   // on a row of centres
  s.add(40 * S, 12 * S, 40 * S, 12 * S, 55 * S + 3, 30 * S);                // two corners equal
  s.add(7 * S + 1, 7 * S + 1, 7 * S + 1, 7 * S + 1, 7 * S + 1, 7 * S + 1);  // one point
  s.add(2 * S, 2 * S, 12 * S, 9 * S, 2 * S, 30 * S);  // a real one, for contrast
  FrameStats st;
  const Compare c = run(s, 64, 40, &st);
  EXPECT_EQ(c.mismatches, 0u);
  EXPECT_EQ(st.culled_zero_area, 4u);
  EXPECT_EQ(st.binned_inputs, 1u);
  EXPECT_EQ(st.triangles_binned, 1u);
  EXPECT_GT(st.pixels_written, 100u);
}

TEST(FillRule, TrianglesWhoseBoundsHoldNoCentreAreDroppedBeforeSetup) {
  // Inside one pixel, away from its centre; between two rows of centres; between two columns;
  // and, for contrast, a tiny one around a centre (binned, one pixel).
  ScreenScene s;
  s.add(20 * S + 10, 10 * S + 10, 20 * S + 100, 10 * S + 20, 20 * S + 30, 10 * S + 90);
  s.add(5 * S, 20 * S + H + 4, 60 * S, 20 * S + H + 40, 30 * S, 21 * S + H - 1);
  s.add(40 * S + H + 1, 2 * S, 41 * S + H - 1, 3 * S, 40 * S + H + 50, 35 * S);
  s.add(30 * S + H - 8, 30 * S + H - 8, 30 * S + H + 8, 30 * S + H - 8, 30 * S + H, 30 * S + H + 8);
  FrameStats st;
  const Compare c = run(s, 64, 40, &st);
  EXPECT_EQ(c.mismatches, 0u);
  EXPECT_EQ(st.culled_offscreen, 3u);
  EXPECT_EQ(st.triangles_binned, 1u);
  EXPECT_EQ(st.pixels_written, 1u);
}

}  // namespace
}  // namespace lr
