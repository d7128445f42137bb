// The rows and edges of a binned triangle, for every family: the part of setup that comes before
// any plane, so that a triangle whose rows cover no pixel centre costs no more than this
// (docs/raster-rules.md, rule 6), and what a row loop needs to pick a huge triangle's edges up.
#pragma once

#include <cstdint>
#include <utility>

#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/setup/row_edge.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr {

// Sorts three vertices by y (display rows, top first) with a fixed network, so that ties are
// deterministic and every step of setup sorts alike.
inline void sort_by_y(const ScreenVertex* v[3]) {
  if (v[1]->y < v[0]->y) std::swap(v[0], v[1]);
  if (v[2]->y < v[1]->y) std::swap(v[1], v[2]);
  if (v[1]->y < v[0]->y) std::swap(v[0], v[1]);
}

// sort_by_y for a binned triangle's vertices (topmost first: store_top_first in
// core/binning/binned_triangle.hpp): the other two in its order with its last compare (the same
// order as sort_by_y's on them).
inline void sort_below_top(const ScreenVertex* v[3]) {
  if (v[2]->y < v[1]->y) std::swap(v[1], v[2]);
}

// The rows (first..last, inclusive: the strip loop's, clamped to the viewport), the middle row,
// the edges and the flags of the triangle whose vertices v are sorted by y and whose area is not
// zero. False when none of those rows has a pixel centre inside the triangle and inside the
// columns [0, width): a sliver, which gets no planes and no active slot.
bool setup_rows(const ScreenVertex* const v[3], int32_t first, int32_t last, int32_t width,
                ActiveTriangle& t);

// An edge of a kWideEdges triangle (v sorted by y; which: ActiveTriangle::kLong, kTop or
// kBottom) picked up at row r for the rows r..r_last of one strip visit (at most 32): a record
// at row r relative to a base of its own, exact on those rows.
struct PickedEdge {
  RowEdge e;
  int32_t cb;
};
PickedEdge wide_edge(const ScreenVertex* const v[3], int which, int32_t r, int32_t r_last);

}  // namespace lr
