// The front end's bin lane in C (core/binning/bin_lane.hpp, the twin of the Armv7E-M loop that
// firmware/bin_check compares with it on the target) against the binner's own tests
// (EdgeTable::classify_inline, EdgeTable::strip_of_row) on the random meshes of
// firmware/bin_check/bin_cases.hpp: the same records, buckets, counts, stops and vertices to light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <span>
#include <utility>

#include "firmware/bin_check/bin_cases.hpp"
#include "lineraster/core/binning/edge_table.hpp"
#include "lineraster/core/setup/triangle_rows.hpp"

namespace lr {
namespace {

namespace bins = fw::bins;

// The order in which a binned triangle's vertices are stored, from its definition: the rotation
// of (a, b, c) that starts at sort_by_y's first (the topmost, the earliest of a tie); where
// kBinnedSorted (the lane stores store_sorted's order), its last two swapped when the later lies
// strictly above.
std::array<uint16_t, 3> reference_order(const ScreenVertex* base,
                                        const std::array<uint16_t, 3>& in) {
  const ScreenVertex* s[3] = {&base[in[0]], &base[in[1]], &base[in[2]]};
  sort_by_y(s);
  size_t top = 0;
  while (&base[in[top]] != s[0]) ++top;
  std::array<uint16_t, 3> r = {in[top], in[(top + 1) % 3], in[(top + 2) % 3]};
  if (kBinnedSorted && base[r[2]].y < base[r[1]].y) std::swap(r[1], r[2]);
  return r;
}

// The lane as the binner would do it: classify_inline() with back faces culled, then the
// pending vertices, then EdgeTable::add()'s bucket push, the vertices in reference_order().
BinLaneStop reference(const std::array<uint16_t, 3>*& tp, BinLane& k) {
  static BinnedTriangle scratch[bins::kCapacity];
  static uint16_t buckets[bins::kStrips];
  EdgeTable table;
  if (!table.configure(scratch, {}, buckets, {}, k.width, k.height, 8)) return kBinLaneEnd;
  for (; tp != k.end; ++tp) {
    ScreenVertex& v0 = k.vertices[(*tp)[0]];
    ScreenVertex& v1 = k.vertices[(*tp)[1]];
    ScreenVertex& v2 = k.vertices[(*tp)[2]];
    int32_t r0 = 0, r1 = 0;
    const Outcome o = table.classify_inline(v0, v1, v2, Cull::kBack, r0, r1);
    if (o == Outcome::kBackface) continue;
    if (o == Outcome::kZeroArea) {
      ++k.zero;
      continue;
    }
    if (o == Outcome::kOffscreen) {
      ++k.offscreen;
      continue;
    }
    if ((v0.color_pending | v1.color_pending | v2.color_pending) != 0) {
      if (k.list > k.list_limit) return kBinLaneFlush;
      for (ScreenVertex* v : {&v0, &v1, &v2})
        if (v->color_pending != 0) {
          v->color_pending = 0;
          *k.list++ = v;
        }
    }
    const uint32_t index = k.count++;
    uint16_t& head = k.buckets[table.strip_of_row(r0)];
    BinnedTriangle& t = k.triangles[index];
    const std::array<uint16_t, 3> order = reference_order(k.vertices, *tp);
    for (size_t c = 0; c < 3; ++c) t.v[c] = static_cast<uint16_t>(k.first2 + order[c]);
    t.next = head;
    head = static_cast<uint16_t>(index);
  }
  return kBinLaneEnd;
}

TEST(BinLane, CLaneBinsWhatTheEdgeTableBins) {
  static bins::Mesh m;
  static bins::Run a, b;
  const auto portable = [](const std::array<uint16_t, 3>*& tp, BinLane& k) {
    return bin_lane_portable(tp, k);
  };
  const bins::Tally t = bins::run_cases(3000, m, a, b, portable, reference);
  std::printf(
      "[ bins ] %u meshes, %u binned, %u without area, %u without a pixel centre, %u to "
      "light, %u stops, %u with twice the area a multiple of 2^32: %u differ; %u index scans, "
      "%u differ\n",
      t.meshes, t.binned, t.zero, t.offscreen, t.lit, t.stops, t.low_word_zero, t.differing,
      t.scans, t.scans_differing);
  EXPECT_EQ(t.differing, 0u);
  EXPECT_EQ(t.scans_differing, 0u);
  EXPECT_GT(t.binned, 20000u);
  EXPECT_GT(t.zero, 1000u);
  EXPECT_GT(t.offscreen, 500u);
  EXPECT_GT(t.lit, 20000u);
  EXPECT_GT(t.low_word_zero, 1000u);
}

// f(v, ya, yb, yc) for every triangle with corners on rows 0..3 (ties of every kind).
template <class F>
void each_row_triple(F f) {
  for (int32_t ya = 0; ya < 4; ++ya)
    for (int32_t yb = 0; yb < 4; ++yb)
      for (int32_t yc = 0; yc < 4; ++yc) {
        ScreenVertex v[3]{};
        v[0].y = ya * 256;
        v[1].y = yb * 256;
        v[2].y = yc * 256;
        f(v, ya, yb, yc);
      }
}

// Stored as the rotation that starts at sort_by_y's first (the winding kept), and sorted by one
// compare as sort_by_y sorts it, and as sort_by_y sorts the submitted order except where b is on
// top and a level with c.
TEST(BinLane, TopFirstIsARotationThatOneCompareSorts) {
  uint32_t other_order = 0;
  each_row_triple([&](const ScreenVertex(&v)[3], int32_t ya, int32_t yb, int32_t yc) {
    uint16_t t[3];
    store_top_first(t, uint16_t{0}, uint16_t{1}, uint16_t{2}, v[1].y - v[0].y, v[2].y - v[0].y);
    EXPECT_TRUE(t[1] == (t[0] + 1) % 3 && t[2] == (t[0] + 2) % 3) << ya << yb << yc;
    const ScreenVertex* s[3] = {&v[0], &v[1], &v[2]};
    sort_by_y(s);
    const ScreenVertex* r[3] = {&v[t[0]], &v[t[1]], &v[t[2]]};
    EXPECT_EQ(r[0], s[0]) << ya << yb << yc;
    const ScreenVertex* sr[3] = {r[0], r[1], r[2]};
    sort_by_y(sr);
    sort_below_top(r);
    EXPECT_TRUE(r[0] == sr[0] && r[1] == sr[1] && r[2] == sr[2]) << ya << yb << yc;
    if (yb < ya && ya == yc) {
      EXPECT_TRUE(r[1] == &v[2] && r[2] == &v[0]) << ya << yb << yc;
      ++other_order;
    } else {
      EXPECT_TRUE(r[1] == s[1] && r[2] == s[2]) << ya << yb << yc;
    }
  });
  EXPECT_EQ(other_order, 6u);  // yb < ya == yc: (ya, yb) in {(1, 0), (2, 0..1), (3, 0..2)}
}

// store_sorted (where setup's hand-made lanes block reads binned vertices as they are,
// kBinnedSorted) is the rotation followed by sort_below_top's compare: the order setup made from
// the rotation, every tie included. store_binned stores it where kBinnedSorted and asked to,
// else the rotation (the draws the block never takes; two-sided Phong reads the winding).
TEST(BinLane, SortedIsTheRotationSortedBelowItsTop) {
  uint32_t swapped = 0;
  each_row_triple([&](const ScreenVertex(&v)[3], int32_t ya, int32_t yb, int32_t yc) {
    const int32_t dy1 = v[1].y - v[0].y, dy2 = v[2].y - v[0].y;
    uint16_t rot[3], sorted[3], asked[3], kept[3];
    store_top_first(rot, uint16_t{0}, uint16_t{1}, uint16_t{2}, dy1, dy2);
    store_sorted(sorted, uint16_t{0}, uint16_t{1}, uint16_t{2}, dy1, dy2);
    store_binned(asked, uint16_t{0}, uint16_t{1}, uint16_t{2}, dy1, dy2, true);
    store_binned(kept, uint16_t{0}, uint16_t{1}, uint16_t{2}, dy1, dy2, false);
    const ScreenVertex* r[3] = {&v[rot[0]], &v[rot[1]], &v[rot[2]]};
    sort_below_top(r);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(r[k], &v[sorted[k]]) << ya << yb << yc << k;
      EXPECT_EQ(asked[k], kBinnedSorted ? sorted[k] : rot[k]) << ya << yb << yc << k;
      EXPECT_EQ(kept[k], rot[k]) << ya << yb << yc << k;
    }
    EXPECT_LE(v[sorted[0]].y, v[sorted[1]].y);
    EXPECT_LE(v[sorted[1]].y, v[sorted[2]].y);
    swapped += sorted[1] != rot[1];
  });
  EXPECT_EQ(swapped, 18u);  // the rotation's last two strictly out of order
}

// Triangles whose bounds hold one pixel centre of the viewport (one_centre) are binned exactly
// when they cover it: the binner's answer (classify_inline, both windings, nothing culled by its
// facing) against the rows and columns setup_rows gives them. Small triangles around a centre,
// half of them with their corners on a lattice of half pixels (centres on edges and corners).
TEST(BinLane, OneCentreBoundsAreBinnedExactlyWhenTheCentreIsCovered) {
  static BinnedTriangle scratch[4];
  static uint16_t buckets[8];
  EdgeTable table;
  ASSERT_TRUE(table.configure(scratch, {}, buckets, {}, 40, 30, 8));
  uint64_t s = 88172645463325252ull;
  auto next = [&s](int32_t lo, int32_t hi) {  // xorshift64, in [lo, hi]
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return lo + static_cast<int32_t>(s % static_cast<uint64_t>(hi - lo + 1));
  };
  uint32_t in = 0, out = 0, other = 0;
  for (int i = 0; i < 400000; ++i) {
    ScreenVertex v[3]{};
    const int32_t cx = next(-1, 40) * kSubpixel + kHalfPixel, cy = next(-1, 30) * kSubpixel;
    const bool lattice = next(0, 1) == 0;
    for (ScreenVertex& x : v) {
      x.x = cx + (lattice ? next(-2, 2) * kHalfPixel : next(-300, 300));
      x.y = cy + (lattice ? next(-2, 2) * kHalfPixel : next(-300, 300));
    }
    int32_t r0 = 0, r1 = 0;
    const Outcome o = table.classify_inline(v[0], v[1], v[2], Cull::kNone, r0, r1);
    if (o == Outcome::kZeroArea) continue;
    const ScreenVertex* sv[3] = {&v[0], &v[1], &v[2]};
    sort_by_y(sv);
    ActiveTriangle t;
    const int32_t first = std::max(first_row_below(sv[0]->y), 0);
    const int32_t last = std::min(last_row_at_or_above(sv[2]->y), 29);
    const bool covered = first <= last && setup_rows(sv, first, last, 40, t);
    const bool binned = o == Outcome::kBinned;
    // Bounds of one centre inside the viewport: binned exactly when covered.
    const int32_t xmin = std::min({v[0].x, v[1].x, v[2].x}),
                  xmax = std::max({v[0].x, v[1].x, v[2].x});
    const int32_t c0 = std::max((xmin - kHalfPixel + kSubpixel - 1) >> kSubpixelBits, 0);
    const int32_t c1 = (xmax - kHalfPixel + kSubpixel - 1) >> kSubpixelBits;
    const int32_t a = std::max(first_row_below(std::min({v[0].y, v[1].y, v[2].y})), 0);
    const int32_t b = last_row_at_or_above(std::max({v[0].y, v[1].y, v[2].y})) + 1;
    if (one_centre(a, b, c0, c1) && a < 30 && c0 < 40) {
      ASSERT_EQ(binned, covered) << i;
      (covered ? in : out)++;
    } else {
      ASSERT_TRUE(binned || !covered) << i;  // never a covered triangle culled
      ++other;
    }
  }
  std::printf("[ one centre ] %u covered, %u not (culled), %u other bounds\n", in, out, other);
  EXPECT_GT(in, 20000u);
  EXPECT_GT(out, 20000u);
}

}  // namespace
}  // namespace lr
