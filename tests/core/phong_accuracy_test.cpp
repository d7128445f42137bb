// Per-pixel lighting against the double-precision reference renderer: Phong (exact and table),
// point lights with attenuation, the local viewer, two-sided lighting, textures, the sphere
// environment map and the tangent-space normal map. Bounds are in 8-bit levels over the pixels
// both renderers cover.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "lineraster/host_sim/formats/image_io.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "tests/support/scene_compare.hpp"
#include "tests/support/scenes.hpp"
#include "tests/support/tmp_dir.hpp"

namespace lr {
namespace {

host::HostMesh torus_knot() {
  return host::make_torus_knot(2, 3, 0.12, 200, 10);
}
// Its tube fitted to radius 1 at distance 3 covers under a tenth of the 320 x 240 frame; the
// bound sits just below.
constexpr size_t kKnotPixels = 7000;

host::SceneOptions phong(host::SceneOptions o) {
  o.shading = Shading::kPhong;
  return o;
}

host::SceneOptions sphere_scene() {
  return test::phong_sphere();
}

test::Comparison compare(const host::HostMesh& mesh, const host::SceneOptions& o,
                         const char* what) {
  test::Comparison c;
  std::string err;
  EXPECT_TRUE(test::compare_scene(mesh, o, c, err)) << err;
  std::printf("%s: %s\n", what, c.summary().c_str());
  return c;
}

// The exact per-pixel method evaluates the same lighting model as the reference per pixel: its
// error is the fixed-point arithmetic (Q1.30 normals renormalised with the 8-bit inverse-square-
// root table, the specular power table) plus the snapping of vertices.
TEST(PhongAccuracy, ExactSphereWithTwoLightsWithinTwoLevels) {
  test::Comparison c = compare(host::make_uv_sphere(40, 60), sphere_scene(), "phong exact sphere");
  EXPECT_GT(c.both, test::kUnitSpherePixels);
  EXPECT_GE(c.fraction_within1(), 0.999);
  EXPECT_LE(c.max_error, 2);
}

TEST(PhongAccuracy, ExactTorusKnotWithinTwoLevels) {
  test::Comparison c = compare(torus_knot(), phong(test::gold_options()), "phong exact knot");
  EXPECT_GT(c.both, kKnotPixels);
  EXPECT_GE(c.fraction_within1(), 0.999);
  EXPECT_LE(c.max_error, 2);
}

TEST(PhongAccuracy, PointLightsWithAttenuationAndTheLocalViewer) {
  host::SceneOptions o = sphere_scene();
  o.lights = {{true, {1.5, 1.0, 1.5}, {1, 0.9, 0.7}, 1.0, 0.2, 0.1},
              {true, {-1.5, 0.5, 1.0}, {0.3, 0.4, 1.0}, 0.5, 0.0, 0.4},
              {false, {0, -1, 0.3}, {0.2, 0.2, 0.2}, 1, 0, 0}};
  o.local_viewer = true;
  test::Comparison c = compare(host::make_uv_sphere(40, 60), o, "phong exact point lights");
  EXPECT_GT(c.both, test::kUnitSpherePixels);
  EXPECT_GE(c.fraction_within1(), 0.999);
  EXPECT_LE(c.max_error, 2);
  // Gouraud with the same lights: per-vertex point lighting, compared with its own reference.
  o.shading = Shading::kGouraud;
  test::Comparison g = compare(host::make_uv_sphere(40, 60), o, "gouraud point lights");
  EXPECT_GT(g.both, test::kUnitSpherePixels);
  EXPECT_GE(g.fraction_within1(), 0.999);
  EXPECT_LE(g.max_error, 2);
}

TEST(PhongAccuracy, TableOf64BilinearStaysCloseToTheReference) {
  host::SceneOptions o = sphere_scene();
  o.pixel_lighting = PixelLighting::kTable;
  o.table = {64, true};
  test::Comparison c = compare(host::make_uv_sphere(40, 60), o, "phong table 64 bilinear");
  EXPECT_GT(c.both, test::kUnitSpherePixels);
  EXPECT_GE(c.psnr, 40.0);
  EXPECT_LE(c.max_error, 12);
}

TEST(PhongAccuracy, TwoSidedLightingOfAnOpenSurfaceSeenFromBothSides) {
  // A grid tilted about y, seen from behind: the back face shows, lit with the negated normal.
  host::HostMesh grid = host::make_grid(8, 8);
  for (Shading s : {Shading::kFlat, Shading::kGouraud, Shading::kPhong}) {
    host::SceneOptions o;
    o.shading = s;
    o.two_sided = true;
    o.model_rotate_y = 150;
    o.material.specular = {0.6, 0.6, 0.6};
    o.material.shininess = 40;
    o.lights = {{false, {0.3, 0.4, 1.0}, {1, 1, 1}, 1, 0, 0}};
    test::Comparison c = compare(grid, o, "two-sided, back face");
    // The 2 x 2 square turned by 150 degrees, 3 units away: 1.7 x 2 units at 69 pixels per
    // unit (120 / tan(30) / 3), more on its near side.
    EXPECT_GT(c.both, 16000u);
    EXPECT_GE(c.fraction_within1(), 0.999);
    EXPECT_LE(c.max_error, s == Shading::kFlat ? 85 : 2);  // flat: an edge pixel may differ
    // The back face is really lit from the negated normal: brighter than one-sided lighting.
    host::SceneOptions one = o;
    one.two_sided = false;
    test::Comparison d = compare(grid, one, "one-sided, back face");
    EXPECT_GT(d.both, 16000u);
    EXPECT_GT(c.core.image.rgb[3 * (120 * 320 + 160)],
              d.core.image.rgb[3 * (120 * 320 + 160)] + 40);
  }
}

TEST(PhongAccuracy, TexturedPhongModulatesAndAddsSpecular) {
  host::HostMesh mesh = host::make_uv_sphere(24, 32);
  host::SceneOptions o = sphere_scene();
  host::HostTexture tex;
  std::string err;
  ASSERT_TRUE(host::texture_from_image(test::checker64(), TexelFormat::kRgb888, true, tex, err))
      << err;
  o.texture_object = &tex.texture;
  o.filter = Filter::kBilinear;
  o.mipmap = MipMode::kLinear;
  test::Comparison c = compare(mesh, o, "phong textured, bilinear, mip linear");
  EXPECT_GT(c.both, test::kUnitSpherePixels);
  // The texture is sampled as for Gouraud (texel choices at the checker's edges differ where
  // the level of detail is taken per chunk): Phong adds no error of its own to it.
  o.shading = Shading::kGouraud;
  test::Comparison g = compare(mesh, o, "gouraud textured, bilinear, mip linear");
  EXPECT_GT(g.both, test::kUnitSpherePixels);
  EXPECT_GE(c.psnr, g.psnr - 0.5);
  EXPECT_LE(c.mean_error, g.mean_error + 0.05);
  EXPECT_GE(c.fraction_within1(), 0.97);
}

// A radial pattern for the sphere map and bumps for the normal map, written as PNG files.
host::ImageRgb8 sphere_map_image() {
  host::ImageRgb8 img;
  img.width = img.height = 64;
  img.rgb.resize(64 * 64 * 3);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      double dx = (x + 0.5) / 32 - 1, dy = (y + 0.5) / 32 - 1;
      double r = std::sqrt(dx * dx + dy * dy);
      uint8_t* p = &img.rgb[3 * (size_t(y) * 64 + size_t(x))];
      p[0] = static_cast<uint8_t>(std::lround(127.5 + 127.5 * std::cos(6 * r)));
      p[1] = static_cast<uint8_t>(std::lround(255 * std::min(1.0, r)));
      p[2] = static_cast<uint8_t>(std::lround(127.5 + 127.5 * dx));
    }
  return img;
}
host::ImageRgb8 bump_image() {
  host::ImageRgb8 img;
  img.width = img.height = 32;
  img.rgb.resize(32 * 32 * 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      double a = 2 * M_PI * (x + 0.5) / 8, b = 2 * M_PI * (y + 0.5) / 8;
      double nx = 0.4 * std::cos(a), ny = 0.4 * std::cos(b), nz = 1;
      double l = std::sqrt(nx * nx + ny * ny + nz * nz);
      uint8_t* p = &img.rgb[3 * (size_t(y) * 32 + size_t(x))];
      p[0] = static_cast<uint8_t>(std::lround((nx / l + 1) * 127.5));
      p[1] = static_cast<uint8_t>(std::lround((ny / l + 1) * 127.5));
      p[2] = static_cast<uint8_t>(std::lround((nz / l + 1) * 127.5));
    }
  return img;
}

TEST(PhongAccuracy, SphereEnvironmentMap) {
  test::TmpDir dir("lr_envmap");
  std::string err;
  ASSERT_TRUE(host::write_png(dir.file("env.png"), sphere_map_image(), err)) << err;
  host::SceneOptions o = phong(test::gold_options());
  o.envmap = dir.file("env.png");
  o.texture_format = TexelFormat::kRgb888;
  for (PixelLighting m : {PixelLighting::kExact, PixelLighting::kTable}) {
    o.pixel_lighting = m;
    o.table = {128, true};
    test::Comparison c = compare(torus_knot(), o, "phong environment map");
    EXPECT_GT(c.both, kKnotPixels);
    EXPECT_GE(c.fraction_within1(), m == PixelLighting::kExact ? 0.99 : 0.9);
    EXPECT_LE(c.max_error, m == PixelLighting::kExact ? 8 : 16);
  }
}

TEST(PhongAccuracy, TangentSpaceNormalMap) {
  test::TmpDir dir("lr_normalmap");
  std::string err;
  ASSERT_TRUE(host::write_png(dir.file("bumps.png"), bump_image(), err)) << err;
  host::SceneOptions o = sphere_scene();
  o.normalmap = dir.file("bumps.png");
  o.filter = Filter::kBilinear;
  for (PixelLighting m : {PixelLighting::kExact, PixelLighting::kTable}) {
    o.pixel_lighting = m;
    o.table = {128, true};
    test::Comparison c = compare(host::make_uv_sphere(24, 32), o, "phong normal map");
    // The map's texels are blended bilinearly in 8 bits: a normal moves by up to 1/255 per
    // component, which the highlight (shininess 64) turns into a few levels.
    EXPECT_GT(c.both, test::kUnitSpherePixels);
    EXPECT_GE(c.fraction_within1(), 0.95);
    EXPECT_LE(c.max_error, m == PixelLighting::kExact ? 4 : 8);
    // The bumps show: far from plain Phong.
    host::SceneOptions plain = o;
    plain.normalmap.clear();
    test::Comparison p = compare(host::make_uv_sphere(24, 32), plain, "phong without the map");
    EXPECT_GT(p.both, test::kUnitSpherePixels);
    int differ = 0;
    for (size_t i = 0; i < p.core.image.rgb.size(); ++i)
      differ += std::abs(p.core.image.rgb[i] - c.core.image.rgb[i]) > 8;
    EXPECT_GT(differ, 5000);
  }
}

}  // namespace
}  // namespace lr
