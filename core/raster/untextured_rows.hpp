// The row loop of the untextured family: one call per triangle and strip visit, the span of
// the triangle's kind (core/span/untextured_span.hpp) inlined into it, its values at the span's
// first pixel evaluated from the planes in place (two multiply-adds each).
//
// The routines a renderer links: one per (depth test, kind), resolved per triangle at setup
// from kUntexturedRowTable<PF, kSpans>, whose entries no admitted state selects are nullptr (never
// referenced, never linked). A draw's colour planes select kinds as follows:
//   kNone (flat)   kFlat
//   kAffine        kLanes (RGB565 formats; edges within 128 pixels), kAffine
//   kPerspective   kPerspective, and the affine kinds for triangles whose screen-linear colours
//                  are close enough (setup_untextured)
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "lineraster/core/raster/row_loop.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/setup/untextured_setup.hpp"
#include "lineraster/core/span/lane_rows.hpp"
#include "lineraster/core/span/span_state.hpp"
#include "lineraster/core/span/untextured_span.hpp"

namespace lr {

// Whether the per-span row loops of every kind share one walk of the rows, their spans called
// through a pointer (one call per span): at -Os, where the walk is most of a row loop's code
// (0.7 KB a kind on Cortex-M4F) and GCC calls the span out of line anyway. Elsewhere each
// (depth test, kind) has its walk with its span inlined. The same pixels either way.
#if defined(__OPTIMIZE_SIZE__)
inline constexpr bool kSharedRowWalk = true;
#else
inline constexpr bool kSharedRowWalk = false;
#endif

namespace detail {
// The rows of one visit through for_each_span, span(t, px, depth, col, row, n) per span (it
// returns the pixels the depth test rejected).
template <class PF, class Span>
[[gnu::always_inline]] inline void untextured_walk(const ActiveTriangle& t, StripRows& s,
                                                   Span&& span) {
  using Pixel = typename PF::Storage;
  Pixel* const pixels = static_cast<Pixel*>(s.pixels);
  uint16_t* const depth = s.depth;
  const auto width = static_cast<size_t>(s.width);
  const int32_t y0 = s.y0;
  uint32_t spans = 0, tested = 0, rejected = 0;
  const int32_t rows = for_each_span(t, s, [&](int32_t r, int32_t left, int32_t n) {
    const size_t off = static_cast<size_t>(r - y0) * width + static_cast<size_t>(left);
    rejected += span(t, pixels + off, depth + off, left, r, n);
    tested += static_cast<uint32_t>(n);
    ++spans;
  });
  s.spans += spans;
  s.tested += tested;
  s.written += tested - rejected;
  s.rows += static_cast<uint32_t>(rows);
}
}  // namespace detail

// A span of a (depth test, kind) out of line, for the shared walk (kSharedRowWalk).
template <class PF>
using UntexturedSpanFn = uint32_t (*)(const ActiveTriangle& t, typename PF::Storage* px,
                                      uint16_t* depth, int32_t col, int32_t row, int32_t count);
// The perspective and affine colour spans of a depth test, one routine (persp: which), for the
// shared walk: their loops differ only in the pixel's colour.
template <class PF, bool kDepth>
[[gnu::noinline]] uint32_t untextured_colors_call(const ActiveTriangle& t, typename PF::Storage* px,
                                                  uint16_t* depth, int32_t col, int32_t row,
                                                  int32_t count, bool persp) {
  return untextured_span<PF, kDepth, UntexturedKind::kPerspective>(t, px, depth, col, row, count,
                                                                   persp);
}
template <class PF, bool kDepth, UntexturedKind kKind>
[[gnu::noinline]] uint32_t untextured_span_call(const ActiveTriangle& t, typename PF::Storage* px,
                                                uint16_t* depth, int32_t col, int32_t row,
                                                int32_t count) {
  if constexpr (kKind == UntexturedKind::kPerspective || kKind == UntexturedKind::kAffine)
    return untextured_colors_call<PF, kDepth>(t, px, depth, col, row, count,
                                              kKind == UntexturedKind::kPerspective);
  else
    return untextured_span<PF, kDepth, kKind>(t, px, depth, col, row, count);
}
// The shared walk (kSharedRowWalk): one per pixel format.
template <class PF>
[[gnu::noinline]] void untextured_rows_walk(const ActiveTriangle& t, StripRows& s,
                                            UntexturedSpanFn<PF> span) {
  detail::untextured_walk<PF>(t, s, span);
}

// The rows of one visit through for_each_span and a span routine per row.
template <class PF, bool kDepth, UntexturedKind kKind>
[[gnu::noinline]] void untextured_rows_per_span(const ActiveTriangle& t, StripRows& s) {
  if constexpr (kSharedRowWalk) {
    untextured_rows_walk<PF>(t, s, &untextured_span_call<PF, kDepth, kKind>);
  } else {
    detail::untextured_walk<PF>(
        t, s,
        [](const ActiveTriangle& tt, typename PF::Storage* px, uint16_t* depth, int32_t col,
           int32_t row,
           int32_t n) { return untextured_span<PF, kDepth, kKind>(tt, px, depth, col, row, n); });
  }
}

// The lanes kind with the depth test where lane_visit has its hand-allocated form: one loop for
// the visit. Lanes triangles' edges always fit their records (no kWideEdges): their edge
// components are below 2^kLanesMaxEdgeBits subpixels, so the columns of their rows span fewer
// than 2^(kLanesMaxEdgeBits - 7) and their height is below 2^kLanesMaxEdgeBits subpixels
// (setup_rows' bound, docs/numerics.md#edge-columns).
static_assert((kLanesMaxEdgeBits - kSubpixelBits + 1) + kLanesMaxEdgeBits <= 32);
// A run of lanes triangles (t the first) in one call: the strip loop's visit (visit_active).
template <class PF>
[[gnu::noinline]] void lanes_run(const ActiveTriangle& t, LaneRun& run, StripRows& s) {
  lane_run<PF>(t, run, s);
}
// One visit (crowded strips): a run of one, its slot in neither list (one copy of the loop).
template <class PF>
void lanes_rows(const ActiveTriangle& t, StripRows& s) {
  uint16_t slot = 0, list = 0;
  LaneRun run;
  run.start(&slot, &list, &list, &slot + 1, &t, nullptr, s.y_last);
  lanes_run<PF>(t, run, s);
}

// The lanes row loop of a renderer's set when the strip loop visits them in runs (lanes_run):
// where they have the hand-allocated form; nullptr elsewhere.
template <class PF, SpanSet kSet>
constexpr RowFn lanes_run_rows();

// The row loop of a (depth test, kind).
template <class PF, bool kDepth, UntexturedKind kKind>
constexpr RowFn untextured_rows() {
  if constexpr (kKind == UntexturedKind::kLanes && kDepth && kLaneVisitAsm)
    return &lanes_rows<PF>;
  else
    return &untextured_rows_per_span<PF, kDepth, kKind>;
}

// The index of a (depth test, kind) in kUntexturedRowTable<PF, kSet>: the row loops of a
// renderer's untextured kinds, nullptr where no state its set admits uses one.
constexpr size_t untextured_row_index(bool depth, UntexturedKind kind) {
  return static_cast<size_t>(kind) * 2 + (depth ? 1 : 0);
}

// The draw colour planes whose state selects a kind's routine.
constexpr ColorPlanes colors_of(UntexturedKind k) {
  return k == UntexturedKind::kFlat          ? ColorPlanes::kNone
         : k == UntexturedKind::kPerspective ? ColorPlanes::kPerspective
                                             : ColorPlanes::kAffine;
}

// The kind a draw's colour planes select first: the one every triangle of a state gets unless
// setup chooses another (kPerspective may give the affine kinds, kLanes gives kAffine to
// triangles too large for lanes).
template <class PF>
constexpr UntexturedKind primary_kind(ColorPlanes c) {
  return c == ColorPlanes::kNone          ? UntexturedKind::kFlat
         : c == ColorPlanes::kPerspective ? UntexturedKind::kPerspective
         : kRgb565Lanes<PF>               ? UntexturedKind::kLanes
                                          : UntexturedKind::kAffine;
}

// Whether entry i of kUntexturedRowTable is used (not nullptr) by a renderer of PF whose set
// uses the untextured routines u.
template <class PF>
constexpr bool untextured_row_used(const UsedRoutines& u, size_t i) {
  const bool depth = i % 2 != 0;
  const auto kind = static_cast<UntexturedKind>(i / 2);
  return u.untextured[untextured_index(depth, colors_of(kind))] &&
         (kind != UntexturedKind::kLanes || kRgb565Lanes<PF>);
}

namespace detail {
template <class PF, SpanSet kSet, size_t I>
constexpr RowFn untextured_row_entry() {
  constexpr bool kDepth = I % 2 != 0;
  constexpr auto kKind = static_cast<UntexturedKind>(I / 2);
  if constexpr (untextured_row_used<PF>(kUsedRoutines<kSet>, I))
    return untextured_rows<PF, kDepth, kKind>();
  else
    return nullptr;
}
template <class PF, SpanSet kSet, size_t... I>
constexpr std::array<RowFn, sizeof...(I)> untextured_row_table(std::index_sequence<I...> /*rows*/) {
  return {untextured_row_entry<PF, kSet, I>()...};
}
}  // namespace detail

inline constexpr size_t kUntexturedRows = 2 * static_cast<size_t>(kUntexturedKinds);

template <class PF, SpanSet kSet = kAllSpans>
inline constexpr std::array<RowFn, kUntexturedRows> kUntexturedRowTable =
    detail::untextured_row_table<PF, kSet>(std::make_index_sequence<kUntexturedRows>{});

template <class PF, SpanSet kSet>
constexpr RowFn lanes_run_rows() {
  if constexpr (kLaneVisitAsm && kRgb565Lanes<PF>) {
    constexpr RowFn kRows =
        kUntexturedRowTable<PF, kSet>[untextured_row_index(true, UntexturedKind::kLanes)];
    if constexpr (kRows != nullptr && kRows == &lanes_rows<PF>) return kRows;
  }
  return nullptr;
}

}  // namespace lr
