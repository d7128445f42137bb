// The RGB565 lanes span and row loop (core/span/lane_span.hpp, lane_rows.hpp) on the host:
// the C loop of a strip visit against the renderer's generic row loop (the cases the firmware
// check lr_span_check runs on the targets, where it also compares the hand-allocated loop), the
// lane span against a direct evaluation of its planes at every pixel, and the lanes' colours
// against the exact (double) colour of each pixel centre: within one RGB565 step everywhere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "firmware/span_check/lane_cases.hpp"
#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/raster/strip_visit.hpp"
#include "lineraster/core/raster/untextured_rows.hpp"
#include "lineraster/core/setup/row_edge.hpp"
#include "lineraster/core/setup/untextured_setup.hpp"
#include "lineraster/core/span/lane_rows.hpp"
#include "lineraster/core/span/lane_span.hpp"

namespace lr {
namespace {

using PF = Rgb565Be;
namespace lanes = fw::lanes;

// One in two of lanes::random_triangle's triangles drawn towards its first vertex by 1/8: most
// of them then below kSurelyPixelsArea2 (one pixel), whose pixel centres small_rows tests.
void small_rows_triangle(lanes::Random& rng, ScreenVertex v[3]) {
  lanes::random_triangle(rng, v);
  if (rng.in(0, 1) == 0) {
    for (int i = 1; i < 3; ++i) {
      v[i].x = v[0].x + (v[i].x - v[0].x) / 8;
      v[i].y = v[0].y + (v[i].y - v[0].y) / 8;
    }
  }
}

TEST(LaneRows, CLoopDrawsWhatTheGenericRowLoopDraws) {
  static lanes::Strip a, b;
  const auto portable = [](const ActiveTriangle& t, StripRows& s) {
    lane_visit_portable<PF>(t, s);
  };
  const auto generic = [](const ActiveTriangle& t, StripRows& s) {
    untextured_rows_per_span<PF, true, UntexturedKind::kLanes>(t, s);
  };
  const lanes::Tally t = lanes::run_cases(20000, a, b, portable, generic, 777u);
  std::printf("[ lanes ] %u triangles, %u strip visits, %u pixels: %u visits differ\n", t.triangles,
              t.visits, t.pixels, t.differing);
  EXPECT_EQ(t.differing, 0u);
  EXPECT_GT(t.triangles, 8000u);
  EXPECT_GT(t.pixels, 100000u);
}

// The strip visit with runs of lanes triangles in one call (visit_active with lane_run) against
// the visit one triangle at a time: strips of lanes triangles mixed with others, kept and
// freed. lr_span_check runs the same cases on the targets with the hand-allocated run.
TEST(LaneRows, RunsOfLanesTrianglesVisitAsOneAtATime) {
  static lanes::Strip a, b;
  constexpr RowFn kLanes = &lanes_rows<PF>;
  const auto runs = [](ActiveList& x, StripRows& s) {
    LaneRun words{};
    visit_active(x, s, kLanes, words, [](const ActiveTriangle& t, LaneRun& r, StripRows& sr) {
      lane_run_portable<PF>(t, r, sr);
    });
  };
  const auto single = [](ActiveList& x, StripRows& s) {
    LaneRun words{};
    visit_active(x, s, nullptr, words, [](const ActiveTriangle&, LaneRun&, StripRows&) {});
  };
  const lanes::StripTally t = lanes::run_strips(6000, a, b, kLanes, runs, single);
  std::printf(
      "[ lanes ] %u strips, %u triangles (%u in runs, %u others, %u kept, %u freed), "
      "%u pixels: %u strips differ\n",
      t.strips, t.triangles, t.in_runs, t.others, t.kept, t.freed, t.pixels, t.differing);
  EXPECT_EQ(t.differing, 0u);
  EXPECT_GT(t.strips, 5000u);
  EXPECT_GT(t.in_runs, 10000u);
  EXPECT_GT(t.others, 1000u);
  EXPECT_GT(t.kept, 5000u);
  EXPECT_GT(t.freed, 5000u);
  EXPECT_GT(t.pixels, 100000u);
}

// small_rows' answer (kPixels: twice the area is kSurelyPixelsArea2 or more, or the middle
// vertex's row, or the first, has a pixel centre inside the triangle and the viewport's columns)
// against that row's columns from the record it made, whichever way it reached it (a candidate
// column's products, or the divisions).
TEST(SmallRows, PixelsOnTheMiddleRowAsTheRecordsColumnsSay) {
  lanes::Random rng;
  rng.s = 31337u;
  int pixels = 0, later = 0, all_nudged = 0, untested_without = 0;
  for (int c = 0; c < 200000; ++c) {
    ScreenVertex v[3];
    small_rows_triangle(rng, v);
    if (rng.in(0, 2) == 0) {  // centres on edges, columns on their bounds
      const int32_t nudge = rng.in(-1, 1);
      for (ScreenVertex& x : v) {
        x.x = (x.x & ~(kHalfPixel - 1)) + nudge;
        x.y = (x.y & ~(kHalfPixel - 1)) + nudge;
      }
      ++all_nudged;
    }
    if (signed_area2(v[0], v[1], v[2]) == 0) continue;
    const ScreenVertex* s[3] = {&v[0], &v[1], &v[2]};
    sort_by_y(s);
    const RowWindow window{rng.in(-4, lanes::kHeight), lanes::kHeight - 1, lanes::kWidth};
    ActiveTriangle t;
    const SmallRows r = small_rows(s, window, t);
    if (r.result == SmallRows::kSlow) continue;
    const int32_t rm = t.mid_row >= t.first_row ? t.mid_row : t.first_row;
    const int ss = t.short_side(), ls = 1 - ss;
    int32_t col[2];
    col[ls] = DivideEdge(t.side_edge(ls), t.col_base, rm - t.first_row).column();
    col[ss] = t.mid_row >= t.first_row
                  ? DivideEdge(t.side_edge(ss), t.col_base, rm - t.first_row).column()
                  : DivideEdge(t.bottom, t.col_base, 0).column();
    const bool has = col[0] < lanes::kWidth && col[1] > 0 && col[0] < col[1];
    // From kSurelyPixelsArea2 on, kPixels untested.
    const bool untested = surely_pixels(r.d);
    ASSERT_EQ(r.result, has || untested ? SmallRows::kPixels : SmallRows::kLaterRows) << c;
    (has ? pixels : untested ? untested_without : later)++;
  }
  EXPECT_GT(pixels, 20000);
  EXPECT_GT(later, 2000);
  EXPECT_GT(untested_without, 100);
  EXPECT_GT(all_nudged, 10000);
}

// What the -Os build relies on (setup_untextured_triangle makes every triangle's rows with
// setup_rows there): for the small path's triangles setup_rows makes the same rows, flags, column
// base and words of every edge a row reads as small_rows, and finds pixels exactly when the
// small path does (small_rows' kPixels, or kLaterRows and a later row with a pixel centre, which
// setup_untextured_triangle tells by making planes).
TEST(SmallRows, SetupRowsMakesTheSameRecordAndSlivers) {
  lanes::Random rng;
  rng.s = 4711u;
  int compared = 0, slivers = 0, later = 0, flat = 0, untested = 0;
  for (int c = 0; c < 200000; ++c) {
    ScreenVertex v[3];
    small_rows_triangle(rng, v);
    if (rng.in(0, 2) == 0) {  // centres on edges, flat tops and bottoms
      for (ScreenVertex& x : v) {
        x.x &= ~(kHalfPixel - 1);
        x.y &= ~(kHalfPixel - 1);
      }
    }
    if (signed_area2(v[0], v[1], v[2]) == 0) continue;
    const ScreenVertex* s[3] = {&v[0], &v[1], &v[2]};
    sort_by_y(s);
    const RowWindow window{rng.in(-4, lanes::kHeight), lanes::kHeight - 1, lanes::kWidth};
    ActiveTriangle a, b;
    const SmallRows r = small_rows(s, window, a);
    if (r.result == SmallRows::kSlow) continue;
    UntexturedInput in;
    in.colors = ColorPlanes::kAffine;
    in.lanes = true;
    ActiveTriangle u;
    const bool small_pixels = setup_untextured_triangle(s, window, in, u).pixels();
    const int32_t first = std::max(first_row_below(s[0]->y), window.first_min);
    const int32_t last = std::min(last_row_at_or_above(s[2]->y), window.last_max);
    const bool rows_pixels = setup_rows(s, first, last, window.width, b);
    if (surely_pixels(r.d) && !rows_pixels) {  // untested there: planes its rows never use
      ++untested;
      continue;
    }
    ASSERT_EQ(rows_pixels, small_pixels) << c;
    later += r.result == SmallRows::kLaterRows;
    if (!rows_pixels) {
      ++slivers;
      continue;
    }
    ASSERT_EQ(a.first_row, b.first_row) << c;
    ASSERT_EQ(a.mid_row, b.mid_row) << c;
    ASSERT_EQ(a.last_row, b.last_row) << c;
    ASSERT_EQ(a.col_base, b.col_base) << c;
    ASSERT_EQ(a.flags, b.flags) << c;
    const int ss = a.short_side();
    const auto same_edge = [](const RowEdge& x, const RowEdge& y) {
      return x.q == y.q && x.dx == y.dx && x.dy == y.dy;
    };
    ASSERT_TRUE(same_edge(a.side_edge(1 - ss), b.side_edge(1 - ss))) << c;  // the long edge
    if (a.mid_row >= a.first_row) {
      ASSERT_TRUE(same_edge(a.side_edge(ss), b.side_edge(ss))) << c;
    }
    if (a.last_row > a.mid_row) {
      ASSERT_TRUE(same_edge(a.bottom, b.bottom)) << c;
    }
    flat += s[0]->y == s[1]->y || s[1]->y == s[2]->y;
    ++compared;
  }
  std::printf("compared %d, slivers %d, later rows only %d, flat %d, untested without pixels %d\n",
              compared, slivers, later, flat, untested);
  EXPECT_GT(compared, 25000);
  EXPECT_GT(slivers, 1000);
  EXPECT_GT(later, 1000);
  EXPECT_GT(flat, 500);
}

// LanesSetup (the strip loop's call for lanes draws: by hand on Armv7E-M, lr_span_check compares
// it there) against sort_by_y and setup_untextured_triangle.
TEST(LanesSetup, FromIndicesAsSortAndSetup) {
  const lanes::Tally t = lanes::run_lanes_setup(30000);
  EXPECT_EQ(t.differing, 0u);
  EXPECT_GT(t.triangles, 5000u);
  EXPECT_GT(t.pixels, 1000u);
  EXPECT_GT(t.visits, 1000u);
}

TEST(LaneSpan, StepsEqualTheDirectEvaluationOfThePlanes) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<uint32_t> any;
  size_t rejected_seen = 0;
  for (int c = 0; c < 2000; ++c) {
    const int32_t n = static_cast<int32_t>(any(rng) % 200 + 1);
    // Lanes that stay in range over the span (as inside a triangle): starts and steps small
    // enough in both halves.
    const auto lane = [&](uint32_t lo, uint32_t hi) { return lo + any(rng) % (hi - lo); };
    const uint32_t r0 = lane(2000, 60000), b0 = lane(2000, 60000), g0 = lane(2000, 60000);
    const auto step = [&](uint32_t v0) {
      const int32_t room = static_cast<int32_t>(std::min(v0, 65535u - v0)) / n;
      return static_cast<int32_t>(any(rng) % (2 * static_cast<uint32_t>(room) + 1)) - room;
    };
    const int32_t dr = step(r0), db = step(b0), dg = step(g0);
    const uint32_t br = (b0 << 16) + r0,
                   dbr = (static_cast<uint32_t>(db) << 16) + static_cast<uint32_t>(dr);
    const uint32_t g = g0 << 16, dgg = static_cast<uint32_t>(dg) << 16;
    const uint32_t z = any(rng) >> 1, dz = any(rng) % 4096;
    std::vector<uint16_t> px(static_cast<size_t>(n), 0x1234), depth(static_cast<size_t>(n));
    for (auto& d : depth) d = static_cast<uint16_t>(any(rng));
    std::vector<uint16_t> depth_before = depth;
    const uint32_t rejected =
        lane_span_portable<PF, true>(px.data(), depth.data(), n, z, dz, br, dbr, g, dgg);
    uint32_t expect_rejected = 0;
    for (int32_t i = 0; i < n; ++i) {
      const auto ui = static_cast<uint32_t>(i);
      const uint32_t rv = r0 + static_cast<uint32_t>(dr) * ui,
                     bv = b0 + static_cast<uint32_t>(db) * ui;
      const uint32_t gv = g0 + static_cast<uint32_t>(dg) * ui;
      const auto d = static_cast<uint16_t>((z + dz * ui) >> 15);
      const size_t k = static_cast<size_t>(i);
      if (d < depth_before[k]) {
        ASSERT_EQ(depth[k], d);
        const unsigned v = (rv >> 11) << 11 | (gv >> 10) << 5 | (bv >> 11);
        ASSERT_EQ(PF::to_value(px[k]), v) << "case " << c << " pixel " << i;
      } else {
        ASSERT_EQ(depth[k], depth_before[k]);
        ASSERT_EQ(px[k], 0x1234);
        ++expect_rejected;
      }
    }
    EXPECT_EQ(rejected, expect_rejected);
    rejected_seen += rejected;
  }
  EXPECT_GT(rejected_seen, 1000u);
}

// The exact colour of a pixel centre: the barycentric mix of the vertex colours (Q1.15).
double exact_channel(const ScreenVertex* const v[3], int c, double px, double py) {
  const double x0 = v[0]->x, y0 = v[0]->y;
  const double e1x = v[1]->x - x0, e1y = v[1]->y - y0, e2x = v[2]->x - x0, e2y = v[2]->y - y0;
  const double d = e1x * e2y - e2x * e1y;
  const double l1 = ((px - x0) * e2y - (py - y0) * e2x) / d;
  const double l2 = ((py - y0) * e1x - (px - x0) * e1y) / d;
  const double a0 = channel(v[0]->color, c), a1 = channel(v[1]->color, c),
               a2 = channel(v[2]->color, c);
  return (a0 + l1 * (a1 - a0) + l2 * (a2 - a0)) / Color15::kOne;
}

struct LanesTally {
  int triangles = 0;
  uint64_t pixels = 0, exact = 0, worst = 0;
};

// Random triangles up to 128 px (the lanes' limit), drawn whole in one strip of 32 rows with the
// generic row loop; each written pixel against the exact colour at its centre, rounded to RGB565.
// one_hue: the colours green times two random ratios below 2 (as one_hue() admits them), red and
// blue rounded, their planes made from green's differences (UntexturedInput::hue).
LanesTally lanes_against_exact(bool one_hue, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int32_t> pos(0, 96 * kSubpixel),
      size(-128 * kSubpixel, 128 * kSubpixel);
  std::uniform_int_distribution<int> col(0, Color15::kOne);
  std::uniform_int_distribution<int32_t> ratio(0, INT32_MAX);
  UntexturedInput in;
  in.colors = ColorPlanes::kAffine;
  in.depth = true;
  in.lanes = true;
  in.affine = kAffineBound565;
  in.hue.valid = one_hue;
  static lanes::Strip strip;
  LanesTally tally;
  while (tally.triangles < 3000) {
    // Q1.30 ratios of red and blue to green (one hue).
    const int32_t hr = ratio(rng), hb = ratio(rng);
    in.hue.red = hr;
    in.hue.blue = hb;
    const uint64_t most = std::max<uint64_t>({uint64_t(hr), uint64_t(hb), 1u << 30});
    ScreenVertex v[3];
    const int32_t cx = pos(rng),
                  cy = std::uniform_int_distribution<int32_t>(0, 32 * kSubpixel)(rng);
    const int32_t reach = tally.triangles % 3 == 0 ? 128 * kSubpixel : 24 * kSubpixel;
    for (auto& p : v) {
      p.x = cx + size(rng) % reach;
      p.y = cy + size(rng) % reach;
      p.z = 1000;
      p.w = 1u << 16;
      if (one_hue) {
        const auto g = static_cast<uint64_t>(col(rng)) * (uint64_t{1} << 30) / most;
        const auto times = [g](uint64_t h) {
          return static_cast<uint16_t>((g * h + (uint64_t{1} << 29)) >> 30);
        };
        p.color = Color15{times(uint64_t(hr)), static_cast<uint16_t>(g), times(uint64_t(hb))};
      } else {
        p.color = Color15{static_cast<uint16_t>(col(rng)), static_cast<uint16_t>(col(rng)),
                          static_cast<uint16_t>(col(rng))};
      }
    }
    if (signed_area2(v[0], v[1], v[2]) == 0) continue;
    const ScreenVertex* s[3] = {&v[0], &v[1], &v[2]};
    sort_by_y(s);
    ActiveTriangle t;
    const UntexturedTriangle u =
        setup_untextured_triangle(s, RowWindow{0, 31, lanes::kWidth}, in, t);
    if (!u.pixels() || u.kind() != UntexturedKind::kLanes) continue;
    ++tally.triangles;
    std::fill(strip.depth.begin(), strip.depth.end(), 0xFFFF);
    std::fill(strip.px.begin(), strip.px.end(), 0);
    StripRows sr;
    sr.pixels = strip.px.data();
    sr.depth = strip.depth.data();
    sr.y0 = 0;
    sr.y_last = 31;
    sr.width = lanes::kWidth;
    untextured_rows_per_span<PF, true, UntexturedKind::kLanes>(t, sr);
    for (int32_t r = 0; r < 32; ++r) {
      for (int32_t c = 0; c < lanes::kWidth; ++c) {
        const size_t i = static_cast<size_t>(r * lanes::kWidth + c);
        if (strip.depth[i] == 0xFFFF) continue;
        const double x = c * kSubpixel + kHalfPixel, y = r * kSubpixel + kHalfPixel;
        const unsigned v565 = PF::to_value(strip.px[i]);
        const int got[3] = {static_cast<int>(v565 >> 11), static_cast<int>((v565 >> 5) & 63),
                            static_cast<int>(v565 & 31)};
        const int levels[3] = {31, 63, 31};
        bool same = true;
        for (int ch = 0; ch < 3; ++ch) {
          const double e = std::clamp(exact_channel(s, ch, x, y), 0.0, 1.0) * levels[ch];
          const auto want = static_cast<int>(std::floor(e + 0.5));
          const auto diff = static_cast<uint64_t>(std::abs(got[ch] - want));
          tally.worst = std::max(tally.worst, diff);
          same = same && diff == 0;
        }
        ++tally.pixels;
        tally.exact += same ? 1 : 0;
      }
    }
  }
  std::printf(
      "[ lanes ] %s: %d triangles, %llu pixels: %.4f %% exactly the rounded exact colour, "
      "worst %llu step\n",
      one_hue ? "one hue" : "three planes", tally.triangles,
      static_cast<unsigned long long>(tally.pixels),
      100.0 * static_cast<double>(tally.exact) / static_cast<double>(tally.pixels),
      static_cast<unsigned long long>(tally.worst));
  return tally;
}

TEST(Lanes, EveryPixelWithinOneRgb565StepOfTheExactColour) {
  const LanesTally t = lanes_against_exact(false, 21);
  EXPECT_GT(t.pixels, 200000u);
  EXPECT_LE(t.worst, 1u);
  // Red and blue are 16-bit lanes (a unit is 1/2048 of a step): about 1 % of the pixels round one
  // step off where the exact value lies that close to a rounding boundary.
  EXPECT_GT(static_cast<double>(t.exact), 0.985 * static_cast<double>(t.pixels));
}

// Red and blue made from green's products (docs/numerics.md#one-hue): no lane carries into the
// other (blue would be a level off), every pixel within one step of the exact colour of the
// rounded vertex colours, and nearly as many exact as with three planes.
TEST(Lanes, OneHueWithinOneRgb565StepOfTheExactColour) {
  const LanesTally t = lanes_against_exact(true, 22);
  EXPECT_GT(t.pixels, 200000u);
  EXPECT_LE(t.worst, 1u);
  EXPECT_GT(static_cast<double>(t.exact), 0.98 * static_cast<double>(t.pixels));
}

}  // namespace
}  // namespace lr
