// The front end's bin lane in C (core/binning/bin_lane.hpp, the twin of the Armv7E-M loop that
// firmware/bin_check compares with it on the target) against the binner's own tests
// (EdgeTable::classify_inline, EdgeTable::strip_of_row) on the random meshes of
// firmware/bin_check/bin_cases.hpp: the same records, buckets, counts, stops and vertices to light.
#include <gtest/gtest.h>

#include <cstdio>
#include <span>

#include "firmware/bin_check/bin_cases.hpp"
#include "lineraster/core/binning/edge_table.hpp"

namespace lr {
namespace {

namespace bins = fw::bins;

// The lane as the binner would do it: classify_inline() with back faces culled, then the
// pending vertices, then EdgeTable::add()'s bucket push.
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
    for (size_t c = 0; c < 3; ++c) t.v[c] = static_cast<uint16_t>(k.first2 + (*tp)[c]);
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
      "light, %u stops: %u differ; %u index scans, %u differ\n",
      t.meshes, t.binned, t.zero, t.offscreen, t.lit, t.stops, t.differing, t.scans,
      t.scans_differing);
  EXPECT_EQ(t.differing, 0u);
  EXPECT_EQ(t.scans_differing, 0u);
  EXPECT_GT(t.binned, 20000u);
  EXPECT_GT(t.zero, 1000u);
  EXPECT_GT(t.offscreen, 500u);
  EXPECT_GT(t.lit, 20000u);
}

}  // namespace
}  // namespace lr
