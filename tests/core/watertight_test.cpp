// Closed meshes through the whole pipeline (transform, projection, snapping): the core's
// coverage equals the exact reference evaluated on the core's own snapped vertices, and a
// convex closed mesh with back faces culled is covered exactly once inside its silhouette.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace lr
