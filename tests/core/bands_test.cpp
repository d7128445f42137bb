// Frames larger than the stores (docs/bands.md): binned and drawn band by band, they must be the
// frame of one pass, pixel for pixel and depth for depth, for any store capacities from the
// documented minimum upward; below it render() says kCapacity and the drop is counted.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "host_sim/formats/texture_load.hpp"
#include "host_sim/scene/mesh_prep.hpp"
#include "host_sim/scene/scene.hpp"
#include "tests/support/scenes.hpp"

namespace lr {
namespace {

// The coloured ground of test::coloured_ground (y = 0, 12 x 12 units) as a grid of n x n cells:
// triangles from the horizon to the near plane, many cut by it.
host::HostMesh ground_grid(int n) {
  host::HostMesh m = host::make_grid(n, n);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const auto p = m.positions[i];
    m.positions[i] = {6 * p[0], 0, -6 * p[1]};
    m.normals[i] = {0, 1, 0};
    m.colors.push_back({(p[0] + 1) / 2, (p[1] + 1) / 2, 0.5});
  }
  return m;
}

struct Case {
  std::string name;
  host::HostMesh mesh;
  host::SceneOptions options;
};

// Scenes that stress what bands change: many small triangles (the knot), per-pixel lighting
// (its surface store is compacted with the vertices), near-plane clipping (vertices made in
// each band), triangles spanning every strip (the ground), no depth test (only the submission
// order decides overlaps), two-sided back faces (their own vertex copies), strips of 1 and 32.
std::vector<Case> cases() {
  std::vector<Case> out;
  {
    Case c{"knot_gouraud", host::make_torus_knot(2, 3, 0.15, 96, 10), {}};
    c.options.width = 160;
    c.options.height = 120;
    c.options.fit = true;
    c.options.cull = Cull::kBack;
    c.options.eye = {0.3, 0.4, 2.6};
    out.push_back(c);
  }
  {
    Case c{"sphere_phong", host::make_uv_sphere(16, 24), test::phong_sphere()};
    c.options.width = 128;
    c.options.height = 96;
    c.options.strip_height = 4;
    out.push_back(c);
  }
  {
    Case c{"ground_clipped", ground_grid(10), test::ground_view()};
    c.options.width = 96;
    c.options.height = 80;
    c.options.strip_height = 1;
    out.push_back(c);
  }
  {
    Case c{"torus_no_depth", host::make_torus(1.0, 0.4, 24, 12), {}};
    c.options.width = 120;
    c.options.height = 90;
    c.options.depth_test = false;
    c.options.unlit = true;
    c.options.eye = {0.2, 2.0, 2.4};
    out.push_back(c);
  }
  {
    Case c{"sphere_two_sided_flat", host::make_uv_sphere(10, 14), test::sphere_four_lights()};
    c.options.width = 100;
    c.options.height = 100;
    c.options.two_sided = true;
    c.options.shading = Shading::kFlat;
    c.options.eye = {0.1, 0.2, 0.8};  // inside: back faces, and the near plane cuts
    c.options.strip_height = 32;
    out.push_back(c);
  }
  return out;
}

host::RenderResult render(const Case& c, const host::SceneOptions::Stores& stores) {
  host::SceneOptions o = c.options;
  o.stores = stores;
  host::RenderResult r;
  std::string err;
  EXPECT_TRUE(host::render_scene(c.mesh, o, r, err)) << c.name << ": " << err;
  return r;
}

size_t dropped(const FrameStats& s) {
  return s.dropped_triangle_capacity + s.dropped_vertex_capacity;
}

TEST(Bands, AnyStoreCapacitiesFromTheMinimumGiveTheOnePassFrame) {
  std::mt19937 rng(20261203);
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const host::RenderResult one = render(c, {});
    const FrameStats& s1 = one.stats;
    ASSERT_EQ(s1.bands, 1u);
    ASSERT_EQ(dropped(s1), 0u);
    ASSERT_GT(s1.triangles_binned, 20u);
    // The minimum: the mesh's vertices and the pieces clipping makes; the triangles that touch
    // the fullest strip (below it, the frame must say so).
    const size_t min_vertices = c.mesh.positions.size() + 3 * s1.clipped * 10;
    int banded = 0;
    for (int trial = 0; trial < 30; ++trial) {
      host::SceneOptions::Stores st;
      st.triangles = 1 + rng() % s1.triangles_binned;
      st.vertices = min_vertices + rng() % (c.mesh.positions.size() + 1);
      st.active = 1 + rng() % (s1.max_active + 1);
      const host::RenderResult got = render(c, st);
      const FrameStats& s = got.stats;
      SCOPED_TRACE("stores " + std::to_string(st.vertices) + "/" + std::to_string(st.triangles) +
                   "/" + std::to_string(st.active));
      if (dropped(s) != 0) {
        // Below the minimum: reported, never silent.
        EXPECT_GT(s.bands, 1u);
        continue;
      }
      if (s.bands > 1) ++banded;
      EXPECT_EQ(got.image.rgb, one.image.rgb);
      EXPECT_EQ(got.depth, one.depth);
      EXPECT_EQ(s.triangles_binned, s1.triangles_binned);
      EXPECT_EQ(s.binned_inputs, s1.binned_inputs);
      EXPECT_EQ(s.culled_backface, s1.culled_backface);
      EXPECT_EQ(s.clipped, s1.clipped);
      EXPECT_EQ(s.pixels_written, s1.pixels_written);
      EXPECT_EQ(s.bands > 1, st.triangles < s1.triangles_binned) << s.bands;
    }
    EXPECT_GT(banded, 3);
  }
}

// The cost of bands in the statistics: every band transforms every vertex again.
TEST(Bands, EachBandTransformsTheVerticesAgain) {
  const Case c = cases()[0];
  const host::RenderResult one = render(c, {});
  const host::RenderResult banded = render(c, {.triangles = one.stats.triangles_binned / 3});
  ASSERT_EQ(dropped(banded.stats), 0u);
  EXPECT_EQ(banded.image.rgb, one.image.rgb);
  EXPECT_GE(banded.stats.bands, 3u);
  EXPECT_EQ(banded.stats.vertices_transformed, banded.stats.bands * one.stats.vertices_transformed);
}

}  // namespace
}  // namespace lr
