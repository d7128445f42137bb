// The renderer: FrameBuilder's edge table, rasterized strip by strip into a display sink.
//
// Renderer<PF, K, kSpans>: PF the strip's pixel format (Rgb565Be, Rgb888), K the strip height in
// rows (1..32, compile time), kSpans the span states it links routines for (span_state.hpp:
// kAllSpans by default; draws outside the set are refused). Per strip: triangles whose first row
// falls in it join the active list (kept in submission order, so depth ties and no-depth drawing
// resolve as in GL); each active triangle fills its rows of the strip; finished triangles leave;
// the strip goes to the sink. RAM: the caller's FrameStorage; nothing is allocated, nothing holds a
// frame.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>

#include "core/binning/frame_builder.hpp"
#include "core/span/phong_span.hpp"
#include "core/output/pixel_format.hpp"
#include "core/span/span.hpp"
#include "core/raster/strip_fill.hpp"
#include "core/span/tex_span.hpp"
#include "core/output/strip_sink.hpp"

namespace lr {

// Optional receiver of each strip's depth buffer (16-bit, 65535 = far/cleared): for tools.
class DepthSink {
 public:
  virtual void on_depth(const StripRect& rect, std::span<const uint16_t> depth) = 0;

 protected:
  ~DepthSink() = default;
};

template <class PF, int K, SpanSet kSpans = kAllSpans>
class Renderer : public FrameBuilder {
  static_assert(K >= 1 && K <= 32, "strip height K must be 1..32");

 public:
  using Pixel = typename PF::Storage;
  static constexpr int kStripHeight = K;

  Status configure(const FrameStorage& storage, int width, int height) {
    span_set_ = &kSpans;
    return FrameBuilder::configure(storage, width, height, K);
  }

  // Rasterizes the frame built since begin_frame(). On a sink error the frame is abandoned and
  // the sink's status returned; the renderer is ready for the next frame either way.
  // With FrameStorage::strip_inputs, a sink that retains_frame() and no depth sink, strips whose
  // inputs equal the last rendered frame's are not rendered: the sink is told to keep() them.
  // The renderer assumes the sink shows its last frame: after rendering into another sink (or
  // drawing on the display otherwise) call invalidate_strips().
  Status render(StripSink<PF>& sink, DepthSink* depth_sink = nullptr);

 private:
  void activate(int strip);
  void skip_strip(int strip, int y0, int rows);
  void resolve_fetchers();
  void raster_triangle(ActiveTriangle& t, Pixel* pixels, int y0, int rows);
  void retire(int next_row);

  // Whether the set links the affine colour routine, without and with depth: only then may a
  // perspective-colour triangle be given affine planes (setup_triangle).
  static constexpr bool kAffineColors[2] = {
      kUsedRoutines<kSpans>.untextured[untextured_index(false, ColorPlanes::kAffine)],
      kUsedRoutines<kSpans>.untextured[untextured_index(true, ColorPlanes::kAffine)]};
  size_t active_count_ = 0;
  size_t free_count_ = 0;
};

template <class PF, int K, SpanSet kSpans>
Status Renderer<PF, K, kSpans>::render(StripSink<PF>& sink, DepthSink* depth_sink) {
  if (!configured_) return Status::kInvalidArgument;
  resolve_fetchers();
  const auto w = static_cast<size_t>(width_);
  stats_.bytes_per_strip = static_cast<uint32_t>(w * K * (sizeof(Pixel) + sizeof(uint16_t)));
  active_count_ = 0;
  free_count_ = storage_.active.size();
  uint16_t* free_slots = storage_.active_index.data() + storage_.active.size();
  for (size_t i = 0; i < free_count_; ++i)
    free_slots[i] = static_cast<uint16_t>(free_count_ - 1 - i);

  // Until this frame has reached the display whole, the signatures describe nothing shown.
  const bool had_inputs = inputs_known_;
  inputs_known_ = false;
  Status st = sink.begin_frame(static_cast<uint16_t>(width_), static_cast<uint16_t>(height_));
  if (st != Status::kOk) return st;
  const bool may_skip = had_inputs && depth_sink == nullptr && sink.retains_frame();
  uint32_t* inputs = skipping() ? storage_.strip_inputs.data() : nullptr;
  const size_t last = static_cast<size_t>(strips_);  // the last frame's half
  const Pixel bg = PF::encode(background_);
  for (int s = 0; s < strips_; ++s) {
    const int y0 = s * K;
    const int rows = std::min(K, height_ - y0);
    const size_t count = w * static_cast<size_t>(rows);
    const StripRect rect{0, static_cast<uint16_t>(y0), static_cast<uint16_t>(width_),
                         static_cast<uint16_t>(rows)};
    if (inputs != nullptr) {
      const auto i = static_cast<size_t>(s);
      if (may_skip && inputs[i] == inputs[last + i]) {
        skip_strip(s, y0, rows);
        ++stats_.strips_skipped;
        ++stats_.strips;
        st = sink.keep(rect);
        if (st != Status::kOk) return st;
        continue;
      }
      inputs[last + i] = inputs[i];
    }
    StripLease<PF> lease;
    st = sink.acquire(lease);
    if (st != Status::kOk) return st;
    std::span<Pixel> px = lease.pixels();
    if (px.size() < count) return Status::kInvalidArgument;
    fill_pixels(px.data(), count, bg);
    activate(s);
    std::span<uint16_t> depth = storage_.depth.first(count);
    if (active_count_ == 0) {
      ++stats_.empty_strips;
      if (depth_sink) fill_pixels(depth.data(), count, uint16_t{0xFFFF});
    } else {
      fill_pixels(depth.data(), count, uint16_t{0xFFFF});
      const uint16_t* order = storage_.active_index.data();
      for (size_t i = 0; i < active_count_; ++i)
        raster_triangle(storage_.active[order[i]], px.data(), y0, rows);
      retire(y0 + rows);
    }
    if (depth_sink) depth_sink->on_depth(rect, depth);
    ++stats_.strips;
    st = sink.submit(rect, std::move(lease));
    if (st != Status::kOk) return st;
  }
  st = sink.end_frame();
  // A frame that dropped triangles for lack of active slots dropped them by what else was
  // active, which a strip's signature does not describe: the next frame renders everything.
  inputs_known_ = st == Status::kOk && inputs != nullptr && stats_.dropped_active_capacity == 0;
  return st;
}

// A strip whose inputs did not change: the triangles active in it are stepped over its rows
// without drawing; those that start in it and end in it are never set up, those that go on are
// handed to the next strip's bucket (in submission order), to be set up at that strip's first row.
template <class PF, int K, SpanSet kSpans>
void Renderer<PF, K, kSpans>::skip_strip(int strip, int y0, int rows) {
  const int next_row = y0 + rows;
  const uint16_t* order = storage_.active_index.data();
  for (size_t i = 0; i < active_count_; ++i) {
    ActiveTriangle& t = storage_.active[order[i]];
    const int end = std::min<int>(t.last_row, next_row - 1);
    int r = t.row;
    for (; r <= end; ++r) {
      if (r == t.mid_row + 1) t.short_edge = t.bottom_edge;
      t.long_edge.step();
      t.short_edge.step();
    }
    t.row = static_cast<int16_t>(r);
  }
  retire(next_row);

  uint16_t& head = storage_.buckets[static_cast<size_t>(strip)];
  uint16_t carried = kNoTriangle, *tail = &carried;
  if (strip + 1 < strips_) {
    for (uint16_t i = head; i != kNoTriangle; i = storage_.triangles[i].next) {
      const BinnedTriangle& bt = storage_.triangles[i];
      const int32_t ymax = std::max({storage_.vertices[bt.v[0]].y, storage_.vertices[bt.v[1]].y,
                                     storage_.vertices[bt.v[2]].y});
      if (last_row_at_or_above(ymax) >= next_row) {
        *tail = i;
        tail = &storage_.triangles[i].next;
      }
    }
  }
  *tail = kNoTriangle;
  head = kNoTriangle;
  // Both lists run from the latest submission to the earliest: merge them.
  uint16_t& next = storage_.buckets[static_cast<size_t>(strip + 1 < strips_ ? strip + 1 : strip)];
  uint16_t a = carried, b = strip + 1 < strips_ ? next : kNoTriangle, merged = kNoTriangle;
  uint16_t* out = &merged;
  while (a != kNoTriangle || b != kNoTriangle) {
    uint16_t& pick = (b == kNoTriangle || (a != kNoTriangle && a > b)) ? a : b;
    *out = pick;
    out = &storage_.triangles[pick].next;
    pick = storage_.triangles[pick].next;
  }
  *out = kNoTriangle;
  if (strip + 1 < strips_) next = merged;
}

// The texel fetchers of this frame's draws (DrawRecord): here, in the template, from the tables
// of kSpans, so that a renderer references only the fetch routines its set admits (none without
// textured or Phong states). draw() refused every draw whose textures the set does not admit.
template <class PF, int K, SpanSet kSpans>
void Renderer<PF, K, kSpans>::resolve_fetchers() {
  if constexpr (kUsedRoutines<kSpans>.any_fetch()) {
    for (DrawRecord& d : storage_.draws.first(draw_count_)) {
      if (d.texture != nullptr)
        d.fetch = fetch_routine<kSpans>(d.texture->format, d.filter, d.wrap_s, d.wrap_t);
      if (d.envmap != nullptr) d.env_fetch = env_fetch_routine<kSpans>(d.envmap->format);
      if (d.normal_map != nullptr)
        d.nmap_fetch = fetch_routine<kSpans>(d.normal_map->format, d.filter, d.wrap_s, d.wrap_t);
    }
  }
}

template <class PF, int K, SpanSet kSpans>
void Renderer<PF, K, kSpans>::activate(int strip) {
  uint16_t& head = storage_.buckets[static_cast<size_t>(strip)];
  size_t m = 0;
  for (uint16_t i = head; i != kNoTriangle; i = storage_.triangles[i].next) ++m;
  if (m == 0) return;
  // The list runs from the latest submission to the earliest: when the active list cannot take
  // them all, the latest are the ones dropped.
  size_t fit = std::min(m, free_count_);
  stats_.dropped_active_capacity += static_cast<uint32_t>(m - fit);
  uint16_t node = head;
  for (size_t skip = m - fit; skip > 0; --skip) node = storage_.triangles[node].next;
  head = kNoTriangle;

  // Merge from the back: existing entries are in ascending submission order, the bucket gives
  // descending order.
  uint16_t* order = storage_.active_index.data();
  uint16_t* free_slots = order + storage_.active.size();
  ptrdiff_t i = static_cast<ptrdiff_t>(active_count_) - 1;
  ptrdiff_t out = static_cast<ptrdiff_t>(active_count_ + fit) - 1;
  for (; node != kNoTriangle; node = storage_.triangles[node].next) {
    while (i >= 0 && storage_.active[order[i]].index > node) order[out--] = order[i--];
    uint16_t slot = free_slots[--free_count_];
    const BinnedTriangle& bt = storage_.triangles[node];
    const DrawRecord& dr = storage_.draws[bt.draw];
    SetupInput in;
    for (int k = 0; k < 3; ++k) in.v[k] = &storage_.vertices[bt.v[k]];
    int32_t ymin = std::min({in.v[0]->y, in.v[1]->y, in.v[2]->y});
    int32_t ymax = std::max({in.v[0]->y, in.v[1]->y, in.v[2]->y});
    // Triangles carried over a skipped strip start at this strip's first row.
    in.first_row = std::max<int32_t>({first_row_below(ymin), 0, strip * K});
    in.last_row = std::min<int32_t>(last_row_at_or_above(ymax), height_ - 1);
    in.colors = dr.texture ? ColorPlanes::kNone : dr.colors;
    in.depth = dr.depth;
    in.affine_colors_ok = dr.depth ? kAffineColors[1] : kAffineColors[0];
    if (dr.phong) {
      for (int k = 0; k < 3; ++k) in.phong.s[k] = &storage_.surfaces[bt.v[k]];
      in.phong.position = dr.position;
      in.phong.tangent = dr.normal_map != nullptr;
      if (dr.two_sided) {
        // Back face: clockwise in NDC, positive area on the display (y down).
        const int64_t area =
            (int64_t{in.v[1]->x} - in.v[0]->x) * (int64_t{in.v[2]->y} - in.v[0]->y) -
            (int64_t{in.v[2]->x} - in.v[0]->x) * (int64_t{in.v[1]->y} - in.v[0]->y);
        in.phong.negate = area > 0;
      }
      in.colors = ColorPlanes::kNone;
      // Texture coordinates in the texture's texels, or in the normal map's without one.
      const Texture* uv_tex = dr.texture ? dr.texture : dr.normal_map;
      if (uv_tex) {
        in.tex.texture = uv_tex;
        in.tex.perspective = true;
        in.tex.colors = false;
        in.tex.wrap_s = dr.wrap_s;
        in.tex.wrap_t = dr.wrap_t;
      }
    } else if (dr.texture) {
      in.tex.texture = dr.texture;
      in.tex.perspective = dr.persp != TexPersp::kAffine;
      in.tex.colors = dr.env == TexEnv::kModulate;
      in.tex.flat = dr.flat;
      in.tex.flat_primary = from_rgb8(bt.flat);
      in.tex.flat_secondary = from_rgb8(bt.flat_spec);
      in.tex.wrap_s = dr.wrap_s;
      in.tex.wrap_t = dr.wrap_t;
    }
    ActiveTriangle& t = storage_.active[slot];
    setup_triangle(in, t);
    ++stats_.triangles_set_up;
    t.index = node;
    t.draw = bt.draw;
    t.flat = bt.flat;
    order[out--] = slot;
  }
  active_count_ += fit;
  if (active_count_ > stats_.max_active) stats_.max_active = static_cast<uint32_t>(active_count_);
}

template <class PF, int K, SpanSet kSpans>
void Renderer<PF, K, kSpans>::raster_triangle(ActiveTriangle& t, Pixel* pixels, int y0, int rows) {
  const DrawRecord& dr = storage_.draws[t.draw];
  // The routines of kSpans' tables (nullptr outside the set, whose draws draw() refused).
  const SpanFn<PF> fn = span_routine<PF, kSpans>(dr.depth, t.colors);
  TexSpanFn<PF> tex_fn = nullptr;
  PhongSpanFn<PF> phong_fn = nullptr;
  if constexpr (detail::has(kSpans.families, SpanFamily::kPhong))
    if (dr.phong) phong_fn = phong_span_routine<PF, kSpans>(dr);
  if constexpr (detail::has(kSpans.families, SpanFamily::kTextured))
    if (dr.texture && !dr.phong) tex_fn = tex_span_routine<PF, kSpans>(dr);
  const int end = std::min<int>(t.last_row, y0 + rows - 1);
  int r = t.row;
  for (; r <= end; ++r) {
    if (r == t.mid_row + 1) t.short_edge = t.bottom_edge;
    int32_t a = t.long_edge.column(), b = t.short_edge.column();
    int32_t left = t.long_is_left ? a : b, right = t.long_is_left ? b : a;
    left = std::max<int32_t>(left, 0);
    right = std::min<int32_t>(right, width_);
    if (left < right) {
      size_t off =
          static_cast<size_t>(r - y0) * static_cast<size_t>(width_) + static_cast<size_t>(left);
      int32_t n = right - left;
      uint16_t* dp = storage_.depth.data() + off;
      stats_.pixels_written += phong_fn ? phong_fn(t, dr, pixels + off, dp, left, r, n)
                               : tex_fn ? tex_fn(t, dr, pixels + off, dp, left, r, n)
                                        : fn(t, pixels + off, dp, left, r, n);
      stats_.pixels_tested += static_cast<uint32_t>(n);
      ++stats_.spans;
    }
    t.long_edge.step();
    t.short_edge.step();
  }
  t.row = static_cast<int16_t>(r);
}

template <class PF, int K, SpanSet kSpans>
void Renderer<PF, K, kSpans>::retire(int next_row) {
  uint16_t* order = storage_.active_index.data();
  uint16_t* free_slots = order + storage_.active.size();
  size_t kept = 0;
  for (size_t i = 0; i < active_count_; ++i) {
    uint16_t slot = order[i];
    if (storage_.active[slot].last_row < next_row)
      free_slots[free_count_++] = slot;
    else
      order[kept++] = slot;
  }
  active_count_ = kept;
}

}  // namespace lr
