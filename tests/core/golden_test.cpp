// Golden images: small frames of fixed scenes, compared with PNGs in tests/golden.
// The core is integer-only and bit-identical everywhere, so a change here means behaviour
// changed. Tolerance (for deliberate small changes in rounding): at most 0.1 % of pixels may
// differ, none by more than 2 levels. Regenerate with LR_UPDATE_GOLDEN=1 and look at the diff.
#include <gtest/gtest.h>

#include <cstdlib>

#include "host_sim/formats/image_io.hpp"
#include "host_sim/formats/obj_loader.hpp"
#include "host_sim/scene/mesh_prep.hpp"
#include "host_sim/scene/scene.hpp"
#include "tests/support/scene_compare.hpp"

namespace lr {
namespace {

void check_golden(const std::string& name, const host::HostMesh& mesh,
                  const host::SceneOptions& o) {
  host::RenderResult r;
  std::string err;
  ASSERT_TRUE(host::render_scene(mesh, o, r, err)) << err;
  const std::string path = std::string(LR_SOURCE_DIR) + "/tests/golden/" + name + ".png";
  const char* update = std::getenv("LR_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    ASSERT_TRUE(host::write_png(path, r.image, err)) << err;
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
  check_golden("torus_knot_gold", mesh, test::gold_options(small()));
}

TEST(Golden, FlatShadedSphereTwoLights) {
  host::SceneOptions o = small();
  o.shading = Shading::kFlat;
  o.light_dirs = {{1, 1, 1}, {-1, -0.2, 0.4}};
  o.material.diffuse = {0.2, 0.5, 0.9};
  o.cull = Cull::kBack;
  check_golden("sphere_flat", host::make_uv_sphere(12, 18), o);
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
}

}  // namespace
}  // namespace lr
