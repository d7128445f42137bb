// The Cortex-M benchmark cases: each a scene (mesh and texture from flash arrays made by
// lineraster-asset at build time), a camera, lights and one draw state, rendered at 320x240.
//   knot_*     the 4,000-triangle torus knot in "gold", about 22,700 pixels, in each shading mode
//              (unlit, flat, Gouraud, Phong exact, Phong with a 32-cell bilinear lighting table)
//   cube_*     a perspective-correct textured cube (64x64 RGB565 tiles with mipmaps), back faces
//              culled, about 40,600 pixels: nearest, bilinear
//   ground_*   the ground plane to the horizon (two triangles, 100 texture repeats, unlit, lower
//              half of the screen, 38,080 pixels): nearest, bilinear, trilinear
//   knot64k_gouraud  the knot subdivided twice (lineraster-asset --subdivide 2: 64,000
//              triangles, 32,841 vertices), the view and state of knot_gouraud
// Then the cases of the early-out table and of the cost-per-feature table (scripts/
// bench_cortex_m.sh solves them; the comments at kCases say which pairs go together).
// Each case is also lineraster-sim's frame for the arguments in its `sim` string (RGB888 there,
// RGB565 here); the numbers below are the CLI's, converted at compile time (see
// firmware/demo/scene.hpp). Cases with an empty `sim` have no CLI equivalent (a mesh made
// here, or a draw without triangles).
#pragma once

#include <array>
#include <cstddef>

#include "bench_cube_asset.hpp"  // lineraster-asset --obj cube.obj --fit --texture tiles64.png --mipmaps
#include "bench_ground_asset.hpp"   // lineraster-asset --obj ground.obj --mipmaps
#include "bench_knot64k_asset.hpp"  // lineraster-asset --obj torus_knot.obj --fit --subdivide 2
#include "bench_knot_asset.hpp"     // lineraster-asset --obj torus_knot.obj --fit
#include "firmware/bench/knot_view.hpp"
#include "firmware/demo/scene.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/core/scene/mesh.hpp"

namespace lr::fw::bench {

using demo::SceneView;
using demo::vec;

// What a case draws. kKnotVertices: the knot's vertices without its triangles (the vertex stage
// alone: transform and lighting, which draw() does for every vertex). kQuad*: a textured square
// drawn at z = 0 (near) and/or, the same square, at z = -1.2 (far: smaller on the screen and
// entirely behind the near one), in the order named. kNothing: no draw at all.
enum class Mesh3 : uint8_t {
  kKnot,
  kKnot64k,
  kKnotVertices,
  kCube,
  kGround,
  kQuadNear,
  kQuadNearThenFar,
  kQuadFarThenNear,
  kNothing,
};
// The texture of a case: none, the cube's 64x64 tiles (with mipmaps), the ground's.
enum class Tex : uint8_t { kNone, kTiles, kGround };

struct BenchCase {
  const char* name;
  const char* sim;  // lineraster-sim arguments of the same frame
  Mesh3 mesh;
  SceneView view;
  LightSet lights;
  int rotate_y_deg;  // model rotation about y, whole degrees
  bool gold;         // --material gold instead of the mesh's materials
  DrawState state;   // texture pointers are filled in by texture() below
  Tex tex = Tex::kNone;
  uint16_t triangle_store = 0;  // binned-triangle store of the case (0: the benchmark's whole)
  uint16_t vertex_store = 0;    // vertex store, as triangle_store
  uint16_t active_store = 0;    // active list, as triangle_store
  bool shared_fetch = false;    // drawn without the inlined texel fetch (SpanSet::inline_fetch)
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

consteval DrawState textured(Filter f, MipMode mip, bool lit, Cull cull,
                             Perspective persp = Perspective::kExact) {
  DrawState s;
  s.lighting = lit;
  s.cull = cull;
  s.perspective = persp;
  s.sampler.filter = f;
  s.sampler.wrap_s = s.sampler.wrap_t = Wrap::kRepeat;
  s.sampler.mip = mip;
  s.sampler.env = lit ? TexEnv::kModulate : TexEnv::kReplace;
  return s;
}

consteval DrawState with_cull(DrawState s, Cull cull) {
  s.cull = cull;
  return s;
}

consteval DrawState without_depth(DrawState s) {
  s.depth_test = false;
  return s;
}

inline constexpr SceneView kCubeView{demo::kSimDefaultView.fovy,   demo::kSimDefaultView.near,
                                     demo::kSimDefaultView.far,    vec(0, 0.81, 1.35),
                                     demo::kSimDefaultView.target, demo::kSimDefaultView.up};
inline constexpr SceneView kGroundView{demo::kSimDefaultView.fovy, demo::kSimDefaultView.near,
                                       Fixed::from_double(400.0),  vec(0.0173, 1.0131, 0.0219),
                                       vec(0.0173, 1.0131, -5),    demo::kSimDefaultView.up};

// The knot far away (most triangles cover no pixel centre), half as far, and just beside the
// viewport (every triangle off-screen, inside the guard band).
inline constexpr SceneView kKnotFarView{demo::kSimDefaultView.fovy,   demo::kSimDefaultView.near,
                                        demo::kSimDefaultView.far,    vec(0, 0, 24),
                                        demo::kSimDefaultView.target, demo::kSimDefaultView.up};
inline constexpr SceneView kKnotMidView{demo::kSimDefaultView.fovy,   demo::kSimDefaultView.near,
                                        demo::kSimDefaultView.far,    vec(0, 0, 12),
                                        demo::kSimDefaultView.target, demo::kSimDefaultView.up};
inline constexpr SceneView kKnotOffView{demo::kSimDefaultView.fovy,
                                        demo::kSimDefaultView.near,
                                        demo::kSimDefaultView.far,
                                        vec(3.2, 0, 2.4),
                                        vec(3.2, 0, 0),
                                        demo::kSimDefaultView.up};

#define LR_KNOT "--obj tests/host/data/torus_knot.obj --fit --material gold --eye 0,0,2.4"
#define LR_CUBE                                                                               \
  "--obj tests/host/data/cube.obj --fit --texture tests/host/data/tiles64.png --mipmap none " \
  "--eye 0,0.81,1.35 --model-rotate-y 35 --cull back --light-dir -0.3,1,0.8"
#define LR_KNOT_TEX " --texture tests/host/data/tiles64.png --mipmap none"
#define LR_CUBE_UNTEX                                                                       \
  "--obj tests/host/data/cube.obj --fit --eye 0,0.81,1.35 --model-rotate-y 35 --cull back " \
  "--light-dir -0.3,1,0.8"
#define LR_GROUND                                                                          \
  "--obj tests/host/data/ground.obj --eye 0.0173,1.0131,0.0219 --target 0.0173,1.0131,-5 " \
  "--far 400 --unlit"

inline constexpr std::array kCases = {
    BenchCase{"knot_unlit", LR_KNOT " --unlit", Mesh3::kKnot, kKnotView, demo::sim_default_lights(),
              0, true, shading(Shading::kGouraud, false)},
    BenchCase{"knot_flat", LR_KNOT " --shading flat", Mesh3::kKnot, kKnotView,
              demo::sim_default_lights(), 0, true, shading(Shading::kFlat)},
    BenchCase{"knot_gouraud", LR_KNOT, Mesh3::kKnot, kKnotView, demo::sim_default_lights(), 0, true,
              shading(Shading::kGouraud)},
    BenchCase{"knot_phong", LR_KNOT " --shading phong", Mesh3::kKnot, kKnotView,
              demo::sim_default_lights(), 0, true, shading(Shading::kPhong)},
    BenchCase{"knot_phong_table32", LR_KNOT " --shading phong --lighting table --lighting-table 32",
              Mesh3::kKnot, kKnotView, demo::sim_default_lights(), 0, true, phong_table32()},
    BenchCase{"cube_nearest", LR_CUBE " --filter nearest", Mesh3::kCube, kCubeView,
              one_light(-0.3, 1, 0.8), 35, false,
              textured(Filter::kNearest, MipMode::kNone, true, Cull::kBack), Tex::kTiles},
    BenchCase{"cube_bilinear", LR_CUBE " --filter bilinear", Mesh3::kCube, kCubeView,
              one_light(-0.3, 1, 0.8), 35, false,
              textured(Filter::kBilinear, MipMode::kNone, true, Cull::kBack), Tex::kTiles},
    BenchCase{"ground_nearest", LR_GROUND " --filter nearest", Mesh3::kGround, kGroundView,
              demo::sim_default_lights(), 0, false,
              textured(Filter::kNearest, MipMode::kNone, false, Cull::kNone), Tex::kGround},
    BenchCase{"ground_bilinear", LR_GROUND " --filter bilinear", Mesh3::kGround, kGroundView,
              demo::sim_default_lights(), 0, false,
              textured(Filter::kBilinear, MipMode::kNone, false, Cull::kNone), Tex::kGround},
    BenchCase{"ground_trilinear", LR_GROUND " --filter bilinear --mipmap linear", Mesh3::kGround,
              kGroundView, demo::sim_default_lights(), 0, false,
              textured(Filter::kBilinear, MipMode::kLinear, false, Cull::kNone), Tex::kGround},
    // The large mesh: the knot subdivided twice.
    // A closed mesh: back faces culled, as in the budget case of the 4,000-triangle knot
    // (knot_gouraud_cullback).
    BenchCase{"knot64k_gouraud", LR_KNOT " --subdivide 2 --cull back", Mesh3::kKnot64k, kKnotView,
              demo::sim_default_lights(), 0, true, knot64k_state()},

    // Early outs (scripts/bench_cortex_m.sh, second table). Every *_vertices case is the case
    // before it without triangles: the difference is the triangles' cost alone.
    //   back-face: knot_gouraud (no culling) against knot_gouraud_cullback
    BenchCase{"knot_gouraud_cullback", LR_KNOT " --cull back", Mesh3::kKnot, kKnotView,
              demo::sim_default_lights(), 0, true, knot64k_state()},
    BenchCase{"knot_vertices", "", Mesh3::kKnotVertices, kKnotView, demo::sim_default_lights(), 0,
              true, shading(Shading::kGouraud)},
    //   covering no pixel centre: the knot at 24 and at 12 units (two equations: per dropped
    //   and per drawn triangle)
    BenchCase{"knot_far", "--obj tests/host/data/torus_knot.obj --fit --material gold --eye 0,0,24",
              Mesh3::kKnot, kKnotFarView, demo::sim_default_lights(), 0, true,
              shading(Shading::kGouraud)},
    BenchCase{"knot_far_vertices", "", Mesh3::kKnotVertices, kKnotFarView,
              demo::sim_default_lights(), 0, true, shading(Shading::kGouraud)},
    BenchCase{"knot_mid", "--obj tests/host/data/torus_knot.obj --fit --material gold --eye 0,0,12",
              Mesh3::kKnot, kKnotMidView, demo::sim_default_lights(), 0, true,
              shading(Shading::kGouraud)},
    BenchCase{"knot_mid_vertices", "", Mesh3::kKnotVertices, kKnotMidView,
              demo::sim_default_lights(), 0, true, shading(Shading::kGouraud)},
    //   off-screen: the knot beside the viewport
    BenchCase{"knot_offscreen",
              "--obj tests/host/data/torus_knot.obj --fit --material gold --eye 3.2,0,2.4 "
              "--target 3.2,0,0",
              Mesh3::kKnot, kKnotOffView, demo::sim_default_lights(), 0, true,
              shading(Shading::kGouraud)},
    BenchCase{"knot_offscreen_vertices", "", Mesh3::kKnotVertices, kKnotOffView,
              demo::sim_default_lights(), 0, true, shading(Shading::kGouraud)},
    //   depth before texture: a bilinear textured square, and a second one behind it drawn
    //   after it (every pixel hidden) or before it (every pixel written, then overwritten)
    BenchCase{"quad_near", "", Mesh3::kQuadNear, kKnotView, demo::sim_default_lights(), 0, false,
              textured(Filter::kBilinear, MipMode::kNone, false, Cull::kNone), Tex::kTiles},
    BenchCase{"quads_near_then_far", "", Mesh3::kQuadNearThenFar, kKnotView,
              demo::sim_default_lights(), 0, false,
              textured(Filter::kBilinear, MipMode::kNone, false, Cull::kNone), Tex::kTiles},
    BenchCase{"quads_far_then_near", "", Mesh3::kQuadFarThenNear, kKnotView,
              demo::sim_default_lights(), 0, false,
              textured(Filter::kBilinear, MipMode::kNone, false, Cull::kNone), Tex::kTiles},
    //   bands (docs/bands.md): the closed knot with triangle stores too small for its 1,900
    //   binned triangles, and the subdivided knot in a store of 4,096
    BenchCase{"knot_bands_1024", "", Mesh3::kKnot, kKnotView, demo::sim_default_lights(), 0, true,
              with_cull(shading(Shading::kGouraud), Cull::kBack), Tex::kNone, 1024},
    BenchCase{"knot_bands_512", "", Mesh3::kKnot, kKnotView, demo::sim_default_lights(), 0, true,
              with_cull(shading(Shading::kGouraud), Cull::kBack), Tex::kNone, 512},
    BenchCase{"knot_bands_256", "", Mesh3::kKnot, kKnotView, demo::sim_default_lights(), 0, true,
              with_cull(shading(Shading::kGouraud), Cull::kBack), Tex::kNone, 256},
    BenchCase{"knot64k_bands_4096", "", Mesh3::kKnot64k, kKnotView, demo::sim_default_lights(), 0,
              true, with_cull(shading(Shading::kGouraud), Cull::kBack), Tex::kNone, 4096},
    //   the subdivided knot in small stores (108 KB instead of 1.3 MB): 3,072 vertices (its
    //   32,841 go through the vertex cache), 3,072 binned triangles, 64 active triangles
    //   (crowded strips drawn in passes); 2,048 of either does not hold its fullest strip
    BenchCase{"knot64k_small_stores", "", Mesh3::kKnot64k, kKnotView, demo::sim_default_lights(), 0,
              true, with_cull(shading(Shading::kGouraud), Cull::kBack), Tex::kNone, 3072, 3072, 64},
    //   empty strips: no draw at all
    BenchCase{"empty", "", Mesh3::kNothing, kKnotView, demo::sim_default_lights(), 0, false,
              shading(Shading::kGouraud)},

    // Cost per feature (scripts/bench_cortex_m.sh, third table): pairs that differ in one
    // feature, on the knot (many small triangles) and on the cube (a few large ones).
    BenchCase{"knot_gouraud_nodepth", LR_KNOT " --no-depth", Mesh3::kKnot, kKnotView,
              demo::sim_default_lights(), 0, true, without_depth(shading(Shading::kGouraud))},
    BenchCase{"knot_nearest", LR_KNOT LR_KNOT_TEX " --filter nearest", Mesh3::kKnot, kKnotView,
              demo::sim_default_lights(), 0, true,
              textured(Filter::kNearest, MipMode::kNone, true, Cull::kNone), Tex::kTiles},
    BenchCase{"knot_nearest_span16", LR_KNOT LR_KNOT_TEX " --filter nearest --perspective span16",
              Mesh3::kKnot, kKnotView, demo::sim_default_lights(), 0, true,
              textured(Filter::kNearest, MipMode::kNone, true, Cull::kNone, Perspective::kSpan16),
              Tex::kTiles},
    BenchCase{"knot_nearest_affine", LR_KNOT LR_KNOT_TEX " --filter nearest --perspective affine",
              Mesh3::kKnot, kKnotView, demo::sim_default_lights(), 0, true,
              textured(Filter::kNearest, MipMode::kNone, true, Cull::kNone, Perspective::kAffine),
              Tex::kTiles},
    BenchCase{"knot_bilinear", LR_KNOT LR_KNOT_TEX " --filter bilinear", Mesh3::kKnot, kKnotView,
              demo::sim_default_lights(), 0, true,
              textured(Filter::kBilinear, MipMode::kNone, true, Cull::kNone), Tex::kTiles},
    BenchCase{"knot_trilinear",
              LR_KNOT " --texture tests/host/data/tiles64.png --mipmap linear --filter bilinear",
              Mesh3::kKnot, kKnotView, demo::sim_default_lights(), 0, true,
              textured(Filter::kBilinear, MipMode::kLinear, true, Cull::kNone), Tex::kTiles},
    BenchCase{"cube_gouraud", LR_CUBE_UNTEX, Mesh3::kCube, kCubeView, one_light(-0.3, 1, 0.8), 35,
              false, with_cull(shading(Shading::kGouraud), Cull::kBack)},
    BenchCase{"cube_gouraud_nodepth", LR_CUBE_UNTEX " --no-depth", Mesh3::kCube, kCubeView,
              one_light(-0.3, 1, 0.8), 35, false,
              without_depth(with_cull(shading(Shading::kGouraud), Cull::kBack))},
    BenchCase{"cube_flat", LR_CUBE_UNTEX " --shading flat", Mesh3::kCube, kCubeView,
              one_light(-0.3, 1, 0.8), 35, false, with_cull(shading(Shading::kFlat), Cull::kBack)},
    BenchCase{"cube_phong", LR_CUBE_UNTEX " --shading phong", Mesh3::kCube, kCubeView,
              one_light(-0.3, 1, 0.8), 35, false, with_cull(shading(Shading::kPhong), Cull::kBack)},
    BenchCase{"cube_phong_table32",
              LR_CUBE_UNTEX " --shading phong --lighting table --lighting-table 32", Mesh3::kCube,
              kCubeView, one_light(-0.3, 1, 0.8), 35, false,
              with_cull(phong_table32(), Cull::kBack)},
    BenchCase{"cube_nearest_span16", LR_CUBE " --filter nearest --perspective span16", Mesh3::kCube,
              kCubeView, one_light(-0.3, 1, 0.8), 35, false,
              textured(Filter::kNearest, MipMode::kNone, true, Cull::kBack, Perspective::kSpan16),
              Tex::kTiles},
    BenchCase{"cube_nearest_affine", LR_CUBE " --filter nearest --perspective affine", Mesh3::kCube,
              kCubeView, one_light(-0.3, 1, 0.8), 35, false,
              textured(Filter::kNearest, MipMode::kNone, true, Cull::kBack, Perspective::kAffine),
              Tex::kTiles},
    BenchCase{"cube_trilinear",
              "--obj tests/host/data/cube.obj --fit --texture tests/host/data/tiles64.png "
              "--mipmap linear --eye 0,0.81,1.35 --model-rotate-y 35 --cull back "
              "--light-dir -0.3,1,0.8 --filter bilinear",
              Mesh3::kCube, kCubeView, one_light(-0.3, 1, 0.8), 35, false,
              textured(Filter::kBilinear, MipMode::kLinear, true, Cull::kBack), Tex::kTiles},

    // Sharing (scripts/bench_cortex_m.sh, fourth table): the cube (modulated by the constant
    // colours of its faces) and the ground (replaced) without the inlined texel fetch, against
    // cube_* and ground_* with it: the same frames.
    BenchCase{"cube_nearest_shared", LR_CUBE " --filter nearest", Mesh3::kCube, kCubeView,
              one_light(-0.3, 1, 0.8), 35, false,
              textured(Filter::kNearest, MipMode::kNone, true, Cull::kBack), Tex::kTiles, 0, 0, 0,
              true},
    BenchCase{"cube_bilinear_shared", LR_CUBE " --filter bilinear", Mesh3::kCube, kCubeView,
              one_light(-0.3, 1, 0.8), 35, false,
              textured(Filter::kBilinear, MipMode::kNone, true, Cull::kBack), Tex::kTiles, 0, 0, 0,
              true},
    BenchCase{"ground_nearest_shared", LR_GROUND " --filter nearest", Mesh3::kGround, kGroundView,
              demo::sim_default_lights(), 0, false,
              textured(Filter::kNearest, MipMode::kNone, false, Cull::kNone), Tex::kGround, 0, 0, 0,
              true},
    BenchCase{"ground_bilinear_shared", LR_GROUND " --filter bilinear", Mesh3::kGround, kGroundView,
              demo::sim_default_lights(), 0, false,
              textured(Filter::kBilinear, MipMode::kNone, false, Cull::kNone), Tex::kGround, 0, 0,
              0, true},
};

#undef LR_KNOT
#undef LR_CUBE
#undef LR_GROUND
#undef LR_KNOT_TEX
#undef LR_CUBE_UNTEX

// The knot's vertices without triangles, and the square of the kQuad* scenes (side 2, normal
// +z, four texture repeats each way: Q16.16 positions, Q1.14 normals, Q12.20 uvs).
inline constexpr std::array<lr::Mesh, 1> kKnotVertices{
    lr::Mesh{bench_knot_asset::meshes[0].positions,
             bench_knot_asset::meshes[0].normals,
             bench_knot_asset::meshes[0].colors,
             bench_knot_asset::meshes[0].uvs,
             {}}};
inline constexpr lr::Vec3 kQuadPositions[] = {vec(-1, -1, 0), vec(1, -1, 0), vec(1, 1, 0),
                                              vec(-1, 1, 0)};
inline constexpr lr::Normal16 kQuadNormals[] = {
    {0, 0, 16384}, {0, 0, 16384}, {0, 0, 16384}, {0, 0, 16384}};
inline constexpr lr::TexCoord kQuadUvs[] = {{0, 0}, {4 << 20, 0}, {4 << 20, 4 << 20}, {0, 4 << 20}};
inline constexpr std::array<uint16_t, 3> kQuadTriangles[] = {{0, 1, 2}, {0, 2, 3}};
inline constexpr lr::Mesh kQuad{kQuadPositions, kQuadNormals, {}, kQuadUvs, kQuadTriangles};
inline constexpr std::array<lr::Mesh, 2> kQuads{kQuad, kQuad};

// The meshes a case draws, in order.
inline std::span<const lr::Mesh> meshes(Mesh3 m) {
  switch (m) {
    case Mesh3::kKnot:
      return bench_knot_asset::meshes;
    case Mesh3::kKnot64k:
      return bench_knot64k_asset::meshes;
    case Mesh3::kKnotVertices:
      return kKnotVertices;
    case Mesh3::kCube:
      return bench_cube_asset::meshes;
    case Mesh3::kGround:
      return bench_ground_asset::meshes;
    case Mesh3::kQuadNear:
      return std::span<const lr::Mesh>(kQuads).first(1);
    case Mesh3::kQuadNearThenFar:
    case Mesh3::kQuadFarThenNear:
      return kQuads;
    case Mesh3::kNothing:
      break;
  }
  return {};
}

// The model matrix of a case's draw: the rotation about y, and for the squares their depth.
inline lr::Mat4 model(const BenchCase& c, size_t draw) {
  const bool far = (c.mesh == Mesh3::kQuadNearThenFar && draw == 1) ||
                   (c.mesh == Mesh3::kQuadFarThenNear && draw == 0);
  if (far) return lr::translate(vec(0, 0, -1.2));
  return lr::rotate_y(lr::Fixed::from_int(c.rotate_y_deg));
}

inline Material material(const BenchCase& c, size_t draw) {
  if (c.gold) {
    const NamedMaterial* gold = find_material("gold");
    return gold != nullptr ? to_material(*gold) : Material{};
  }
  switch (c.mesh) {
    case Mesh3::kCube:
      return bench_cube_asset::materials[draw];
    case Mesh3::kGround:
      return bench_ground_asset::materials[draw];
    default:
      break;
  }
  return Material{};
}

inline const Texture* texture(const BenchCase& c) {
  switch (c.tex) {
    case Tex::kTiles:
      return &bench_cube_asset::texture;
    case Tex::kGround:
      return &bench_ground_asset::texture;
    case Tex::kNone:
      break;
  }
  return nullptr;
}

// Whether a case's frame has pixels (the measured frames of the early-out table may have none).
constexpr bool draws_pixels(const BenchCase& c) {
  return c.mesh != Mesh3::kKnotVertices && c.mesh != Mesh3::kNothing &&
         c.view.eye.x.raw != kKnotOffView.eye.x.raw;
}

}  // namespace lr::fw::bench
