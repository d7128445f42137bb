// Bit-identical frames on every platform: fixed scenes rendered through
// host::render_scene, each frame's bytes (8-bit RGB, then the 16-bit depth buffer as
// little-endian bytes) hashed with 64-bit FNV-1a and compared with constants computed on x86-64.
// The same test built for 32-bit ARM Linux runs under qemu-arm (the armhf preset,
// scripts/ci_armhf.sh): passing there proves the ARM frames equal the x86-64 ones byte for byte.
//
// A deliberate change of the core's output changes these hashes: check the new frames first
// (golden and accuracy tests), then take the new values from this test's output ("frame hash
// <scene>: rgb 0x... depth 0x...") computed on x86-64.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "lineraster/core/math/hash.hpp"
#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/support/scene_compare.hpp"
#include "tests/support/scenes.hpp"

namespace lr {
namespace {

struct FrameHash {
  uint64_t rgb = 0, depth = 0;
};

FrameHash hash_frame(const host::RenderResult& r) {
  Fnv1a64 rgb, depth;
  for (uint8_t b : r.image.rgb) rgb.add(b);
  for (uint16_t d : r.depth) {  // little-endian whatever the target's byte order
    depth.add(static_cast<uint8_t>(d & 0xFF));
    depth.add(static_cast<uint8_t>(d >> 8));
  }
  return {rgb.value, depth.value};
}

// Renders, checks that the frame shows something, prints and compares its hashes.
void expect_hashes(const char* scene, const host::HostMesh& mesh, const host::SceneOptions& o,
                   uint64_t rgb, uint64_t depth) {
  host::RenderResult r;
  std::string err;
  ASSERT_TRUE(host::render_scene(mesh, o, r, err)) << scene << ": " << err;
  ASSERT_EQ(r.image.rgb.size(), size_t(o.width) * size_t(o.height) * 3) << scene;
  ASSERT_EQ(r.depth.size(), size_t(o.width) * size_t(o.height)) << scene;
  // A blank frame would hash the same everywhere too: require a real picture.
  EXPECT_GT(r.stats.pixels_written, uint64_t(o.width) * uint64_t(o.height) / 20) << scene;
  const FrameHash h = hash_frame(r);
  std::printf("frame hash %s: rgb 0x%016llx depth 0x%016llx (%llu pixels written)\n", scene,
              static_cast<unsigned long long>(h.rgb), static_cast<unsigned long long>(h.depth),
              static_cast<unsigned long long>(r.stats.pixels_written));
  EXPECT_EQ(h.rgb, rgb) << scene << ": the frame's colours differ from the x86-64 frame";
  EXPECT_EQ(h.depth, depth) << scene << ": the depth buffer differs from the x86-64 one";
}

std::string data(const char* name) {
  return std::string(LR_SOURCE_DIR) + "/tests/host/data/" + name;
}

TEST(FrameHash, GouraudTorusKnotGold) {
  host::HostMesh mesh;
  std::string err;
  ASSERT_TRUE(host::load_obj(data("torus_knot.obj"), mesh, err)) << err;
  host::SceneOptions o = test::gold_options();  // 320 x 240, Gouraud, one light
  o.strip_height = 16;
  expect_hashes("gouraud_torus_knot", mesh, o, 0x13abbecf954b7f2bu, 0x9b13aa0ee39331b5u);
}

TEST(FrameHash, TexturedGroundPlaneTrilinear) {
  host::HostTexture tex;
  std::string err;
  ASSERT_TRUE(host::texture_from_image(test::pattern(64, 64), TexelFormat::kRgb565, true, tex, err))
      << err;
  // The textured ground plane to the horizon (as in texture_test.cpp), seen from 1 unit above it.
  host::SceneOptions o = test::ground_view();
  o.texture_object = &tex.texture;
  o.filter = Filter::kBilinear;
  o.mipmap = MipMode::kLinear;
  o.perspective = Perspective::kExact;
  expect_hashes("ground_trilinear", test::ground_plane(200, 200), o, 0x0ff529cc215f7f38u,
                0x37d5804807f04525u);
}

TEST(FrameHash, FlatSphereTwoLights) {
  host::SceneOptions o;
  o.shading = Shading::kFlat;
  o.light_dirs = {{1, 1, 1}, {-1, -0.2, 0.4}};
  o.material.diffuse = {0.2, 0.5, 0.9};
  o.cull = Cull::kBack;
  o.strip_height = 4;
  expect_hashes("flat_sphere", host::make_uv_sphere(12, 18), o, 0xa480b7144ecd5426u,
                0xcdca79c0bd08d296u);
}

TEST(FrameHash, GroundPlaneClippedByTheNearPlane) {
  // Both triangles cross the near plane; the near corners project to |x_ndc| ~ 100 (guard band).
  const host::HostMesh m = test::coloured_ground(50);
  host::SceneOptions o;
  o.unlit = true;
  o.eye = {0, 1, 0};
  o.target = {0, 0.7, -5};
  o.far = 200;
  o.strip_height = 1;
  expect_hashes("ground_clipped", m, o, 0xba15789c4df329b2u, 0x43d62faf01470a25u);
}

TEST(FrameHash, GouraudSphereFourLightsLocalViewer) {
  // Specular highlights (the power table) from four lights, local viewer, global ambient.
  host::SceneOptions o = test::sphere_four_lights();
  o.local_viewer = true;
  expect_hashes("gouraud_sphere_4_lights", host::make_uv_sphere(40, 60), o, 0x2c671a5796833731u,
                0xa52e2c2af7eade18u);
}

TEST(FrameHash, LitTexturedCubeSpan16NearestMip) {
  // cube.obj names checker.png through cube.mtl: the texture comes through libpng.
  host::HostMesh mesh;
  std::string err;
  ASSERT_TRUE(host::load_obj(data("cube.obj"), mesh, err)) << err;
  host::SceneOptions o;
  o.eye = {2.2, 1.6, 3.1};
  o.model_rotate_y = 20;
  o.filter = Filter::kBilinear;
  o.mipmap = MipMode::kNearest;
  o.perspective = Perspective::kSpan16;
  o.strip_height = 32;
  expect_hashes("textured_cube", mesh, o, 0xaaf527355cacbc78u, 0x209fd7aeaa117445u);
}

}  // namespace
}  // namespace lr
