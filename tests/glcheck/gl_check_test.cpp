// The independent OpenGL check: the same scenes rendered by the fixed-point core and by Mesa's
// software OpenGL (OSMesa, fixed-function state per docs/conventions.md), compared pixel by
// pixel. Bounds: coverage mismatches at most 0.05 % of the pixels; lit scenes PSNR
// >= 40 dB over the pixels both cover; nearest-textured scenes the same texel on >= 99.5 % of
// the pixels. The double reference is compared with Mesa too, so that a difference can be told
// apart as the core's (core differs, reference agrees) or a convention (both differ).
//
// LR_GLCHECK_DUMP=DIR writes each scene's core, Mesa and difference images as PNG into DIR.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "lineraster/host_sim/formats/image_io.hpp"
#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "tests/glcheck/osmesa_scene.hpp"
#include "tests/support/scene_compare.hpp"
#include "tests/support/scenes.hpp"

// Mesa's OSMesa keeps a small allocation per OSMesaMakeCurrent after the context is destroyed
// (libOSMesa.so.8, Mesa 22.3): not ours to fix; LeakSanitizer (the ASan run) ignores it.
extern "C" __attribute__((used)) const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\n";
}

namespace lr {
namespace {

const std::string kData = std::string(LR_SOURCE_DIR) + "/tests/host/data/";

// One image against Mesa's: coverage disagreements over the whole frame, colour error over the
// pixels both cover.
struct GlDiff {
  size_t pixels = 0;
  size_t coverage_diff = 0;
  size_t both = 0;
  size_t within2 = 0;  // of `both`: every channel within 2 levels (nearest: "the same texel")
  size_t within1 = 0;
  int max_error = 0;
  double mean_error = 0;
  double psnr = 99.0;
  std::string examples;  // the first few coverage mismatches: " (x,y) ours|gl"

  double coverage_pct() const { return 100.0 * double(coverage_diff) / double(pixels); }
  double within2_pct() const { return both ? 100.0 * double(within2) / double(both) : 100.0; }
  std::string summary() const {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "coverage mismatches %zu of %zu (%.4f %%), both %zu, PSNR %.2f dB, max %d, "
                  "mean %.4f, within 1: %.3f %%, within 2: %.3f %%",
                  coverage_diff, pixels, coverage_pct(), both, psnr, max_error, mean_error,
                  both ? 100.0 * double(within1) / double(both) : 100.0, within2_pct());
    return examples.empty() ? std::string(buf) : buf + std::string("; coverage:") + examples;
  }
};

// `mask` (optional): only pixels where it is true are compared (coverage included).
template <typename CovA, typename Mask>
GlDiff diff(const std::vector<uint8_t>& rgb, CovA covered, const glcheck::GlFrame& gl, Mask mask) {
  GlDiff d;
  double sum = 0, sq = 0;
  for (size_t p = 0; p < gl.covered.size(); ++p) {
    if (!mask(p)) continue;
    ++d.pixels;
    const bool a = covered(p), b = gl.covered[p] != 0;
    if (a != b) {
      if (++d.coverage_diff <= 4) {
        const size_t w = size_t(gl.width);
        d.examples +=
            " (" + std::to_string(p % w) + "," + std::to_string(p / w) + ") " + (a ? "ours" : "gl");
      }
      continue;
    }
    if (!a) continue;
    ++d.both;
    int worst = 0;
    for (size_t k = 0; k < 3; ++k) {
      const int e = std::abs(int(rgb[3 * p + k]) - int(gl.rgb[3 * p + k]));
      worst = std::max(worst, e);
      sum += e;
      sq += double(e) * e;
    }
    d.max_error = std::max(d.max_error, worst);
    d.within1 += worst <= 1;
    d.within2 += worst <= 2;
  }
  if (d.both) {
    d.mean_error = sum / (3.0 * double(d.both));
    const double mse = sq / (3.0 * double(d.both));
    d.psnr = mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : 99.0;
  }
  return d;
}

// A scene rendered three ways: core, double reference, Mesa.
struct Triple {
  test::Comparison c;  // core and reference
  glcheck::GlFrame gl;
  GlDiff core_gl, ref_gl;
};

void dump(const std::string& name, const Triple& t) {
  const char* dir = std::getenv("LR_GLCHECK_DUMP");
  if (dir == nullptr) return;
  host::ImageRgb8 img{t.gl.width, t.gl.height, t.gl.rgb};
  std::string err;
  const std::string base = std::string(dir) + "/" + name;
  EXPECT_TRUE(host::write_png(base + "_mesa.png", img, err)) << err;
  EXPECT_TRUE(host::write_png(base + "_core.png", t.c.core.image, err)) << err;
  // Difference: coverage mismatches magenta (core only) or cyan (Mesa only), colour error x 16.
  for (size_t p = 0; p < t.gl.covered.size(); ++p) {
    const bool a = t.c.core.depth[p] != 0xFFFF, b = t.gl.covered[p] != 0;
    for (size_t k = 0; k < 3; ++k) {
      const int e = std::abs(int(t.c.core.image.rgb[3 * p + k]) - int(t.gl.rgb[3 * p + k]));
      img.rgb[3 * p + k] =
          uint8_t(a != b ? (a ? (k != 1 ? 255 : 0) : (k != 0 ? 255 : 0)) : std::min(255, 16 * e));
    }
  }
  EXPECT_TRUE(host::write_png(base + "_diff.png", img, err)) << err;
}

template <typename Mask>
Triple render_three(const std::string& name, const host::HostMesh& mesh,
                    const host::SceneOptions& o, Mask mask) {
  Triple t;
  std::string err;
  EXPECT_TRUE(test::compare_scene(mesh, o, t.c, err)) << err;
  EXPECT_TRUE(glcheck::render_gl(mesh, o, t.gl, err)) << err;
  if (t.gl.rgb.empty() || t.c.core.image.rgb.empty()) return t;
  const auto& core_depth = t.c.core.depth;
  const auto& owner = t.c.reference.owner;
  t.core_gl = diff(
      t.c.core.image.rgb, [&](size_t p) { return core_depth[p] != 0xFFFF; }, t.gl, mask);
  t.ref_gl = diff(
      t.c.reference.rgb8, [&](size_t p) { return owner[p] >= 0; }, t.gl, mask);
  std::printf("[%s] Mesa: %s\n", name.c_str(), t.gl.renderer.c_str());
  std::printf("[%s] core vs Mesa:      %s\n", name.c_str(), t.core_gl.summary().c_str());
  std::printf("[%s] reference vs Mesa: %s\n", name.c_str(), t.ref_gl.summary().c_str());
  std::printf("[%s] core vs reference: %s\n", name.c_str(), t.c.summary().c_str());
  dump(name, t);
  return t;
}

Triple render_three(const std::string& name, const host::HostMesh& mesh,
                    const host::SceneOptions& o) {
  return render_three(name, mesh, o, [](size_t) { return true; });
}

// At most 0.05 % of the frame's pixels covered by one renderer only.
void expect_coverage(const GlDiff& d) {
  EXPECT_LE(double(d.coverage_diff), 0.0005 * double(d.pixels)) << d.summary();
}

host::HostMesh torus_knot() {
  host::HostMesh m;
  std::string err;
  EXPECT_TRUE(host::load_obj(kData + "torus_knot.obj", m, err)) << err;
  return m;
}

host::HostTexture tiles64() {
  host::HostTexture t;
  std::string err;
  EXPECT_TRUE(host::load_texture(kData + "tiles64.png", TexelFormat::kRgb888, false, t, err))
      << err;
  return t;
}

// ---- Lit scenes ----

TEST(GlCheck, GouraudTorusKnotGold) {
  const Triple t = render_three("torus_knot_gold", torus_knot(), test::gold_options());
  expect_coverage(t.core_gl);
  EXPECT_GT(t.core_gl.both, 9000u);
  EXPECT_GE(t.core_gl.psnr, 40.0);
}

TEST(GlCheck, FlatTorusKnotWithFaceNormalsAndLocalViewer) {
  // GL's flat shading lights the provoking (last) vertex; the core lights the face normal. With
  // every triangle given its own vertices carrying the face normal both light the same normal
  // (the local viewer's eye vector is taken at the last vertex by GL, at a point of the face by
  // the core: a small difference on the highlights).
  const host::HostMesh smooth = torus_knot();
  host::HostMesh m;
  for (const auto& tri : smooth.triangles) {
    const host::Vec3d& a = smooth.positions[tri[0]];
    const host::Vec3d& b = smooth.positions[tri[1]];
    const host::Vec3d& c = smooth.positions[tri[2]];
    const ref::Vec3d n = ref::normalize(ref::cross(ref::sub(b, a), ref::sub(c, a)));
    const auto base = uint32_t(m.positions.size());
    for (const host::Vec3d* v : {&a, &b, &c}) {
      m.positions.push_back(*v);
      m.normals.push_back(n);
    }
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangle_material.push_back(-1);
  }
  host::SceneOptions o = test::gold_options();
  o.shading = Shading::kFlat;
  const Triple infinite = render_three("torus_knot_flat", m, o);
  expect_coverage(infinite.core_gl);
  EXPECT_GE(infinite.core_gl.psnr, 40.0);
  o.local_viewer = true;
  const Triple local = render_three("torus_knot_flat_local_viewer", m, o);
  expect_coverage(local.core_gl);
  // The core (and the reference) take the local viewer's eye vector at the triangle's centroid,
  // GL at the provoking vertex.
  EXPECT_GE(local.core_gl.psnr, 40.0);
}

TEST(GlCheck, GouraudSphereFourLights) {
  host::SceneOptions o = test::sphere_four_lights();
  o.width = 240;
  o.height = 240;
  const Triple t = render_three("sphere_4_lights", host::make_uv_sphere(40, 60), o);
  expect_coverage(t.core_gl);
  EXPECT_GT(t.core_gl.both, 13000u);
  EXPECT_GE(t.core_gl.psnr, 40.0);
}

// ---- Unlit, clipped ----

TEST(GlCheck, UnlitGroundPlaneThroughTheNearPlane) {
  host::SceneOptions o;
  o.unlit = true;
  o.eye = {0, 1, 0};
  o.target = {0, 0.7, -5};
  o.far = 200;
  const Triple t = render_three("ground_unlit_near_plane", test::coloured_ground(50), o);
  EXPECT_EQ(t.c.core.stats.clipped, 2u);
  expect_coverage(t.core_gl);
  EXPECT_GE(t.core_gl.psnr, 40.0);
}

TEST(GlCheck, FlatUnlitGroundPlaneTakesTheLastVertexColourAndBreaksTiesAsGl) {
  // A symmetric view of a square with integer corners: the shared diagonal passes exactly
  // through a pixel centre every few pixels, and the fill rule alone decides which triangle (and
  // so which flat colour) each of those centres gets. The reference snaps the exact projection;
  // Mesa agrees with it on every pixel. The core projects with Q16.16 matrices: its snapped
  // vertices may lie one subpixel from the exact rounding (here all four y do), which moves the
  // diagonal off the tied centres, and those take the other triangle's colour. Bound: at most
  // 0.5 % of the pixels, all on the diagonal.
  host::SceneOptions o;
  o.unlit = true;
  o.shading = Shading::kFlat;
  o.eye = {0, 3, 4};
  o.target = {0, 0, 0};
  const Triple t = render_three("ground_unlit_flat", test::coloured_ground(2), o);
  expect_coverage(t.core_gl);
  EXPECT_EQ(t.ref_gl.coverage_diff, 0u);
  EXPECT_EQ(t.ref_gl.max_error, 0);
  EXPECT_GE(t.core_gl.within2_pct(), 99.5);
}

// ---- Textured ----

TEST(GlCheck, NearestTexturedGroundPlane) {
  const host::HostTexture tex = tiles64();
  // The textured ground plane (tests/core/texture_test.cpp): 400 x 400 units, the texture
  // repeated 200 times, far plane 400, eye 1 unit above it looking slightly down. Unlit
  // (GL_REPLACE): every pixel is a texel.
  host::SceneOptions o = test::ground_view();
  o.texture_object = &tex.texture;
  o.texture_format = TexelFormat::kRgb888;
  o.filter = Filter::kNearest;
  o.wrap = Wrap::kRepeat;
  const host::HostMesh mesh = test::ground_plane(200, 200);
  const Triple t = render_three("ground_nearest", mesh, o);
  expect_coverage(t.core_gl);
  // Where a texel covers at least about a pixel (level of detail < 1, from the reference) the
  // texel choice is determined; nearer the horizon many texels fall into one pixel and which one
  // the centre hits depends on the last bits of any implementation's arithmetic.
  const auto& lod = t.c.reference.lod;
  const auto magnified = [&](size_t p) { return lod[p] < 1.0; };
  const GlDiff near_part = diff(
      t.c.core.image.rgb, [&](size_t p) { return t.c.core.depth[p] != 0xFFFF; }, t.gl, magnified);
  const GlDiff ref_near = diff(
      t.c.reference.rgb8, [&](size_t p) { return t.c.reference.owner[p] >= 0; }, t.gl, magnified);
  std::printf("[ground_nearest] lod < 1: core vs Mesa:      %s\n", near_part.summary().c_str());
  std::printf("[ground_nearest] lod < 1: reference vs Mesa: %s\n", ref_near.summary().c_str());
  std::printf(
      "[ground_nearest] same texel: %.3f %% of all %zu pixels both cover, %.3f %% of the "
      "%zu with lod < 1\n",
      t.core_gl.within2_pct(), t.core_gl.both, near_part.within2_pct(), near_part.both);
  EXPECT_GT(near_part.both, 20000u);
  EXPECT_GE(near_part.within2_pct(), 99.5);
}

host::SceneOptions cube_options(const host::HostTexture& tex, Filter f) {
  // The texture benchmark's cube: seen from above and in front, turned 35 degrees about y,
  // back faces culled, one light, default material (specular 0.5, shininess 32).
  host::SceneOptions o = test::cube_view();
  o.texture_object = &tex.texture;
  o.texture_format = TexelFormat::kRgb888;
  o.filter = f;
  o.wrap = Wrap::kRepeat;
  return o;
}

TEST(GlCheck, TexturedLitCube) {
  const host::HostTexture tex = tiles64();
  const host::HostMesh cube = host::make_cube();
  const Triple nearest =
      render_three("cube_nearest_lit", cube, cube_options(tex, Filter::kNearest));
  expect_coverage(nearest.core_gl);
  EXPECT_GT(nearest.core_gl.both, 30000u);
  EXPECT_GE(nearest.core_gl.psnr, 40.0);
  const Triple bilinear =
      render_three("cube_bilinear_lit", cube, cube_options(tex, Filter::kBilinear));
  expect_coverage(bilinear.core_gl);
  EXPECT_GE(bilinear.core_gl.psnr, 40.0);
  // Unlit (GL_REPLACE) and nearest: every pixel a texel.
  host::SceneOptions o = cube_options(tex, Filter::kNearest);
  o.unlit = true;
  const Triple replace = render_three("cube_nearest_replace", cube, o);
  expect_coverage(replace.core_gl);
  std::printf("[cube_nearest_replace] same texel on %.3f %% of %zu pixels\n",
              replace.core_gl.within2_pct(), replace.core_gl.both);
  EXPECT_GE(replace.core_gl.within2_pct(), 99.5);
}

}  // namespace
}  // namespace lr
