// The front half of a frame: the vertex stage and binning, up to the edge table.
//
// draw() transforms, lights, clips, projects and snaps a mesh's vertices into the vertex store
// (core/vertex/vertex_stage.hpp, vertex_store.hpp), culls its triangles and bins the survivors by
// their first strip (core/binning/edge_table.hpp), each draw with a record of its state
// (core/binning/draw_records.hpp). A vertex position goes one way: the mesh, the vertex stage,
// the vertex store, the triangle loop here, the edge table. Nothing here depends on the pixel
// format or the strip height's type: the strip loop reads what was binned through frame() (a
// BinnedFrame).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "lineraster/core/binning/binned_triangle.hpp"
#include "lineraster/core/binning/draw_record.hpp"
#include "lineraster/core/binning/draw_records.hpp"
#include "lineraster/core/binning/edge_table.hpp"
#include "lineraster/core/binning/outcome.hpp"
#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/lighting/object_lights.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/output/frame_stats.hpp"
#include "lineraster/core/output/status.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/core/scene/mesh.hpp"
#include "lineraster/core/vertex/clip.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"
#include "lineraster/core/vertex/surface_vertex.hpp"
#include "lineraster/core/vertex/vertex_stage.hpp"
#include "lineraster/core/vertex/vertex_store.hpp"

namespace lr {

struct DrawPlan;  // what draw() decides about a draw (front_end.cpp)

// The front end's stores (its part of FrameStorage, core/raster/frame_storage.hpp).
struct FrontEndStorage {
  std::span<ScreenVertex> vertices;
  std::span<BinnedTriangle> triangles;
  std::span<DrawRecord> draws;
  std::span<uint16_t> buckets;
  std::span<SurfaceVertex> surfaces{};
  std::span<uint32_t> lighting_tables{};
  std::span<PreparedLighting> pixel_lights{};
  std::span<uint32_t> strip_inputs{};
  std::span<TexVertex> tex_vertices{};
  bool active_extra = false;  // the strip loop has the planes of textured and Phong triangles
  std::span<TriangleColors> triangle_colors{};  // flat-shaded draws: one per binned triangle
};

// What the strip loop reads of a binned frame. It consumes the edge table as it goes: it
// empties the buckets, relinks the triangles it carries over a skipped strip, fills in the
// draws' texel fetchers and writes the second half of the strip signatures (the last rendered
// frame's).
struct BinnedFrame {
  std::span<const ScreenVertex> vertices;
  std::span<const SurfaceVertex> surfaces;  // Phong draws: indexed like vertices
  std::span<const TexVertex> tex_vertices;  // draws with texture coordinates: the same
  std::span<BinnedTriangle> triangles;
  std::span<const TriangleColors> triangle_colors;  // flat-shaded draws: indexed like triangles
  std::span<DrawRecord> draws;
  std::span<uint16_t> buckets;       // one list head per strip
  std::span<uint32_t> strip_inputs;  // empty, or this frame's signatures then the last frame's
  int width = 0, height = 0, strip_height = 0, strips = 0;
  Rgb8 background{};
};

// A LightSet of zero bytes (no light, every field zero): the front end's default.
constexpr LightSet zero_lights() {
  LightSet s;
  for (Light& l : s.lights) l = Light{LightKind::kDirectional, {}, {}, {}, {}, {}, {}, {}};
  return s;
}

class FrontEnd;
struct MeshDraw;  // one draw()'s context (mesh_draw.hpp)

// The front end's routines for features a renderer may leave out
// (core/raster/renderer_features.hpp), as plain functions that FrontEndRoutines can point at
// (front_end.cpp, front_end_parts.cpp).
struct FrontEndParts {
  // Bands (docs/bands.md): the table full, the band ends higher up (false: it is one strip); a
  // band's draw keeps only the vertices its triangles use; a clipped polygon outside the band.
  static bool shrink_band(FrontEnd& fe);
  static void compact_vertices(FrontEnd& fe, size_t first_vertex, bool surfaces, bool tex);
  static bool polygon_outside_band(FrontEnd& fe, uint16_t first, int m, Cull cull);
  // The colours of a triangle without colour planes (MeshDraw::flat_colors): flat shading, an
  // unlit mesh's one colour.
  static void flat_colors(const MeshDraw& d, const std::array<uint16_t, 3>& tri,
                          const ScreenVertex& last, bool back, Rgb8& flat, Rgb8& flat_spec);
  // An unlit one-coloured draw's colour: c saturated to 8 bits (to_rgb8_sat).
  static Rgb8 one_color(Color15 c);
  // A textured or Phong draw's maps against the mesh and the state (plan_draw's checks of
  // them): kInvalidArgument when a texture is invalid (validate()), mipmapping is asked of a
  // texture without levels, the texture coordinates or tangents are not one per vertex, or a
  // lighting table is not usable; else kOk.
  static Status check_maps(const Mesh& mesh, const DrawState& state, const LightSet& lights,
                           const DrawPlan& p);
  // Whether a textured or Phong draw lacks a store it needs (tex_vertices, active_extra; Phong:
  // surfaces, pixel_lights, and for kTable lighting_tables): draw()'s kMissingStore.
  static bool maps_store_missing(const FrontEnd& fe, const DrawPlan& p, const DrawState& state);
  // Bands: a draw's arguments kept in its record, for the bands that bin it again (replay).
  static void record_call(DrawCall& call, const Mesh& mesh, const Mat4& model,
                          const Material& material, const DrawState& state,
                          const FineMat4* fine_model);
  // Strip signatures (strip_inputs.hpp): the frame's, a draw's, a binned triangle's.
  static uint32_t sign_frame(const FrontEnd& fe);
  static void sign_draw(FrontEnd& fe, uint8_t draw, const Material* per_pixel_material);
  static void sign_triangle(FrontEnd& fe, uint16_t a, uint16_t b, uint16_t c, uint8_t draw,
                            Rgb8 flat, Rgb8 flat_spec, int32_t r0, int32_t r1);
  // The general triangle loop (FrontEnd::general_triangles) with or without two-sided
  // lighting's back faces, the vertex cache, the clipper, and bands or strip signatures
  // (kBandsOrSigns): the renderer links the one of its features.
  template <bool kTwoSided, bool kCache, bool kClip, bool kBandsOrSigns>
  static uint32_t triangles(FrontEnd& fe, MeshDraw& d, uint32_t t, uint32_t end);
};
struct BandRoutines {
  bool (*shrink)(FrontEnd&) = &FrontEndParts::shrink_band;
  void (*compact)(FrontEnd&, size_t, bool, bool) = &FrontEndParts::compact_vertices;
  bool (*outside)(FrontEnd&, uint16_t, int, Cull) = &FrontEndParts::polygon_outside_band;
  void (*record)(DrawCall&, const Mesh&, const Mat4&, const Material&, const DrawState&,
                 const FineMat4*) = &FrontEndParts::record_call;
};
inline constexpr BandRoutines kBandRoutines{};
// What only textured and Phong draws need of the front end: their maps' checks, their stores'
// check and their record's texture fields (DrawRecords::texture_fields).
struct MapRoutines {
  Status (*check)(const Mesh&, const DrawState&, const LightSet&,
                  const DrawPlan&) = &FrontEndParts::check_maps;
  bool (*store_missing)(const FrontEnd&, const DrawPlan&,
                        const DrawState&) = &FrontEndParts::maps_store_missing;
  void (*record)(DrawRecord&, const DrawState&) = &DrawRecords::texture_fields;
};
inline constexpr MapRoutines kMapRoutines{};
// The vertex cache (vertex_store.hpp): a mesh larger than the free vertex store.
struct CacheRoutines {
  bool (VertexStore::*begin)(bool, bool) = &VertexStore::begin_cache;
  std::array<uint16_t, 3> (VertexStore::*corners)(const VertexStage&, const Mesh&,
                                                  const VertexColors&,
                                                  const std::array<uint16_t, 3>&, uint32_t&,
                                                  uint32_t&) = &VertexStore::cache_corners;
  bool (VertexStore::*persist)(uint16_t&) = &VertexStore::persist;
};
inline constexpr CacheRoutines kCacheRoutines{};
struct SignRoutines {
  uint32_t (*frame)(const FrontEnd&) = &FrontEndParts::sign_frame;
  void (*draw)(FrontEnd&, uint8_t, const Material*) = &FrontEndParts::sign_draw;
  void (*triangle)(FrontEnd&, uint16_t, uint16_t, uint16_t, uint8_t, Rgb8, Rgb8, int32_t,
                   int32_t) = &FrontEndParts::sign_triangle;
};
inline constexpr SignRoutines kSignRoutines{};

// What the front end calls for draws only some renderers take. Renderer<PF, K, kSpans> passes
// the routines its span set admits draws for and nullptr for the others, which are then never
// referenced (never linked: a Gouraud renderer links no flat, point, textured or Phong code of
// the front end); the front end refuses a draw that would need a missing one (kNotLinked). The
// defaults admit every draw and link everything (a front end driven alone, in tests).
struct FrontEndRoutines {
  AdmitFn admit = nullptr;                                  // the set's test (nullptr: every draw)
  PhongRecordFn phong = &DrawRecords::phong_record;         // Phong draws' records
  FaceLightFn face_light = &VertexStage::light_face<true>;  // lit flat draws' face colours
  // Lit Gouraud, flat and textured draws whose lighting reads the position (point lights, the
  // local viewer): per vertex and per face.
  PointLightFn point_light = &light_point_at;
  AttributesFn attributes = &VertexStage::attributes;  // textured and Phong draws' vertices
  // The colours of triangles without colour planes (flat-shaded or one-coloured draws), where
  // the set admits such draws (else nullptr: they are refused).
  void (*flat)(const MeshDraw&, const std::array<uint16_t, 3>&, const ScreenVertex&, bool, Rgb8&,
               Rgb8&) = &FrontEndParts::flat_colors;
  // A one-coloured draw's colour (its material's diffuse colour, to_rgb8_sat), where flat is
  // set (else nullptr: such draws are refused, as they need flat too).
  Rgb8 (*one_color)(Color15) = &FrontEndParts::one_color;
  // What textured and Phong draws need (MapRoutines: their maps' checks, the textures' validate()
  // among them, their stores' check, their record's texture fields), wherever attributes is set;
  // nullptr where not (those draws are refused then, kNotLinked).
  const MapRoutines* maps = &kMapRoutines;
  // The clipper: clip_polygon<true> (texture coordinates, specular colour and surface carried)
  // wherever attributes is set; clip_polygon<false> only where it is not (no draw then has them);
  // nullptr without RendererFeatures::clipping (triangles then is a loop without the clipper).
  int (*clip)(ClipPolygon, ClipPolygon, int, uint8_t, GuardBand) = &clip_polygon<true>;
  // The features of RendererFeatures (renderer_features.hpp), nullptr when left out: bands (a
  // frame larger than the stores is then drawn as far as it fits: kCapacity), the vertex cache
  // (a mesh larger than the vertex store: kNotLinked; one larger than its free part: as if the
  // store were full), two-sided lighting's back-face test of clipped triangles (a lit Gouraud
  // or flat draw under LightSet::two_sided: kNotLinked), strip signatures (a strip_inputs
  // store: configure() returns kNotLinked).
  const BandRoutines* bands = &kBandRoutines;
  const CacheRoutines* cache = &kCacheRoutines;
  bool (*front_facing)(const ClipCoord (&)[3]) = &front_facing_clip;
  const SignRoutines* sign = &kSignRoutines;
  // The general triangle loop: FrontEndParts::triangles<kTwoSided, kCache, kClip,
  // kBandsOrSigns>, true where front_facing, cache, clip, bands or sign are set (a loop without
  // them would draw those draws wrong).
  uint32_t (*triangles)(FrontEnd&, MeshDraw&, uint32_t,
                        uint32_t) = &FrontEndParts::triangles<true, true, true, true>;
  // A lit vertex's colours (VertexStage::light<kSpecular, kWorld>), whether its specular term is
  // linked (RendererFeatures::specular): when not (light<false, ...>, and light_face<false>
  // above), a lit draw whose material has a specular colour is refused (kNotLinked); and whether
  // its world-space path is (RendererFeatures::world_lighting): when not, a lit Gouraud or
  // textured draw that cannot be lit in model space is refused (kNotLinked).
  LightFn light = &VertexStage::light<true, true>;
  bool specular = true;
  bool world_lighting = true;
  // A lit draw's lighting preparation: prepare_lighting, or prepare_diffuse_lighting where no
  // draw the renderer takes reads more than directional lights' diffuse terms (no specular,
  // point light, local viewer or Phong: those draws are refused before it is called).
  PrepareLightingFn prepare = &prepare_lighting;
  // And the lights in model space: prepare_object_lights, or prepare_diffuse_object_lights with
  // prepare_diffuse_lighting.
  PrepareObjectLightsFn object_lights = &prepare_object_lights;
};
inline constexpr FrontEndRoutines kEveryRoutine{};

class FrontEnd {
 public:
  // Checks the viewport (width, height in [1, kMaxViewport]), the strip height (1..32) and the
  // draw records (at most 256): kInvalidArgument; then the stores against them: kStoreTooSmall.
  // Must succeed before begin_frame; leaves no frame begun (on failure: not configured).
  // routines: the renderer's test of a draw and the routines of the draws only some renderers
  // take (kEveryRoutine: every draw admitted, every routine linked). Kept by address (4 bytes of
  // RAM, not a copy): it must outlive the front end (a constant, as the renderer's); nullptr is
  // kInvalidArgument.
  Status configure(const FrontEndStorage& storage, int width, int height, int strip_height,
                   const FrontEndRoutines* routines = &kEveryRoutine);
  // Refuses every call until the next successful configure().
  void deconfigure() { configured_ = false; }
  bool configured() const { return configured_; }

  // Starts a frame: clears the stores and the statistics. kNotConfigured before configure();
  // kInvalidArgument for more than kMaxLights lights (no frame is begun then: a frame begun
  // before is abandoned).
  Status begin_frame(const Camera& camera, const LightSet& lights, Rgb8 background);

  // Where the frame is: kOk while one is begun and not rendered (draws are taken), else the
  // status naming why not: kNotConfigured, kNoFrame (none begun since configure(), or the last
  // begin_frame() failed), kFrameRendered (render() ended it).
  LR_SIZE_NOINLINE Status frame_status() const {
    if (!configured_) return Status::kNotConfigured;
    if (phase_ == Phase::kIdle) return Status::kNoFrame;
    return phase_ == Phase::kRendered ? Status::kFrameRendered : Status::kOk;
  }
  // The renderer ends the frame as its render() starts: whatever render() returns, the next
  // draw or render needs a begin_frame().
  void end_frame() { phase_ = Phase::kRendered; }
  // The status of this frame's first refused draw (kOk: none was refused): what render() returns.
  Status refused() const { return refused_; }

  // Adds a mesh (see Renderer::draw; fine_model: the draw's FineMat4 model, or nullptr, and
  // compose the function that composes its model-view-projection: fine_model_view_projection).
  Status draw(const Mesh& mesh, const Mat4& model, const Material& material, const DrawState& state,
              const FineMat4* fine_model = nullptr, FineComposeFn compose = nullptr);
  // Adds triangles already in screen space (see Renderer::draw_screen).
  Status draw_screen(std::span<const ScreenVertex> vertices,
                     std::span<const std::array<uint16_t, 3>> triangles, const DrawState& state,
                     std::span<const TexVertex> tex = {});

  // Bands (docs/bands.md). When the frame's triangles overflow their store, the frame becomes
  // its first band, which ends where the store is full (band_end()); when its vertices do not
  // fit, binning stops and the draws are only recorded. The renderer then bins the frame again
  // for one band of strips at a time (bin_band), each holding only what touches it.
  bool needs_bands() const { return overflow_ || edges_.banding(); }
  // Whether the first band is binned already (the triangle store overflowed, not the vertices).
  bool first_band_binned() const { return edges_.banding() && !overflow_; }
  // Restarts the statistics for binning in bands (the triangles given and those of refused
  // draws are kept).
  void begin_bands();
  // Bins every draw again for strips [s0, s1) at most: the triangles that touch them, those
  // that start above in the band's first strip. When the triangle store fills up the band ends
  // higher up (band_end()); when it is one strip the triangles that do not fit are dropped and
  // counted (band_dropped()). kCapacity when the vertices do not fit: the band is left
  // unusable and the statistics as they were (the caller tries a smaller band), unless
  // keep_partial (what fit is kept and the rest counted as dropped).
  Status bin_band(int s0, int s1, bool keep_partial);
  int band_end() const { return edges_.window_end(); }
  bool band_dropped() const { return edges_.dropped(); }

  const FrameStats& stats() const { return stats_; }
  // The strip loop counts its work into the same statistics.
  FrameStats& mutable_stats() { return stats_; }
  std::span<const ScreenVertex> screen_vertices() const { return store_.vertices(); }
  std::span<const BinnedTriangle> binned_triangles() const { return edges_.triangles(); }
  // Flat-shaded draws' triangles: their colours, indexed like binned_triangles().
  std::span<const TriangleColors> triangle_colors() const { return edges_.colors(); }
  int width() const { return width_; }
  int height() const { return height_; }
  int strip_height() const { return strip_height_; }
  GuardBand guard_band() const { return guard_; }

  // The frame binned since begin_frame().
  BinnedFrame frame() {
    return {store_.vertices(),
            store_.surfaces(),
            store_.tex_entries(),
            edges_.triangles(),
            edges_.colors(),
            records_.records(),
            edges_.buckets(),
            edges_.strip_inputs(),
            width_,
            height_,
            strip_height_,
            edges_.strips(),
            background_};
  }

 private:
  // The triangle loop (front_end.cpp): the lane (lane.cpp) for its common triangles, and
  // general_triangles(), one copy of draw_triangle() with its two ends always inlined into it
  // (one stack frame), for the rest and for every draw the lane does not take. kTwoSided,
  // kCache: with two-sided lighting's back faces, with the vertex cache (FrontEndRoutines::
  // triangles: the renderer's features).
  [[gnu::noinline]] void triangle_loop(MeshDraw& d);
  template <bool kTwoSided, bool kCache, bool kClip, bool kBandsOrSigns>
  [[gnu::noinline]] uint32_t general_triangles(MeshDraw& d, uint32_t t, uint32_t end);
  [[gnu::noinline]] uint32_t lane_triangles(MeshDraw& d, uint32_t t);
  [[gnu::noinline]] uint32_t lane_run_triangles(MeshDraw& d, uint32_t t);
  [[gnu::noinline]] void light_corners(MeshDraw& d, const std::array<uint16_t, 3>& tri);
  // The lane's vertices to light (lane.cpp), at most kLightList at a time.
  static constexpr size_t kLightList = 48;
  [[gnu::noinline]] void light_list(MeshDraw& d, std::span<ScreenVertex* const> list);
  [[gnu::noinline]] void light_other(MeshDraw& d, uint32_t i);
  template <bool kTwoSided, bool kCache, bool kClip, bool kBandsOrSigns>
  [[gnu::always_inline]] inline void draw_triangle(MeshDraw& d, const std::array<uint16_t, 3>& tri);
  template <bool kLeanBin>
  [[gnu::always_inline]] inline void bin_inside(MeshDraw& d, uint16_t (&vi)[3],
                                                ScreenVertex* const (&sv)[3], bool back_copies,
                                                Rgb8 flat, Rgb8 flat_spec, const int32_t* rows,
                                                bool cached);
  [[gnu::always_inline]] inline void clip_and_bin(MeshDraw& d, const uint16_t (&vi)[3],
                                                  ScreenVertex* const (&sv)[3],
                                                  const ClipCoord (&clip)[3], uint8_t oc_or,
                                                  bool back_colored, Rgb8 flat, Rgb8 flat_spec);

  // The vertex stage and binning of a recorded draw (draw() runs it unless the stores have
  // overflowed; bin_band runs it for each band).
  void run_mesh(uint8_t index, const Mesh& mesh, const Mat4& model, const Material& material,
                const DrawState& state, const DrawPlan& plan, const PreparedLighting& pl,
                const FineMat4* fine_model);
  void run_screen(uint8_t index, std::span<const ScreenVertex> vertices,
                  std::span<const TexVertex> tex,
                  std::span<const std::array<uint16_t, 3>> triangles, const DrawState& state);
  [[gnu::noinline]] void replay(uint8_t index);
  // run_screen() for replay(), set by draw_screen(): a renderer whose application never calls
  // draw_screen() does not link it (only bands replay a draw). A plain function pointer: 4
  // bytes of RAM.
  static void replay_screen(FrontEnd& fe, uint8_t index, const DrawState& state);
  void (*replay_screen_)(FrontEnd& fe, uint8_t index, const DrawState& state) = nullptr;
  bool polygon_outside_band(uint16_t first, int m, Cull cull);
  friend struct FrontEndParts;
  // The table full: the band (the frame's first, until then) ends higher up (EdgeTable::
  // shrink_window), its evicted triangles uncounted. False when it is one strip.
  bool shrink_band();
  // Binning a band: the draw's vertices from `first_vertex` on kept only where its triangles
  // (from draw_first_triangle_ on) refer to them (VertexStore::compact).
  void compact_vertices(size_t first_vertex, bool surfaces, bool tex);
  // A draw refused whole, for `why` (front_end.cpp): counted in the reason's draws_refused_*,
  // and the frame's first refusal kept for render(). kCapacity (draw records, per-pixel
  // lighting pools, a mesh larger than a store below the vertex cache's minimum: no band can
  // take it) also counts its triangles as dropped, in this frame's statistics for good. Returns
  // `why`.
  LR_SIZE_NOINLINE Status refuse(Status why, uint32_t triangles = 0, bool vertex_store = false);

  // rows: the triangle's first and last row when classify() already passed it (its tests are
  // not repeated), else nullptr.
  // cached: a, b, c are vertex cache slots, copied into the store when the triangle is binned.
  // (A flag, not a template parameter: one copy for the general triangle loop's rare paths.)
  Outcome bin(uint16_t a, uint16_t b, uint16_t c, uint8_t draw, Rgb8 flat, Rgb8 flat_spec,
              Cull cull, const int32_t* rows = nullptr, bool cached = false);
  // bin() where no band, strip signature or vertex cache can be (the general loop of a renderer
  // without them: FrontEndParts::triangles<..., false, ..., false>): the same without their
  // paths (their code is not linked), cached false.
  [[gnu::noinline]] Outcome bin_lean(uint16_t a, uint16_t b, uint16_t c, uint8_t draw, Rgb8 flat,
                                     Rgb8 flat_spec, Cull cull, const int32_t* rows);
  // The body of both (kLean: bin_lean).
  template <bool kLean>
  [[gnu::always_inline]] inline Outcome bin_as(uint16_t a, uint16_t b, uint16_t c, uint8_t draw,
                                               Rgb8 flat, Rgb8 flat_spec, Cull cull,
                                               const int32_t* rows, bool cached);
  bool needs_cache(size_t n, const DrawPlan& plan) const;
  // Refuses a draw the renderer links no routine for.
  bool admitted(const DrawState& state, const DrawKind& kind) const {
    return (!kind.phong || routines_->phong != nullptr) &&
           (routines_->admit == nullptr || routines_->admit(state, kind));
  }

  // The stages' own state: the vertex store (vertices, surfaces, texture entries, the vertex
  // cache), the draw records, the edge table (with the band's row window).
  VertexStore store_{};
  DrawRecords records_{};
  EdgeTable edges_{};
  FrameStats stats_{};
  // Every default is zero bytes (configure() and begin_frame() set what a frame uses), so that a
  // static renderer is constant-initialised into .bss, not copied from flash into .data: hence
  // the camera's zero matrices and the lights' zero fields instead of their types' defaults.
  int width_ = 0, height_ = 0, strip_height_ = 0;
  GuardBand guard_{0, 0};
  Camera camera_{Mat4{}, Mat4{}, Vec3{}};
  LightSet lights_ = zero_lights();
  Rgb8 background_{};
  bool configured_ = false;
  // The frame's phase (frame_status()), and its first refused draw's status.
  enum class Phase : uint8_t { kIdle, kOpen, kRendered };
  Phase phase_ = Phase::kIdle;
  Status refused_ = Status::kOk;
  // (The bytes together, before the words: no padding between them.)
  bool active_extra_ = false;  // FrontEndStorage::active_extra
  // Bands: the stores overflowed (the rest of the frame is only recorded), and the refused
  // draws' triangles (counted in every band's statistics).
  bool overflow_ = false;
  // The composition of fine draws' model-view-projection (set by the first draw with a FineMat4
  // model: nullptr until then, so that an image without one links none).
  FineComposeFn fine_compose_ = nullptr;
  // The routines of configure() (nullptr until then: zero bytes).
  const FrontEndRoutines* routines_ = nullptr;
  uint32_t refused_triangles_ = 0, refused_vertices_ = 0;
  // The statistics binning changes (nothing else changes while a band is binned), as they were
  // before the band: kept here, not on the stack, and not the whole FrameStats (RAM: the
  // micro:bit's 16 KB holds a renderer with a few bytes to spare).
  struct BinningCounts {
    uint32_t culled_backface, culled_zero_area, culled_offscreen, clipped_away, rejected_invalid,
        dropped_vertex_capacity, dropped_triangle_capacity, binned_inputs, clipped,
        triangles_binned, vertices_transformed;
  };
  BinningCounts band_before_{};
  // Out of line: inlined, they widened bin_band's frame, which is on the deepest stack path.
  [[gnu::noinline]] void save_binning_counts();
  [[gnu::noinline]] void restore_binning_counts();
  // The running draw: its first binned triangle, whether its triangles have TriangleColors,
  // whether they are binned sorted by y (kBinnedSorted and sorts_for_lanes: store_binned).
  size_t draw_first_triangle_ = 0;
  bool draw_colors_ = false;
  bool draw_sorted_ = false;
  // Working memory of one draw, kept here rather than on the stack (the worst-case stack is a
  // budget of its own, and these are the largest locals of the deepest path): the draw's
  // prepared lighting, its lights in model space (VertexColors::object), a clipped polygon with
  // the clipper's scratch.
  PreparedLighting lighting_{};
  ObjectLights object_lights_{};
  ClipBuffers clip_{};
};

}  // namespace lr
