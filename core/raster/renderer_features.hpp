// What a renderer links beyond its span routines: the front end's features a scene may not need.
//
// Renderer<PF, K, kSpans, kFeatures> (renderer.hpp) links the code of a feature only when
// kFeatures has it; kAllFeatures, the default, has every one. A renderer without a feature
// refuses what needs it with a status naming it, never draws it wrong (docs/footprint.md):
//  - bands: a frame larger than the stores (docs/bands.md) is drawn as far as the stores hold
//    it, and render() returns kCapacity (FrameStats counts what was dropped);
//  - vertex_cache: a mesh with more vertices than the vertex store (surface, texture-entry
//    store) is refused by draw() with kNotLinked; one larger than the store's free part is
//    dropped as if the store were full (kCapacity, or the next band with bands);
//  - two_sided: a lit Gouraud or flat draw under LightSet::two_sided is refused with kNotLinked;
//  - strip_skipping: configure() with a FrameStorage::strip_inputs store returns kNotLinked;
//  - crowded_strips: in a strip whose triangles (those active and those starting in it)
//    outnumber the active list, the triangles starting in it are dropped (dropped_triangle_-
//    capacity counts them), the others drawn, and render() returns kCapacity;
//  - clipping: a triangle that crosses a clip plane (the near or far plane, or the guard band's
//    edges: a triangle that only crosses the viewport's edges needs none) is dropped and
//    counted in FrameStats::dropped_unclipped, the rest of its draw drawn, and render() returns
//    kNotLinked;
//  - world_lighting: a lit Gouraud or textured draw (per-vertex lighting) is refused by draw()
//    with kNotLinked unless it can be lit in model space: directional lights and the infinite
//    viewer, a rigid model matrix (a rotation times a uniform scale, within core/math/rigid.hpp's
//    tolerance) and normals of unit length (within 2^-12: unit_normal(), object_lights.hpp; the
//    project's meshes have them). Those draws are lit the same either way; without it the
//    world-space path (the normal matrix's transform and normalisation of each normal) is left
//    out. Flat-shaded faces and Phong keep their own world-space lighting;
//  - specular: a lit draw whose material has a specular colour (Material::specular not zero)
//    is refused by draw() with kNotLinked (diffuse materials, as the peer scenes', are drawn
//    the same: their specular term is zero). Without it the per-vertex lighting links no
//    specular term and no power tables (2 KB).
// A draw that needs none of them gives the same frame in every configuration.
#pragma once

namespace lr {

struct RendererFeatures {
  bool bands = true;           // frames larger than the stores, in bands of strips
  bool vertex_cache = true;    // meshes larger than the vertex store, through the cache
  bool two_sided = true;       // two-sided lighting (LightSet::two_sided)
  bool strip_skipping = true;  // strips whose inputs did not change not rendered again
  bool crowded_strips = true;  // strips with more triangles than the active list, in passes
  bool specular = true;        // materials with a specular colour (highlights)
  bool clipping = true;        // triangles crossing the near or far plane or the guard band
  bool world_lighting = true;  // per-vertex lighting beyond rigid models, unit normals, far lights

  constexpr bool operator==(const RendererFeatures&) const = default;
};

// Every feature: the default, what every renderer had before the features were chosen.
inline constexpr RendererFeatures kAllFeatures{};
// None of them: the smallest renderer, for a scene whose frame fits its stores (its active list
// too, in every strip), one-sided directional lighting of rigid models with unit normals,
// diffuse materials, no triangle crossing the near or far plane or the guard band, every strip
// rendered each frame
// (the footprint images, which add specular where their material has it:
// docs/measurements/footprint.md).
inline constexpr RendererFeatures kNoFeatures{false, false, false, false,
                                              false, false, false, false};

}  // namespace lr
