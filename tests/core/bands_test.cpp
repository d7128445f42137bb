// Frames larger than the stores (docs/bands.md): binned and drawn band by band, they must be the
// frame of one pass, pixel for pixel and depth for depth, for any store capacities from the
// documented minimum upward; below it render() says kCapacity and the drop is counted.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/support/core_harness.hpp"
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
// order decides overlaps), two-sided back faces (their own vertex copies), textures (the
// TexVertex store), strips of 1 and 32.
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
    Case c{"ground_clipped", ground_grid(24), test::ground_view()};
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
    Case c{"sphere_two_sided_flat", host::make_uv_sphere(20, 28), test::sphere_four_lights()};
    c.options.width = 100;
    c.options.height = 100;
    c.options.two_sided = true;
    c.options.shading = Shading::kFlat;
    c.options.eye = {0.1, 0.2, 0.8};  // inside: back faces, and the near plane cuts
    c.options.strip_height = 32;
    out.push_back(c);
  }
  {
    // Textured, lit and modulated (texture coordinates and secondary colours in the TexVertex
    // store, compacted and cached with the vertices), two-sided Gouraud seen from inside (back
    // faces get their own vertex and texture copies) and cut by the near plane.
    static const host::HostTexture tex = [] {
      host::HostTexture t;
      std::string err;
      EXPECT_TRUE(host::texture_from_image(test::checker64(), TexelFormat::kRgb565, false, t, err))
          << err;
      return t;
    }();
    Case c{"sphere_textured_two_sided", host::make_uv_sphere(14, 20), test::sphere_four_lights()};
    c.options.width = 112;
    c.options.height = 84;
    c.options.two_sided = true;
    c.options.texture_object = &tex.texture;
    c.options.filter = Filter::kNearest;
    c.options.material.specular = {0.6, 0.6, 0.6};
    c.options.material.shininess = 24;
    c.options.eye = {0.15, 0.25, 0.7};
    c.options.strip_height = 2;
    out.push_back(c);
  }
  {
    // The same texture from outside, the near plane cutting the sphere: front faces, whose
    // texture entries are copied out of the vertex cache with their vertices.
    Case c{"sphere_textured_front", host::make_uv_sphere(18, 26), test::sphere_four_lights()};
    c.options.width = 120;
    c.options.height = 90;
    c.options.texture_object = out.back().options.texture_object;
    c.options.filter = Filter::kBilinear;
    c.options.eye = {0.3, 0.4, 1.25};
    c.options.near = 0.45;  // cuts the sphere in front of the eye
    c.options.strip_height = 4;
    out.push_back(c);
  }
  {
    // Rows of 64 vertices: a cell's corners in one row and the next are 64 indices apart, the
    // vertex cache's slot count (corners sharing a slot take the spares).
    host::HostMesh grid = host::make_grid(63, 6);
    for (const auto& p : grid.positions) grid.colors.push_back({(p[0] + 1) / 2, (p[1] + 1) / 2, 1});
    Case c{"grid_rows_of_64", grid, {}};
    c.options.width = 128;
    c.options.height = 64;
    c.options.unlit = true;
    c.options.eye = {0, 0, 1.8};
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
    // The minimum: the vertex cache and what the fullest strip's triangles refer to; the
    // triangles that touch the fullest strip (below it, the frame must say so).
    const size_t min_vertices = 96;
    int banded = 0;
    for (int trial = 0; trial < 30; ++trial) {
      host::SceneOptions::Stores st;
      st.triangles = 1 + rng() % s1.triangles_binned;
      st.vertices = min_vertices + rng() % (2 * c.mesh.positions.size());
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

// A vertex store smaller than the mesh: the mesh goes through the vertex cache, and the frame
// is the one-pass frame. The smallest stores hold less than the fullest strip refers to: they
// must say so.
TEST(Bands, MeshesLargerThanTheVertexStoreGoThroughTheCache) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const host::RenderResult one = render(c, {});
    const size_t n = c.mesh.positions.size();
    for (size_t vertices : {size_t{96}, size_t{200}, size_t{400}, size_t{800}, n - 1}) {
      if (vertices >= n) continue;
      const host::RenderResult got = render(c, {.vertices = vertices});
      // Below the minimum: reported. One vertex short of the mesh is far above it.
      if (vertices < n - 1 && dropped(got.stats) != 0) continue;
      ASSERT_EQ(dropped(got.stats), 0u) << vertices;
      EXPECT_EQ(got.image.rgb, one.image.rgb) << vertices;
      EXPECT_EQ(got.depth, one.depth) << vertices;
      EXPECT_EQ(got.stats.triangles_binned, one.stats.triangles_binned);
      EXPECT_GT(got.stats.vertices_transformed, one.stats.vertices_transformed / 2);
    }
  }
}

// Triangles whose three corners fall into one set of the vertex cache (mesh indices k, k + 32,
// k + 64; FrontEnd::cache_corners): the third corner takes its spare. The mesh is given to the
// core as it is (the host tools number vertices by first use, which never does this).
TEST(Bands, ThreeCornersInOneCacheSetTakeTheSpare) {
  std::vector<Vec3> pos(160);  // 64 unused: the mesh is larger than the store
  std::vector<Rgb8> col(160);
  std::vector<std::array<uint16_t, 3>> tri;
  const auto fx = [](double v) { return Fixed::from_raw(static_cast<int32_t>(v * 65536)); };
  for (uint16_t k = 0; k < 32; ++k) {
    const double x = -0.95 + 0.24 * (k % 8), y = -0.95 + 0.48 * (k / 8);
    pos[k] = {fx(x), fx(y), fx(0.5)};
    pos[k + 32u] = {fx(x + 0.2), fx(y), fx(0.5)};
    pos[k + 64u] = {fx(x), fx(y + 0.4), fx(0.5)};
    for (int m = 0; m < 3; ++m)
      col[k + 32u * static_cast<unsigned>(m)] = {static_cast<uint8_t>(8 * k),
                                                 static_cast<uint8_t>(80 * m), 200};
    tri.push_back({k, static_cast<uint16_t>(k + 32), static_cast<uint16_t>(k + 64)});
  }
  const Mesh mesh{pos, {}, col, {}, tri};
  DrawState st;
  st.lighting = false;
  auto frame = [&](size_t vertices, FrameStats& stats) {
    test::CoreHarness<8> h(64, 64, vertices);
    h.begin();
    EXPECT_EQ(h.renderer().draw(mesh, Mat4::identity(), Material{}, st), Status::kOk);
    const host::ImageRgb8 img = h.render();
    stats = h.renderer().stats();
    return img;
  };
  FrameStats one{}, cached{};
  const host::ImageRgb8 want = frame(0xFFFF, one);
  const host::ImageRgb8 got = frame(110, cached);
  EXPECT_EQ(one.triangles_binned, 32u);
  EXPECT_EQ(dropped(cached), 0u);
  EXPECT_EQ(cached.triangles_binned, 32u);
  EXPECT_EQ(cached.vertices_transformed, 96u * cached.bands);  // no corner missed twice
  EXPECT_EQ(got.rgb, want.rgb);
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
