// The front end's bin lane in C (core/binning/bin_lane.hpp, the twin of the Armv7E-M loop that
// firmware/bin_check compares with it on the target) against the binner's own tests
// (EdgeTable::classify_inline, EdgeTable::strip_of_row) on the random meshes of
// firmware/bin_check/bin_cases.hpp: the same records, buckets, counts, stops and vertices to light.
#include <gtest/gtest.h>

#include <cstdio>
#include <span>

#include "firmware/bin_check/bin_cases.hpp"
#include "lineraster/core/binning/edge_table.hpp"
#include "lineraster/core/setup/triangle_rows.hpp"

namespace lr {
namespace {

namespace bins = fw::bins;

// The order in which a binned triangle's vertices are stored, from its definition: the rotation
// of (a, b, c) that starts at sort_by_y's first (the topmost, the earliest of a tie).
std::array<uint16_t, 3> reference_order(const ScreenVertex* base,
                                        const std::array<uint16_t, 3>& in) {
  const ScreenVertex* s[3] = {&base[in[0]], &base[in[1]], &base[in[2]]};
  sort_by_y(s);
  size_t top = 0;
  while (&base[in[top]] != s[0]) ++top;
  return {in[top], in[(top + 1) % 3], in[(top + 2) % 3]};
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

// Every triangle with corners on rows 0..3 (ties of every kind): stored as the rotation that
// starts at sort_by_y's first (the winding kept), and sorted by one compare as sort_by_y sorts
// it, and as sort_by_y sorts the submitted order except where b is on top and a level with c.
TEST(BinLane, TopFirstIsARotationThatOneCompareSorts) {
  uint32_t other_order = 0;
  for (int32_t ya = 0; ya < 4; ++ya)
    for (int32_t yb = 0; yb < 4; ++yb)
      for (int32_t yc = 0; yc < 4; ++yc) {
        ScreenVertex v[3]{};
        v[0].y = ya * 256;
        v[1].y = yb * 256;
        v[2].y = yc * 256;
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
      }
  EXPECT_EQ(other_order, 6u);  // yb < ya == yc: (ya, yb) in {(1, 0), (2, 0..1), (3, 0..2)}
}

}  // namespace
}  // namespace lr
