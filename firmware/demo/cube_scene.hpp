// A textured, lit cube seen from above one corner: the two-material cube of tests/host/data
// (one material with a 64x64 checker texture in RGB565, sampled bilinear with perspective-exact
// coordinates, the other untextured red), 320x240. Small enough for a 16 KB-RAM Cortex-M0+
// (the micro:bit board). The same frame as
// sim: --obj tests/host/data/cube.obj --fit --eye 2,1.6,2.6 --width 320 --height 240
#pragma once

#include <cstddef>

#include "cube_asset.hpp"  // generated at build time: lineraster-asset --obj cube.obj --fit
#include "firmware/demo/scene.hpp"
#include "lineraster/core/scene/mesh.hpp"
#include "lineraster/core/span/span_state.hpp"

namespace lr::fw::demo::cube {

namespace asset = ::cube_asset;
inline constexpr const char* kName = "cube";
inline constexpr int kWidth = 320, kHeight = 240;
// LR_DEMO_SMALL_RAM: the 16 KB of a micro:bit. Strips of 2 rows (two RGB888 strip buffers of
// 1,920 B, a depth strip of 1,280 B), stores exactly as large as the cube (24 vertices, 12
// triangles; this view clips nothing, and a store that ran out would fail the run loudly), 4
// active triangles (this view has up to 10 on one strip: those strips are drawn in passes,
// docs/bands.md). The stack gets the rest (scripts/footprint.sh checks the static worst case
// against it).
#if LR_DEMO_SMALL_RAM
inline constexpr int kStripRows = 2;
inline constexpr size_t kClipMargin = 0;
inline constexpr size_t kActiveCapacity = 4;
#else
inline constexpr int kStripRows = 8;
inline constexpr size_t kClipMargin = 16;      // vertices and triangles clipping may add
inline constexpr size_t kActiveCapacity = 12;  // every triangle of the cube
#endif
inline constexpr SceneView kView{kSimDefaultView.fovy, kSimDefaultView.near,   kSimDefaultView.far,
                                 vec(2, 1.6, 2.6),     kSimDefaultView.target, kSimDefaultView.up};
inline constexpr LightSet kLights = sim_default_lights();
inline constexpr Rgb8 kBackground{0, 0, 0};

// The mesh's own materials (cube.mtl), as the CLI uses them.
inline Material material(size_t draw) {
  return asset::materials[draw];
}

inline DrawState state(size_t draw) {
  DrawState s;  // Gouraud, lit, depth test, no culling, perspective-exact: the CLI's defaults
  if (asset::textured[draw]) {
    s.texture = &asset::texture;
    s.sampler.filter = Filter::kBilinear;
    s.sampler.wrap_s = s.sampler.wrap_t = Wrap::kRepeat;
    s.sampler.mip = MipMode::kNone;
    s.sampler.env = TexEnv::kModulate;
  }
  return s;
}

// The span states of state(): Gouraud, lit, depth test, perspective-exact colours; the textured
// draw bilinear, repeat, level 0 only, modulated, in the asset texture's format. The renderer
// links these routines and this fetcher only (a product set: each family's masks apply to it).
inline constexpr SpanSet kSpans = kTexturedSpans.only_depth(true)
                                      .only(ColorPlanes::kPerspective)
                                      .only(TexPersp::kExact)
                                      .only(TexEnv::kModulate)
                                      .only(MipMode::kNone)
                                      .only(Filter::kBilinear)
                                      .only(asset::texture.format)
                                      .only_wraps(Wrap::kRepeat, Wrap::kRepeat);

}  // namespace lr::fw::demo::cube
