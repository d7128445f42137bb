// The Cortex-M benchmark cases: each a scene (mesh and texture from flash arrays made by
// lineraster-asset at build time), a camera, lights and one draw state, rendered at 320x240.
//   knot_*     the 4,000-triangle torus knot in "gold", about 22,700 pixels, in each shading mode
//              (unlit, flat, Gouraud, Phong exact, Phong with a 32-cell bilinear lighting table)
//   cube_*     a perspective-correct textured cube (64x64 RGB565 tiles with mipmaps), back faces
//              culled, about 40,600 pixels: nearest, bilinear
//   ground_*   the ground plane to the horizon (two triangles, 100 texture repeats, unlit, lower
//              half of the screen, 38,080 pixels): nearest, bilinear, trilinear
// Each case is also lineraster-sim's frame for the arguments in its `sim` string (RGB888 there,
// RGB565 here); the numbers below are the CLI's, converted at compile time (see
// firmware/demo/scene.hpp).
#pragma once

#include <array>
#include <cstddef>

#include "bench_cube_asset.hpp"  // lineraster-asset --obj cube.obj --fit --texture tiles64.png --mipmaps
#include "bench_ground_asset.hpp"  // lineraster-asset --obj ground.obj --mipmaps
#include "bench_knot_asset.hpp"    // lineraster-asset --obj torus_knot.obj --fit
#include "core/material.hpp"
#include "core/mesh.hpp"
#include "firmware/demo/scene.hpp"

namespace lr::fw::bench {

using demo::SceneView;
using demo::vec;

enum class Mesh3 : uint8_t { kKnot, kCube, kGround };

struct BenchCase {
  const char* name;
  const char* sim;  // lineraster-sim arguments of the same frame
  Mesh3 mesh;
  SceneView view;
  LightSet lights;
  int rotate_y_deg;  // model rotation about y, whole degrees
  bool gold;         // --material gold instead of the mesh's materials
  DrawState state;   // texture pointers are filled in by textured() below
};

consteval LightSet one_light(double x, double y, double z) {
  LightSet s;
  s.lights[0] = demo::white_directional(x, y, z);
  s.count = 1;
  return s;
}

consteval DrawState shading(Shading sh, bool lit = true) {
  DrawState s;
  s.shading = sh;
  s.lighting = lit;
  return s;
}

consteval DrawState phong_table32() {
  DrawState s = shading(Shading::kPhong);
  s.pixel_lighting = PixelLighting::kTable;
  s.table = LightingTableSpec{32, true};
  return s;
}

consteval DrawState textured(Filter f, MipMode mip, bool lit, Cull cull) {
  DrawState s;
  s.lighting = lit;
  s.cull = cull;
  s.sampler.filter = f;
  s.sampler.wrap_s = s.sampler.wrap_t = Wrap::kRepeat;
  s.sampler.mip = mip;
  s.sampler.env = lit ? TexEnv::kModulate : TexEnv::kReplace;
  return s;
}

inline constexpr SceneView kKnotView{demo::kSimDefaultView.fovy, demo::kSimDefaultView.near,
                                     demo::kSimDefaultView.far, vec(0, 0, 2.4),
                                     demo::kSimDefaultView.target, demo::kSimDefaultView.up};
inline constexpr SceneView kCubeView{demo::kSimDefaultView.fovy, demo::kSimDefaultView.near,
                                     demo::kSimDefaultView.far, vec(0, 0.81, 1.35),
                                     demo::kSimDefaultView.target, demo::kSimDefaultView.up};
inline constexpr SceneView kGroundView{demo::kSimDefaultView.fovy, demo::kSimDefaultView.near,
                                       Fixed::from_double(400.0), vec(0.0173, 1.0131, 0.0219),
                                       vec(0.0173, 1.0131, -5), demo::kSimDefaultView.up};

#define LR_KNOT "--obj tests/host/data/torus_knot.obj --fit --material gold --eye 0,0,2.4"
#define LR_CUBE                                                                               \
  "--obj tests/host/data/cube.obj --fit --texture tests/host/data/tiles64.png --mipmap none " \
  "--eye 0,0.81,1.35 --model-rotate-y 35 --cull back --light-dir -0.3,1,0.8"
#define LR_GROUND                                                                         \
  "--obj tests/host/data/ground.obj --eye 0.0173,1.0131,0.0219 --target 0.0173,1.0131,-5 " \
  "--far 400 --unlit"

inline constexpr std::array kCases = {
    BenchCase{"knot_unlit", LR_KNOT " --unlit", Mesh3::kKnot, kKnotView,
              demo::sim_default_lights(), 0, true, shading(Shading::kGouraud, false)},
    BenchCase{"knot_flat", LR_KNOT " --shading flat", Mesh3::kKnot, kKnotView,
              demo::sim_default_lights(), 0, true, shading(Shading::kFlat)},
    BenchCase{"knot_gouraud", LR_KNOT, Mesh3::kKnot, kKnotView, demo::sim_default_lights(), 0,
              true, shading(Shading::kGouraud)},
    BenchCase{"knot_phong", LR_KNOT " --shading phong", Mesh3::kKnot, kKnotView,
              demo::sim_default_lights(), 0, true, shading(Shading::kPhong)},
    BenchCase{"knot_phong_table32", LR_KNOT " --shading phong --lighting table --lighting-table 32",
              Mesh3::kKnot, kKnotView, demo::sim_default_lights(), 0, true, phong_table32()},
    BenchCase{"cube_nearest", LR_CUBE " --filter nearest", Mesh3::kCube, kCubeView,
              one_light(-0.3, 1, 0.8), 35, false,
              textured(Filter::kNearest, MipMode::kNone, true, Cull::kBack)},
    BenchCase{"cube_bilinear", LR_CUBE " --filter bilinear", Mesh3::kCube, kCubeView,
              one_light(-0.3, 1, 0.8), 35, false,
              textured(Filter::kBilinear, MipMode::kNone, true, Cull::kBack)},
    BenchCase{"ground_nearest", LR_GROUND " --filter nearest", Mesh3::kGround, kGroundView,
              demo::sim_default_lights(), 0, false,
              textured(Filter::kNearest, MipMode::kNone, false, Cull::kNone)},
    BenchCase{"ground_bilinear", LR_GROUND " --filter bilinear", Mesh3::kGround, kGroundView,
              demo::sim_default_lights(), 0, false,
              textured(Filter::kBilinear, MipMode::kNone, false, Cull::kNone)},
    BenchCase{"ground_trilinear", LR_GROUND " --filter bilinear --mipmap linear", Mesh3::kGround,
              kGroundView, demo::sim_default_lights(), 0, false,
              textured(Filter::kBilinear, MipMode::kLinear, false, Cull::kNone)},
};

#undef LR_KNOT
#undef LR_CUBE
#undef LR_GROUND

// The meshes of a case's asset.
inline std::span<const lr::Mesh> meshes(Mesh3 m) {
  switch (m) {
    case Mesh3::kKnot:
      return bench_knot_asset::meshes;
    case Mesh3::kCube:
      return bench_cube_asset::meshes;
    case Mesh3::kGround:
      break;
  }
  return bench_ground_asset::meshes;
}

inline Material material(const BenchCase& c, size_t draw) {
  if (c.gold) {
    const NamedMaterial* gold = find_material("gold");
    return gold != nullptr ? to_material(*gold) : Material{};
  }
  return c.mesh == Mesh3::kCube ? bench_cube_asset::materials[draw]
                                : bench_ground_asset::materials[draw];
}

inline const Texture* texture(const BenchCase& c) {
  switch (c.mesh) {
    case Mesh3::kCube:
      return &bench_cube_asset::texture;
    case Mesh3::kGround:
      return &bench_ground_asset::texture;
    case Mesh3::kKnot:
      break;
  }
  return nullptr;
}

}  // namespace lr::fw::bench
