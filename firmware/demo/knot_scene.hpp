// The README's demo scene: the 4,000-triangle torus knot in the classic "gold" material, lit by
// the CLI's default light, Gouraud-shaded, depth-tested, 320x240. The same frame as
// sim: --obj tests/host/data/torus_knot.obj --fit --material gold --width 320 --height 240
// (scripts/ci_firmware.sh runs lineraster-sim with the arguments after "sim:" above).
#pragma once

#include <cstddef>

#include "firmware/demo/scene.hpp"
#include "knot_asset.hpp"  // generated at build time: lineraster-asset --obj torus_knot.obj --fit
#include "lineraster/core/scene/material.hpp"
#include "lineraster/core/scene/mesh.hpp"
#include "lineraster/core/span/span_state.hpp"

namespace lr::fw::demo::knot {

namespace asset = ::knot_asset;
inline constexpr const char* kName = "knot";
inline constexpr int kWidth = 320, kHeight = 240;
inline constexpr int kStripRows = 8;
inline constexpr size_t kClipMargin = 16;  // vertices and triangles clipping may add
// Triangles on one strip at once: 565 at most for this view (lineraster-sim --stats:
// max_active), plus room for a slightly different view.
inline constexpr size_t kActiveCapacity = 640;
inline constexpr SceneView kView = kSimDefaultView;
inline constexpr LightSet kLights = sim_default_lights();
inline constexpr Rgb8 kBackground{0, 0, 0};

// --material gold replaces the mesh's material (the knot has none).
inline Material material(size_t) {
  const NamedMaterial* gold = find_material("gold");
  return gold != nullptr ? to_material(*gold) : Material{};
}

inline DrawState state(size_t) {
  DrawState s;  // Gouraud, lit, depth test, no culling: the CLI's defaults
  return s;
}

// The span state of state(): Gouraud, lit, depth test, perspective-exact colours.
inline constexpr SpanSet kSpans = kUntexturedSpans.only_depth(true).only(ColorPlanes::kPerspective);

}  // namespace lr::fw::demo::knot
