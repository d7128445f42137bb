// Closed meshes through the whole pipeline (transform, projection, snapping): the core's
// coverage equals the exact reference evaluated on the core's own snapped vertices, and a
// convex closed mesh with back faces culled is covered exactly once inside its silhouette.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>

#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "tests/support/core_harness.hpp"

namespace lr {
namespace {

struct Result {
  size_t mismatches = 0, covered = 0, cracks = 0;
  int max_hits = 0;
  uint64_t ref_hits = 0;
  uint32_t written = 0;
};

// Every triangle gets its own three vertices (same positions as its neighbours', so the same
// snapped coordinates) coloured with its id; flat unlit shading, no depth test.
Result run(const host::HostMesh& m, Vec3 eye, int w, int h) {
  std::vector<Vec3> pos;
  std::vector<Rgb8> col;
  std::vector<std::array<uint16_t, 3>> tri;
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const auto& p = m.positions[m.triangles[t][size_t(k)]];
      pos.push_back({Fixed::from_raw(int32_t(std::lround(p[0] * 65536))),
                     Fixed::from_raw(int32_t(std::lround(p[1] * 65536))),
                     Fixed::from_raw(int32_t(std::lround(p[2] * 65536)))});
      col.push_back(to_rgb8(test::id_color(uint32_t(t))));
    }
    auto b = uint16_t(3 * t);
    tri.push_back({b, uint16_t(b + 1), uint16_t(b + 2)});
  }
  Camera cam;
  cam.eye = eye;
  EXPECT_TRUE(perspective(Fixed::from_int(50), Fixed::ratio(w, h), Fixed::from_double(0.1),
                          Fixed::from_int(50), cam.projection));
  EXPECT_TRUE(look_at(eye, {}, {Fixed{}, Fixed::from_int(1), Fixed{}}, cam.view));
  test::CoreHarness<8> core(w, h);
  core.begin({0, 0, 0}, cam);
  DrawState st = test::coverage_state();
  st.cull = Cull::kBack;
  EXPECT_EQ(core.renderer().draw(Mesh{pos, {}, col, {}, tri}, Mat4::identity(), Material{}, st),
            Status::kOk);
  host::ImageRgb8 img = core.render();

  // The reference on exactly the vertices the core snapped, in the order it binned them.
  std::vector<ref::ScreenTri> tris;
  std::vector<int32_t> id_of_binned;
  auto sv = core.renderer().screen_vertices();
  const auto colors = core.renderer().triangle_colors();
  size_t ids_seen = 0;
  for (const BinnedTriangle& bt : core.renderer().binned_triangles()) {
    ref::ScreenTri s{};
    for (int k = 0; k < 3; ++k) {
      s.x[k] = sv[bt.v[k]].x;
      s.y[k] = sv[bt.v[k]].y;
    }
    tris.push_back(s);
    const Rgb8 c = colors[ids_seen++].primary;  // flat: the provoking vertex's colour
    id_of_binned.push_back(int32_t(c.r | (c.g << 8) | (c.b << 16)) - 1);
  }
  std::vector<int32_t> hits, owner;
  ref::coverage(tris, w, h, kSubpixelBits, hits, owner);
  Result r;
  r.written = core.renderer().stats().pixels_written;
  for (size_t p = 0; p < hits.size(); ++p) {
    int32_t expect = owner[p] < 0 ? -1 : id_of_binned[size_t(owner[p])];
    r.mismatches += test::id_of(img, p) != expect;
    r.covered += hits[p] > 0;
    r.ref_hits += uint64_t(hits[p]);
    r.max_hits = std::max(r.max_hits, hits[p]);
  }
  // A crack: an uncovered pixel whose four neighbours are all covered.
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      auto at = [&](int xx, int yy) { return hits[size_t(yy) * size_t(w) + size_t(xx)] > 0; };
      r.cracks += !at(x, y) && at(x - 1, y) && at(x + 1, y) && at(x, y - 1) && at(x, y + 1);
    }
  return r;
}

TEST(Watertight, ConvexClosedMeshIsCoveredExactlyOnce) {
  host::HostMesh sphere = host::make_uv_sphere(24, 36);
  Result r =
      run(sphere, {Fixed::from_double(0.4), Fixed::from_double(0.9), Fixed::from_double(2.6)}, 200,
          160);
  EXPECT_EQ(r.mismatches, 0u);
  EXPECT_EQ(r.max_hits, 1);
  EXPECT_EQ(r.cracks, 0u);
  EXPECT_EQ(r.written, r.covered);
  EXPECT_GT(r.covered, 8000u);
}

TEST(Watertight, SelfOverlappingClosedMeshMatchesTheReferenceHitForHit) {
  host::HostMesh knot = host::make_torus_knot(2, 3, 0.25, 180, 12);
  Result r = run(knot, {Fixed::from_double(0.2), Fixed::from_double(0.3), Fixed::from_double(3.2)},
                 240, 180);
  EXPECT_EQ(r.mismatches, 0u);
  EXPECT_EQ(r.written, r.ref_hits);  // overlapping front faces: several hits, the same ones
  EXPECT_GE(r.max_hits, 2);
  EXPECT_GT(r.covered, 5000u);
}

// Binning stores each triangle top first (store_top_first): the rotation of its submitted order
// that starts at its topmost vertex, of a tie the earliest (where kBinnedSorted, a Gouraud draw's
// with the other two in y order: store_sorted). Through the front end's C lane
// (Gouraud, one-sided, nothing cut), its per-triangle path (flat colours; both facings drawn)
// and the fans of triangles cut by the near plane (new vertices: topmost first).
TEST(Watertight, BinnedTrianglesComeTopFirstAsRotations) {
  const host::HostMesh sphere = host::make_uv_sphere(24, 36);
  const auto fx = [](double v) { return Fixed::from_raw(int32_t(std::lround(v * 65536))); };
  std::vector<Vec3> pos;
  std::vector<Rgb8> col;
  std::vector<std::array<uint16_t, 3>> tri;
  for (size_t t = 0; t < sphere.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const auto& p = sphere.positions[sphere.triangles[t][size_t(k)]];
      pos.push_back({fx(p[0]), fx(p[1]), fx(p[2])});
      col.push_back(to_rgb8(test::id_color(uint32_t(t))));
    }
    const auto b = uint16_t(3 * t);
    tri.push_back({b, uint16_t(b + 1), uint16_t(b + 2)});
  }
  uint32_t rotations = 0, ties = 0, fanned = 0;
  for (const double distance : {2.6, 1.08})
    for (const bool flat : {false, true}) {
      // Level with the equator: its corners on one row (ties of every kind).
      const Vec3 eye{fx(0.3 * distance), Fixed{}, fx(0.95 * distance)};
      Camera cam;
      cam.eye = eye;
      ASSERT_TRUE(perspective(Fixed::from_int(60), Fixed::ratio(160, 120), Fixed::from_double(0.1),
                              Fixed::from_int(50), cam.projection));
      // Far: at the centre. Near: along the surface, which crosses the near plane on screen.
      const Vec3 target = distance > 2 ? Vec3{} : Vec3{fx(1.5), Fixed{}, fx(0.6)};
      ASSERT_TRUE(look_at(eye, target, {Fixed{}, Fixed::from_int(1), Fixed{}}, cam.view));
      test::CoreHarness<8> core(160, 120);
      core.begin({0, 0, 0}, cam);
      DrawState st = test::coverage_state();
      st.shading = flat ? Shading::kFlat : Shading::kGouraud;
      st.cull = flat ? Cull::kNone : Cull::kBack;
      ASSERT_EQ(core.renderer().draw(Mesh{pos, {}, col, {}, tri}, Mat4::identity(), Material{}, st),
                Status::kOk);
      core.render();
      const auto sv = core.renderer().screen_vertices();
      for (const BinnedTriangle& bt : core.renderer().binned_triangles()) {
        const int32_t top = sv[bt.v[0]].y;
        EXPECT_LE(top, sv[bt.v[1]].y);
        EXPECT_LE(top, sv[bt.v[2]].y);
        const uint32_t base = bt.v[0] - bt.v[0] % 3u, first = bt.v[0] - base;
        if (size_t{bt.v[0]} >= pos.size() || bt.v[1] - base >= 3u || bt.v[2] - base >= 3u) {
          ++fanned;  // a piece of a cut triangle
          continue;
        }
        // The rotation; where kBinnedSorted, a Gouraud draw's (sorts_for_lanes) with its last
        // two in y order (store_sorted: swapped only when strictly out of order).
        uint32_t v1 = base + (first + 1) % 3, v2 = base + (first + 2) % 3;
        if (kBinnedSorted && !flat && sv[v2].y < sv[v1].y) std::swap(v1, v2);
        EXPECT_EQ(bt.v[1], v1);
        EXPECT_EQ(bt.v[2], v2);
        for (uint32_t k = 0; k < first; ++k) EXPECT_GT(sv[base + k].y, top);  // the earliest
        ++rotations;
        ties += sv[bt.v[1]].y == top || sv[bt.v[2]].y == top;
      }
    }
  EXPECT_GT(rotations, 1000u);
  EXPECT_GT(ties, 20u);  // the equator's corners
  EXPECT_GT(fanned, 0u);
  std::printf("[ top first ] %u rotations (%u with a level corner at the top), %u fanned pieces\n",
              rotations, ties, fanned);
}

}  // namespace
}  // namespace lr
