// The front half of a frame: the vertex stage and triangle setup up to the edge table.
//
// draw() transforms, lights, clips, projects and snaps a mesh's vertices into the vertex store,
// culls its triangles and bins the survivors by their first strip (the edge table: one list head
// per strip, linked through the triangle records in submission order). Nothing here depends on
// the pixel format or the strip height; Renderer<PF, K> adds the strip loop.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/vertex/clip.hpp"
#include "core/output/frame_stats.hpp"
#include "core/lighting/lighting.hpp"
#include "core/lighting/lighting_table.hpp"
#include "core/scene/material.hpp"
#include "core/scene/mesh.hpp"
#include "core/span/sampler.hpp"
#include "core/vertex/screen_vertex.hpp"
#include "core/span/span_state.hpp"
#include "core/output/status.hpp"
#include "core/binning/strip_inputs.hpp"
#include "core/vertex/surface_vertex.hpp"
#include "core/setup/triangle_setup.hpp"

namespace lr {

inline constexpr uint16_t kNoTriangle = 0xFFFF;
inline constexpr size_t kMaxStoreEntries = 0xFFFF;  // indices are uint16; 0xFFFF = none

// A triangle in the edge table: 16 bytes.
struct BinnedTriangle {
  uint16_t v[3];   // vertex store indices
  uint16_t next;   // next triangle of the same bucket (lists are built by prepending, so
                   // they run from the latest submission to the earliest)
  uint8_t draw;    // draw record
  Rgb8 flat;       // flat-shaded colour (the primary colour when textured)
  Rgb8 flat_spec;  // flat-shaded secondary colour of textured, lit draws
  uint8_t reserved;
};
static_assert(sizeof(BinnedTriangle) == 16);

// The per-draw state the strip loop needs: which span routine, and its texture.
struct DrawRecord {
  ColorPlanes colors = ColorPlanes::kNone;  // untextured draws
  bool depth = true;
  bool flat = false;
  const Texture* texture = nullptr;  // textured draws
  // The texel fetchers (fetch, env_fetch, nmap_fetch) are chosen by the Renderer when it renders
  // (Renderer::resolve_fetchers), from the texture's format, the filter and the wraps, in the
  // tables of its SpanSet: firmware links only the fetchers of the states its set admits.
  FetchFn fetch = nullptr;
  Filter filter = Filter::kNearest;  // the sampler's, for the texture and the normal map
  TexPersp persp = TexPersp::kExact;
  uint8_t span_len = 0;  // kSpan: 8, 16 or 32 (zero default: static stores stay in .bss)
  TexEnv env = TexEnv::kModulate;
  MipMode mip = MipMode::kNone;
  Wrap wrap_s = Wrap::kRepeat, wrap_t = Wrap::kRepeat;  // the sampler's, as filter
  // Phong (per-pixel lighting) draws.
  bool phong = false;
  PixelLighting method = PixelLighting::kExact;
  bool two_sided = false;  // back faces get the negated normal
  bool position = false;   // planes of the world position (point lights, local viewer)
  bool table_bilinear = false;
  const PreparedLighting* lighting = nullptr;  // exact mode; the viewer for environment maps
  LightingTable table{};                       // table mode
  const Texture* envmap = nullptr;
  FetchFn env_fetch = nullptr;
  const Texture* normal_map = nullptr;
  FetchFn nmap_fetch = nullptr;
  Mat4 view{};  // the camera's view matrix (environment maps: world to eye directions)
  // Signature of everything above that decides pixels (core/binning/strip_inputs.hpp), with the
  // material of per-pixel lighting; set once per draw when strip skipping is on.
  uint32_t inputs = 0;
};

// Storage for one frame, owned by the caller. Capacities are the spans' sizes (at most 65535
// vertices and triangles); running out drops work and counts it in FrameStats.
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
  // Skipping unchanged strips (core/binning/strip_inputs.hpp; may stay empty: every strip is rendered):
  // 2 x ceil(height / K) words, this frame's input signature of each strip and the last
  // rendered frame's. The renderer leaves out a strip whose signatures agree when its sink
  // retains the previous frame (StripSink::retains_frame).
  std::span<uint32_t> strip_inputs{};
};

class FrameBuilder {
 public:
  // Checks the storage against the viewport (width, height in [1, kMaxViewport]) and strip
  // height. Must succeed before begin_frame.
  Status configure(const FrameStorage& storage, int width, int height, int strip_height);

  // Starts a frame: clears the stores and the statistics.
  Status begin_frame(const Camera& camera, const LightSet& lights, Rgb8 background);

  // Adds a mesh. On a full store the triangles that do not fit are dropped and counted, and
  // kCapacity is returned; what fit is kept. kInvalidArgument (nothing added) when the mesh's
  // arrays disagree in size, Gouraud lighting is asked of a mesh without normals, or the
  // renderer's SpanSet does not admit the draw's span state or its textures (span_state.hpp).
  Status draw(const Mesh& mesh, const Mat4& model, const Material& material,
              const DrawState& state);

  // Adds triangles already in screen space (snapped subpixel positions, depth, colour):
  // for 2D overlays and for tests of the raster rules. Lighting does not apply. kInvalidArgument
  // (nothing added) when the renderer's SpanSet does not admit the draw's span state.
  Status draw_screen(std::span<const ScreenVertex> vertices,
                     std::span<const std::array<uint16_t, 3>> triangles, const DrawState& state);

  const FrameStats& stats() const { return stats_; }
  std::span<const ScreenVertex> screen_vertices() const {
    return storage_.vertices.first(vertex_count_);
  }
  std::span<const BinnedTriangle> binned_triangles() const {
    return storage_.triangles.first(triangle_count_);
  }
  int width() const { return width_; }
  int height() const { return height_; }
  int strip_height() const { return strip_height_; }
  GuardBand guard_band() const { return guard_; }
  // Forgets the strip signatures of the last frame, so that the next render draws every strip:
  // call it after changing texel or table memory in place, or when the display was drawn on by
  // someone else. (configure() and a render that fails or overflows the active list do it too.)
  void invalidate_strips() { inputs_known_ = false; }

 protected:
  enum class BinResult : uint8_t { kBinned, kBackface, kZeroArea, kOffscreen, kCapacity };
  // rows: the triangle's first and last row when classify() already passed it (its tests are
  // not repeated), else nullptr.
  BinResult bin(uint16_t a, uint16_t b, uint16_t c, uint8_t draw, Rgb8 flat, Rgb8 flat_spec,
                Cull cull, const int32_t* rows = nullptr);
  // bin()'s tests without binning: kBinned when the triangle would be binned (capacity aside).
  BinResult classify(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2,
                     Cull cull, int32_t& r0, int32_t& r1) const;
  bool project(const ClipCoord& c, ScreenVertex& out) const;
  Status add_draw_record(const DrawState& state, bool has_color_planes, size_t vertices,
                         uint32_t triangles, uint8_t& index);
  // The span state of a draw (draw(): phong and color_planes as it decides them; draw_screen():
  // phong false), and whether the renderer's set admits it and its textures.
  SpanState span_state(const DrawState& state, bool phong, bool color_planes) const;
  bool admitted(const DrawState& state, bool phong, bool color_planes) const;
  Status add_phong_state(const DrawState& state, const PreparedLighting& pl, DrawRecord& r);
  bool skipping() const { return !storage_.strip_inputs.empty(); }
  // The signature of draw record `index`, once its state is final.
  void sign_draw(uint8_t index, const Material* per_pixel_material);
  bool surfaces_fit(size_t vertices) const {
    return storage_.surfaces.size() >= vertex_count_ &&
           vertices <= storage_.surfaces.size() - vertex_count_;
  }

  FrameStorage storage_{};
  FrameStats stats_{};
  int width_ = 0, height_ = 0, strip_height_ = 1, strips_ = 0;
  GuardBand guard_{};
  Camera camera_{};
  LightSet lights_{};
  Rgb8 background_{};
  size_t vertex_count_ = 0, triangle_count_ = 0, draw_count_ = 0;
  size_t pixel_light_count_ = 0, table_words_used_ = 0;
  bool configured_ = false;
  bool inputs_known_ = false;  // strip_inputs' second half describes the last frame rendered
  // The span states the Renderer links routines for (its SpanSet template argument, a constant
  // in flash: the builder keeps a pointer, as small as the mask it replaces): draws outside it
  // are refused.
  const SpanSet* span_set_ = &kAllSpans;
};

}  // namespace lr
