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
#include "lineraster/core/setup/triangle_rows.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr {

// One strip as the row loops see it, and what they count in it.
struct StripRows {
  void* pixels = nullptr;     // the strip's first pixel (the renderer's PF::Storage)
  uint16_t* depth = nullptr;  // the strip's depth (width x rows)
  int32_t y0 = 0;             // first row of the strip
  int32_t y_last = 0;         // last row of the strip (inclusive)
  int32_t width = 0;
  const ScreenVertex* vertices = nullptr;     // the frame's vertex store (wide edges)
  const BinnedTriangle* triangles = nullptr;  // and its binned triangles
  const DrawRecord* draws = nullptr;          // the frame's draw records
  // Spans drawn, pixels inside them, pixels written (depth test passed).
  uint32_t spans = 0, tested = 0, written = 0;
};

namespace detail {

// Edge `which` of t picked up at row r, for rows up to r_last of this visit.
template <class Walker>
[[gnu::always_inline]] inline Walker pick_up(const ActiveTriangle& t, const StripRows& s, int which,
                                             int32_t r, int32_t r_last) {
  if ((t.flags & ActiveTriangle::kWideEdges) == 0) [[likely]]
    return Walker(t.edge[which], t.col_base, r - t.first_row);
  const BinnedTriangle& bt = s.triangles[t.index];
  const ScreenVertex* v[3] = {&s.vertices[bt.v[0]], &s.vertices[bt.v[1]], &s.vertices[bt.v[2]]};
  sort_by_y(v);
  const PickedEdge p = wide_edge(v, which, r, r_last);
  return Walker(p.e, p.cb, 0);
}

}  // namespace detail

// Calls span(row, left, count) for each row of t in the strip whose span, clamped to the
// columns [0, width), is not empty.
template <class Walker = RowEdgeWalker, class SpanFn>
[[gnu::always_inline]] inline void for_each_span(const ActiveTriangle& t, const StripRows& s,
                                                 SpanFn&& span) {
  int32_t r = std::max<int32_t>(t.first_row, s.y0);
  const int32_t end = std::min<int32_t>(t.last_row, s.y_last);
  const int32_t mid = t.mid_row, width = s.width;
  const bool long_left = (t.flags & ActiveTriangle::kLongIsLeft) != 0;
  // The walkers of the left and the right edge; at the middle vertex the short one changes.
  bool top = r <= mid;
  int32_t seg_end = top ? std::min(end, mid) : end;
  Walker lng = detail::pick_up<Walker>(t, s, ActiveTriangle::kLong, r, end);
  Walker shrt = detail::pick_up<Walker>(t, s, top ? ActiveTriangle::kTop : ActiveTriangle::kBottom,
                                        r, seg_end);
  Walker left = long_left ? lng : shrt, right = long_left ? shrt : lng;
  for (;;) {
    for (; r <= seg_end; ++r) {
      const int32_t a = std::max<int32_t>(left.column(), 0);
      const int32_t b = std::min<int32_t>(right.column(), width);
      left.step();
      right.step();
      if (a < b) span(r, a, b - a);
    }
    if (r > end) return;
    // Below the middle vertex: the bottom edge replaces the top one.
    const Walker bottom = detail::pick_up<Walker>(t, s, ActiveTriangle::kBottom, r, end);
    (long_left ? right : left) = bottom;
    seg_end = end;
  }
}

}  // namespace lr
