// The row loop: one triangle's rows of one strip, from its edges to its spans. Every family's
// row loop walks the rows the same way (for_each_span); what it does per span is the family's
// (the untextured one: core/raster/untextured_rows.hpp; textured and Phong: legacy_rows below,
// which calls their span routines per row).
//
// A strip visit picks the triangle up at the strip's first row (or its own first row) from the
// records (one multiply-add per edge, core/setup/row_edge.hpp), walks the rows above the middle
// vertex with the top edge and those below with the bottom edge, and clamps each span to the
// viewport's columns. Nothing of the triangle is written: a visit may start at any strip.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "lineraster/core/binning/binned_triangle.hpp"
#include "lineraster/core/binning/draw_record.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/setup/row_edge.hpp"
#include "lineraster/core/setup/strip_rows.hpp"
#include "lineraster/core/setup/triangle_rows.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr {

namespace detail {

// pick_up() of a kWideEdges triangle: out of line where the code is built for size (one copy for
// a visit's three pick-ups), inlined elsewhere.
#if defined(__OPTIMIZE_SIZE__)
#define LR_PICK_UP_WIDE [[gnu::noinline]]
#else
#define LR_PICK_UP_WIDE [[gnu::always_inline]] inline
#endif
template <class Walker>
LR_PICK_UP_WIDE Walker pick_up_wide(const ActiveTriangle& t, const StripRows& s, int side,
                                    bool bottom, int32_t r, int32_t r_last) {
  const BinnedTriangle& bt = s.triangles[t.index];
  const ScreenVertex* v[3] = {&s.vertices[bt.v[0]], &s.vertices[bt.v[1]], &s.vertices[bt.v[2]]};
  sort_by_y(v);
  const int which = bottom                   ? ActiveTriangle::kBottom
                    : side == t.short_side() ? ActiveTriangle::kTop
                                             : ActiveTriangle::kLong;
  const PickedEdge p = wide_edge(v, which, r, r_last);
  return Walker(p.e, p.cb, 0);
}
#undef LR_PICK_UP_WIDE

// The edge of side `side` (0 left, 1 right) of t's rows down to mid_row (bottom: the bottom
// edge) picked up at row r, for rows up to r_last of this visit.
template <class Walker>
[[gnu::always_inline]] inline Walker pick_up(const ActiveTriangle& t, const StripRows& s, int side,
                                             bool bottom, int32_t r, int32_t r_last) {
  if ((t.flags & ActiveTriangle::kWideEdges) == 0) [[likely]] {
    if (bottom) return Walker(t.bottom, t.col_base, r - t.mid_row - 1);
    return Walker(t.side_edge(side), t.col_base, r - t.first_row);
  }
  return pick_up_wide<Walker>(t, s, side, bottom, r, r_last);
}

}  // namespace detail

// Calls span(row, left, count) for each row of t in the strip whose span, clamped to the
// columns [0, width), is not empty. Returns the rows walked.
template <class Walker = RowEdgeWalker, class SpanFn>
[[gnu::always_inline]] inline int32_t for_each_span(const ActiveTriangle& t, const StripRows& s,
                                                    SpanFn&& span) {
  int32_t r = std::max<int32_t>(t.first_row, s.y0);
  const int32_t end = std::min<int32_t>(t.last_row, s.y_last);
  const int32_t mid = t.mid_row, width = s.width, rows = end - r + 1;
  const int ss = t.short_side();
  // The walkers of the left and the right edge; below the middle vertex the bottom edge
  // replaces the top one (on the short side).
  const bool top = r <= mid;
  int32_t seg_end = top ? std::min(end, mid) : end;
  Walker w[2] = {detail::pick_up<Walker>(t, s, 0, !top && ss == 0, r, ss == 0 ? seg_end : end),
                 detail::pick_up<Walker>(t, s, 1, !top && ss == 1, r, ss == 1 ? seg_end : end)};
  for (;;) {
    for (; r <= seg_end; ++r) {
      const int32_t a = std::max<int32_t>(w[0].column(), 0);
      const int32_t b = std::min<int32_t>(w[1].column(), width);
      w[0].step();
      w[1].step();
      if (a < b) span(r, a, b - a);
    }
    if (r > end) return rows;
    w[ss] = detail::pick_up<Walker>(t, s, ss, true, r, end);
    seg_end = end;
  }
}

}  // namespace lr
