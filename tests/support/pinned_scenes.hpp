// The scenes whose frames the tests pin: each is hashed on every host and core
// (tests/core/frame_hash_test.cpp: the same bytes everywhere) and measured against the double
// reference (tests/core/frame_accuracy_test.cpp: not worse than recorded). Eight 320x240 frames
// that exercise the main paths (Gouraud and flat lighting, highlights from four lights with the
// local viewer, clipping at the near plane with the guard band, trilinear and nearest-mip
// perspective texturing through an MTL file, Phong lighting exact and from a nearest lighting
// table) and three small 160x120 ones (they were the golden images).
#pragma once

#include <array>
#include <memory>
#include <string>

#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/support/scene_compare.hpp"
#include "tests/support/scenes.hpp"

namespace lr::test {

enum class Pinned {
  kGouraudTorusKnot,     // the gold torus knot, one light, strips of 16
  kGroundTrilinear,      // the textured ground plane to the horizon: bilinear, linear mips
  kFlatSphere,           // a 12 x 18 UV sphere, flat, two lights, back faces culled, strips of 4
  kGroundClipped,        // a coloured ground plane through the near plane, unlit, strips of 1
  kGouraudSphereLights,  // a 40 x 60 UV sphere, four lights with highlights, local viewer
  kTexturedCube,         // cube.obj + cube.mtl (one material textured), span16, nearest mips
  kPhongSphere,          // a 40 x 60 UV sphere, Phong, two lights, exact per-pixel lighting
  kPhongTableNearest,    // the same lit from a 32-cell lighting table, nearest sample
  kSmallTorusKnot,       // 160x120: the gold torus knot
  kSmallFlatSphere,      // 160x120: the flat sphere
  kSmallGroundUnlit,     // 160x120: a ground plane with vertex colours to far away, unlit
};

inline constexpr std::array<Pinned, 11> kPinnedScenes = {
    Pinned::kGouraudTorusKnot, Pinned::kGroundTrilinear,     Pinned::kFlatSphere,
    Pinned::kGroundClipped,    Pinned::kGouraudSphereLights, Pinned::kTexturedCube,
    Pinned::kPhongSphere,      Pinned::kPhongTableNearest,   Pinned::kSmallTorusKnot,
    Pinned::kSmallFlatSphere,  Pinned::kSmallGroundUnlit};

struct PinnedScene {
  std::string name;  // as frame_hash_test prints it
  host::HostMesh mesh;
  host::SceneOptions options;
  std::unique_ptr<host::HostTexture> texture;  // options.texture_object points here, if set
};

inline std::string host_data(const char* file) {
  return std::string(LR_SOURCE_DIR) + "/tests/host/data/" + file;
}

inline host::SceneOptions small_frame(host::SceneOptions o = {}) {
  o.width = 160;
  o.height = 120;
  return o;
}

inline host::SceneOptions flat_sphere_options(host::SceneOptions o) {
  o.shading = Shading::kFlat;
  o.light_dirs = {{1, 1, 1}, {-1, -0.2, 0.4}};
  o.material.diffuse = {0.2, 0.5, 0.9};
  o.cull = Cull::kBack;
  return o;
}

// The scene; false with a one-line error when a file does not load.
inline bool pinned_scene(Pinned id, PinnedScene& s, std::string& error) {
  s = PinnedScene{};
  switch (id) {
    case Pinned::kGouraudTorusKnot:
      s.name = "gouraud_torus_knot";
      s.options = gold_options();  // 320 x 240, Gouraud, one light
      s.options.strip_height = 16;
      return host::load_obj(host_data("torus_knot.obj"), s.mesh, error);
    case Pinned::kGroundTrilinear:
      s.name = "ground_trilinear";
      s.texture = std::make_unique<host::HostTexture>();
      if (!host::texture_from_image(pattern(64, 64), TexelFormat::kRgb565, true, *s.texture, error))
        return false;
      // The textured ground plane to the horizon (as in texture_test.cpp), seen from 1 unit
      // above it.
      s.mesh = ground_plane(200, 200);
      s.options = ground_view();
      s.options.texture_object = &s.texture->texture;
      s.options.filter = Filter::kBilinear;
      s.options.mipmap = MipMode::kLinear;
      s.options.perspective = Perspective::kExact;
      return true;
    case Pinned::kFlatSphere:
      s.name = "flat_sphere";
      s.mesh = host::make_uv_sphere(12, 18);
      s.options = flat_sphere_options({});
      s.options.strip_height = 4;
      return true;
    case Pinned::kGroundClipped:
      // Both triangles cross the near plane; the near corners project to |x_ndc| ~ 100 (guard
      // band).
      s.name = "ground_clipped";
      s.mesh = coloured_ground(50);
      s.options.unlit = true;
      s.options.eye = {0, 1, 0};
      s.options.target = {0, 0.7, -5};
      s.options.far = 200;
      s.options.strip_height = 1;
      return true;
    case Pinned::kGouraudSphereLights:
      // Specular highlights (the power table) from four lights, local viewer, global ambient.
      s.name = "gouraud_sphere_4_lights";
      s.mesh = host::make_uv_sphere(40, 60);
      s.options = sphere_four_lights();
      s.options.local_viewer = true;
      return true;
    case Pinned::kTexturedCube:
      // cube.obj names checker.png through cube.mtl: the texture comes through libpng.
      s.name = "textured_cube";
      s.options.eye = {2.2, 1.6, 3.1};
      s.options.model_rotate_y = 20;
      s.options.filter = Filter::kBilinear;
      s.options.mipmap = MipMode::kNearest;
      s.options.perspective = Perspective::kSpan16;
      s.options.strip_height = 32;
      return host::load_obj(host_data("cube.obj"), s.mesh, error);
    case Pinned::kPhongSphere:
      s.name = "phong_sphere";
      s.mesh = host::make_uv_sphere(40, 60);
      s.options = phong_sphere();
      return true;
    case Pinned::kPhongTableNearest:
      // The table's nearest sample: the cheapest per-pixel lighting (the bilinear table is the
      // default kTable; tests/core/phong_accuracy_test.cpp bounds it).
      s.name = "phong_table_nearest";
      s.mesh = host::make_uv_sphere(40, 60);
      s.options = phong_sphere();
      s.options.pixel_lighting = PixelLighting::kTable;
      s.options.table = {32, false};
      return true;
    case Pinned::kSmallTorusKnot:
      s.name = "small_torus_knot";
      s.options = gold_options(small_frame());
      return host::load_obj(host_data("torus_knot.obj"), s.mesh, error);
    case Pinned::kSmallFlatSphere:
      s.name = "small_flat_sphere";
      s.mesh = host::make_uv_sphere(12, 18);
      s.options = flat_sphere_options(small_frame());
      return true;
    case Pinned::kSmallGroundUnlit:
      s.name = "small_ground_unlit";
      s.mesh.positions = {{-40, 0, -40}, {40, 0, -40}, {40, 0, 40}, {-40, 0, 40}};
      s.mesh.normals.assign(4, {0, 1, 0});
      s.mesh.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
      s.mesh.triangles = {{0, 3, 2}, {0, 2, 1}};
      s.mesh.triangle_material = {-1, -1};
      s.options = small_frame();
      s.options.unlit = true;
      s.options.eye = {0, 1, 0};
      s.options.target = {0, 0.6, -5};
      s.options.background = {0.1, 0.1, 0.2};
      return true;
  }
  error = "unknown pinned scene";
  return false;
}

}  // namespace lr::test
