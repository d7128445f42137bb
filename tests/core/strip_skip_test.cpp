// Skipping unchanged strips: a renderer with strip input signatures
// (FrameStorage::strip_inputs) and a display that retains the last frame must show, frame after
// frame, exactly what a renderer that draws every strip shows, while leaving out the strips whose
// inputs did not change.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/support/scenes.hpp"

namespace lr {
namespace {

constexpr int kW = 160, kH = 120, kK = 8;
constexpr int kStrips = (kH + kK - 1) / kK;
using PF = Rgb565Be;

// A host mesh in the core's formats.
struct FixedMesh {
  std::vector<Vec3> positions;
  std::vector<Normal16> normals;
  std::vector<TexCoord> uvs;
  std::vector<std::array<uint16_t, 3>> triangles;
  Mesh mesh() const { return Mesh{positions, normals, {}, uvs, triangles}; }
};

int16_t q14(double v) {
  return static_cast<int16_t>(std::lround(v * 16384.0));
}

FixedMesh to_fixed_mesh(const host::HostMesh& h) {
  FixedMesh m;
  for (const auto& p : h.positions) {
    Vec3 v;
    EXPECT_TRUE(host::to_fixed(p[0], v.x) && host::to_fixed(p[1], v.y) &&
                host::to_fixed(p[2], v.z));
    m.positions.push_back(v);
  }
  for (const auto& n : h.normals) m.normals.push_back(Normal16{q14(n[0]), q14(n[1]), q14(n[2])});
  for (const auto& uv : h.uvs) {
    TexCoord t;
    EXPECT_TRUE(host::to_texcoord(uv, t));
    m.uvs.push_back(t);
  }
  for (const auto& t : h.triangles)
    m.triangles.push_back(
        {static_cast<uint16_t>(t[0]), static_cast<uint16_t>(t[1]), static_cast<uint16_t>(t[2])});
  return m;
}

Fixed fx(double v) {
  Fixed f;
  EXPECT_TRUE(host::to_fixed(v, f));
  return f;
}
Vec3 v3(double x, double y, double z) {
  return {fx(x), fx(y), fx(z)};
}

// A renderer with its own storage and capture display; `skip` gives it strip signatures.
struct Rig {
  explicit Rig(bool skip, size_t max_active = 256, size_t max_triangles = 8192)
      : store(FrameCapacities{.width = kW,
                              .height = kH,
                              .strip_height = kK,
                              .vertices = 8192,
                              .triangles = max_triangles,
                              .draws = 16,
                              .active = max_active,
                              .surfaces = 8192,
                              .pixel_lights = 8,
                              .tex_vertices = 8192,
                              .active_extra = max_active,
                              .triangle_colors = max_triangles,
                              .strip_skipping = skip}),
        display(size_t{kW} * kK) {
    configured = renderer.configure(store.storage(), kW, kH);
  }
  BasicFrameStorage<std::vector> store;
  host::CaptureDisplay<PF> display;
  Renderer<PF, kK> renderer;
  Status configured = Status::kInvalidArgument;
};

// The scene: a static lit sphere, a static textured cube, and a small cube at `x` (moving).
struct Scene {
  FixedMesh sphere = to_fixed_mesh(host::make_uv_sphere(12, 18));
  FixedMesh cube = to_fixed_mesh(host::make_cube());
  host::HostTexture texture, texture2;
  Camera camera;
  LightSet lights;
  Rgb8 background{10, 20, 30};
  Shading sphere_shading = Shading::kGouraud;
  const Texture* cube_texture = nullptr;

  Scene() {
    std::string err;
    EXPECT_TRUE(
        host::texture_from_image(test::pattern(16, 16), TexelFormat::kRgb565, false, texture, err))
        << err;
    EXPECT_TRUE(
        host::texture_from_image(test::checker64(), TexelFormat::kRgb565, false, texture2, err))
        << err;
    cube_texture = &texture.texture;
    EXPECT_TRUE(perspective(fx(60), fx(double(kW) / kH), fx(0.1), fx(50), camera.projection));
    camera.eye = v3(0, 0, 4);
    EXPECT_TRUE(look_at(camera.eye, v3(0, 0, 0), v3(0, 1, 0), camera.view));
    lights.lights[0] = Light::directional(v3(0.5, 1, 1), Color15{32768, 32768, 32768});
    lights.count = 1;
  }

  void build(Rig& rig, double x, double y) const {
    ASSERT_EQ(rig.renderer.begin_frame(camera, lights, background), Status::kOk);
    Material m;
    m.specular = Color15{16384, 16384, 16384};
    m.shininess_q8 = 32 * 256;
    DrawState lit;
    lit.shading = sphere_shading;
    lit.cull = Cull::kBack;
    ASSERT_EQ(rig.renderer.draw(sphere.mesh(), translate(v3(-0.9, 0.2, 0)), m, lit), Status::kOk);
    DrawState tex;
    tex.texture = cube_texture;
    tex.cull = Cull::kBack;
    tex.sampler.filter = Filter::kBilinear;
    ASSERT_EQ(rig.renderer.draw(cube.mesh(),
                                translate(v3(1.0, -0.3, -0.5)) * rotate_y(fx(30)) * scale(fx(0.6)),
                                Material{}, tex),
              Status::kOk);
    DrawState small;
    small.cull = Cull::kBack;
    ASSERT_EQ(rig.renderer.draw(cube.mesh(), translate(v3(x, y, 1)) * scale(fx(0.15)), m, small),
              Status::kOk);
  }
};

struct FrameResult {
  std::vector<uint16_t> pixels;
  FrameStats stats;
};

FrameResult render(Rig& rig, DepthSink* depth = nullptr) {
  FrameResult r;
  Status st = rig.renderer.render(rig.display, depth);
  EXPECT_EQ(st, Status::kOk) << rig.display.error();
  r.stats = rig.renderer.stats();
  r.pixels = rig.display.raw_frame();
  return r;
}

TEST(StripSkip, MovingObjectOverStaticSceneMatchesFullRendering) {
  Scene scene;
  Rig skip(true), full(false);
  ASSERT_EQ(skip.configured, Status::kOk);
  ASSERT_EQ(full.configured, Status::kOk);
  // The small cube moves right for three frames, stops for one, then moves down.
  const double xs[] = {-1.2, -1.0, -0.8, -0.8, -0.8, -0.8};
  const double ys[] = {0.6, 0.6, 0.6, 0.6, 0.3, 0.0};
  std::vector<uint16_t> previous;
  for (int f = 0; f < 6; ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    scene.build(skip, xs[f], ys[f]);
    scene.build(full, xs[f], ys[f]);
    const FrameResult a = render(skip), b = render(full);
    ASSERT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(b.stats.strips_skipped, 0u);
    EXPECT_EQ(a.stats.strips, uint32_t(kStrips));
    if (f == 0) {
      EXPECT_EQ(a.stats.strips_skipped, 0u);  // nothing known yet
    } else if (f == 3) {
      // Nothing changed: no strip rendered, no triangle set up, the frame is the last one.
      EXPECT_EQ(a.pixels, previous);
      EXPECT_EQ(a.stats.strips_skipped, uint32_t(kStrips));
      EXPECT_EQ(a.stats.triangles_set_up, 0u);
      EXPECT_EQ(skip.display.kept(), uint32_t(kStrips));
    } else {
      EXPECT_NE(a.pixels, previous);  // the object moved
      // Moving the object re-renders the strips it left and entered, and only those: the sphere
      // and the textured cube alone stay in most strips.
      EXPECT_GT(a.stats.strips_skipped, uint32_t(kStrips) / 2);
      EXPECT_LT(a.stats.strips_skipped, uint32_t(kStrips));
      EXPECT_LT(a.stats.triangles_set_up, b.stats.triangles_set_up);
      EXPECT_LT(a.stats.pixels_tested, b.stats.pixels_tested);
      EXPECT_EQ(skip.display.kept() + skip.display.strips(), uint32_t(kStrips));
    }
    previous = a.pixels;
  }
}

// Changes that move no vertex still change what strips show: each must re-render them.
TEST(StripSkip, StateChangesAreSeen) {
  Scene scene;
  scene.sphere_shading = Shading::kPhong;  // per-pixel lighting: lights are not in the vertices
  Rig skip(true), full(false);
  auto frame = [&](const char* what, uint32_t expect_skipped_at_most) -> uint32_t {
    SCOPED_TRACE(what);
    scene.build(skip, -0.8, 0.6);
    scene.build(full, -0.8, 0.6);
    const FrameResult a = render(skip), b = render(full);
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_LE(a.stats.strips_skipped, expect_skipped_at_most);
    return a.stats.strips_skipped;
  };
  frame("first", 0);
  EXPECT_EQ(frame("unchanged", kStrips), uint32_t(kStrips));
  scene.lights.lights[0].diffuse = Color15{16384, 32768, 8192};
  EXPECT_EQ(frame("light colour", 0), 0u);  // the frame seed changed: every strip
  EXPECT_EQ(frame("unchanged again", kStrips), uint32_t(kStrips));
  scene.cube_texture = &scene.texture2.texture;
  const uint32_t skipped = frame("other texture", kStrips - 1);
  EXPECT_GT(skipped, 0u);  // strips without the textured cube are kept
  scene.background = Rgb8{200, 0, 0};
  EXPECT_EQ(frame("background", 0), 0u);
  scene.camera.eye = v3(0, 0.1, 4);
  ASSERT_TRUE(look_at(scene.camera.eye, v3(0, 0, 0), v3(0, 1, 0), scene.camera.view));
  EXPECT_EQ(frame("camera", 0), 0u);
}

// When skipping is not possible, every strip is rendered (and nothing is lost).
TEST(StripSkip, RendersEverythingWhenThePreviousFrameIsUnknown) {
  Scene scene;
  Rig skip(true);
  scene.build(skip, -0.8, 0.6);
  render(skip);
  scene.build(skip, -0.8, 0.6);
  EXPECT_EQ(render(skip).stats.strips_skipped, uint32_t(kStrips));

  skip.renderer.invalidate_strips();
  scene.build(skip, -0.8, 0.6);
  EXPECT_EQ(render(skip).stats.strips_skipped, 0u);

  // A depth sink wants every strip's depth.
  host::DepthCapture depth;
  depth.resize(kW, kH);
  scene.build(skip, -0.8, 0.6);
  EXPECT_EQ(render(skip, &depth).stats.strips_skipped, 0u);
  EXPECT_NE(depth.depth()[size_t{kW} * (kH / 2) + kW / 4], 0xFFFF);  // the sphere's depth

  // A display that does not retain its pixels.
  skip.display.set_retain(false);
  scene.build(skip, -0.8, 0.6);
  const FrameResult a = render(skip);
  EXPECT_EQ(a.stats.strips_skipped, 0u);
  EXPECT_EQ(skip.display.strips(), uint32_t(kStrips));
  skip.display.set_retain(true);

  // A display whose frame size changed has nothing to keep.
  scene.build(skip, -0.8, 0.6);
  EXPECT_EQ(render(skip).stats.strips_skipped, uint32_t(kStrips));
  ASSERT_EQ(skip.display.begin_frame(kW / 2, kH), Status::kOk);
  EXPECT_FALSE(skip.display.retains_frame());
  scene.build(skip, -0.8, 0.6);
  EXPECT_EQ(render(skip).stats.strips_skipped, 0u);
}

// An active list too small for the frame draws crowded strips in passes: the same pixels, so
// strip signatures still describe them and the next frame skips what did not change.
TEST(StripSkip, CrowdedStripsAreSkippedLikeAnyOther) {
  Scene scene;
  Rig skip(true, 24), full(false);
  skip.display.set_retain(true);
  scene.build(skip, -0.8, 0.6);
  const FrameResult first = render(skip);
  ASSERT_GT(first.stats.strip_passes, 0u);
  scene.build(full, -0.8, 0.6);
  EXPECT_EQ(first.pixels, render(full).pixels);
  scene.build(skip, -0.8, 0.2);
  const FrameResult second = render(skip);
  EXPECT_GT(second.stats.strips_skipped, 0u);
  scene.build(full, -0.8, 0.2);
  EXPECT_EQ(second.pixels, render(full).pixels);
}

// A frame binned in bands signs each strip in its band with the triangles that touch it: the
// signatures of one pass, so that skipping works across bands and across frames that change
// from one pass to bands.
TEST(StripSkip, BandedFramesSkipLikeOnePassFrames) {
  Scene scene;
  Rig banded(true, 256, 120), one(true);
  banded.display.set_retain(true);
  one.display.set_retain(true);
  int frame = 0;
  for (double x : {-0.8, -0.8, 0.3, 0.3}) {
    scene.build(banded, x, 0.6);
    scene.build(one, x, 0.6);
    const FrameResult a = render(banded), b = render(one);
    EXPECT_GT(a.stats.bands, 1u);
    EXPECT_EQ(b.stats.bands, 1u);
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(a.stats.strips_skipped, b.stats.strips_skipped);
    // The second frame of each position repeats the first: every strip is left out.
    if (frame++ % 2 == 1) {
      EXPECT_EQ(a.stats.strips_skipped, uint32_t(kStrips));
    }
  }
}

TEST(StripSkip, SignatureStorageIsChecked) {
  BasicFrameStorage<std::vector> store(FrameCapacities{.width = kW,
                                                       .height = kH,
                                                       .strip_height = kK,
                                                       .vertices = 16,
                                                       .triangles = 16,
                                                       .active = 8,
                                                       .strip_skipping = true});
  FrameStorage s = store.storage();
  constexpr size_t kWords = 2 * kStrips;
  ASSERT_EQ(s.strip_inputs.size(), kWords);
  s.strip_inputs = s.strip_inputs.first(kWords - 1);  // one word short
  Renderer<PF, kK> r;
  EXPECT_EQ(r.configure(s, kW, kH), Status::kStoreTooSmall);
  s.strip_inputs = store.storage().strip_inputs;
  EXPECT_EQ(r.configure(s, kW, kH), Status::kOk);
}

}  // namespace
}  // namespace lr
