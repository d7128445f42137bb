// Fixed point against the double reference on whole scenes: lit meshes made by the project.
#include <gtest/gtest.h>

#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "tests/support/scene_compare.hpp"
#include "tests/support/scenes.hpp"

namespace lr {
namespace {

host::HostMesh torus_knot() {
  host::HostMesh m;
  std::string err;
  EXPECT_TRUE(
      host::load_obj(std::string(LR_SOURCE_DIR) + "/tests/host/data/torus_knot.obj", m, err))
      << err;
  return m;
}

host::SceneOptions gold() {
  return test::gold_options();
}

TEST(Accuracy, GouraudTorusKnotWithinOneLevelOnAlmostEveryPixel) {
  host::HostMesh mesh = torus_knot();
  ASSERT_EQ(mesh.triangles.size(), 4000u);
  test::Comparison c;
  std::string err;
  ASSERT_TRUE(test::compare_scene(mesh, gold(), c, err)) << err;
  std::printf("gouraud torus knot: %s\n", c.summary().c_str());
  // The knot fitted to radius 1 at distance 3 is a thin tube: it covers about an eighth of the
  // frame.
  EXPECT_GT(c.both, 9000u);
  EXPECT_GE(c.fraction_within1(), 0.999);
  EXPECT_LE(c.max_error, 2);
  EXPECT_LE(c.coverage_diff, c.both / 2000);  // vertices are snapped from slightly different math
}

TEST(Accuracy, GouraudSphereWithHighlightsFromSeveralLights) {
  host::HostMesh mesh = host::make_uv_sphere(40, 60);
  host::SceneOptions o = test::sphere_four_lights();
  o.width = 240;
  o.height = 240;
  test::Comparison c;
  std::string err;
  ASSERT_TRUE(test::compare_scene(mesh, o, c, err)) << err;
  std::printf("gouraud sphere, 4 lights: %s\n", c.summary().c_str());
  EXPECT_GT(c.both, test::kUnitSpherePixels);
  EXPECT_GE(c.fraction_within1(), 0.999);
  EXPECT_LE(c.max_error, 2);
}

TEST(Accuracy, LocalViewerAndFlatShading) {
  host::HostMesh mesh = torus_knot();
  host::SceneOptions o = gold();
  o.local_viewer = true;
  o.shading = Shading::kFlat;
  test::Comparison c;
  std::string err;
  ASSERT_TRUE(test::compare_scene(mesh, o, c, err)) << err;
  std::printf("flat, local viewer: %s\n", c.summary().c_str());
  EXPECT_GT(c.both, 9000u);  // the knot's coverage, as in the Gouraud test above
  // One colour per triangle: the error is the lighting arithmetic, except on the few pixels
  // along shared edges whose owner differs because a vertex snapped one subpixel apart (the
  // core projects in fixed point): there the neighbour's flat colour shows.
  EXPECT_GE(c.fraction_within1(), 0.999);
}

TEST(Accuracy, UnlitVertexColoursInterpolatePerspectiveCorrectly) {
  host::HostMesh mesh = host::make_grid(1, 1);  // two large triangles: interpolation shows
  host::set_colors_from_normals(mesh);
  // Give the grid a colour ramp along x and y so that interpolation shows.
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    mesh.colors[i] = {0.5 + 0.5 * mesh.positions[i][0], 0.5 + 0.5 * mesh.positions[i][1], 0.25};
  host::SceneOptions o;
  o.unlit = true;
  o.model_rotate_y = 0;
  o.eye = {0, -2.2, 1.2};  // a steep view: strong perspective
  test::Comparison c;
  std::string err;
  ASSERT_TRUE(test::compare_scene(mesh, o, c, err)) << err;
  std::printf("unlit perspective grid: %s\n", c.summary().c_str());
  EXPECT_GT(c.both, 15000u);  // the 2 x 2 square seen steeply from about 2.5 units
  EXPECT_GE(c.fraction_within1(), 0.999);
  EXPECT_LE(c.max_error, 2);
  // Affine interpolation is a quality setting: it must visibly differ on this view.
  o.perspective = Perspective::kAffine;
  test::Comparison a;
  ASSERT_TRUE(test::compare_scene(mesh, o, a, err)) << err;
  std::printf("unlit affine grid: %s\n", a.summary().c_str());
  EXPECT_GT(a.both, 15000u);
  EXPECT_GT(a.max_error, 8);
}

}  // namespace
}  // namespace lr
