// Random meshes for the front end's bin lane (core/binning/bin_lane.hpp): screen vertices
// on and off the viewport, at the guard band's reach, on and next to pixel centres, degenerate
// (repeated and collinear corners), some waiting for their colour, some meshes with a right
// triangle whose twice signed area is a multiple of 2^32 (its low word 0, which the hand-made lane
// tests apart from a zero area); triangles of both facings, some with an index out of range
// (first_out_of_range() ends the lane's run there). run_cases() runs two lanes on equal copies of
// each mesh (with a small table and list, so that they stop, flush and resume) and counts the
// meshes on which anything differs: the stop reasons, the triangle each stopped at, the records
// (order, vertices, next), the buckets, the counts, the list of vertices to light and the vertices'
// flags. Shared by lr_bin_check (the hand-allocated lane against the C one on the target) and the
// host test.
#pragma once

#include <array>
#include <cstdint>

#include "lineraster/core/binning/bin_lane.hpp"

namespace lr::fw::bins {

inline constexpr uint32_t kVertices = 64, kTriangles = 96, kCapacity = 80, kStrips = 8;
inline constexpr uint32_t kList = 16;  // entries (the lane needs room for three)
inline constexpr int32_t kWidth = 64, kHeight = 60;

struct Mesh {
  ScreenVertex v[kVertices];
  std::array<uint16_t, 3> t[kTriangles];
};

// One lane's state and results on a mesh.
struct Run {
  ScreenVertex v[kVertices];
  BinnedTriangle tris[kCapacity];
  uint16_t buckets[kStrips];
  ScreenVertex* list[kList];
  uint16_t lit[kVertices * 4];  // the vertices put on the list, in order, over every stop
  uint32_t lit_count;
  uint32_t stops[kTriangles * 4];  // (reason << 16) | triangle
  uint32_t stop_count;
  uint32_t count, zero, offscreen;
};

struct Tally {
  uint32_t meshes = 0, binned = 0, back = 0, zero = 0, offscreen = 0, lit = 0, stops = 0;
  uint32_t low_word_zero = 0;  // triangles with twice the area a non-zero multiple of 2^32
  uint32_t differing = 0;
  uint32_t scans = 0, scans_differing = 0;  // first_out_of_range() against one index at a time
};

struct Rng {
  uint32_t s;
  uint32_t next() {
    s ^= s << 13;
    s ^= s >> 17;
    s ^= s << 5;
    return s;
  }
  int32_t range(int32_t lo, int32_t hi) {  // [lo, hi]
    return lo + static_cast<int32_t>(next() % static_cast<uint32_t>(hi - lo + 1));
  }
};

inline void make_mesh(Rng& r, Mesh& m) {
  const uint32_t kind = r.next() % 5;
  // Kind 4: every vertex within 300 subpixels of one pixel centre's (tiny triangles, many of
  // whose bounds hold one centre: the binner tests it, holds_centre()).
  const int32_t cx = r.range(0, kWidth) * 256 + 128, cy = r.range(0, kHeight) * 256 + 128;
  for (uint32_t i = 0; i < kVertices; ++i) {
    ScreenVertex& v = m.v[i];
    v = ScreenVertex{};
    const uint32_t where = r.next() % 16;
    if (where == 0) {  // at the guard band's reach (deltas below 2^23)
      v.x = r.range(-(1 << 21), 1 << 21);
      v.y = r.range(-(1 << 21), 1 << 21);
    } else if (where < 4) {  // around the viewport
      v.x = r.range(-kWidth * 256, 2 * kWidth * 256);
      v.y = r.range(-kHeight * 256, 2 * kHeight * 256);
    } else if (where < 6 && i > 0) {  // on or near another vertex (no area, slivers)
      v.x = m.v[i - 1].x + r.range(-2, 2) * (kind == 0 ? 1 : 128);
      v.y = m.v[i - 1].y + r.range(-2, 2) * (kind == 1 ? 1 : 128);
    } else {  // small triangles on the viewport
      v.x = r.range(-300, kWidth * 256 + 300);
      v.y = r.range(-300, kHeight * 256 + 300);
    }
    if (kind == 4) {  // half of them on a lattice of 64 subpixels (centres on edges)
      const int32_t step = i % 2 == 0 ? 1 : 64;
      v.x = cx + r.range(-300 / step, 300 / step) * step;
      v.y = cy + r.range(-300 / step, 300 / step) * step;
    }
    if (kind == 2 && r.next() % 2 == 0) {  // on a pixel centre's row or column, or next to it
      v.x = (v.x & ~255) + 128 + r.range(-1, 1);
      v.y = (v.y & ~255) + 128 + r.range(-1, 1);
    }
    v.color = {static_cast<uint16_t>(i), 0, 0};
    v.color_pending = (kind == 3 || r.next() % 3 == 0) ? 1 : 0;
  }
  if (r.next() % 4 == 0) {  // vertices 0 to 2: legs of 2^16 and 2^16 << s subpixels
    const int32_t x = r.range(-300 * 256, kWidth * 256), y = r.range(-300 * 256, kHeight * 256);
    const int32_t leg = 1 << (16 + r.next() % 3);
    m.v[0].x = x;
    m.v[0].y = y;
    m.v[1].x = x + leg;
    m.v[1].y = y;
    m.v[2].x = x;
    m.v[2].y = y + (1 << 16);
  }
  for (uint32_t t = 0; t < kTriangles; ++t) {
    const auto a = static_cast<uint16_t>(r.next() % kVertices);
    uint16_t b = static_cast<uint16_t>(r.next() % kVertices);
    uint16_t c = static_cast<uint16_t>(r.next() % kVertices);
    const uint32_t shape = r.next() % 32;
    if (shape == 0) b = a;                                         // repeated corner
    if (shape == 1) c = static_cast<uint16_t>(kVertices + shape);  // out of range (slow path)
    m.t[t] = {a, b, c};
    // Vertices 0 to 2 (the right triangle, when it is there) in each order: each vertex on top.
    constexpr std::array<uint16_t, 3> kCorners[6] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                                                     {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    if (shape >= 2 && shape < 8) m.t[t] = kCorners[shape - 2];
  }
}

// The lane `lane` on mesh m from the start to the end, as FrontEnd::lane_run_triangles() drives
// it: the list emptied at every stop, a slow triangle skipped.
template <class Lane>
void run_lane(const Mesh& m, Run& out, Lane&& lane, uint32_t strip_reciprocal, uint32_t first,
              uint32_t capacity) {
  for (uint32_t i = 0; i < kVertices; ++i) out.v[i] = m.v[i];
  for (BinnedTriangle& t : out.tris) t = BinnedTriangle{{0, 0, 0}, 0};
  for (uint16_t& b : out.buckets) b = kNoTriangle;
  out.lit_count = out.stop_count = 0;
  BinLane k{0,
            strip_reciprocal,
            out.buckets,
            out.tris,
            first * 0x10001u,
            out.v,
            sizeof(ScreenVertex),
            kHeight,
            kWidth,
            out.list,
            out.list + kList - 3,
            0,
            0,
            capacity,
            kVertices,
            m.t + kTriangles};
  const std::array<uint16_t, 3>* tp = m.t;
  const std::array<uint16_t, 3>* const end = m.t + kTriangles;
  // As FrontEnd::lane_run_triangles() runs the lane: up to the next index out of range (that
  // triangle skipped here), in runs that cannot fill the table, until it is full (and a lane
  // that stops short without progress ends at the room of the stops: a difference, not a hang).
  constexpr uint32_t kStops = sizeof(out.stops) / sizeof(out.stops[0]);
  while (tp != end && k.count < k.capacity && out.stop_count < kStops) {
    const std::array<uint16_t, 3>* const stop = first_out_of_range(tp, end, kVertices);
    if (tp == stop) {
      out.stops[out.stop_count++] = 3u << 16 | static_cast<uint32_t>(tp - m.t);
      ++tp;
      continue;
    }
    const auto room = static_cast<uint32_t>(k.capacity - k.count);
    k.end = static_cast<uint32_t>(stop - tp) > room ? tp + room : stop;
    const BinLaneStop why = lane(tp, k);
    for (ScreenVertex** e = out.list; e != k.list; ++e)
      out.lit[out.lit_count++] = static_cast<uint16_t>(*e - out.v);
    k.list = out.list;
    out.stops[out.stop_count++] =
        static_cast<uint32_t>(why) << 16 | static_cast<uint32_t>(tp - m.t);
  }
  out.count = k.count;
  out.zero = k.zero;
  out.offscreen = k.offscreen;
}

inline bool same(const Run& a, const Run& b) {
  if (a.count != b.count || a.zero != b.zero || a.offscreen != b.offscreen ||
      a.lit_count != b.lit_count || a.stop_count != b.stop_count)
    return false;
  for (uint32_t i = 0; i < a.count; ++i)
    for (uint32_t c = 0; c < 3; ++c)
      if (a.tris[i].v[c] != b.tris[i].v[c] || a.tris[i].next != b.tris[i].next) return false;
  for (uint32_t s = 0; s < kStrips; ++s)
    if (a.buckets[s] != b.buckets[s]) return false;
  for (uint32_t i = 0; i < a.lit_count; ++i)
    if (a.lit[i] != b.lit[i]) return false;
  for (uint32_t i = 0; i < a.stop_count; ++i)
    if (a.stops[i] != b.stops[i]) return false;
  for (uint32_t i = 0; i < kVertices; ++i)
    if (a.v[i].color_pending != b.v[i].color_pending) return false;
  return true;
}

// `meshes` random meshes through lanes p and q: strips of 8 rows (the viewport's 60 rows in 8
// strips), the draw's first store index and the table's room varying.
template <class P, class Q>
Tally run_cases(uint32_t meshes, Mesh& m, Run& a, Run& b, P&& p, Q&& q, uint32_t seed = 2024u) {
  Rng r{seed};
  Tally t;
  constexpr uint32_t kStripHeight = 8;
  constexpr uint32_t kReciprocal = ((1u << 17) + kStripHeight - 1) / kStripHeight;
  for (uint32_t i = 0; i < meshes; ++i) {
    make_mesh(r, m);
    const uint32_t first = r.next() % 1000;
    const uint32_t capacity = 10 + r.next() % (kCapacity - 9);  // [10, kCapacity]
    run_lane(m, a, p, kReciprocal, first, capacity);
    run_lane(m, b, q, kReciprocal, first, capacity);
    ++t.meshes;
    for (const std::array<uint16_t, 3>& tri : m.t) {
      if (tri[0] >= kVertices || tri[1] >= kVertices || tri[2] >= kVertices) continue;
      const ScreenVertex &v0 = m.v[tri[0]], &v1 = m.v[tri[1]], &v2 = m.v[tri[2]];
      const int64_t area =
          int64_t{v1.x - v0.x} * (v2.y - v0.y) - int64_t{v2.x - v0.x} * (v1.y - v0.y);
      if (area != 0 && (area & 0xFFFFFFFF) == 0) ++t.low_word_zero;
    }
    t.binned += a.count;
    t.zero += a.zero;
    t.offscreen += a.offscreen;
    t.lit += a.lit_count;
    t.stops += a.stop_count;
    if (!same(a, b)) ++t.differing;
    // The scan that ends the lane's runs, from every start, for a random n.
    const uint32_t n = 1 + r.next() % (kVertices + 8);
    for (uint32_t s = 0; s <= kTriangles; ++s) {
      const std::array<uint16_t, 3>* want = m.t + s;
      while (want != m.t + kTriangles && (*want)[0] < n && (*want)[1] < n && (*want)[2] < n) ++want;
      ++t.scans;
      if (first_out_of_range(m.t + s, m.t + kTriangles, n) != want) ++t.scans_differing;
    }
  }
  return t;
}

}  // namespace lr::fw::bins
