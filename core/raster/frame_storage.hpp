// Storage for one frame, owned by the caller: every store the renderer's parts use, as spans.
// FrameStorage is what Renderer::configure takes; FrameCapacities sizes every store from a few
// numbers, and StaticFrameStorage<caps> holds them (a static in firmware, constexpr-sized).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "lineraster/core/binning/front_end.hpp"
#include "lineraster/core/raster/strip_loop.hpp"

namespace lr {

// Capacities are the spans' sizes (at most 65535 vertices and triangles). A frame larger than
// the vertex, triangle or active stores is drawn in bands or passes, identically
// (docs/bands.md, with the minimum capacities); below the minimum work is dropped, counted in
// FrameStats and reported by render(). The order is that of the aggregate initialisers callers
// write: FrameStorage{vertices, triangles, draws, buckets, active, active_index, depth, ...}.
struct FrameStorage {
  std::span<ScreenVertex> vertices;
  std::span<BinnedTriangle> triangles;
  std::span<DrawRecord> draws;
  std::span<uint16_t> buckets;       // one per strip: ceil(height / K)
  std::span<ActiveTriangle> active;  // triangles being rasterized at once
  std::span<uint16_t> active_index;  // 2 x active.size(): draw order and free slots
  std::span<uint16_t> depth;         // width x K (16-bit depth of one strip)
  // Phong draws only (may stay empty otherwise): one SurfaceVertex per vertex-store entry
  // (give it the size of `vertices`), and the pool the normal-indexed lighting tables of
  // PixelLighting::kTable draws are filled into ((size + 1)^2 words per table, twice that for
  // textured draws; draws with equal material, lights and table spec share one table).
  std::span<SurfaceVertex> surfaces{};
  std::span<uint32_t> lighting_tables{};
  // Phong draws: lighting prepared per material (draws of equal materials share an entry).
  std::span<PreparedLighting> pixel_lights{};
  // Skipping unchanged strips (core/binning/strip_inputs.hpp; may stay empty: every strip is
  // rendered): 2 x ceil(height / K) words, this frame's input signature of each strip and the
  // last rendered frame's. The renderer leaves out a strip whose signatures agree when its sink
  // retains the previous frame (StripSink::retains_frame).
  std::span<uint32_t> strip_inputs{};
  // Textured draws, and Phong draws with a texture or a normal map (may stay empty otherwise):
  // their vertices' texture coordinates and secondary colours, one TexVertex per vertex-store
  // entry (give it the size of `vertices`; a smaller one sends every such mesh larger than it
  // through the vertex cache, docs/bands.md).
  std::span<TexVertex> tex_vertices{};
  // Textured and Phong draws (may stay empty otherwise): the planes of those families, one
  // ActiveExtra per active slot (give it the size of `active`). Without it such draws are
  // refused (kCapacity).
  std::span<ActiveExtra> active_extra{};
  // Flat-shaded draws (may stay empty otherwise): each binned triangle's colours, one
  // TriangleColors per entry of `triangles` (give it that size). Without it such draws are
  // refused (kCapacity).
  std::span<TriangleColors> triangle_colors{};

  // The parts' shares.
  FrontEndStorage front_end() const {
    return {vertices,        triangles,    draws,        buckets,      surfaces,
            lighting_tables, pixel_lights, strip_inputs, tex_vertices, !active_extra.empty(),
            triangle_colors};
  }
  StripStorage strip_loop() const { return {active, active_index, depth, active_extra}; }
};

// How much one frame may hold at once. Every store's size follows from these (the accessors
// below); see FrameStorage for what happens when a frame needs more.
struct FrameCapacities {
  int width = 0, height = 0;  // the viewport
  int strip_height = 8;       // the renderer's K
  size_t vertices = 0;        // vertex store: mesh vertices of every draw, and clipped polygons
  size_t triangles = 0;       // binned triangles
  size_t draws = 1;           // draw records (draw() and draw_screen() calls), at most 256
  size_t active = 0;          // triangles crossing one strip at once
  // Phong draws only.
  size_t surfaces = 0;              // SurfaceVertex store: 0, or the size of the vertex store
  size_t lighting_table_words = 0;  // PixelLighting::kTable pool (lighting_table_words())
  size_t pixel_lights = 0;          // materials of per-pixel lit draws
  // Draws with texture coordinates (textured, or Phong with a normal map).
  size_t tex_vertices = 0;  // TexVertex store: 0, or the size of the vertex store
  size_t active_extra = 0;  // ActiveExtra store (textured, Phong): 0, or the size of `active`
  // Flat-shaded draws.
  size_t triangle_colors = 0;   // TriangleColors store: 0, or the size of `triangles`
  bool strip_skipping = false;  // keep strip signatures (2 words per strip)

  constexpr size_t strips() const {
    return static_cast<size_t>((height + strip_height - 1) / strip_height);
  }
  constexpr size_t buckets() const { return strips(); }
  constexpr size_t active_index() const { return 2 * active; }
  constexpr size_t depth() const {
    return static_cast<size_t>(width) * static_cast<size_t>(strip_height);
  }
  constexpr size_t strip_inputs() const { return strip_skipping ? 2 * strips() : 0; }
  friend constexpr bool operator==(const FrameCapacities&, const FrameCapacities&) = default;
};

// The stores of FrameCapacities in fixed-size arrays: a static or global in firmware (every
// default is zero bytes, so the object is constant-initialised into .bss: no constructor runs
// at startup and the image's flash holds none of it).
template <FrameCapacities kCaps>
struct StaticFrameStorage {
  static constexpr FrameCapacities kCapacities = kCaps;
  std::array<PreparedLighting, kCaps.pixel_lights> pixel_lights{};
  std::array<DrawRecord, kCaps.draws> draws{};
  std::array<ActiveTriangle, kCaps.active> active{};
  std::array<ActiveExtra, kCaps.active_extra> active_extra{};
  std::array<ScreenVertex, kCaps.vertices> vertices{};
  std::array<SurfaceVertex, kCaps.surfaces> surfaces{};
  std::array<TexVertex, kCaps.tex_vertices> tex_vertices{};
  std::array<BinnedTriangle, kCaps.triangles> triangles{};
  std::array<TriangleColors, kCaps.triangle_colors> triangle_colors{};
  std::array<uint32_t, kCaps.lighting_table_words> lighting_tables{};
  std::array<uint32_t, kCaps.strip_inputs()> strip_inputs{};
  std::array<uint16_t, kCaps.buckets()> buckets{};
  std::array<uint16_t, kCaps.active_index()> active_index{};
  // Word-aligned whatever precedes it: the strip's depth is cleared with word stores.
  alignas(4) std::array<uint16_t, kCaps.depth()> depth{};

  FrameStorage storage() {
    return {vertices,     triangles,    draws,        buckets,         active,
            active_index, depth,        surfaces,     lighting_tables, pixel_lights,
            strip_inputs, tex_vertices, active_extra, triangle_colors};
  }
};

// The same stores in containers sized at run time: Container<T>(n) holds n value-initialised
// T (e.g. BasicFrameStorage<std::vector> on a host; the core itself allocates nothing).
template <template <class...> class Container>
struct BasicFrameStorage {
  explicit BasicFrameStorage(const FrameCapacities& c)
      : capacities(c),
        pixel_lights(c.pixel_lights),
        draws(c.draws),
        active(c.active),
        active_extra(c.active_extra),
        vertices(c.vertices),
        surfaces(c.surfaces),
        tex_vertices(c.tex_vertices),
        triangles(c.triangles),
        triangle_colors(c.triangle_colors),
        lighting_tables(c.lighting_table_words),
        strip_inputs(c.strip_inputs()),
        buckets(c.buckets()),
        active_index(c.active_index()),
        depth(c.depth()) {}

  FrameCapacities capacities;
  Container<PreparedLighting> pixel_lights;
  Container<DrawRecord> draws;
  Container<ActiveTriangle> active;
  Container<ActiveExtra> active_extra;
  Container<ScreenVertex> vertices;
  Container<SurfaceVertex> surfaces;
  Container<TexVertex> tex_vertices;
  Container<BinnedTriangle> triangles;
  Container<TriangleColors> triangle_colors;
  Container<uint32_t> lighting_tables;
  Container<uint32_t> strip_inputs;
  Container<uint16_t> buckets;
  Container<uint16_t> active_index;
  Container<uint16_t> depth;

  FrameStorage storage() {
    return {vertices,     triangles,    draws,        buckets,         active,
            active_index, depth,        surfaces,     lighting_tables, pixel_lights,
            strip_inputs, tex_vertices, active_extra, triangle_colors};
  }
};

}  // namespace lr
