// The renderer: a front end (vertex stage and binning) and a strip loop, composed.
//
// Renderer<PF, K, kSpans, kFeatures>: PF the strip's pixel format (core/output/pixel_format.hpp:
// Rgb565Be, Rgb565, Xrgb8888, Rgb888), K the strip height in rows (1..32, compile time), kSpans
// the span states it links routines for (span_state.hpp: kAllSpans by default; draws outside the
// set are refused), kFeatures the front end's features it links (renderer_features.hpp: bands,
// the vertex cache, two-sided lighting, strip skipping, crowded strips, specular; kAllFeatures by
// default).
// draw() and draw_screen() go to the front end (core/binning/front_end.hpp), which bins the frame;
// render() hands the binned frame to the strip loop (core/raster/strip_loop.hpp), which rasterizes
// it strip by strip into the sink. RAM: the caller's FrameStorage; nothing is allocated, nothing
// holds a frame.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

#include "lineraster/core/binning/front_end.hpp"
#include "lineraster/core/output/depth_sink.hpp"
#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/output/status.hpp"
#include "lineraster/core/output/strip_sink.hpp"
#include "lineraster/core/raster/frame_storage.hpp"
#include "lineraster/core/raster/renderer_features.hpp"
#include "lineraster/core/raster/strip_loop.hpp"
#include "lineraster/core/span/admission.hpp"
#include "lineraster/core/span/span_state.hpp"

namespace lr {

template <class PF, int K, SpanSet kSpans = kAllSpans, RendererFeatures kFeatures = kAllFeatures>
class Renderer {
 public:
  using Pixel = typename PF::Storage;
  static constexpr int kStripHeight = K;

  // Every call names what it refuses (docs/api-errors.md): a call out of order changes nothing
  // and returns kNotConfigured (before a successful configure), kNoFrame (draw or render with
  // no frame begun) or kFrameRendered (draw or render after render, before begin_frame).

  // Checks the viewport (width, height in [1, kMaxViewport]) and the stores' index limits (at
  // most 256 draw records, 65535 active slots): kInvalidArgument; then the stores against the
  // viewport and the strip height K (FrameCapacities' sizes): kStoreTooSmall. Must succeed
  // before begin_frame. Success leaves no frame begun; failure leaves the renderer not
  // configured (every call kNotConfigured until a configure succeeds).
  Status configure(const FrameStorage& storage, int width, int height) {
    Status st = front_.configure(storage.front_end(), width, height, K, &kRoutines);
    if (st == Status::kOk) st = strip_.configure(storage.strip_loop(), width);
    if (st != Status::kOk) front_.deconfigure();
    return st;
  }

  // Starts a frame: clears the stores and the statistics. kNotConfigured before configure;
  // kInvalidArgument for more than kMaxLights lights, and then no frame is begun (a frame begun
  // before is abandoned). begin_frame may start over a frame begun or rendered.
  Status begin_frame(const Camera& camera, const LightSet& lights, Rgb8 background) {
    const Status st = front_.begin_frame(camera, lights, background);
    if (st == Status::kOk)
      front_.mutable_stats().bytes_per_active_triangle =
          sizeof(ActiveTriangle) + 2 * sizeof(uint16_t);
    return st;
  }

  // Adds a mesh. The mesh's arrays must stay valid until render() returns: a frame larger than
  // the stores is drawn in bands, which read them again (docs/bands.md); the Mesh, the matrix,
  // the material and the state are copied. A refused draw adds nothing, is counted in its
  // reason's FrameStats::draws_refused_*, and makes render() return its status (the frame's
  // first refusal's): kInvalidArgument when the mesh's arrays disagree in size, Gouraud
  // lighting is asked of a mesh without normals, or a texture or lighting table is invalid;
  // kNotLinked when the renderer's SpanSet does not admit the draw's span state or its textures
  // (span_state.hpp; Phong in a renderer without Phong spans), or a feature it leaves out
  // (renderer_features.hpp: e.g. a lit draw of a specular material without kFeatures.specular);
  // kMissingStore when a store the
  // draw needs was not given (FrameStorage: textured draws tex_vertices and active_extra, Phong
  // draws surfaces, pixel_lights, active_extra and for kTable lighting_tables, flat-shaded
  // draws triangle_colors); kCapacity (its triangles counted as dropped too) when no draw
  // record is left, the mesh is larger than a vertex (surface, texture-entry) store too small
  // for the vertex cache (docs/bands.md), or a Phong draw's lighting pools are full.
  Status draw(const Mesh& mesh, const Mat4& model, const Material& material,
              const DrawState& state) {
    return front_.draw(mesh, model, material, state);
  }
  // draw() with a model of more fraction bits (rotate_y_fine ..., FineMat4 products): the vertex
  // stage composes it with the camera (its fine_projection when given) without rounding to
  // Q16.16; the lighting reads it rounded to Q16.16. The matrix must stay valid until render()
  // returns (bands replay the draw); kInvalidArgument when its frac is outside [16, 30]; else
  // as draw(). docs/numerics.md#fine-transforms.
  Status draw(const Mesh& mesh, const FineMat4& model, const Material& material,
              const DrawState& state) {
    return front_.draw(mesh, to_mat4(model), material, state, &model, &fine_model_view_projection);
  }

  // Adds triangles already in screen space (snapped subpixel positions, depth, colour):
  // for 2D overlays and for tests of the raster rules. Lighting does not apply. A textured
  // state needs `tex`, one entry per vertex (texture coordinates, secondary colour); others
  // ignore it. The arrays must stay valid until render() returns. Refused as draw() is:
  // kInvalidArgument when a textured state's `tex` is not as long as `vertices`; kNotLinked,
  // kMissingStore as draw(); kCapacity when no draw record is left or the vertices outnumber
  // the vertex store (or, textured, the tex_vertices store).
  Status draw_screen(std::span<const ScreenVertex> vertices,
                     std::span<const std::array<uint16_t, 3>> triangles, const DrawState& state,
                     std::span<const TexVertex> tex = {}) {
    return front_.draw_screen(vertices, triangles, state, tex);
  }

  // Rasterizes the frame built since begin_frame(), in bands when it did not fit the stores
  // (docs/bands.md), and ends it: whatever it returns, the next draw or render needs a
  // begin_frame() (kFrameRendered until then). When a draw of the frame was refused, the frame
  // is drawn without it and the first refused draw's status returned (kInvalidArgument,
  // kNotLinked, kMissingStore or kCapacity; FrameStats::draws_refused_* count them). Else
  // kCapacity when a single strip needed more binned triangles or vertices than the stores
  // hold: that strip is drawn with what fit and the rest counted as dropped; without
  // kFeatures.crowded_strips also when a strip's triangles outnumbered the active list (the
  // ones starting in it dropped and counted). On a sink error
  // the frame is abandoned and the sink's status returned.
  // With FrameStorage::strip_inputs, a sink that retains_frame() and no depth sink, strips whose
  // inputs equal the last rendered frame's are not rendered: the sink is told to keep() them.
  // The renderer assumes the sink shows its last frame: after rendering into another sink (or
  // drawing on the display otherwise) call invalidate_strips().
  Status render(StripSink<PF>& sink, DepthSink* depth_sink = nullptr);

  const FrameStats& stats() const { return front_.stats(); }
  std::span<const ScreenVertex> screen_vertices() const { return front_.screen_vertices(); }
  std::span<const BinnedTriangle> binned_triangles() const { return front_.binned_triangles(); }
  std::span<const TriangleColors> triangle_colors() const { return front_.triangle_colors(); }
  int width() const { return front_.width(); }
  int height() const { return front_.height(); }
  int strip_height() const { return front_.strip_height(); }
  GuardBand guard_band() const { return front_.guard_band(); }
  // Forgets the strip signatures of the last frame, so that the next render draws every strip:
  // call it after changing texel or table memory in place, or when the display was drawn on by
  // someone else. (configure() and a render that fails or overflows the active list do it too.)
  void invalidate_strips() { strip_.invalidate_strips(); }

  // The parts, for tests that drive them alone.
  FrontEnd& front_end() { return front_; }

 private:
  // The front end's routines for the draws this renderer's set admits, nullptr for the others
  // (never linked; the front end refuses draws that would need them): Phong records (with the
  // lighting tables) only with Phong spans; flat shading's face lighting only where flat draws
  // are admitted (untextured without colour planes, or textured: their flat variant); the
  // lighting that reads the position (point lights, the local viewer) of Gouraud, flat and
  // textured draws only where the set admits the position (SpanSet::position); the vertex
  // attributes of textured and Phong draws only with those spans.
  static constexpr bool kFlat =
      kSpans.has(SpanFamily::kTextured) ||
      (kSpans.has(SpanFamily::kUntextured) && detail::has(kSpans.colors, ColorPlanes::kNone));
  static constexpr bool kAttributes =
      kSpans.has(SpanFamily::kTextured) || kSpans.has(SpanFamily::kPhong);
  // Lighting that reads only directional lights' diffuse terms: no specular term linked, no
  // span that reads the position (point lights, the local viewer), no Phong.
  static constexpr bool kDiffuseLighting =
      !kFeatures.specular && !detail::has(kSpans.position, true) && !kSpans.has(SpanFamily::kPhong);
  // The features of kFeatures, nullptr for those it leaves out.
  static constexpr FrontEndRoutines kRoutines{
      &admits<kSpans>,
      kSpans.has(SpanFamily::kPhong) ? &DrawRecords::phong_record : nullptr,
      kFlat ? &VertexStage::light_face<kFeatures.specular> : nullptr,
      detail::has(kSpans.position, true) ? &light_point_at : nullptr,
      kAttributes ? &VertexStage::attributes : nullptr,
      kFlat ? &FrontEndParts::flat_colors : nullptr,
      kFlat ? &FrontEndParts::one_color : nullptr,
      kAttributes ? &kMapRoutines : nullptr,
      !kFeatures.clipping ? nullptr
      : kAttributes       ? &clip_polygon<true>
                          : &clip_polygon<false>,
      kFeatures.bands ? &kBandRoutines : nullptr,
      kFeatures.vertex_cache ? &kCacheRoutines : nullptr,
      kFeatures.two_sided ? &front_facing_clip : nullptr,
      kFeatures.strip_skipping ? &kSignRoutines : nullptr,
      &FrontEndParts::triangles<kFeatures.two_sided, kFeatures.vertex_cache, kFeatures.clipping,
                                kFeatures.bands || kFeatures.strip_skipping>,
      &VertexStage::light<kFeatures.specular, kFeatures.world_lighting>,
      kFeatures.specular,
      kFeatures.world_lighting,
      kDiffuseLighting ? &prepare_diffuse_lighting
                       : static_cast<PrepareLightingFn>(&prepare_lighting),
      kDiffuseLighting ? &prepare_diffuse_object_lights : &prepare_object_lights};

  // render() with bands (kFeatures.bands), after its checks. Inlined: one stack frame.
  [[gnu::always_inline]] inline Status render_bands(FrameStats& stats, StripSink<PF>& sink,
                                                    DepthSink* depth_sink);

  FrontEnd front_;
  StripLoop<PF, K, kSpans> strip_;
};

// A frame the stores hold whole is one band. One they do not is binned again and rasterized a
// band of strips at a time (docs/bands.md): each band is asked for the rest of the frame and
// ends where the triangle store fills up; a band whose vertices do not fit is binned again at
// half the height, and the next may be one strip taller (a binning pass per retry is the cost:
// doubling again made every other band a retry). Only a single strip that does not fit
// drops work: what fit is drawn and kCapacity returned. One call of the strip loop's strips()
// either way: it is inlined here once.
template <class PF, int K, SpanSet kSpans, RendererFeatures kFeatures>
Status Renderer<PF, K, kSpans, kFeatures>::render(StripSink<PF>& sink, DepthSink* depth_sink) {
  // Only a begun frame has an edge table to walk: configure() leaves the buckets as the caller
  // gave them, and render() consumes them.
  if (const Status open = front_.frame_status(); open != Status::kOk) return open;
  front_.end_frame();
  FrameStats& stats = front_.mutable_stats();
  if constexpr (!kFeatures.bands) {
    // Without bands: what the stores hold, in one pass; what did not fit was dropped (the
    // front end stopped binning when a store was full), and counted.
    bool fit = !front_.needs_bands() && !front_.band_dropped();
    // (One BinnedFrame: each frame() is a copy on this frame, which is on the deepest path.)
    const BinnedFrame frame = front_.frame();
    Status st = strip_.begin(frame, stats, sink, depth_sink);
    if (st == Status::kOk)
      st = strip_.template strips<kFeatures.strip_skipping, kFeatures.crowded_strips>(
          frame, 0, frame.strips, sink, depth_sink);
    fit = fit && !strip_.dropped();
    if (st == Status::kOk) st = strip_.end(sink, fit);
    if (st != Status::kOk) return st;
    if (front_.refused() != Status::kOk) return front_.refused();
    return fit ? Status::kOk : Status::kCapacity;
  } else {
    return render_bands(stats, sink, depth_sink);
  }
}

template <class PF, int K, SpanSet kSpans, RendererFeatures kFeatures>
Status Renderer<PF, K, kSpans, kFeatures>::render_bands(FrameStats& stats, StripSink<PF>& sink,
                                                        DepthSink* depth_sink) {
  const bool bands = front_.needs_bands();
  const bool first_binned = front_.first_band_binned();
  if (bands && !first_binned) front_.begin_bands();
  Status st = strip_.begin(front_.frame(), stats, sink, depth_sink);
  if (st != Status::kOk) return st;
  const int strips = front_.frame().strips;
  int size = strips;
  bool complete = true;
  for (int s0 = 0; s0 < strips;) {
    int s1 = std::min(strips, s0 + size);
    if (bands && (s0 != 0 || !first_binned)) {
      if (front_.bin_band(s0, s1, s1 - s0 == 1) != Status::kOk) {
        if (s1 - s0 > 1) {
          size = (s1 - s0) / 2;
          continue;
        }
        complete = false;
      }
      size = std::min(strips, size + 1);
    }
    if (bands) {
      if (front_.band_dropped()) complete = false;
      s1 = front_.band_end();
    }
    st = strip_.template strips<kFeatures.strip_skipping, kFeatures.crowded_strips>(
        front_.frame(), s0, s1, sink, depth_sink);
    if (st != Status::kOk) return st;
    s0 = s1;
  }
  complete = complete && !strip_.dropped();
  st = strip_.end(sink, complete);
  if (st != Status::kOk) return st;
  if (front_.refused() != Status::kOk) return front_.refused();
  return complete ? Status::kOk : Status::kCapacity;
}

#ifdef LR_EXTERN_RENDERERS
// Hosted builds (core/CMakeLists.txt) link the renderers with every span routine, for the two
// pixel formats of the host tools (Rgb565Be, Rgb888) and every strip height lineraster-sim
// offers, from lr_core (raster/renderer_instances_*.cpp) instead of compiling the strip loop and
// all span routines again in each program. Bare-metal builds instantiate where they are used, so
// that render() can be inlined into its caller and the sink's calls made direct. The frame-buffer
// formats (Rgb565, Xrgb8888) are instantiated where they are used in every build: no tool of the
// project uses them, and their 12 instances would add some 40 s of compilation (Release) to
// every hosted build of lr_core for programs that use one or two.
extern template class Renderer<Rgb565Be, 1>;
extern template class Renderer<Rgb565Be, 2>;
extern template class Renderer<Rgb565Be, 4>;
extern template class Renderer<Rgb565Be, 8>;
extern template class Renderer<Rgb565Be, 16>;
extern template class Renderer<Rgb565Be, 32>;
extern template class Renderer<Rgb888, 1>;
extern template class Renderer<Rgb888, 2>;
extern template class Renderer<Rgb888, 4>;
extern template class Renderer<Rgb888, 8>;
extern template class Renderer<Rgb888, 16>;
extern template class Renderer<Rgb888, 32>;
#endif

}  // namespace lr
