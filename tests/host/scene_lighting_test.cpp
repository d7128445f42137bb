// The simulator's scene conversion for per-pixel lighting: tangents in the core's format, the
// light list, and the one-line errors for what the options cannot describe.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "lineraster/host_sim/formats/image_io.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/support/tmp_dir.hpp"

namespace lr::host {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

SceneOptions small() {
  SceneOptions o;
  o.width = 64;
  o.height = 48;
  return o;
}

// A 16 x 16 PNG of one colour in the test's directory.
std::string png(const lr::test::TmpDir& dir, const std::string& name, int r, int g, int b) {
  ImageRgb8 img;
  img.width = img.height = 16;
  for (int p = 0; p < 16 * 16; ++p)
    img.rgb.insert(img.rgb.end(), {uint8_t(r), uint8_t(g), uint8_t(b)});
  std::string path = dir.file(name), err;
  EXPECT_TRUE(write_png(path, img, err)) << err;
  return path;
}

TEST(SceneTangents, ConvertedToQ14WithUnitHandedness) {
  Tangent16 t;
  ASSERT_TRUE(to_tangent16({1, 0, 0, 1}, t));
  EXPECT_EQ(t, (Tangent16{16384, 0, 0, 16384}));
  ASSERT_TRUE(to_tangent16({0, -1, 0, -1}, t));
  EXPECT_EQ(t, (Tangent16{0, -16384, 0, -16384}));
  ASSERT_TRUE(to_tangent16({0.6, 0, -0.8, 1}, t));
  EXPECT_EQ(t, (Tangent16{9830, 0, -13107, 16384}));  // round(0.6 * 16384) = 9830.4
  EXPECT_FALSE(to_tangent16({kNaN, 0, 0, 1}, t));
  EXPECT_FALSE(to_tangent16({1, 0, 0, kNaN}, t));
}

TEST(SceneTangents, FixedDrawsCarryTheMeshTangents) {
  const HostMesh grid = make_grid(3, 2);
  std::vector<FixedDraw> draws;
  std::string error;
  ASSERT_TRUE(build_fixed_draws(grid, small(), draws, error)) << error;
  ASSERT_EQ(draws.size(), 1u);
  ASSERT_EQ(draws[0].tangents.size(), draws[0].positions.size());
  for (const Tangent16& t : draws[0].tangents) EXPECT_EQ(t, (Tangent16{16384, 0, 0, 16384}));
  EXPECT_EQ(draws[0].mesh().tangents.size(), draws[0].positions.size());
  // The torus knot's mirrored tube: w = -1 everywhere, tangents unit within Q1.14 rounding.
  draws.clear();
  ASSERT_TRUE(build_fixed_draws(make_torus_knot(2, 3, 0.18, 60, 6), small(), draws, error));
  for (const Tangent16& t : draws[0].tangents) {
    EXPECT_EQ(t.w, -16384);
    const double len = std::sqrt(double(t.x) * t.x + double(t.y) * t.y + double(t.z) * t.z);
    EXPECT_NEAR(len, 16384.0, 1.5);
  }
  // No tangents in the mesh: none in the draw.
  HostMesh plain = grid;
  plain.tangents.clear();
  draws.clear();
  ASSERT_TRUE(build_fixed_draws(plain, small(), draws, error));
  EXPECT_TRUE(draws[0].tangents.empty());
  EXPECT_TRUE(draws[0].mesh().tangents.empty());
}

TEST(SceneTangents, BadTangentArraysAreErrors) {
  HostMesh m = make_grid(1, 1);
  m.tangents.pop_back();
  std::vector<FixedDraw> draws;
  std::string error;
  EXPECT_FALSE(build_fixed_draws(m, small(), draws, error));
  EXPECT_EQ(error, "mesh: 3 tangents for 4 vertices");
  m = make_grid(1, 1);
  m.tangents[2][1] = kNaN;
  error.clear();
  EXPECT_FALSE(build_fixed_draws(m, small(), draws, error));
  EXPECT_EQ(error, "mesh: tangent of vertex 2 is not finite");
}

TEST(SceneLights, LightListReplacesLightDirs) {
  const HostMesh sphere = make_uv_sphere(12, 24);
  SceneOptions a = small();
  RenderResult ra, rb;
  std::string error;
  ASSERT_TRUE(render_scene(sphere, a, ra, error)) << error;
  // The default light (1, 1, 1), white, given as a light list; light_dirs is then unused.
  SceneOptions b = small();
  b.light_dirs = {{kNaN, 0, 0}};
  b.lights = {LightOption{}};
  ASSERT_TRUE(render_scene(sphere, b, rb, error)) << error;
  EXPECT_EQ(ra.image.rgb, rb.image.rgb);
  // A coloured light colours the frame: blue only.
  b.lights[0].color = {0, 0, 1};
  ASSERT_TRUE(render_scene(sphere, b, rb, error)) << error;
  size_t blue = 0;
  for (size_t p = 0; p < rb.image.rgb.size() / 3; ++p) {
    EXPECT_EQ(rb.image.rgb[3 * p], 0);
    EXPECT_EQ(rb.image.rgb[3 * p + 1], 0);
    blue += rb.image.rgb[3 * p + 2] > 0;
  }
  EXPECT_GT(blue, 500u);
}

TEST(SceneLights, BadLightsAreOneLineErrors) {
  const HostMesh sphere = make_uv_sphere(6, 8);
  struct Case {
    std::vector<LightOption> lights;
    std::string expect;
  };
  LightOption dir, point;
  point.point = true;
  point.xyz = {0, 0, 3};
  auto with = [](LightOption l, auto f) {
    f(l);
    return l;
  };
  const Case cases[] = {
      {{dir, dir, dir, dir, dir}, "lights: at most 4"},
      {{with(dir,
             [](LightOption& l) {
               l.xyz = {0, 0, 0};
             })},
       "light: direction must be finite"},
      {{with(dir,
             [](LightOption& l) {
               l.xyz = {kNaN, 1, 1};
             })},
       "light: direction must be finite"},
      {{with(point,
             [](LightOption& l) {
               l.xyz = {40000, 0, 0};
             })},
       "light: point light position"},
      {{with(point,
             [](LightOption& l) {
               l.xyz = {0, kNaN, 0};
             })},
       "light: point light position"},
      {{with(point, [](LightOption& l) { l.constant = 0; })}, "light: attenuation coefficients"},
      {{with(point, [](LightOption& l) { l.constant = -1; })}, "light: attenuation coefficients"},
      {{with(point, [](LightOption& l) { l.linear = kNaN; })}, "light: attenuation coefficients"},
      {{with(point, [](LightOption& l) { l.quadratic = 1e6; })}, "light: attenuation coefficients"},
      // Below Q16.16's resolution: all three round to 0.
      {{with(point, [](LightOption& l) { l.constant = l.linear = l.quadratic = 1e-6; })},
       "light: attenuation coefficients"},
  };
  for (const Case& c : cases) {
    SceneOptions o = small();
    o.lights = c.lights;
    RenderResult r;
    std::string error;
    EXPECT_FALSE(render_scene(sphere, o, r, error)) << c.expect;
    EXPECT_EQ(error.find(c.expect), 0u) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

TEST(ScenePhong, OptionsTheCoreCannotUseAreOneLineErrors) {
  const lr::test::TmpDir dir("lr_scene_lighting_test");
  const std::string flat = png(dir, "flat.png", 128, 128, 255);
  const HostMesh sphere = make_uv_sphere(6, 8);
  HostMesh no_uvs = sphere;
  no_uvs.uvs.clear();
  no_uvs.tangents.clear();
  struct Case {
    const HostMesh* mesh;
    void (*set)(SceneOptions&, const std::string&);
    std::string expect;
  };
  const Case cases[] = {
      {&sphere, [](SceneOptions& o, const std::string& f) { o.envmap = f; },
       "an environment map needs Phong shading"},
      {&sphere, [](SceneOptions& o, const std::string& f) { o.normalmap = f; },
       "a normal map needs Phong shading"},
      {&no_uvs,
       [](SceneOptions& o, const std::string& f) {
         o.shading = Shading::kPhong;
         o.normalmap = f;
       },
       "flat.png: the mesh has no texture coordinates (vt) to map it with"},
      {&sphere,
       [](SceneOptions& o, const std::string&) {
         o.shading = Shading::kPhong;
         o.pixel_lighting = PixelLighting::kTable;
         o.table.size = 7;
       },
       "lighting table: size must be 8..256"},
      {&sphere,
       [](SceneOptions& o, const std::string&) {
         o.shading = Shading::kPhong;
         o.pixel_lighting = PixelLighting::kTable;
         o.table.size = 257;
       },
       "lighting table: size must be 8..256"},
      {&sphere,
       [](SceneOptions& o, const std::string&) {
         o.shading = Shading::kPhong;
         o.pixel_lighting = PixelLighting::kTable;
         o.lights = {LightOption{true, {0, 0, 3}}};
       },
       "lighting table: needs directional lights only and no local viewer"},
      {&sphere,
       [](SceneOptions& o, const std::string&) {
         o.shading = Shading::kPhong;
         o.pixel_lighting = PixelLighting::kTable;
         o.local_viewer = true;
       },
       "lighting table: needs directional lights only and no local viewer"},
      {&sphere,
       [](SceneOptions& o, const std::string& f) {
         o.shading = Shading::kPhong;
         o.envmap = f + ".absent.png";
       },
       "flat.png.absent.png"},
  };
  for (const Case& c : cases) {
    SceneOptions o = small();
    c.set(o, flat);
    RenderResult r;
    std::string error;
    EXPECT_FALSE(render_scene(*c.mesh, o, r, error)) << c.expect;
    EXPECT_NE(error.find(c.expect), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

// Phong frames through render_scene: every per-pixel option reaches a frame of the requested
// size with Gouraud's depth (how a pixel is lit does not move it). Colours are tests/core's.
TEST(ScenePhong, EveryPerPixelOptionRendersWithGouraudsDepth) {
  const lr::test::TmpDir dir("lr_scene_lighting_test");
  const std::string flat = png(dir, "flat.png", 128, 128, 255);
  const std::string env = png(dir, "env.png", 200, 180, 160);
  HostMesh sphere = make_uv_sphere(16, 32);
  HostMesh obj_like = sphere;  // as an OBJ loads: uvs, no tangents
  obj_like.tangents.clear();
  SceneOptions g = small();
  RenderResult ref;
  std::string error;
  ASSERT_TRUE(render_scene(sphere, g, ref, error)) << error;
  ASSERT_GT(ref.stats.pixels_written, 500u);
  void (*const variants[])(SceneOptions&, const std::string&, const std::string&) = {
      [](SceneOptions&, const std::string&, const std::string&) {},
      [](SceneOptions& o, const std::string&, const std::string&) {
        o.pixel_lighting = PixelLighting::kTable;
      },
      [](SceneOptions& o, const std::string&, const std::string&) {
        o.pixel_lighting = PixelLighting::kTable;
        o.table = {8, false};
      },
      [](SceneOptions& o, const std::string&, const std::string&) {
        o.lights = {LightOption{true, {0, 1, 2}, {1, 0.5, 0.2}, 1, 0.3, 0.1},
                    LightOption{false, {-1, 0, 1}, {0.2, 0.2, 1}}};
        o.local_viewer = true;
        o.two_sided = true;
        o.global_ambient = {0.2, 0.2, 0.2};
      },
      [](SceneOptions& o, const std::string&, const std::string& e) { o.envmap = e; },
      [](SceneOptions& o, const std::string& n, const std::string&) { o.normalmap = n; },
      [](SceneOptions& o, const std::string& n, const std::string& e) {
        o.normalmap = n;
        o.envmap = e;
        o.pixel_lighting = PixelLighting::kTable;
        o.texture_format = TexelFormat::kRgb888;
      },
  };
  for (size_t i = 0; i < std::size(variants); ++i) {
    for (const HostMesh* m : {&sphere, &obj_like}) {
      SceneOptions o = small();
      o.shading = Shading::kPhong;
      variants[i](o, flat, env);
      RenderResult r;
      error.clear();
      EXPECT_TRUE(render_scene(*m, o, r, error)) << "variant " << i << ": " << error;
      EXPECT_EQ(r.image.width, 64) << i;
      EXPECT_EQ(r.image.height, 48) << i;
      EXPECT_EQ(r.depth, ref.depth) << "variant " << i;
    }
  }
}

}  // namespace
}  // namespace lr::host
