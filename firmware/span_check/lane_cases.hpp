// Random cases for the lanes row loop (core/span/lane_rows.hpp): triangles set up as the
// renderer sets them up (setup_untextured_triangle, RGB565 lanes with the depth test), drawn
// strip by strip by two row loops into two copies of the same random strip buffers, whose
// pixels, depths and counts must be equal; and random spans through two span loops.
// firmware/span_check compares the hand-allocated loops with their C twins on the target;
// tests/core/lane_rows_test.cpp compares the C twin with the renderer's generic row loop on the
// host. Integers only, no heap.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/raster/strip_visit.hpp"
#include "lineraster/core/raster/untextured_rows.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/setup/strip_rows.hpp"
#include "lineraster/core/setup/triangle_rows.hpp"
#include "lineraster/core/setup/untextured_setup.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr::fw::lanes {

using PF = Rgb565Be;
inline constexpr int kWidth = 96;  // the viewport: triangles reach beyond every side
inline constexpr int kHeight = 64;
inline constexpr int kMaxRows = kMaxVisitRows;

// xorshift32: the same sequence on every core.
struct Random {
  uint32_t s = 2463534242u;
  uint32_t next() {
    s ^= s << 13;
    s ^= s >> 17;
    s ^= s << 5;
    return s;
  }
  // In [lo, hi].
  int32_t in(int32_t lo, int32_t hi) {
    return lo + static_cast<int32_t>(next() % static_cast<uint32_t>(hi - lo + 1));
  }
};

// A strip: pixels and depths.
struct Strip {
  std::array<uint16_t, kWidth * kMaxRows> px{};
  std::array<uint16_t, kWidth * kMaxRows> depth{};
};

// A random triangle of the case's kind: small (the 32-bit setup), medium (up to 200 px, the
// general setup and, beyond 128 px, the affine kind), needles, flat tops and bottoms, anywhere
// around the viewport.
inline void random_triangle(Random& rng, ScreenVertex v[3]) {
  const int kind = rng.in(0, 9);
  const int32_t size = kind < 6 ? 12 * kSubpixel : kind < 8 ? 60 * kSubpixel : 200 * kSubpixel;
  const int32_t cx = rng.in(-20 * kSubpixel, (kWidth + 20) * kSubpixel);
  const int32_t cy = rng.in(-20 * kSubpixel, (kHeight + 20) * kSubpixel);
  for (int i = 0; i < 3; ++i) {
    v[i].x = cx + rng.in(-size, size);
    v[i].y = cy + rng.in(-size, size);
    v[i].z = static_cast<uint32_t>(rng.next() % (kDepthMax + 1u));
    v[i].w = 1u << 16;
    v[i].color = Color15{static_cast<uint16_t>(rng.in(0, Color15::kOne)),
                         static_cast<uint16_t>(rng.in(0, Color15::kOne)),
                         static_cast<uint16_t>(rng.in(0, Color15::kOne))};
    v[i].outcode = 0;
    v[i].color_pending = 0;
  }
  if (kind == 8) v[1].y = v[0].y;  // a flat top or bottom (after the sort)
  if (kind == 9) {                 // a needle
    v[1].x = v[0].x + rng.in(-3, 3);
    v[1].y = v[0].y + rng.in(-2 * kSubpixel, 2 * kSubpixel);
  }
}

// The result of a case: how many visits were compared and how many differed.
struct Tally {
  uint32_t triangles = 0, visits = 0, differing = 0, pixels = 0;
};

// Runs `cases` random triangles: each set up at its first strip of a random height, then every
// strip visit drawn by draw_a into `a` and draw_b into `b` from the same random contents.
template <class DrawA, class DrawB>
Tally run_cases(uint32_t cases, Strip& a, Strip& b, DrawA&& draw_a, DrawB&& draw_b,
                uint32_t seed = 2463534242u) {
  Random rng;
  rng.s = seed;
  Tally tally;
  UntexturedInput in;
  in.colors = ColorPlanes::kAffine;
  in.depth = true;
  in.lanes = true;
  in.affine = kAffineBound565;
  in.lanes_first = lanes_first_of(in);
  for (uint32_t c = 0; c < cases; ++c) {
    ScreenVertex v[3];
    random_triangle(rng, v);
    if (signed_area2(v[0], v[1], v[2]) == 0) continue;
    const ScreenVertex* s[3] = {&v[0], &v[1], &v[2]};
    sort_by_y(s);
    const int k = rng.in(1, kMaxRows);  // the strip height
    const int32_t top = std::max<int32_t>(first_row_below(s[0]->y), 0);
    const int32_t bottom = std::min<int32_t>(last_row_at_or_above(s[2]->y), kHeight - 1);
    if (top > bottom) continue;
    const int32_t strip0 = top / k;
    ActiveTriangle t;
    const RowWindow window{strip0 * k, kHeight - 1, kWidth};
    const UntexturedTriangle u = setup_untextured_triangle(s, window, in, t);
    if (!u.pixels() || u.kind() != UntexturedKind::kLanes ||
        (t.flags & ActiveTriangle::kWideEdges) != 0)
      continue;
    ++tally.triangles;
    for (int32_t y0 = strip0 * k; y0 <= t.last_row; y0 += k) {
      const int32_t rows = std::min<int32_t>(k, kHeight - y0);
      for (size_t i = 0; i < static_cast<size_t>(kWidth * rows); ++i) {
        a.px[i] = b.px[i] = static_cast<uint16_t>(rng.next());
        // Depths that pass, fail and tie (the test is LESS).
        a.depth[i] = b.depth[i] = static_cast<uint16_t>(rng.next() % 4 == 0 ? 0xFFFFu : rng.next());
      }
      StripRows sa, sb;
      sa.pixels = a.px.data();
      sa.depth = a.depth.data();
      sb.pixels = b.px.data();
      sb.depth = b.depth.data();
      sa.y0 = sb.y0 = y0;
      sa.y_last = sb.y_last = y0 + rows - 1;
      sa.width = sb.width = kWidth;
      draw_a(t, sa);
      draw_b(t, sb);
      ++tally.visits;
      tally.pixels += sa.tested;
      bool same = sa.spans == sb.spans && sa.tested == sb.tested && sa.written == sb.written &&
                  sa.rows == sb.rows;
      for (size_t i = 0; i < static_cast<size_t>(kWidth * rows); ++i)
        same = same && a.px[i] == b.px[i] && a.depth[i] == b.depth[i];
      if (!same) ++tally.differing;
    }
  }
  return tally;
}

// What run_strips compared: strips, the active triangles in them, those of them in lanes runs
// of two or more, those of another kind, those kept and freed, pixels, and strips that differ.
struct StripTally {
  uint32_t strips = 0, triangles = 0, in_runs = 0, others = 0, kept = 0, freed = 0, pixels = 0,
           differing = 0;
};

// Runs `cases` random strips of up to kSlots active triangles (lanes ones, whose rows are
// `lanes`, and others of the generic row loop: the affine kind, lanes with wide edges), in random
// slots and order beside random free slots, visited by visit_a and visit_b (ActiveList&,
// StripRows&) from two copies of the same lists and strip contents: pixels, depths, counts, the
// kept order and the free list must be equal.
inline constexpr size_t kSlots = 12;
template <class VisitA, class VisitB>
StripTally run_strips(uint32_t cases, Strip& a, Strip& b, RowFn lanes, VisitA&& visit_a,
                      VisitB&& visit_b, uint32_t seed = 60606u) {
  Random rng;
  rng.s = seed;
  StripTally tally;
  UntexturedInput in;
  in.colors = ColorPlanes::kAffine;
  in.depth = true;
  in.lanes = true;
  in.affine = kAffineBound565;
  in.lanes_first = lanes_first_of(in);
  static std::array<ActiveTriangle, kSlots> active;
  for (uint32_t c = 0; c < cases; ++c) {
    const int k = rng.in(1, kMaxRows);
    const int32_t y0 = k * rng.in(0, (kHeight - 1) / k);
    const int32_t rows = std::min<int32_t>(k, kHeight - y0);
    const RowWindow window{y0, kHeight - 1, kWidth};
    // The slots in a random order: the first `count` active, the rest free.
    std::array<uint16_t, kSlots> slots;
    for (size_t i = 0; i < kSlots; ++i) slots[i] = static_cast<uint16_t>(i);
    for (size_t i = kSlots - 1; i > 0; --i)
      std::swap(slots[i], slots[static_cast<size_t>(rng.in(0, static_cast<int32_t>(i)))]);
    const auto want = static_cast<size_t>(rng.in(1, static_cast<int32_t>(kSlots) - 2));
    size_t count = 0;
    for (int attempt = 0; attempt < 200 && count < want; ++attempt) {
      ScreenVertex v[3];
      random_triangle(rng, v);
      // Mostly near the strip.
      const int32_t dy = (y0 + rows / 2) * kSubpixel - (v[0].y + v[1].y + v[2].y) / 3;
      for (ScreenVertex& x : v) x.y += dy + rng.in(-4 * kSubpixel, 4 * kSubpixel);
      if (signed_area2(v[0], v[1], v[2]) == 0) continue;
      const ScreenVertex* s[3] = {&v[0], &v[1], &v[2]};
      sort_by_y(s);
      ActiveTriangle& t = active[slots[count]];
      const UntexturedTriangle u = setup_untextured_triangle(s, window, in, t);
      if (!u.pixels() || t.first_row > y0 + rows - 1) continue;
      const bool wide = (t.flags & ActiveTriangle::kWideEdges) != 0;
      if (u.kind() == UntexturedKind::kLanes && !wide)
        t.rows = lanes;
      else if (u.kind() == UntexturedKind::kLanes)
        t.rows = &untextured_rows_per_span<PF, true, UntexturedKind::kLanes>;
      else if (u.kind() == UntexturedKind::kAffine)
        t.rows = &untextured_rows_per_span<PF, true, UntexturedKind::kAffine>;
      else
        continue;
      ++count;
    }
    if (count == 0) continue;
    ++tally.strips;
    tally.triangles += static_cast<uint32_t>(count);
    for (size_t i = 0; i < count; ++i) {
      const ActiveTriangle& t = active[slots[i]];
      const bool run = t.rows == lanes && ((i > 0 && active[slots[i - 1]].rows == lanes) ||
                                           (i + 1 < count && active[slots[i + 1]].rows == lanes));
      tally.in_runs += run ? 1u : 0u;
      tally.others += t.rows != lanes ? 1u : 0u;
      (t.last_row > y0 + rows - 1 ? tally.kept : tally.freed)++;
    }
    // The lists: order then free slots, as the strip loop keeps them.
    std::array<uint16_t, 2 * kSlots> la{}, lb{};
    std::copy(slots.begin(), slots.begin() + static_cast<std::ptrdiff_t>(count), la.begin());
    const size_t free = kSlots - count;
    std::copy(slots.begin() + static_cast<std::ptrdiff_t>(count), slots.end(), la.begin() + kSlots);
    lb = la;
    ActiveList xa{la.data(), la.data() + kSlots, active.data(), count, free};
    ActiveList xb{lb.data(), lb.data() + kSlots, active.data(), count, free};
    for (size_t i = 0; i < static_cast<size_t>(kWidth * rows); ++i) {
      a.px[i] = b.px[i] = static_cast<uint16_t>(rng.next());
      a.depth[i] = b.depth[i] = static_cast<uint16_t>(rng.next() % 4 == 0 ? 0xFFFFu : rng.next());
    }
    StripRows sa, sb;
    sa.pixels = a.px.data();
    sa.depth = a.depth.data();
    sb.pixels = b.px.data();
    sb.depth = b.depth.data();
    sa.y0 = sb.y0 = y0;
    sa.y_last = sb.y_last = y0 + rows - 1;
    sa.width = sb.width = kWidth;
    visit_a(xa, sa);
    visit_b(xb, sb);
    tally.pixels += sa.tested;
    bool same = sa.spans == sb.spans && sa.tested == sb.tested && sa.written == sb.written &&
                sa.rows == sb.rows && xa.count == xb.count && xa.free == xb.free &&
                xa.free == kSlots - xa.count;
    for (size_t i = 0; same && i < xa.count; ++i) same = la[i] == lb[i];
    for (size_t i = 0; same && i < xa.free; ++i) same = la[kSlots + i] == lb[kSlots + i];
    for (size_t i = 0; i < static_cast<size_t>(kWidth * rows); ++i)
      same = same && a.px[i] == b.px[i] && a.depth[i] == b.depth[i];
    if (!same) ++tally.differing;
  }
  return tally;
}

// Runs `cases` random spans (1 to kWidth pixels, lanes that stay in range over the span, depths
// that pass, fail and tie) through span_a and span_b (fill(px, depth, n, z, dz, br, dbr, g, dg)
// -> rejected pixels) into two copies of the same strip row: pixels, depths and the rejected
// count must be equal.
template <class SpanA, class SpanB>
Tally run_spans(uint32_t cases, Strip& a, Strip& b, SpanA&& span_a, SpanB&& span_b,
                uint32_t seed = 88172645u) {
  Random rng;
  rng.s = seed;
  Tally tally;
  for (uint32_t c = 0; c < cases; ++c) {
    const int32_t n = rng.in(1, kWidth);
    // A lane value and a step that keep it in [0, 2^16) over n pixels.
    const auto lane = [&](uint32_t& v, int32_t& step) {
      v = static_cast<uint32_t>(rng.in(0, 65535));
      const int32_t room = static_cast<int32_t>(std::min<uint32_t>(v, 65535u - v)) / n;
      step = rng.in(-room, room);
    };
    uint32_t r, bl, g;
    int32_t dr, dbl, dg;
    lane(r, dr);
    lane(bl, dbl);
    lane(g, dg);
    const uint32_t br = (bl << 16) + r;
    const uint32_t dbr = (static_cast<uint32_t>(dbl) << 16) + static_cast<uint32_t>(dr);
    const uint32_t z = rng.next() >> 1, dz = rng.next() % 65536;
    for (int32_t i = 0; i < n; ++i) {
      const auto k = static_cast<size_t>(i);
      a.px[k] = b.px[k] = static_cast<uint16_t>(rng.next());
      const uint32_t d = (z + dz * static_cast<uint32_t>(i)) >> 15;
      const uint32_t pick = rng.next() % 4;  // below, equal, above, cleared
      a.depth[k] = b.depth[k] = static_cast<uint16_t>(pick == 0   ? d - 1
                                                      : pick == 1 ? d
                                                      : pick == 2 ? d + 1
                                                                  : 0xFFFFu);
    }
    const uint32_t ra = span_a(a.px.data(), a.depth.data(), n, z, dz, br, dbr, g << 16,
                               static_cast<uint32_t>(dg) << 16);
    const uint32_t rb = span_b(b.px.data(), b.depth.data(), n, z, dz, br, dbr, g << 16,
                               static_cast<uint32_t>(dg) << 16);
    ++tally.visits;
    tally.pixels += static_cast<uint32_t>(n);
    bool same = ra == rb;
    for (size_t i = 0; i < static_cast<size_t>(n); ++i)
      same = same && a.px[i] == b.px[i] && a.depth[i] == b.depth[i];
    if (!same) ++tally.differing;
  }
  return tally;
}

// A random small triangle for run_small_planes and run_small_triangles: a size of a quarter
// pixel to 31 pixels, its centre in [x_lo, x_hi] x [y_lo, y_hi] (subpixels), depths random, close
// (12 bits), spread (26 bits) or equal, random colours.
inline void random_small_triangle(Random& rng, ScreenVertex (&v)[3], int32_t x_lo, int32_t x_hi,
                                  int32_t y_lo, int32_t y_hi) {
  constexpr int32_t kSizes[4] = {kSubpixel / 4, 2 * kSubpixel, 12 * kSubpixel, 31 * kSubpixel};
  const int32_t size = kSizes[rng.in(0, 3)];
  const int32_t cx = rng.in(x_lo, x_hi);
  const int32_t cy = rng.in(y_lo, y_hi);
  const int zmode = rng.in(0, 3);
  const uint32_t z0 = rng.next() % (kDepthMax + 1u);
  for (int i = 0; i < 3; ++i) {
    v[i].x = cx + rng.in(-size, size);
    v[i].y = cy + rng.in(-size, size);
    v[i].z = zmode == 0   ? rng.next() % (kDepthMax + 1u)
             : zmode == 1 ? std::min<uint32_t>(z0 + rng.next() % 4096u, kDepthMax)
             : zmode == 2 ? std::min<uint32_t>(z0 + rng.next() % (1u << 26), kDepthMax)
                          : z0;
    v[i].w = 1u << 16;
    v[i].color = Color15{static_cast<uint16_t>(rng.in(0, Color15::kOne)),
                         static_cast<uint16_t>(rng.in(0, Color15::kOne)),
                         static_cast<uint16_t>(rng.in(0, Color15::kOne))};
  }
}

// Every other case one hue (UntexturedInput::hue) with random ratios below 2: the planes'
// integers do not depend on the colours being one hue.
inline void random_hue(Random& rng, UntexturedInput& in, uint32_t c) {
  in.hue.valid = (c & 1u) != 0;
  in.hue.red = static_cast<int32_t>(rng.next() >> 1);
  in.hue.blue = static_cast<int32_t>(rng.next() >> 1);
}

// Runs `cases` random small triangles (every edge component below 2^kSmallEdgeBits subpixels,
// from a quarter pixel to 62 pixels; depths spread, close (differences of 12 bits, or of up to
// 26 of which the small path keeps 16) or equal; random colours) through
// small_planes' C form and through small_lanes_planes_by_hand (kLanes with depth): the same
// answer and, when planes were made, the same depth and colour planes. visits counts the
// triangles both refused (their spread needs the general setup).
inline Tally run_small_planes(uint32_t cases, uint32_t seed = 777u) {
  Random rng;
  rng.s = seed;
  Tally tally;
  UntexturedInput in;
  in.colors = ColorPlanes::kAffine;
  in.depth = true;
  in.lanes = true;
  for (uint32_t c = 0; c < cases; ++c) {
    ScreenVertex v[3];
    random_small_triangle(rng, v, -40 * kSubpixel, 400 * kSubpixel, -40 * kSubpixel,
                          300 * kSubpixel);
    const ScreenVertex* s[3] = {&v[0], &v[1], &v[2]};
    sort_by_y(s);
    const int32_t e1x = s[1]->x - s[0]->x, e1y = s[1]->y - s[0]->y;
    const int32_t e2x = s[2]->x - s[0]->x, e2y = s[2]->y - s[0]->y;
    const int32_t d = e1x * e2y - e2x * e1y;
    if (d == 0) continue;
    const auto mag = [](int32_t x) { return x < 0 ? 0u - uint32_t(x) : uint32_t(x); };
    const uint32_t m = mag(e1x) | mag(e2x) | uint32_t(e2y);
    random_hue(rng, in, c);
    ActiveTriangle a, b;
    const bool made_a = small_planes(s, d, m, in, UntexturedKind::kLanes, a);
    const bool made_b = small_lanes_planes_by_hand(s, d, m, in, b);
    const auto same = [](const Plane& p, const Plane& q) {
      return p.base == q.base && p.gx == q.gx && p.gy == q.gy;
    };
    if (made_a != made_b ||
        (made_a && !(same(a.z, b.z) && same(a.c[0], b.c[0]) && same(a.c[1], b.c[1]))))
      ++tally.differing;
    if (made_a)
      ++tally.triangles;
    else
      ++tally.visits;
  }
  return tally;
}

// Runs `cases` random small triangles (run_small_planes' kinds) in random windows through the
// C forms (small_rows, then small_planes when the rows have pixels on their first rows) and
// through small_lanes_triangle_by_hand (both steps in one call): the same rows, edges, flags and
// answers, and the same planes when they were made. triangles counts those with planes, visits
// those with rows only (pixels on later rows only, or planes refused).
inline Tally run_small_triangles(uint32_t cases, uint32_t seed = 99991u) {
  Random rng;
  rng.s = seed;
  Tally tally;
  UntexturedInput in;
  in.colors = ColorPlanes::kAffine;
  in.depth = true;
  in.lanes = true;
  for (uint32_t c = 0; c < cases; ++c) {
    ScreenVertex v[3];
    random_small_triangle(rng, v, -8 * kSubpixel, (kWidth + 8) * kSubpixel, -8 * kSubpixel,
                          (kHeight + 8) * kSubpixel);
    if (signed_area2(v[0], v[1], v[2]) == 0) continue;
    const ScreenVertex* s[3] = {&v[0], &v[1], &v[2]};
    sort_by_y(s);
    const RowWindow window{rng.in(-4, kHeight / 2), kHeight - 1, kWidth};
    random_hue(rng, in, c);
    ActiveTriangle a, b;
    const SmallRows ra = small_rows(s, window, a);
    const bool made_a = ra.result == SmallRows::kPixels &&
                        small_planes(s, ra.d, ra.m, in, UntexturedKind::kLanes, a);
    SmallRows rb;
    const bool made_b = small_lanes_triangle_by_hand(s, window, in, b, rb);
    bool same = ra.result == rb.result && ra.m == rb.m && made_a == made_b;
    if (same && ra.result != SmallRows::kSlow) {
      same = ra.d == rb.d && a.first_row == b.first_row && a.mid_row == b.mid_row &&
             a.last_row == b.last_row && a.col_base == b.col_base && a.flags == b.flags &&
             a.bottom.q == b.bottom.q && a.bottom.dx == b.bottom.dx && a.bottom.dy == b.bottom.dy;
      for (int i = 0; i < 2; ++i)
        same = same && a.edge_q[i] == b.edge_q[i] && a.edge_dx[i] == b.edge_dx[i] &&
               a.edge_dy[i] == b.edge_dy[i];
    }
    const auto same_plane = [](const Plane& p, const Plane& q) {
      return p.base == q.base && p.gx == q.gx && p.gy == q.gy;
    };
    if (same && made_a)
      same = same_plane(a.z, b.z) && same_plane(a.c[0], b.c[0]) && same_plane(a.c[1], b.c[1]);
    if (!same) ++tally.differing;
    if (made_a)
      ++tally.triangles;
    else if (ra.result != SmallRows::kSlow)
      ++tally.visits;
  }
  return tally;
}

// LanesSetup's row loop for its lanes triangles in run_lanes_setup: a mark, never called.
inline void marker_rows(const ActiveTriangle& /*t*/, StripRows& /*s*/) {}

// Runs `cases` random triangles of random_triangle's kinds, their w and colours spread so that
// the affine colour test goes every way, through LanesSetup (from their vertex indices in a
// random order, stored as binning stores them: store_binned) and through sort_by_y and
// setup_untextured_triangle without lanes_first: the same result and the same record. triangles
// counts the lanes ones, visits the slivers and pixels the others (perspective planes, or the
// general path).
inline Tally run_lanes_setup(uint32_t cases, uint32_t seed = 5151u) {
  Random rng;
  rng.s = seed;
  Tally tally;
  UntexturedInput in;
  in.depth = true;
  in.lanes = true;
  in.affine_ok = true;
  in.affine = kAffineBound565;
  for (uint32_t c = 0; c < cases; ++c) {
    in.colors = rng.in(0, 7) == 0 ? ColorPlanes::kAffine : ColorPlanes::kPerspective;
    in.lanes_first = lanes_first_of(in);
    // One hue half the time, as one_hue admits it: ratios below 2 to 15 bits, and every vertex
    // colour within a few units of rho green (the block's affine test relies on it).
    in.hue.valid = (c & 1u) != 0;
    const uint32_t qr = rng.next() % (1u << 16), qb = rng.next() % (1u << 16);
    in.hue.red = static_cast<int32_t>(qr << 15);
    in.hue.blue = static_cast<int32_t>(qb << 15);
    const uint32_t g_max =
        (uint32_t{Color15::kOne} << 15) / std::max({qr, qb, uint32_t{1} << 15}) - 16;
    ScreenVertex v[3];
    random_triangle(rng, v);
    if (signed_area2(v[0], v[1], v[2]) == 0) continue;
    const uint32_t w0 = (1u << 16) + rng.next() % (1u << 22);
    const int wmode = rng.in(0, 2);       // w equal, close (the quick test) or spread
    const int cmode = rng.in(0, 2);       // colours random, close or equal
    const bool near = rng.in(0, 3) != 0;  // depths close: the small path's planes
    const uint32_t z0 = rng.next() % (kDepthMax - 8192u);
    for (ScreenVertex& x : v) {
      if (near) x.z = z0 + rng.next() % 8192u;
      x.w = wmode == 0 ? w0 : wmode == 1 ? w0 + rng.next() % (w0 >> 5) : w0 + rng.next() % w0;
      if (cmode > 0) {
        const uint16_t spread = cmode == 1 ? 600 : 0;
        x.color = Color15{static_cast<uint16_t>(16000 + rng.in(0, spread)),
                          static_cast<uint16_t>(16000 + rng.in(0, spread)),
                          static_cast<uint16_t>(16000 + rng.in(0, spread))};
      }
      if (in.hue.valid) {  // green kept below g_max, red and blue rho green within 9 units
        const uint32_t g = x.color.g % g_max + 9;
        const auto of_hue = [&](uint32_t q) {
          const int32_t e = static_cast<int32_t>((g * q) >> 15) + rng.in(-9, 9);
          return static_cast<uint16_t>(std::clamp<int32_t>(e, 0, Color15::kOne));
        };
        x.color = Color15{of_hue(qr), static_cast<uint16_t>(g), of_hue(qb)};
      }
    }
    uint16_t order[3] = {0, 1, 2};
    for (int i = 2; i > 0; --i) std::swap(order[i], order[rng.in(0, i)]);
    // As binned (store_binned: sorted by y where the block reads them so).
    uint16_t index[3];
    store_binned(index, order[0], order[1], order[2], v[order[1]].y - v[order[0]].y,
                 v[order[2]].y - v[order[0]].y);
    const RowWindow window{rng.in(-4, kHeight / 2), kHeight - 1, kWidth};
    ActiveTriangle a, b;
    std::memset(static_cast<void*>(&a), 0, sizeof a);
    std::memset(static_cast<void*>(&b), 0, sizeof b);
    LanesSetup lanes;
    lanes.prepare(window, in, v, &marker_rows);
    const UntexturedTriangle ua = lanes.set_up(index, a);
    // A lanes triangle gets the prepared row loop (the block stores it beside the depth plane),
    // which setup_untextured_triangle leaves to its caller; the other kinds' are the caller's.
    const bool rows_ok =
        !(ua == UntexturedTriangle::made(UntexturedKind::kLanes, false)) || a.rows == &marker_rows;
    a.rows = nullptr;
    const ScreenVertex* s[3] = {&v[index[0]], &v[index[1]], &v[index[2]]};
    sort_by_y(s);
    UntexturedInput plain = in;
    plain.lanes_first = false;
    const UntexturedTriangle ub = setup_untextured_triangle(s, window, plain, b);
    if (!(ua == ub) || !rows_ok || std::memcmp(&a, &b, sizeof a) != 0) ++tally.differing;
    if (!ub.pixels())
      ++tally.visits;
    else if (ub.kind() == UntexturedKind::kLanes && !ub.wide())
      ++tally.triangles;
    else
      ++tally.pixels;
  }
  return tally;
}

// Runs `cases` random triangles of random_triangle's kinds (small ones take the 32-bit path,
// the others are refused as kSlow) in random windows through small_rows and small_rows_by_hand:
// the same answer, d and m, and the same rows, edges and flags. visits counts the refused ones.
inline Tally run_small_rows(uint32_t cases, uint32_t seed = 4242u) {
  Random rng;
  rng.s = seed;
  Tally tally;
  for (uint32_t c = 0; c < cases; ++c) {
    ScreenVertex v[3];
    random_triangle(rng, v);
    // A third on the half-pixel lattice plus one subpixel or none: centres on edges, columns
    // and rows on their bounds.
    if (rng.in(0, 2) == 0) {
      const int32_t nudge = rng.in(-1, 1);
      for (ScreenVertex& x : v) {
        x.x = (x.x & ~(kHalfPixel - 1)) + nudge;
        x.y = (x.y & ~(kHalfPixel - 1)) + nudge;
      }
    }
    if (signed_area2(v[0], v[1], v[2]) == 0) continue;
    const ScreenVertex* s[3] = {&v[0], &v[1], &v[2]};
    sort_by_y(s);
    const int32_t first_min = rng.in(-4, kHeight);
    const RowWindow window{first_min, kHeight - 1, kWidth};
    ActiveTriangle a, b;
    const SmallRows ra = small_rows(s, window, a);
    const SmallRows rb = small_rows_by_hand(s, window, b);
    bool same = ra.result == rb.result && ra.m == rb.m;
    if (same && ra.result != SmallRows::kSlow) {
      same = ra.d == rb.d && a.first_row == b.first_row && a.mid_row == b.mid_row &&
             a.last_row == b.last_row && a.col_base == b.col_base && a.flags == b.flags &&
             a.bottom.q == b.bottom.q && a.bottom.dx == b.bottom.dx && a.bottom.dy == b.bottom.dy;
      for (int i = 0; i < 2; ++i)
        same = same && a.edge_q[i] == b.edge_q[i] && a.edge_dx[i] == b.edge_dx[i] &&
               a.edge_dy[i] == b.edge_dy[i];
    }
    if (!same) ++tally.differing;
    if (ra.result == SmallRows::kSlow)
      ++tally.visits;
    else
      ++tally.triangles;
    if (ra.result == SmallRows::kLaterRows) ++tally.pixels;  // the sliver test's second step
  }
  return tally;
}

}  // namespace lr::fw::lanes
