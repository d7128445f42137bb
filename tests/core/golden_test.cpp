// Golden images: small frames of fixed scenes, compared with PNGs in tests/golden.
// The core is integer-only and bit-identical everywhere, so a change here means behaviour
// changed. Tolerance (for deliberate small changes in rounding): at most 0.1 % of pixels may
// differ, none by more than 2 levels. Regenerate with LR_UPDATE_GOLDEN=1 and look at the diff:
// that run writes the PNGs and skips the comparison (an image compared with itself proves
// nothing). A golden is only as right as the renderer that wrote it: each is also compared
// with the double reference, so that a wrong frame cannot become the golden unnoticed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "lineraster/host_sim/formats/image_io.hpp"
#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/support/scene_compare.hpp"

namespace lr {
namespace {

std::string golden_path(const std::string& name) {
  return std::string(LR_SOURCE_DIR) + "/tests/golden/" + name + ".png";
}

// The golden PNG against the double reference's frame of the same scene: at least
// `min_covered` pixels covered by the reference, on at least `min_within1` of them every
// channel within one level of it, and outside them the golden shows the background (a
// coverage difference on at most 0.1 % of the pixels).
void check_against_reference(const std::string& name, const host::HostMesh& mesh,
                             const host::SceneOptions& o, size_t min_covered, double min_within1) {
  host::ImageRgb8 golden;
  std::string err;
  ASSERT_TRUE(host::read_png(golden_path(name), golden, err)) << err;
  ref::RefFrame reference;
  ref::render(mesh, test::ref_params(mesh, o), reference);
  ASSERT_EQ(golden.width, reference.width);
  ASSERT_EQ(golden.height, reference.height);
  size_t covered = 0, within1 = 0, outside = 0;
  for (size_t p = 0; p < reference.owner.size(); ++p) {
    int e = 0;
    for (size_t k = 0; k < 3; ++k)
      e = std::max(e, std::abs(int(golden.rgb[3 * p + k]) - int(reference.rgb8[3 * p + k])));
    if (reference.owner[p] >= 0) {
      ++covered;
      within1 += e <= 1;
    } else {
      outside += e > 1;
    }
  }
  std::printf("%s against the reference: %zu covered, %zu within one level, %zu outside differ\n",
              name.c_str(), covered, within1, outside);
  EXPECT_GE(covered, min_covered) << name;
  EXPECT_GE(double(within1), min_within1 * double(covered)) << name;
  EXPECT_LE(outside, reference.owner.size() / 1000) << name;
}

void check_golden(const std::string& name, const host::HostMesh& mesh,
                  const host::SceneOptions& o) {
  host::RenderResult r;
  std::string err;
  ASSERT_TRUE(host::render_scene(mesh, o, r, err)) << err;
  const std::string path = golden_path(name);
  const char* update = std::getenv("LR_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    ASSERT_TRUE(host::write_png(path, r.image, err)) << err;
    GTEST_SKIP() << "LR_UPDATE_GOLDEN=1: wrote " << path
                 << ", not compared; run again without it to compare";
  }
  host::ImageRgb8 golden;
  ASSERT_TRUE(host::read_png(path, golden, err))
      << err << " (run with LR_UPDATE_GOLDEN=1 to create)";
  ASSERT_EQ(golden.width, r.image.width);
  ASSERT_EQ(golden.height, r.image.height);
  size_t differ = 0;
  int worst = 0;
  for (size_t p = 0; p < golden.rgb.size() / 3; ++p) {
    int e = 0;
    for (size_t k = 0; k < 3; ++k)
      e = std::max(e, std::abs(int(golden.rgb[3 * p + k]) - int(r.image.rgb[3 * p + k])));
    differ += e > 0;
    worst = std::max(worst, e);
  }
  EXPECT_LE(differ, golden.rgb.size() / 3 / 1000) << name;
  EXPECT_LE(worst, 2) << name;
  // The scene must show something: a blank frame would match a blank golden.
  size_t lit = 0;
  for (size_t p = 0; p < golden.rgb.size() / 3; ++p)
    lit += golden.rgb[3 * p] + golden.rgb[3 * p + 1] + golden.rgb[3 * p + 2] > 0;
  EXPECT_GT(lit, golden.rgb.size() / 3 / 20) << name;
}

host::SceneOptions small() {
  host::SceneOptions o;
  o.width = 160;
  o.height = 120;
  return o;
}

TEST(Golden, GoldTorusKnotGouraud) {
  host::HostMesh mesh;
  std::string err;
  ASSERT_TRUE(
      host::load_obj(std::string(LR_SOURCE_DIR) + "/tests/host/data/torus_knot.obj", mesh, err))
      << err;
  const host::SceneOptions o = test::gold_options(small());
  check_golden("torus_knot_gold", mesh, o);
  // The knot fitted to radius 1 at distance 3 is a thin tube: about an eighth of the frame.
  check_against_reference("torus_knot_gold", mesh, o, 160 * 120 / 9, 0.999);
}

TEST(Golden, FlatShadedSphereTwoLights) {
  host::SceneOptions o = small();
  o.shading = Shading::kFlat;
  o.light_dirs = {{1, 1, 1}, {-1, -0.2, 0.4}};
  o.material.diffuse = {0.2, 0.5, 0.9};
  o.cull = Cull::kBack;
  const host::HostMesh mesh = host::make_uv_sphere(12, 18);
  check_golden("sphere_flat", mesh, o);
  // The unit sphere 3 units away: a disc of radius 60 tan(asin(1 / 3)) / tan(30) = 36.7 pixels
  // (pi 36.7^2 > 4200), the 12 x 18 polygon somewhat inside. Flat colours: a pixel on an edge
  // between two facets may take its neighbour's colour where the core's snapped vertices move
  // the edge across its centre.
  check_against_reference("sphere_flat", mesh, o, 3800, 0.99);
}

TEST(Golden, UnlitVertexColoursOnAGroundPlane) {
  host::HostMesh m;
  m.positions = {{-40, 0, -40}, {40, 0, -40}, {40, 0, 40}, {-40, 0, 40}};
  m.normals.assign(4, {0, 1, 0});
  m.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  m.triangles = {{0, 3, 2}, {0, 2, 1}};
  m.triangle_material = {-1, -1};
  host::SceneOptions o = small();
  o.unlit = true;
  o.eye = {0, 1, 0};
  o.target = {0, 0.6, -5};
  o.background = {0.1, 0.1, 0.2};
  check_golden("ground_plane_unlit", m, o);
  // The far edge (40 units away, 1 below the eye) is 3.1 degrees above the view axis: row
  // 60 - 60 tan(3.1) / tan(30) = 54 of 120, every row below it covered edge to edge.
  check_against_reference("ground_plane_unlit", m, o, 160 * 64, 0.999);
}

}  // namespace
}  // namespace lr
