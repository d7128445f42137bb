// Numerical stress: exact edge columns and attribute drift across the whole guard band.
//
// Edges: the column of an edge on every row, as both row walkers (DivideEdge, DdaEdge) step it
// from a record (core/setup/row_edge.hpp), equals the exact rational formula
// c = ceil(((xa - 128) dy + dx (yc - ya)) / (256 dy)), evaluated here independently in
// __int128, for edges of every octant of slope (vertical, horizontal, slope 1 and its neighbours,
// very steep, very shallow, random) with end points anywhere in |x|, |y| < 2^22 subpixels:
// picked up per strip visit of 32 rows from the vertices (wide_edge, every edge), and from one
// record at the first row (and at a middle row) where the record fits 32 bits.
//
// Attributes: along the longest spans and edges, the values stepped by adding the gradient equal
// Plane::at (modular arithmetic: exact), and differ from the exact rational plane through the
// three vertex values by at most 0.5 (|Dx| + |Dy| + 1) units, Dx and Dy the pixel distances to
// the plane's first vertex (the rounded gradients are off by at most half a unit per pixel; the
// base by half a unit). The largest drift measured is printed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "lineraster/core/setup/row_edge.hpp"
#include "lineraster/core/setup/triangle_rows.hpp"
#include "lineraster/core/setup/triangle_setup.hpp"

namespace lr {
namespace {

using i128 = __int128;

constexpr int64_t S = kSubpixel;
constexpr int64_t kLimit = (int64_t{1} << 22) - 1;  // largest |coordinate| in the guard band

i128 floor_div128(i128 n, i128 d) {
  i128 q = n / d;
  return (n % d != 0 && n < 0) ? q - 1 : q;
}
i128 ceil_div128(i128 n, i128 d) {
  i128 q = n / d;
  return (n % d != 0 && n > 0) ? q + 1 : q;
}

// Rows whose centre lies in (ya, yb]: the rows an edge from ya to yb is used on.
int64_t first_row(int64_t ya) {
  return static_cast<int64_t>(floor_div128(ya - S / 2, S)) + 1;
}
int64_t last_row(int64_t yb) {
  return static_cast<int64_t>(floor_div128(yb - S / 2, S));
}

struct EdgeCheck {
  uint64_t rows = 0, column_mismatch = 0, record_rows = 0;
};

// The exact column of the edge on row r: the first column whose centre is at or right of it.
i128 exact_column(i128 xa, i128 ya, i128 xb, i128 yb, i128 r) {
  const i128 dx = xb - xa, dy = yb - ya;
  const i128 yc = r * S + S / 2;
  return ceil_div128((xa - S / 2) * dy + dx * (yc - ya), dy * S);
}

// Steps both walkers from their constructors' row over `rows` rows against the exact columns.
template <class W>
void walk(W w, int64_t xa, int64_t ya, int64_t xb, int64_t yb, int64_t r, int64_t rows,
          EdgeCheck& c) {
  for (int64_t k = 0; k < rows; ++k, ++r) {
    const i128 col = exact_column(xa, ya, xb, yb, r);
    if (i128{w.column()} != col && c.column_mismatch++ < 5)
      ADD_FAILURE() << "edge (" << xa << "," << ya << ")-(" << xb << "," << yb << ") row " << r
                    << ": " << w.column() << ", exact " << static_cast<int64_t>(col);
    w.step();
  }
}

// Walks the edge over every row it is used on (top to bottom), picked up per visit of 32 rows
// (as a strip loop with strips of 32 does for a triangle whose records do not fit), and, when its
// record fits 32 bits (edges_fit's condition for a triangle of this one edge), from one record at
// its first row and from the same record at a middle row.
void check_edge(int64_t xa, int64_t ya, int64_t xb, int64_t yb, EdgeCheck& c) {
  if (ya > yb) {
    std::swap(xa, xb);
    std::swap(ya, yb);
  }
  if (ya == yb) return;  // horizontal: no rows use it
  const int64_t r0 = first_row(ya), r1 = last_row(yb);
  if (r0 > r1) return;
  const ScreenVertex a{static_cast<int32_t>(xa), static_cast<int32_t>(ya), 0, 0, {}, 0, 0};
  const ScreenVertex b{static_cast<int32_t>(xb), static_cast<int32_t>(yb), 0, 0, {}, 0, 0};
  const ScreenVertex* v[3] = {&a, &a, &b};  // the long edge of a triangle
  for (int64_t r = r0; r <= r1; r += 32) {
    const int64_t rows = std::min<int64_t>(32, r1 - r + 1);
    const PickedEdge p = wide_edge(v, ActiveTriangle::kLong, static_cast<int32_t>(r),
                                   static_cast<int32_t>(r + rows - 1));
    walk(DivideEdge(p.e, p.cb, 0), xa, ya, xb, yb, r, rows, c);
    walk(DdaEdge(p.e, p.cb, 0), xa, ya, xb, yb, r, rows, c);
    c.rows += static_cast<uint64_t>(rows);
  }
  const int32_t cb = static_cast<int32_t>(std::min(xa, xb) - S / 2) >> kSubpixelBits;
  const int64_t cmax = static_cast<int64_t>(ceil_div128(std::max(xa, xb) - S / 2, S));
  if ((cmax - cb + 1) * (yb - ya) >= (int64_t{1} << 32)) return;
  const RowEdge e =
      make_row_edge(static_cast<int32_t>(xa), static_cast<int32_t>(ya), static_cast<int32_t>(xb),
                    static_cast<int32_t>(yb), cb, static_cast<int32_t>(r0));
  walk(DivideEdge(e, cb, 0), xa, ya, xb, yb, r0, r1 - r0 + 1, c);
  walk(DdaEdge(e, cb, 0), xa, ya, xb, yb, r0, r1 - r0 + 1, c);
  const int64_t rm = r0 + (r1 - r0) / 2;
  walk(DivideEdge(e, cb, static_cast<int32_t>(rm - r0)), xa, ya, xb, yb, rm, r1 - rm + 1, c);
  walk(DdaEdge(e, cb, static_cast<int32_t>(rm - r0)), xa, ya, xb, yb, rm, r1 - rm + 1, c);
  c.record_rows += static_cast<uint64_t>(r1 - r0 + 1);
}

TEST(EdgeStress, LongEdgesOfEveryOctantStepExactlyOnEveryRow) {
  const int64_t L = 2 * kLimit;  // longest delta inside the band: 2^23 - 2
  // (dx, dy) directions with dy >= 0; each is also used mirrored (dx -> -dx) and reversed
  // (end points swapped), which covers the eight octants.
  std::vector<std::pair<int64_t, int64_t>> dirs = {
      {0, L},                                              // vertical
      {L, L},     {L - 1, L}, {L, L - 1}, {L - 2, L - 1},  // slope 1 and neighbours
      {1, L},     {3, L},     {255, L},   {257, L},        // very steep
      {L, 1},     {L, 2},     {L, 3},     {L, 255},        // very shallow
      {L, 256},   {L, 257},   {L, 511},   {L / 2, L},      // ... and in between
      {L, L / 2}, {L / 3, L}, {L, L / 3}, {L / 7, L / 5},  //
      {12345, L}, {L, 12345}, {L, 65535}, {65537, L},      //
  };
  std::mt19937_64 rng(2024);
  std::uniform_int_distribution<int64_t> phase(0, S - 1);
  EdgeCheck c;
  size_t edges = 0;
  for (auto [dx, dy] : dirs) {
    for (int mirror = 0; mirror < 2; ++mirror) {
      for (int reverse = 0; reverse < 2; ++reverse) {
        for (int trial = 0; trial < 3; ++trial) {
          int64_t ddx = mirror ? -dx : dx;
          // Place the edge so both ends stay in |v| <= kLimit, with a random sub-pixel phase
          // (trial 0: the extreme corners exactly).
          int64_t sx = trial == 0 ? 0 : phase(rng), sy = trial == 0 ? 0 : phase(rng);
          int64_t xa = -ddx / 2 + (ddx >= 0 ? -sx : sx), ya = -dy / 2 - sy;
          int64_t xb = xa + ddx, yb = ya + dy;
          // Shift back inside when the phase pushed an end out.
          int64_t hi = std::max(xa, xb), lo = std::min(xa, xb);
          int64_t shift = hi > kLimit ? kLimit - hi : lo < -kLimit ? -kLimit - lo : 0;
          xa += shift;
          xb += shift;
          if (ya < -kLimit) {
            yb += -kLimit - ya;
            ya = -kLimit;
          }
          if (trial == 0) {  // pin to the band's edges
            xa = ddx >= 0 ? -kLimit : kLimit;
            xb = xa + ddx;
            ya = -kLimit;
            yb = ya + dy;
          }
          ASSERT_LE(std::max({std::abs(xa), std::abs(xb), std::abs(ya), std::abs(yb)}), kLimit);
          if (reverse) {
            check_edge(xb, yb, xa, ya, c);
          } else {
            check_edge(xa, ya, xb, yb, c);
          }
          ++edges;
        }
      }
    }
  }
  EXPECT_EQ(c.column_mismatch, 0u);
  // 13 of the directions span the band's full height (2^15 rows), each tried 12 times.
  EXPECT_GT(c.rows, uint64_t{13 * 12} * 32000);
  std::printf(
      "[ stress ] %zu long edges, %llu rows stepped (%llu from one record), 0 allowed "
      "mismatches: %llu found\n",
      edges, static_cast<unsigned long long>(c.rows),
      static_cast<unsigned long long>(c.record_rows),
      static_cast<unsigned long long>(c.column_mismatch));
}

TEST(EdgeStress, RandomEdgesAnywhereInTheGuardBandStepExactly) {
  std::mt19937_64 rng(77);
  std::uniform_int_distribution<int64_t> any(-kLimit, kLimit), small(-3 * S, 3 * S);
  EdgeCheck c;
  for (int i = 0; i < 4000; ++i) {
    int64_t xa = any(rng), ya = any(rng), xb, yb;
    switch (i % 4) {
      case 0:  // anywhere to anywhere; only a window of rows to bound the time
        xb = any(rng);
        yb = std::clamp<int64_t>(ya + small(rng) * 40, -kLimit, kLimit);
        break;
      case 1:  // short edges: a few rows
        xb = std::clamp<int64_t>(xa + small(rng), -kLimit, kLimit);
        yb = std::clamp<int64_t>(ya + small(rng), -kLimit, kLimit);
        break;
      case 2:  // shallow across the band
        xb = -xa;
        yb = std::clamp<int64_t>(ya + small(rng) / 8, -kLimit, kLimit);
        break;
      default:  // steep across the band, limited rows
        xb = std::clamp<int64_t>(xa + small(rng) / 16, -kLimit, kLimit);
        yb = std::clamp<int64_t>(ya + 300 * S + small(rng), -kLimit, kLimit);
        break;
    }
    check_edge(xa, ya, xb, yb, c);
  }
  EXPECT_EQ(c.column_mismatch, 0u);
  // A quarter of the edges are steep ones 300 rows long; the short ones fit one record.
  EXPECT_GT(c.rows, uint64_t{1000} * 290);
  EXPECT_GT(c.record_rows, uint64_t{1000});
  std::printf(
      "[ stress ] 4000 random edges, %llu rows stepped (%llu from one record), exact on "
      "all\n",
      static_cast<unsigned long long>(c.rows), static_cast<unsigned long long>(c.record_rows));
}

// ---- Attribute drift ----

struct Drift {
  long double max_abs = 0;    // largest |stepped - exact| in attribute units
  long double max_ratio = 0;  // largest |stepped - exact| / bound
  long double max_dist = 0;   // largest |Dx| + |Dy| (pixels) of a checked sample
  uint64_t samples = 0, step_mismatch = 0, over_bound = 0;
};

struct Tri {
  ScreenVertex v[3];
  uint32_t a[3];
};

// Exact value of the plane through (x_i, y_i, a_i) at subpixel point (X, Y), minus `got`
// (taken modulo 2^32 as the representative nearest to the exact value).
long double plane_error(const ScreenVertex* const v[3], const uint32_t a[3], i128 X, i128 Y,
                        uint32_t got) {
  const i128 x0 = v[0]->x, y0 = v[0]->y;
  const i128 ex1 = v[1]->x - x0, ey1 = v[1]->y - y0, ex2 = v[2]->x - x0, ey2 = v[2]->y - y0;
  i128 area = ex1 * ey2 - ex2 * ey1;
  const i128 da1 = i128{a[1]} - a[0], da2 = i128{a[2]} - a[0];
  const i128 nx = da1 * ey2 - da2 * ey1, ny = da2 * ex1 - da1 * ex2;
  // value = a0 + (nx (X - x0) + ny (Y - y0)) / area
  i128 num = nx * (X - x0) + ny * (Y - y0);
  if (area < 0) {
    area = -area;
    num = -num;
  }
  const i128 q = floor_div128(num, area);
  const long double frac =
      static_cast<long double>(num - q * area) / static_cast<long double>(area);
  const i128 whole = i128{a[0]} + q;
  const auto diff = static_cast<int32_t>(got - static_cast<uint32_t>(static_cast<uint64_t>(whole)));
  return static_cast<long double>(diff) - frac;
}

// The short path's error term for the triangle's planes, 0 on the exact path.
long double fast_plane_term(const ScreenVertex* const v[3]) {
  if (!PlaneBasis(v).fast) return 0;
  auto mag = [](int64_t e) { return static_cast<uint32_t>(e < 0 ? -e : e); };
  const int64_t e1x = v[1]->x - v[0]->x, e1y = v[1]->y - v[0]->y;
  const int64_t e2x = v[2]->x - v[0]->x, e2y = v[2]->y - v[0]->y;
  const int bm = 32 - clz32(mag(e1x) | mag(e1y) | mag(e2x) | mag(e2y));
  const auto d = static_cast<uint32_t>(abs64(e1x * e2y - e2x * e1y));
  return 9.0L * std::ldexp(1.0L, 2 * bm + clz32(d) - 30);
}

// Rasterizes the triangle's rows with the exact columns (clamped to a window), and checks the
// planes make_plane gives (the textured and Phong families', and the untextured family's exact
// wide path) along the edges (both span ends on every row) and along whole spans
// (every pixel stepped; the exact error every `every` pixels) on `span_rows` rows.
struct Window {
  int32_t c0 = INT32_MIN, c1 = INT32_MAX, r0 = INT32_MIN, r1 = INT32_MAX;  // [c0, c1), [r0, r1]
};

// The span of the triangle with sorted vertices v on row r (exact columns), clamped to win.
struct RowSpan {
  int32_t left, right;
};
RowSpan span_at(const ScreenVertex* const v[3], int32_t r, const Window& win) {
  const int32_t mid = last_row_at_or_above(v[1]->y);
  const ScreenVertex &a = *v[r <= mid ? 0 : 1], &b = *v[r <= mid ? 1 : 2];
  const auto lng = static_cast<int32_t>(exact_column(v[0]->x, v[0]->y, v[2]->x, v[2]->y, r));
  const auto sht = static_cast<int32_t>(exact_column(a.x, a.y, b.x, b.y, r));
  const bool long_left = signed_area2(*v[0], *v[1], *v[2]) > 0;
  return {std::max(long_left ? lng : sht, win.c0), std::min(long_left ? sht : lng, win.c1)};
}

void check_drift(const Tri& tri, int span_rows, int every, std::mt19937_64& rng, Drift& d,
                 Window win = {}) {
  // The planes' vertex 0 is the top vertex (setup sorts by y): do the same here.
  const ScreenVertex* v[3] = {&tri.v[0], &tri.v[1], &tri.v[2]};
  sort_by_y(v);
  const int32_t first = std::max(first_row_below(v[0]->y), win.r0);
  const int32_t last = std::min(last_row_at_or_above(v[2]->y), win.r1);
  if (first > last) return;
  const uint32_t z[3] = {v[0]->z, v[1]->z, v[2]->z};
  const Plane zp = make_plane(v, z);
  const Plane generic = make_plane(v, tri.a);

  // The planes' documented bound (docs/numerics.md#attribute-plane-equations): the short path
  // adds its reciprocal and coefficient rounding, 9 x 2^(2 bm + sh - 30).
  const long double short_term = fast_plane_term(v);
  auto sample = [&](const uint32_t* vals, int32_t c, int32_t r, uint32_t got) {
    const i128 X = i128{c} * S + S / 2, Y = i128{r} * S + S / 2;
    const long double e = plane_error(v, vals, X, Y, got);
    const long double dx = std::fabs(static_cast<long double>(X - v[0]->x) / S);
    const long double dy = std::fabs(static_cast<long double>(Y - v[0]->y) / S);
    const long double bound = short_term + 0.5L * (dx + dy + 1) + 1e-9L;
    ++d.samples;
    d.max_abs = std::max(d.max_abs, std::fabs(e));
    d.max_ratio = std::max(d.max_ratio, std::fabs(e) / bound);
    d.max_dist = std::max(d.max_dist, dx + dy);
    if (std::fabs(e) > bound) {
      if (d.over_bound++ < 5)
        ADD_FAILURE() << "drift " << static_cast<double>(e) << " > bound "
                      << static_cast<double>(bound) << " at (" << c << "," << r << ")";
    }
  };

  const int32_t rows = last - first + 1;
  std::uniform_int_distribution<int32_t> pick(0, rows - 1);
  std::vector<int32_t> full_rows;
  for (int i = 0; i < span_rows; ++i) full_rows.push_back(first + pick(rng));
  int32_t widest_row = first, widest = -1;
  // First pass: find the widest span (the longest span is always checked in full).
  for (int32_t r = first; r <= last; ++r) {
    const RowSpan sp = span_at(v, r, win);
    if (sp.right - sp.left > widest) {
      widest = sp.right - sp.left;
      widest_row = r;
    }
  }
  full_rows.push_back(widest_row);
  std::sort(full_rows.begin(), full_rows.end());

  uint32_t left_prev = 0;
  int32_t col_prev = 0, row_prev = INT32_MIN;
  size_t next_full = 0;
  for (int32_t r = first; r <= last; ++r) {
    const RowSpan sp = span_at(v, r, win);
    const int32_t left = sp.left, right = sp.right;
    if (left < right) {
      // Along the edge: the left end stepped vertically (gy per row, gx per column moved).
      uint32_t z_left = zp.at(left, r);
      if (row_prev != INT32_MIN) {
        uint32_t stepped = left_prev + zp.gy * static_cast<uint32_t>(r - row_prev) +
                           zp.gx * static_cast<uint32_t>(left - col_prev);
        if (stepped != z_left) ++d.step_mismatch;
      }
      left_prev = z_left;
      col_prev = left;
      row_prev = r;
      sample(z, left, r, z_left);
      sample(z, right - 1, r, zp.at(right - 1, r));
      sample(tri.a, left, r, generic.at(left, r));
      sample(tri.a, right - 1, r, generic.at(right - 1, r));
      bool full = false;
      while (next_full < full_rows.size() && full_rows[next_full] <= r) {
        full = full || full_rows[next_full] == r;
        ++next_full;
      }
      if (full) {
        // Along the span, as the spans step it.
        uint32_t zs = zp.at(left, r), gs = generic.at(left, r);
        for (int32_t c = left; c < right; ++c) {
          if (zs != zp.at(c, r) || gs != generic.at(c, r)) ++d.step_mismatch;
          if ((c - left) % every == 0 || c == right - 1) {
            sample(z, c, r, zs);
            sample(tri.a, c, r, gs);
          }
          zs += zp.gx;
          gs += generic.gx;
        }
      }
    }
  }
}

Tri random_tri(std::mt19937_64& rng, int64_t extent) {
  std::uniform_int_distribution<int64_t> pos(-extent, extent);
  std::uniform_int_distribution<uint32_t> depth(0, kDepthMax), any(0, 0xFFFFFFFFu);
  Tri t;
  for (int k = 0; k < 3; ++k) {
    t.v[k].x = static_cast<int32_t>(pos(rng));
    t.v[k].y = static_cast<int32_t>(pos(rng));
    t.v[k].z = depth(rng);
    t.a[k] = any(rng);
  }
  // Extreme values at the vertices half the time: 0 and the top of the range.
  if (rng() % 2) {
    t.v[0].z = 0;
    t.v[1].z = kDepthMax;
    t.a[0] = 0;
    t.a[2] = 0xFFFFFFFFu;
  }
  return t;
}

int64_t area2(const Tri& t) {
  return signed_area2(t.v[0], t.v[1], t.v[2]);
}

TEST(AttributeDrift, SteppedPlanesStayWithinHalfAUnitPerPixelOfDistance) {
  std::mt19937_64 rng(4242);
  // 1. The whole coordinate budget (|x|, |y| < 2^22: spans and edges up to 2^15 pixels), every
  //    pixel of the triangle; 2. the guard band of a 4096 x 4096 viewport (vertices within
  //    4096 pixels of its centre, pixels inside the viewport: what the renderer draws);
  //    3. medium triangles.
  Drift budget, band, medium;
  int budget_count = 0, band_count = 0, medium_count = 0;
  while (budget_count < 40) {
    Tri t = random_tri(rng, kLimit);
    if (std::abs(area2(t)) < (int64_t{1} << 40)) continue;  // fat: needles fall back (below)
    check_drift(t, 3, 61, rng, budget);
    ++budget_count;
  }
  {  // A right triangle with the budget's full width and height: the longest span and edges.
    Tri t{};
    const auto m = static_cast<int32_t>(kLimit);
    t.v[0] = ScreenVertex{-m, -m, 0, 0, {}, 0, 0};
    t.v[1] = ScreenVertex{m, m, kDepthMax, 0, {}, 0, 0};
    t.v[2] = ScreenVertex{-m, m, 12345, 0, {}, 0, 0};
    t.a[0] = 0xFFFFFFFFu;
    t.a[1] = 0;
    t.a[2] = 0x80000001u;
    check_drift(t, 2, 1, rng, budget);
    ++budget_count;
  }
  const int32_t W = kMaxViewport;
  const Window viewport{0, W, 0, W - 1};
  while (band_count < 40) {
    Tri t = random_tri(rng, 4096 * S);
    for (auto& v : t.v) {
      v.x += W / 2 * static_cast<int32_t>(S);
      v.y += W / 2 * static_cast<int32_t>(S);
    }
    if (std::abs(area2(t)) < (int64_t{1} << 36)) continue;
    check_drift(t, 3, 31, rng, band, viewport);
    ++band_count;
  }
  while (medium_count < 3000) {
    Tri t = random_tri(rng, 400 * S);
    if (std::abs(area2(t)) < 64 * S * S) continue;
    check_drift(t, 2, 3, rng, medium);
    ++medium_count;
  }
  for (const Drift* d : {&budget, &band, &medium}) {
    EXPECT_EQ(d->step_mismatch, 0u) << "stepping must equal direct evaluation exactly";
    EXPECT_EQ(d->over_bound, 0u);
    EXPECT_GT(d->samples, 1000u);
  }
  // README: "< 2^13 units anywhere in the guard band" (depth: 1/8 of a 16-bit step).
  EXPECT_LT(band.max_abs, 8192.0L);
  auto report = [](const char* what, int n, const Drift& d) {
    std::printf(
        "[ stress ] drift, %d %s: max %.2f units (%.4f of a 16-bit depth step), %.3f of the bound "
        "0.5(|Dx|+|Dy|+1) (+ the short path's term) at most, distances up to %.0f px, %llu "
        "samples, stepped == direct\n",
        n, what, static_cast<double>(d.max_abs), static_cast<double>(d.max_abs / 65536),
        static_cast<double>(d.max_ratio), static_cast<double>(d.max_dist),
        static_cast<unsigned long long>(d.samples));
  };
  report("triangles across the coordinate budget |x| < 2^22", budget_count, budget);
  report("guard-band triangles of a 4096 x 4096 viewport", band_count, band);
  report("triangles within 400 px", medium_count, medium);
}

TEST(AttributeDrift, NeedlesThinnerThanTheGradientLimitGetTheVertexMean) {
  // Documented in triangle_setup.hpp: gradients of 2^38 or more per pixel (needles much thinner
  // than a subpixel across the attribute's range) give a constant plane, the vertex mean.
  ScreenVertex a{0, 0, 0, 0, {}, 0, 0}, b{1000 * S, 1, 0, 0, {}, 0, 0},
      c{2000 * S, 1, 0, 0, {}, 0, 0};
  const ScreenVertex* v[3] = {&a, &b, &c};
  const uint32_t vals[3] = {0, 0xFFFFFFFFu, 0x7FFFFFFFu};
  Plane p = make_plane(v, vals);
  EXPECT_EQ(p.gx, 0u);
  EXPECT_EQ(p.gy, 0u);
  EXPECT_EQ(p.base, static_cast<uint32_t>((uint64_t{0xFFFFFFFFu} + 0x7FFFFFFFu) / 3));
}

}  // namespace
}  // namespace lr
