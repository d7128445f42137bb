// Clipping: triangles crossing the near plane and reaching far outside the viewport (guard
// band) render as the reference does: no gaps, no spikes.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "lineraster/core/raster/frame_storage.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "tests/support/recording_sink.hpp"
#include "tests/support/scene_compare.hpp"

namespace lr {
namespace {

// A square ground plane y = 0 of half-size `half`, colours varying over its corners.
host::HostMesh ground(double half) {
  host::HostMesh m;
  m.positions = {{-half, 0, -half}, {half, 0, -half}, {half, 0, half}, {-half, 0, half}};
  m.normals.assign(4, {0, 1, 0});
  m.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}};
  m.triangles = {{0, 3, 2}, {0, 2, 1}};  // counter-clockwise seen from above
  m.triangle_material = {-1, -1};
  return m;
}

TEST(Clipping, WideGroundPlaneThroughTheNearPlaneRendersExactly) {
  host::HostMesh mesh = ground(50);
  host::SceneOptions o;
  o.unlit = true;
  o.eye = {0, 1, 0};
  o.target = {0, 0.7, -5};
  o.far = 200;
  test::Comparison c;
  std::string err;
  ASSERT_TRUE(test::compare_scene(mesh, o, c, err)) << err;
  std::printf("ground plane (unlit): %s, clipped=%u\n", c.summary().c_str(), c.core.stats.clipped);
  EXPECT_EQ(c.core.stats.clipped, 2u);  // both triangles cross the near plane
  EXPECT_EQ(c.core.stats.binned_inputs, 2u);
  // The two corners behind the eye take the exact path (FrameStats::vertices_wide), the two far
  // ones the 32-bit short path.
  EXPECT_EQ(c.core.stats.vertices_transformed, 4u);
  EXPECT_EQ(c.core.stats.vertices_wide, 2u);
  // The plane's far edge (50 units away, 1 below the eye) is 2.3 degrees above the view axis:
  // row 120 - 120 tan(2.3) / tan(30) = 112; every row below it is covered edge to edge.
  EXPECT_GE(c.both, size_t(o.width) * 127);
  // The near corners of the plane project to |x_ndc| ~ 100 and beyond.
  EXPECT_LE(c.coverage_diff, size_t(o.width * o.height) / 2000);  // <= 0.05 %
  EXPECT_GE(c.fraction_within1(), 0.999);
  EXPECT_LE(c.max_error, 2);
  // No gaps: every row below the horizon is covered from edge to edge; no spikes above it.
  int first_full = -1;
  for (int y = 0; y < o.height; ++y) {
    int covered = 0;
    for (int x = 0; x < o.width; ++x)
      covered += c.core.depth[size_t(y) * size_t(o.width) + size_t(x)] != 0xFFFF;
    if (covered == o.width && first_full < 0) first_full = y;
    if (first_full >= 0) {
      EXPECT_EQ(covered, o.width) << "gap in row " << y;
    } else {
      EXPECT_LT(covered, o.width);
    }
  }
  EXPECT_GT(first_full, 60);
  EXPECT_LT(first_full, 160);
}

TEST(Clipping, LitGroundPlaneSeenFromLowAngle) {
  host::HostMesh mesh = ground(300);
  host::SceneOptions o;
  o.eye = {0, 0.5, 0};
  o.target = {0, 0.45, -10};
  o.far = 400;
  o.light_dirs = {{0.3, 1, 0.2}};
  test::Comparison c;
  std::string err;
  ASSERT_TRUE(test::compare_scene(mesh, o, c, err)) << err;
  std::printf("ground plane (lit, far 400): %s\n", c.summary().c_str());
  // The far edge (300 units away, 0.5 below the eye) is 0.2 degrees above the view axis: the
  // plane covers the lower half of the frame and a row more.
  EXPECT_GE(c.both, size_t(o.width) * 120);
  EXPECT_LE(c.coverage_diff, size_t(o.width * o.height) / 2000);
  EXPECT_GE(c.fraction_within1(), 0.999);
}

TEST(Clipping, TriangleBehindTheCameraIsClippedAway) {
  host::HostMesh m;
  m.positions = {{-1, -1, 5}, {1, -1, 5}, {0, 1, 5}};  // eye at z = 3 looking down -z
  m.normals.assign(3, {0, 0, 1});
  m.triangles = {{0, 1, 2}};
  m.triangle_material = {-1};
  host::RenderResult r;
  std::string err;
  ASSERT_TRUE(host::render_scene(m, host::SceneOptions{}, r, err)) << err;
  EXPECT_EQ(r.stats.clipped_away, 1u);
  EXPECT_EQ(r.stats.pixels_written, 0u);
}

TEST(Clipping, SidePlanesOnlyCutFarOutsideTheViewport) {
  // A huge triangle in front of the camera: the guard band cuts it, the picture is unchanged.
  host::HostMesh m;
  m.positions = {{-30000, -30000, -1}, {30000, -30000, -1}, {0, 30000, -1}};
  m.normals.assign(3, {0, 0, 1});
  m.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 1, 2}};
  m.triangle_material = {-1};
  host::SceneOptions o;
  o.unlit = true;
  o.far = 10;
  test::Comparison c;
  std::string err;
  ASSERT_TRUE(test::compare_scene(m, o, c, err)) << err;
  std::printf("giant triangle: %s\n", c.summary().c_str());
  EXPECT_EQ(c.core.stats.clipped, 1u);
  EXPECT_EQ(c.both, size_t(o.width) * size_t(o.height));
  EXPECT_GE(c.fraction_within1(), 0.999);
}

// A renderer without textured or Phong spans clips with the clipper that carries only position
// and colour (clip_polygon<false>: FrontEndRoutines::clip): lit Gouraud ground planes through the
// near plane and out past the guard band give the full renderer's frame, byte for byte.
TEST(Clipping, AGouraudOnlyRendererClipsAsTheFullOne) {
  using PF = Rgb565Be;
  constexpr int kW = 96, kH = 64, kK = 8;
  auto fx = [](double v) { return Fixed::from_raw(static_cast<int32_t>(std::lround(v * 65536))); };
  // Ground quads y = -1 from behind the eye to far ahead and wide beyond the guard band, their
  // normals leaning so that the lit colour varies along every clipped edge.
  std::vector<Vec3> positions;
  std::vector<Normal16> normals;
  std::vector<std::array<uint16_t, 3>> triangles;
  for (int j = 0; j <= 4; ++j)
    for (int i = 0; i <= 4; ++i) {
      positions.push_back({fx(-300.0 + 150.0 * i), fx(-1.0), fx(40.0 - 60.0 * j)});
      normals.push_back(
          {static_cast<int16_t>(-7000 + 3500 * i), 14000, static_cast<int16_t>(-6000 + 3000 * j)});
    }
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const auto a = static_cast<uint16_t>(j * 5 + i);
      triangles.push_back({a, static_cast<uint16_t>(a + 5), static_cast<uint16_t>(a + 6)});
      triangles.push_back({a, static_cast<uint16_t>(a + 6), static_cast<uint16_t>(a + 1)});
    }
  const Mesh mesh{positions, normals, {}, {}, triangles, {}};
  Camera camera;
  ASSERT_TRUE(perspective(fx(60), Fixed::ratio(kW, kH), fx(0.5), fx(400), camera.projection));
  LightSet lights;
  lights.lights[0].position = {fx(0.4), fx(1.0), fx(0.3)};
  lights.count = 1;
  lights.global_ambient = {6554, 6554, 6554};
  Material material;
  material.diffuse = {26000, 20000, 9000};
  material.specular = {16000, 16000, 16000};
  material.shininess_q8 = 20 * 256;
  DrawState state;
  state.lighting = true;
  state.shading = Shading::kGouraud;
  state.depth_test = true;
  state.cull = Cull::kNone;
  SpanState span;
  span.colors = ColorPlanes::kPerspective;
  constexpr SpanSet kGouraudOnly = [] {
    SpanState s;
    s.colors = ColorPlanes::kPerspective;
    return span_set_of(s);
  }();
  ASSERT_TRUE(kGouraudOnly.admits(span));
  ASSERT_FALSE(kGouraudOnly.has(SpanFamily::kTextured));
  FrameCapacities caps;
  caps.width = kW;
  caps.height = kH;
  caps.strip_height = kK;
  caps.vertices = 256;
  caps.triangles = 256;
  caps.draws = 2;
  caps.active = 128;
  auto frame = [&](auto& renderer, FrameStats& stats) {
    BasicFrameStorage<std::vector> store(caps);
    test::RecordingSink<PF> sink{size_t{kW} * kK};
    EXPECT_EQ(renderer.configure(store.storage(), kW, kH), Status::kOk);
    EXPECT_EQ(renderer.begin_frame(camera, lights, Rgb8{10, 20, 30}), Status::kOk);
    EXPECT_EQ(renderer.draw(mesh, Mat4::identity(), material, state), Status::kOk);
    EXPECT_EQ(renderer.render(sink), Status::kOk);
    stats = renderer.stats();
    return sink.frame();
  };
  FrameStats full_stats, lean_stats;
  auto full = std::make_unique<Renderer<PF, kK>>();
  auto lean = std::make_unique<Renderer<PF, kK, kGouraudOnly>>();
  const auto want = frame(*full, full_stats);
  const auto got = frame(*lean, lean_stats);
  EXPECT_GE(full_stats.clipped, 8u);  // the near row and the sides past the guard band
  EXPECT_GT(full_stats.pixels_written, uint32_t{kW * kH / 3});
  EXPECT_EQ(lean_stats.clipped, full_stats.clipped);
  EXPECT_EQ(got, want);
}

}  // namespace
}  // namespace lr
