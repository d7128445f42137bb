// The strip loop: a binned frame rasterized strip by strip into a display sink.
//
// StripLoop<PF, K, kSpans>: PF the strip's pixel format, K the strip height in rows (1..32),
// kSpans the span states it links routines for (span_state.hpp). Per strip: triangles whose
// first row falls in it join the active list (kept in submission order, so depth ties and
// no-depth drawing resolve as in GL) and are set up (core/setup/triangle_setup.hpp); each active
// triangle fills its rows of the strip with its span routine; finished triangles leave; the
// strip goes to the sink. A strip whose triangles do not fit the active list at once is drawn
// in passes of as many as fit, in submission order (crowded_strip): the same pixels, only
// slower. With strip signatures, a strip whose inputs did not change since the last rendered
// frame is stepped over instead (skip_strip).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

#include "lineraster/core/binning/front_end.hpp"
#include "lineraster/core/output/depth_sink.hpp"
#include "lineraster/core/output/frame_stats.hpp"
#include "lineraster/core/output/status.hpp"
#include "lineraster/core/output/strip_sink.hpp"
#include "lineraster/core/raster/legacy_rows.hpp"
#include "lineraster/core/raster/row_loop.hpp"
#include "lineraster/core/raster/strip_fill.hpp"
#include "lineraster/core/raster/strip_visit.hpp"
#include "lineraster/core/raster/untextured_rows.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/setup/triangle_rows.hpp"
#include "lineraster/core/setup/triangle_setup.hpp"
#include "lineraster/core/setup/untextured_setup.hpp"
#include "lineraster/core/span/span_state.hpp"

namespace lr {

// The strip loop's stores (its part of FrameStorage, core/raster/frame_storage.hpp).
struct StripStorage {
  std::span<ActiveTriangle> active;       // triangles being rasterized at once
  std::span<uint16_t> active_index;       // 2 x active.size(): draw order and free slots
  std::span<uint16_t> depth;              // width x K (16-bit depth of one strip)
  std::span<ActiveExtra> active_extra{};  // empty, or one per active slot: textured and Phong
};

template <class PF, int K, SpanSet kSpans = kAllSpans>
class StripLoop {
  static_assert(K >= 1 && K <= 32, "strip height K must be 1..32");

 public:
  using Pixel = typename PF::Storage;

  // Checks the stores against the viewport width (kStoreTooSmall; kInvalidArgument: an active
  // list beyond its index type); forgets the strip signatures. On failure nothing changes.
  Status configure(const StripStorage& s, int width) {
    if (s.active.size() > kMaxStoreEntries) return Status::kInvalidArgument;
    if (s.depth.size() < static_cast<size_t>(width) * static_cast<size_t>(K) || s.active.empty() ||
        s.active_index.size() < 2 * s.active.size() ||
        (!s.active_extra.empty() && s.active_extra.size() < s.active.size()))
      return Status::kStoreTooSmall;
    storage_ = s;
    inputs_known_ = false;
    return Status::kOk;
  }

  // Rasterizes `frame` into the sink, counting into `stats` (see Renderer::render). Always
  // inlined into Renderer::render, its one caller: the renderer's render() is then the strip
  // loop itself, which the compiler inlines where the sink's type is known (direct calls).
  [[gnu::always_inline]] Status render(const BinnedFrame& frame, FrameStats& stats,
                                       StripSink<PF>& sink, DepthSink* depth_sink) {
    Status st = begin(frame, stats, sink, depth_sink);
    if (st == Status::kOk) st = strips(frame, 0, frame.strips, sink, depth_sink);
    return st == Status::kOk ? end(sink, true) : st;
  }
  // render() in its three steps: a frame binned in bands (Renderer::render) runs strips() once
  // per band, with that band's binned frame. end(complete = false): the frame dropped work, so
  // its strip signatures describe nothing to keep. kSkip: strips whose inputs did not change
  // may be left out (RendererFeatures::strip_skipping; false: skip_strip() is not linked, and
  // the frame's strip_inputs are not read). kCrowded: a strip whose triangles outnumber the
  // active list is drawn in passes (RendererFeatures::crowded_strips; false: crowded_strip() is
  // not linked, the triangles starting in such a strip are dropped and counted, and dropped()
  // says so until the next begin()).
  [[gnu::always_inline]] Status begin(const BinnedFrame& frame, FrameStats& stats,
                                      StripSink<PF>& sink, DepthSink* depth_sink);
  template <bool kSkip = true, bool kCrowded = true>
  [[gnu::noinline]] Status strips(const BinnedFrame& frame, int s0, int s1, StripSink<PF>& sink,
                                  DepthSink* depth_sink);
  Status end(StripSink<PF>& sink, bool complete) {
    const Status st = sink.end_frame();
    inputs_known_ = st == Status::kOk && !frame_.strip_inputs.empty() && complete;
    return st;
  }

  // Whether strips<kSkip, false>() dropped triangles of a crowded strip since begin().
  bool dropped() const { return dropped_; }

  // Forgets the strip signatures of the last frame (see Renderer::invalidate_strips).
  void invalidate_strips() { inputs_known_ = false; }

 private:
  // The hand-made lanes setup only in renderers that can draw a lanes triangle (their lanes row
  // loop linked): its 112-byte frame would otherwise sit in the strip loop's stack for nothing
  // (the textured images' worst-case stack, docs/measurements/footprint.md).
  static constexpr bool kHandLanes =
      kSmallPlanesByHand &&
      kUntexturedRowTable<PF, kSpans>[untextured_row_index(true, UntexturedKind::kLanes)] !=
          nullptr;
  using SetupLanes = std::conditional_t<kHandLanes, LanesSetup, NoLanesSetup>;
  // What set_up shares between the triangles of one strip: the rows they may take, and what it
  // needs of the last draw found (consecutive triangles mostly share their draw).
  struct SetupContext {
    RowWindow window;
    // The vertices of the draw found last: [vertex_lo, vertex_lo + vertex_count), draw_of's
    // answer for every triangle whose first vertex lies there (none at first).
    uint32_t vertex_lo = 0, vertex_count = 0;
    // vertex_count when the draw is lanes, else 0: the lanes path's one test per triangle.
    uint32_t lanes_count = 0;
    uint8_t draw = 0;
    bool legacy = false;          // textured or Phong: setup_rows and setup_planes
    bool triangle_pixel = false;  // flat with a colour per triangle
    const RowFn* rows = nullptr;  // the untextured row loops of the draw's depth test, by kind
    RowFn lanes_rows = nullptr;   // rows' kLanes entry (what the setup block mostly makes)
    UntexturedInput in;           // the untextured setup's input for the draw
    bool lanes = false;           // in.lanes_first where kHandLanes: lanes_setup's
    [[no_unique_address]] SetupLanes lanes_setup;  // prepared for the draw when lanes
  };
  RowWindow strip_window(int strip) const {
    return RowWindow{std::max(0, strip * K), frame_.height - 1, frame_.width};
  }
  // The context as setup_context(strip) makes it, for what set_up reads before a draw is found
  // (the rest is set when one is).
  void renew(SetupContext& c, int strip) const {
    c.window = strip_window(strip);
    c.vertex_count = 0;
    c.lanes_count = 0;
  }
  SetupContext setup_context(int strip) const {
    SetupContext c;
    c.window = strip_window(strip);
    return c;
  }
  bool activate(int strip, SetupContext& context);
  bool set_up(uint16_t node, const BinnedTriangle& bt, SetupContext& c, uint16_t slot,
              ActiveTriangle& t);
  bool set_up_lanes(uint16_t node, const BinnedTriangle& bt, SetupContext& c, ActiveTriangle& t,
                    uint32_t& slivers);
  void set_up_lanes_run(uint16_t& node, uint16_t*& top_slot, size_t& room, SetupContext& c);
  SetupInput setup_input(uint16_t node, const BinnedTriangle& bt, const DrawRecord& dr) const;
  uint8_t draw_of(const BinnedTriangle& bt) const;
  void crowded_strip(int strip, Pixel* pixels, int y0, int rows, SetupContext& context);
  void drop_bucket(int strip);
  void skip_strip(int strip, int y0, int rows);
  void carry_into(int strip, uint16_t carried);
  void resolve_fetchers();
  StripRows strip_rows(Pixel* pixels, int y0, int rows) const;
  void add_counts(const StripRows& s);
  void retire(int next_row);
  void visit(StripRows& sr);

  // Whether the set links the affine colour routine, without and with depth: only then may a
  // perspective-colour triangle be given affine planes (setup_untextured_triangle).
  static constexpr bool kAffineColors[2] = {
      kUsedRoutines<kSpans>.untextured[untextured_index(false, ColorPlanes::kAffine)],
      kUsedRoutines<kSpans>.untextured[untextured_index(true, ColorPlanes::kAffine)]};

  // Whether the set admits untextured draws without colour planes (flat-shaded, one-coloured):
  // only then has a draw or a triangle a pixel of its own to encode (the others' code is not
  // linked: no such draw is admitted).
  static constexpr bool kFlatPixels = detail::has(kSpans.colors, ColorPlanes::kNone);

  // The lanes row loop where visit() takes runs of lanes triangles in one call (else nullptr),
  // and the run's words (in the object: on the stack they would deepen its deepest path).
  static constexpr RowFn kRunRows = lanes_run_rows<PF, kSpans>();
  struct NoLaneRun {};
  [[no_unique_address]] std::conditional_t<kRunRows != nullptr, LaneRun, NoLaneRun> lane_run_{};

  StripStorage storage_{};
  BinnedFrame frame_{};  // the frame being rendered
  FrameStats* stats_ = nullptr;
  size_t active_count_ = 0;
  size_t free_count_ = 0;
  bool inputs_known_ = false;  // strip_inputs' second half describes the last frame rendered
  bool may_skip_ = false;      // this frame may leave out strips whose inputs did not change
  bool dropped_ = false;       // a crowded strip's triangles were dropped (strips<kSkip, false>)
};

template <class PF, int K, SpanSet kSpans>
inline Status StripLoop<PF, K, kSpans>::begin(const BinnedFrame& frame, FrameStats& stats,
                                              StripSink<PF>& sink, DepthSink* depth_sink) {
  frame_ = frame;
  stats_ = &stats;
  dropped_ = false;
  resolve_fetchers();
  const auto w = static_cast<size_t>(frame_.width);
  stats.bytes_per_strip = static_cast<uint32_t>(w * K * (sizeof(Pixel) + sizeof(uint16_t)));
  // Until this frame has reached the display whole, the signatures describe nothing shown.
  const bool had_inputs = inputs_known_;
  inputs_known_ = false;
  const Status st =
      sink.begin_frame(static_cast<uint16_t>(frame_.width), static_cast<uint16_t>(frame_.height));
  may_skip_ = had_inputs && depth_sink == nullptr && sink.retains_frame();
  return st;
}

// Strips [s0, s1) of `frame` (the whole frame, or a band's binned frame: every triangle that
// touches the band is in it, those from above in its first strip's bucket).
template <class PF, int K, SpanSet kSpans>
template <bool kSkip, bool kCrowded>
Status StripLoop<PF, K, kSpans>::strips(const BinnedFrame& frame, int s0, int s1,
                                        StripSink<PF>& sink, DepthSink* depth_sink) {
  frame_ = frame;
  FrameStats& stats = *stats_;
  const auto w = static_cast<size_t>(frame_.width);
  active_count_ = 0;
  free_count_ = storage_.active.size();
  uint16_t* free_slots = storage_.active_index.data() + storage_.active.size();
  for (size_t i = 0; i < free_count_; ++i)
    free_slots[i] = static_cast<uint16_t>(free_count_ - 1 - i);

  Status st = Status::kOk;
  const bool may_skip = may_skip_;
  uint32_t* inputs = !kSkip || frame_.strip_inputs.empty() ? nullptr : frame_.strip_inputs.data();
  const auto last = static_cast<size_t>(frame_.strips);  // the last frame's half
  const Pixel bg = PF::encode(frame_.background);
  SetupContext context = setup_context(s0);  // made once: activate renews what a strip needs
  for (int s = s0; s < s1; ++s) {
    const int y0 = s * K;
    const int rows = std::min(K, frame_.height - y0);
    const size_t count = w * static_cast<size_t>(rows);
    const StripRect rect{0, static_cast<uint16_t>(y0), static_cast<uint16_t>(frame_.width),
                         static_cast<uint16_t>(rows)};
    if (inputs != nullptr) {
      const auto i = static_cast<size_t>(s);
      if (may_skip && inputs[i] == inputs[last + i]) {
        skip_strip(s, y0, rows);
        ++stats.strips_skipped;
        ++stats.strips;
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
    bool fits = activate(s, context);
    if constexpr (!kCrowded) {
      if (!fits) {
        drop_bucket(s);
        fits = true;
      }
    }
    std::span<uint16_t> depth = storage_.depth.first(count);
    if (!fits) {
      fill_pixels(depth.data(), count, uint16_t{0xFFFF});
      crowded_strip(s, px.data(), y0, rows, context);
    } else if (active_count_ == 0) {
      ++stats.empty_strips;
      if (depth_sink) fill_pixels(depth.data(), count, uint16_t{0xFFFF});
    } else {
      fill_pixels(depth.data(), count, uint16_t{0xFFFF});
      StripRows sr = strip_rows(px.data(), y0, rows);
      visit(sr);
      add_counts(sr);
    }
    if (depth_sink) depth_sink->on_depth(rect, depth);
    ++stats.strips;
    st = sink.submit(rect, std::move(lease));
    if (st != Status::kOk) return st;
  }
  return Status::kOk;
}

// A strip whose inputs did not change: the triangles active in it stay as they are (a visit of
// the next strip picks them up at its own first row); those that start in it and end in it are
// never set up, those that go on are handed to the next strip's bucket (in submission order), to
// be set up at that strip's first row.
template <class PF, int K, SpanSet kSpans>
void StripLoop<PF, K, kSpans>::skip_strip(int strip, int y0, int rows) {
  const int next_row = y0 + rows;
  retire(next_row);

  const std::span<BinnedTriangle> tris = frame_.triangles;
  const std::span<uint16_t> buckets = frame_.buckets;
  const int strips = frame_.strips;
  uint16_t& head = buckets[static_cast<size_t>(strip)];
  uint16_t carried = kNoTriangle, *tail = &carried;
  if (strip + 1 < strips) {
    for (uint16_t i = head; i != kNoTriangle; i = tris[i].next) {
      const BinnedTriangle& bt = tris[i];
      const int32_t ymax = std::max(
          {frame_.vertices[bt.v[0]].y, frame_.vertices[bt.v[1]].y, frame_.vertices[bt.v[2]].y});
      if (last_row_at_or_above(ymax) >= next_row) {
        *tail = i;
        tail = &tris[i].next;
      }
    }
  }
  *tail = kNoTriangle;
  head = kNoTriangle;
  if (strip + 1 < strips) carry_into(strip + 1, carried);
}

// Merges `carried` (a list from the latest submission to the earliest, like every bucket) into
// the bucket of `strip`.
template <class PF, int K, SpanSet kSpans>
void StripLoop<PF, K, kSpans>::carry_into(int strip, uint16_t carried) {
  const std::span<BinnedTriangle> tris = frame_.triangles;
  uint16_t& next = frame_.buckets[static_cast<size_t>(strip)];
  uint16_t a = carried, b = next, merged = kNoTriangle;
  uint16_t* out = &merged;
  while (a != kNoTriangle || b != kNoTriangle) {
    uint16_t& pick = (b == kNoTriangle || (a != kNoTriangle && a > b)) ? a : b;
    *out = pick;
    out = &tris[pick].next;
    pick = tris[pick].next;
  }
  *out = kNoTriangle;
  next = merged;
}

// A strip whose triangles (those active and those starting in it) outnumber the active slots.
// All of them are drawn in passes of as many as the active list holds, from the earliest
// submission to the latest, each set up at the strip's first row: every pixel sees the same
// fragments in the same order as in one pass. Those that go on are handed to the next strip's
// bucket, like skip_strip's.
template <class PF, int K, SpanSet kSpans>
void StripLoop<PF, K, kSpans>::crowded_strip(int strip, Pixel* pixels, int y0, int rows,
                                             SetupContext& context) {
  const std::span<BinnedTriangle> tris = frame_.triangles;
  uint16_t* order = storage_.active_index.data();
  uint16_t* free_slots = order + storage_.active.size();
  // The bucket, reversed into submission order, merged with the active list (in that order).
  uint16_t& head = frame_.buckets[static_cast<size_t>(strip)];
  uint16_t bucket = kNoTriangle;
  for (uint16_t i = head; i != kNoTriangle;) {
    const uint16_t n = tris[i].next;
    tris[i].next = bucket;
    bucket = i;
    i = n;
  }
  head = kNoTriangle;
  uint16_t all = kNoTriangle, *tail = &all;
  size_t k = 0;
  while (k < active_count_ || bucket != kNoTriangle) {
    const bool take_active =
        k < active_count_ && (bucket == kNoTriangle || storage_.active[order[k]].index < bucket);
    const uint16_t node = take_active ? storage_.active[order[k++]].index : bucket;
    if (!take_active) bucket = tris[bucket].next;
    *tail = node;
    tail = &tris[node].next;
  }
  *tail = kNoTriangle;
  for (size_t i = 0; i < active_count_; ++i) free_slots[free_count_++] = order[i];
  active_count_ = 0;

  const int next_row = y0 + rows;
  uint16_t carried = kNoTriangle;  // from the latest submission to the earliest
  renew(context, strip);  // strips()'s: one context on the stack (the worst-case stack's path)
  for (uint16_t node = all; node != kNoTriangle;) {
    size_t batch = 0;
    while (node != kNoTriangle && free_count_ > 0) {
      const uint16_t n = tris[node].next;
      const uint16_t slot = free_slots[--free_count_];
      if (set_up(node, tris[node], context, slot, storage_.active[slot])) {
        order[batch++] = slot;
        ++stats_->triangles_set_up;
      } else
        free_slots[free_count_++] = slot;
      node = n;
    }
    StripRows sr = strip_rows(pixels, y0, rows);
    for (size_t i = 0; i < batch; ++i) {
      const ActiveTriangle& t = storage_.active[order[i]];
      t.rows(t, sr);
    }
    add_counts(sr);
    for (size_t i = 0; i < batch; ++i) {
      const ActiveTriangle& t = storage_.active[order[i]];
      if (t.last_row >= next_row) {
        tris[t.index].next = carried;
        carried = t.index;
      }
      free_slots[free_count_++] = order[i];
    }
    ++stats_->strip_passes;
  }
  --stats_->strip_passes;  // the first pass is the strip's own
  stats_->max_active = static_cast<uint32_t>(storage_.active.size());
  if (strip + 1 < frame_.strips) carry_into(strip + 1, carried);
}

// A crowded strip in a renderer without crowded_strips: the triangles starting in it are
// dropped (counted as the front end counts what a full store drops), those already active
// are drawn as in any strip.
template <class PF, int K, SpanSet kSpans>
void StripLoop<PF, K, kSpans>::drop_bucket(int strip) {
  uint16_t& head = frame_.buckets[static_cast<size_t>(strip)];
  for (uint16_t i = head; i != kNoTriangle; i = frame_.triangles[i].next)
    ++stats_->dropped_triangle_capacity;
  head = kNoTriangle;
  dropped_ = true;
}

// The texel fetchers of this frame's draws (DrawRecord): here, in the template, from the tables
// of kSpans, so that a renderer references only the fetch routines its set admits (none without
// textured or Phong states). The front end refused every draw whose textures the set does not
// admit.
template <class PF, int K, SpanSet kSpans>
void StripLoop<PF, K, kSpans>::resolve_fetchers() {
  if constexpr (kUsedRoutines<kSpans>.any_fetch()) {
    for (DrawRecord& d : frame_.draws) {
      if (d.texture != nullptr)
        d.fetch = fetch_routine<kSpans>(d.texture->format, d.filter, d.wrap_s, d.wrap_t);
      if (d.envmap != nullptr) d.env_fetch = env_fetch_routine<kSpans>(d.envmap->format);
      if (d.normal_map != nullptr)
        d.nmap_fetch = fetch_routine<kSpans>(d.normal_map->format, d.filter, d.wrap_s, d.wrap_t);
    }
  }
}

// Moves the triangles of the strip's bucket into the active list; false (nothing moved) when
// they do not all fit beside those already active (the strip is then crowded_strip's).
template <class PF, int K, SpanSet kSpans>
bool StripLoop<PF, K, kSpans>::activate(int strip, SetupContext& context) {
  const std::span<BinnedTriangle> tris = frame_.triangles;
  uint16_t& head = frame_.buckets[static_cast<size_t>(strip)];
  if (head == kNoTriangle) return true;
  uint16_t* const order = storage_.active_index.data();
  uint16_t* const free_slots = order + storage_.active.size();
  FrameStats& stats = *stats_;
  const size_t free_before = free_count_;

  // First every triangle of the bucket (latest submission first) is set up in the slot on top
  // of the free list, which a triangle set up takes (a sliver leaves it for the next): the new
  // slots end as free_slots[free, free_before), the earliest submission first. The loop keeps
  // little in registers (set_up's block needs them). A bucket of more triangles than there are
  // free slots is refused when the first one past them comes, as a count beforehand would:
  // what set_up wrote went to free slots only, and its counts are put back.
  const uint32_t without_pixels = stats.triangles_without_pixels, wide = stats.triangles_wide;
  ActiveTriangle* const active = storage_.active.data();
  uint16_t* top_slot = free_slots + free_before;  // one past the top of the free list
  size_t room = free_before;
  renew(context, strip);
  for (uint16_t node = head; node != kNoTriangle;) {
    if (room == 0) [[unlikely]] {
      stats.triangles_without_pixels = without_pixels;
      stats.triangles_wide = wide;
      return false;
    }
    if constexpr (kHandLanes) {
      // Consecutive triangles of the lanes draw found last (the common case) in a loop of their
      // own: fewer values live across the setup block's call than in the general loop's.
      if (uint32_t{tris[node].v[0]} - context.vertex_lo < context.lanes_count) {
        set_up_lanes_run(node, top_slot, room, context);
        continue;
      }
    }
    --room;
    const BinnedTriangle& bt = tris[node];
    const uint16_t slot = top_slot[-1];
    if (set_up(node, bt, context, slot, active[slot])) --top_slot;
    node = bt.next;
  }
  head = kNoTriangle;
  const auto free = static_cast<size_t>(top_slot - free_slots);
  free_count_ = free;

  // Then the new slots are merged into the active list (ascending submission order) from the
  // back: each new one, from the latest, moves up the entries of later submission. `top` is the
  // submission index of the last entry not moved yet (-1: none is left).
  const uint16_t* const fresh = free_slots + free;
  const size_t added = free_before - free;
  uint16_t* src = order + active_count_;
  uint16_t* dst = src + added;
  int32_t top = src == order ? -1 : active[src[-1]].index;
  for (const uint16_t* f = fresh + added; f != fresh;) {
    const uint16_t slot = *--f;
    const int32_t index = active[slot].index;
    while (top > index) {
      *--dst = *--src;
      top = src == order ? -1 : active[src[-1]].index;
    }
    *--dst = slot;
  }
  active_count_ += added;
  stats.triangles_set_up += static_cast<uint32_t>(added);
  if (active_count_ > stats.max_active) stats.max_active = static_cast<uint32_t>(active_count_);
  return true;
}

// activate's loop over consecutive triangles of the lanes draw (the first one is): each set up
// in the slot on top of the free list (top_slot[-1]), which it takes unless it is a sliver, until
// the bucket ends, the room is used up or a triangle of another draw comes.
template <class PF, int K, SpanSet kSpans>
[[gnu::always_inline]] inline void StripLoop<PF, K, kSpans>::set_up_lanes_run(uint16_t& node,
                                                                              uint16_t*& top_slot,
                                                                              size_t& room,
                                                                              SetupContext& c) {
  const BinnedTriangle* const tris = frame_.triangles.data();
  ActiveTriangle* const active = storage_.active.data();
  uint16_t n = node;
  uint16_t* top = top_slot;
  size_t left = room;
  uint32_t slivers = 0;  // added to the statistics once
  const uint32_t lo = c.vertex_lo, count = c.lanes_count;
  do {
    --left;
    const BinnedTriangle& bt = tris[n];
    if (set_up_lanes(n, bt, c, active[top[-1]], slivers)) --top;
    n = bt.next;
  } while (n != kNoTriangle && left != 0 && uint32_t{tris[n].v[0]} - lo < count);
  stats_->triangles_without_pixels += slivers;
  node = n;
  top_slot = top;
  room = left;
}

// Sets binned triangle `node` (bt, its record) up in active slot `slot` (t, its record), from the
// later of its first row and the strip's (triangles carried over a skipped or crowded strip, or
// binned into a band that starts below their top). False for a sliver between pixel centres: no
// planes, the slot unused. The caller counts the triangles set up (FrameStats::triangles_set_up).
template <class PF, int K, SpanSet kSpans>
[[gnu::always_inline]] inline bool StripLoop<PF, K, kSpans>::set_up(uint16_t node,
                                                                    const BinnedTriangle& bt,
                                                                    SetupContext& c, uint16_t slot,
                                                                    ActiveTriangle& t) {
  constexpr bool kPhong = kSpans.has(SpanFamily::kPhong);
  constexpr bool kTexture = kPhong || kSpans.has(SpanFamily::kTextured);
  // The common case first: a triangle of the lanes draw found last.
  if (kHandLanes && uint32_t{bt.v[0]} - c.vertex_lo < c.lanes_count) [[likely]]
    return set_up_lanes(node, bt, c, t, stats_->triangles_without_pixels);
  // Consecutive triangles mostly share their draw: its vertex range before the search, and what
  // setup needs of the draw only when it changes.
  if (uint32_t{bt.v[0]} - c.vertex_lo >= c.vertex_count) [[unlikely]] {
    const uint8_t d = draw_of(bt);
    const DrawRecord& dr = frame_.draws[d];
    c.draw = d;
    c.vertex_lo = dr.first_vertex;
    c.vertex_count =
        (d + 1u < frame_.draws.size() ? frame_.draws[d + 1u].first_vertex : uint32_t{0x10000}) -
        c.vertex_lo;
    // Textured and Phong triangles get their slot's extra planes (the front end refuses such
    // draws when there are none). A renderer without those spans sets up no such planes.
    c.legacy = kTexture && (dr.texture != nullptr || dr.phong);
    c.triangle_pixel = kFlatPixels && dr.colors == ColorPlanes::kNone && dr.triangle_colors;
    c.rows =
        &kUntexturedRowTable<PF, kSpans>[untextured_row_index(dr.depth, UntexturedKind::kFlat)];
    c.lanes_rows = c.rows[UntexturedTriangle::made(UntexturedKind::kLanes, false).row_offset()];
    UntexturedInput& in = c.in;
    in.colors = dr.colors;
    in.depth = dr.depth;
    in.lanes = kRgb565Lanes<PF>;
    in.affine_ok = kAffineColors[dr.depth ? 1 : 0];
    in.affine = kRgb565Lanes<PF> ? kAffineBound565 : kAffineBound8;
    if (kFlatPixels && dr.colors == ColorPlanes::kNone && !dr.triangle_colors)
      in.flat_pixel = pixel_bits<PF>(PF::encode(dr.color));
    in.lanes_first = lanes_first_of(in);
    in.hue = dr.hue;  // (read by lanes Gouraud triangles only)
    c.lanes = kHandLanes && in.lanes_first && !c.legacy;
    if (kHandLanes && c.lanes)
      c.lanes_setup.prepare(c.window, in, frame_.vertices.data(), c.lanes_rows);
    c.lanes_count = c.lanes ? c.vertex_count : 0;
  }
  if (kHandLanes && c.lanes) return set_up_lanes(node, bt, c, t, stats_->triangles_without_pixels);
  const uint8_t draw = c.draw;
  const RowWindow& window = c.window;
  const ScreenVertex* v[3];
  for (int k = 0; k < 3; ++k) v[k] = &frame_.vertices[bt.v[k]];
  sort_below_top(v);  // (binned top first)
  if (kTexture && c.legacy) {
    const DrawRecord& dr = frame_.draws[draw];
    const int32_t first = std::max<int32_t>(first_row_below(v[0]->y), window.first_min);
    const int32_t last = std::min<int32_t>(last_row_at_or_above(v[2]->y), window.last_max);
    if (!setup_rows(v, first, last, window.width, t)) {
      ++stats_->triangles_without_pixels;
      return false;
    }
    t.ext = &storage_.active_extra[slot];
    setup_planes<kTexture, kPhong>(setup_input(node, bt, dr), t);
    t.rows = &legacy_rows<PF, kSpans>;
  } else {
    t.ext = nullptr;
    UntexturedInput& in = c.in;
    if (kFlatPixels && c.triangle_pixel)
      in.flat_pixel = pixel_bits<PF>(PF::encode(frame_.triangle_colors[node].primary));
    const UntexturedTriangle u = setup_untextured_triangle(v, window, in, t);
    if (!u.pixels()) {
      ++stats_->triangles_without_pixels;
      return false;
    }
    if (u.wide()) [[unlikely]]
      ++stats_->triangles_wide;
    // The kinds' entries are untextured_row_index(depth, kind) = the first kind's + 2 kind.
    static_assert(untextured_row_index(true, UntexturedKind::kLanes) ==
                  untextured_row_index(true, UntexturedKind::kFlat) +
                      2 * static_cast<size_t>(UntexturedKind::kLanes));
    t.rows = c.rows[u.row_offset()];
  }
  t.index = node;
  t.draw = draw;
  return true;
}

// set_up of a triangle of a lanes draw (c prepared for it): one call from the indices; a sliver
// is counted in `slivers` (the statistics', or a run's count: set_up_lanes_run). Neither
// t.ext nor t.draw is stored: only the textured and Phong rows read them (legacy_rows), and a
// lanes triangle's rows are untextured.
template <class PF, int K, SpanSet kSpans>
[[gnu::always_inline]] inline bool StripLoop<PF, K, kSpans>::set_up_lanes(uint16_t node,
                                                                          const BinnedTriangle& bt,
                                                                          SetupContext& c,
                                                                          ActiveTriangle& t,
                                                                          uint32_t& slivers) {
  constexpr UntexturedTriangle kLanes = UntexturedTriangle::made(UntexturedKind::kLanes, false);
  const UntexturedTriangle u = c.lanes_setup.set_up(bt.v, t);
  if (u != kLanes) [[unlikely]] {  // (a lanes triangle's t.rows: LanesSetup's, c.lanes_rows)
    if (!u.pixels()) {
      ++slivers;
      return false;
    }
    if (u.wide()) [[unlikely]]
      ++stats_->triangles_wide;
    t.rows = c.rows[u.row_offset()];
  }
  t.index = node;
  return true;
}

// The draw whose vertices a binned triangle's are: the last whose first vertex is at or below
// its first (the draws' vertex ranges follow each other in draw order).
template <class PF, int K, SpanSet kSpans>
uint8_t StripLoop<PF, K, kSpans>::draw_of(const BinnedTriangle& bt) const {
  const std::span<const DrawRecord> draws = frame_.draws;
  size_t lo = 0, n = draws.size();
  while (n > 1) {
    const size_t half = n / 2;
    if (draws[lo + half].first_vertex <= bt.v[0]) {
      lo += half;
      n -= half;
    } else {
      n = half;
    }
  }
  return static_cast<uint8_t>(lo);
}

// What setup_planes needs of a textured or Phong triangle and its draw (the rows are
// setup_rows').
template <class PF, int K, SpanSet kSpans>
SetupInput StripLoop<PF, K, kSpans>::setup_input(uint16_t node, const BinnedTriangle& bt,
                                                 const DrawRecord& dr) const {
  SetupInput in;
  for (int k = 0; k < 3; ++k) in.v[k] = &frame_.vertices[bt.v[k]];
  if (dr.uv)
    for (int k = 0; k < 3; ++k) in.tex.tv[k] = &frame_.tex_vertices[bt.v[k]];
  in.colors = dr.texture ? ColorPlanes::kNone : dr.colors;
  in.depth = dr.depth;
  if (kSpans.has(SpanFamily::kPhong) && dr.phong) {
    for (int k = 0; k < 3; ++k) in.phong.s[k] = &frame_.surfaces[bt.v[k]];
    in.phong.position = dr.position;
    in.phong.tangent = dr.normal_map != nullptr;
    // A two-sided draw's back face gets the negated normal.
    if (dr.two_sided) in.phong.negate = back_facing(signed_area2(*in.v[0], *in.v[1], *in.v[2]));
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
  } else if (kSpans.has(SpanFamily::kTextured) && dr.texture) {
    in.tex.texture = dr.texture;
    in.tex.perspective = dr.persp != TexPersp::kAffine;
    in.tex.colors = dr.env == TexEnv::kModulate;
    in.tex.flat = dr.flat;
    if (dr.triangle_colors) {
      const TriangleColors& c = frame_.triangle_colors[node];
      in.tex.flat_primary = from_rgb8(c.primary);
      in.tex.flat_secondary = from_rgb8(c.secondary);
    }
    in.tex.wrap_s = dr.wrap_s;
    in.tex.wrap_t = dr.wrap_t;
  }
  return in;
}

// The strip at rows y0..y0 + rows - 1 of `pixels` (and the strip's depth) for the row loops.
template <class PF, int K, SpanSet kSpans>
StripRows StripLoop<PF, K, kSpans>::strip_rows(Pixel* pixels, int y0, int rows) const {
  StripRows s;
  s.pixels = pixels;
  s.depth = storage_.depth.data();
  s.y0 = y0;
  s.y_last = y0 + rows - 1;
  s.width = frame_.width;
  s.vertices = frame_.vertices.data();
  s.triangles = frame_.triangles.data();
  s.draws = frame_.draws.data();
  return s;
}

template <class PF, int K, SpanSet kSpans>
void StripLoop<PF, K, kSpans>::add_counts(const StripRows& s) {
  FrameStats& stats = *stats_;
  stats.spans += s.spans;
  stats.pixels_tested += s.tested;
  stats.pixels_written += s.written;
  stats.rows_walked += s.rows;
}

// Draws every active triangle's rows of the strip sr, in submission order, and retires those
// that end in it (retire's work in the same pass: one loop per strip visit; runs of lanes
// triangles in one call where they have the hand-allocated form).
template <class PF, int K, SpanSet kSpans>
void StripLoop<PF, K, kSpans>::visit(StripRows& sr) {
  uint16_t* const order = storage_.active_index.data();
  ActiveList list{order, order + storage_.active.size(), storage_.active.data(), active_count_,
                  free_count_};
  const auto run = [](const ActiveTriangle& t, LaneRun& r, StripRows& s) {
    if constexpr (kRunRows != nullptr) lanes_run<PF>(t, r, s);
  };
  if constexpr (kRunRows != nullptr) {
    visit_active(list, sr, kRunRows, lane_run_, run);
  } else {
    LaneRun unused{};
    visit_active(list, sr, nullptr, unused, run);
  }
  active_count_ = list.count;
  free_count_ = list.free;
}

template <class PF, int K, SpanSet kSpans>
void StripLoop<PF, K, kSpans>::retire(int next_row) {
  uint16_t* const order = storage_.active_index.data();
  uint16_t* const free_slots = order + storage_.active.size();
  const ActiveTriangle* const active = storage_.active.data();
  // The counts in locals: the stores through uint16_t pointers would reload the members.
  const size_t count = active_count_;
  size_t kept = 0, free = free_count_;
  for (size_t i = 0; i < count; ++i) {
    const uint16_t slot = order[i];
    if (active[slot].last_row < next_row)
      free_slots[free++] = slot;
    else
      order[kept++] = slot;
  }
  active_count_ = kept;
  free_count_ = free;
}

}  // namespace lr
