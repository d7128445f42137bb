#include "lineraster/core/setup/triangle_rows.hpp"

#include <algorithm>

#include "lineraster/core/math/wide_divide.hpp"

namespace lr {

namespace {

// The two vertices of edge `which` (sorted vertices).
const ScreenVertex& edge_start(const ScreenVertex* const v[3], int which) {
  return *v[which == ActiveTriangle::kBottom ? 1 : 0];
}
const ScreenVertex& edge_end(const ScreenVertex* const v[3], int which) {
  return *v[which == ActiveTriangle::kTop ? 1 : 2];
}

// floor(q / dy), q = Q(r) of an edge (relative to column 0) on one of the edge's own rows (the
// row centre within the edge's y range, as every caller's rows are): there the edge lies in the
// guard band, |column| <= 2^14 + 1 (screen_vertex.hpp), so |q| < dy 2^32 and the division is one
// 64-by-32 (no C library 64-bit division); below zero the floor is one under the truncated
// quotient when a remainder is left, as floor_div's.
int32_t edge_column(int64_t q, int64_t dy) {
  const Quotient32 d = divide_64by32(abs64(q), static_cast<uint32_t>(dy));  // dy in (0, 2^23)
  return static_cast<int32_t>(q >= 0 ? int64_t{d.q} : -int64_t{d.q} - (d.r != 0 ? 1 : 0));
}

// The column of edge `which` on row r, exact in int64 (wide triangles).
int32_t wide_column(const ScreenVertex* const v[3], int which, int32_t r) {
  const ScreenVertex &a = edge_start(v, which), &b = edge_end(v, which);
  return edge_column(edge_numerator(a.x, a.y, b.x, b.y, 0, r), int64_t{b.y} - a.y);
}

}  // namespace

bool setup_rows(const ScreenVertex* const v[3], int32_t first, int32_t last, int32_t width,
                ActiveTriangle& t) {
  const int32_t x0 = v[0]->x, y0 = v[0]->y, x1 = v[1]->x, y1 = v[1]->y, x2 = v[2]->x, y2 = v[2]->y;
  // Vertices sorted top to bottom: a positive area puts the middle vertex right of the long edge.
  const bool long_left = signed_area2(*v[0], *v[1], *v[2]) > 0;
  uint8_t flags = long_left ? ActiveTriangle::kBottomRight : 0;
  const int32_t mid = std::clamp(last_row_at_or_above(y1), first - 1, last);
  t.first_row = static_cast<int16_t>(first);
  t.mid_row = static_cast<int16_t>(mid);
  t.last_row = static_cast<int16_t>(last);
  // Every column of the triangle's rows lies in [cb, cmax]: an edge's Q - cb dy is then below
  // (cmax - cb + 1) dy, which fits 32 bits when the bit lengths do (docs/numerics.md#edge-columns).
  const int32_t xmin = std::min({x0, x1, x2}), xmax = std::max({x0, x1, x2});
  const int32_t cb = (xmin - kHalfPixel) >> kSubpixelBits;
  const int32_t cmax = (xmax - kHalfPixel + kSubpixel - 1) >> kSubpixelBits;
  const auto ncols = static_cast<uint32_t>(cmax - cb + 1);
  const auto dy = static_cast<uint32_t>(y2 - y0);
  const bool fits = (32 - clz32(ncols)) + (32 - clz32(dy)) <= 32;
  t.col_base = static_cast<int16_t>(cb);
  const RowEdge lng = make_row_edge(x0, y0, x2, y2, cb, first);
  const RowEdge top = y1 > y0 ? make_row_edge(x0, y0, x1, y1, cb, first) : kUnusedEdge;
  const int ls = long_left ? 0 : 1;
  t.edge_q[ls] = lng.q;
  t.edge_dx[ls] = lng.dx;
  t.edge_dy[ls] = lng.dy;
  t.edge_q[1 - ls] = top.q;
  t.edge_dx[1 - ls] = top.dx;
  t.edge_dy[1 - ls] = top.dy;
  t.bottom = y2 > y1 ? make_row_edge(x1, y1, x2, y2, cb, mid + 1) : kUnusedEdge;
  if (!fits) {
    flags |= ActiveTriangle::kWideEdges;
  } else if (cb >= 0 && cmax <= width &&
             (32 - clz32(static_cast<uint32_t>(cmax) + 1)) + (32 - clz32(dy)) <= 32) {
    // Inside the columns [0, width]: the records relative to column 0.
    const auto ucb = static_cast<uint32_t>(cb);
    t.edge_q[0] += ucb * t.edge_dy[0];
    t.edge_q[1] += ucb * t.edge_dy[1];
    t.bottom.q += ucb * t.bottom.dy;
    flags |= ActiveTriangle::kInside;
    t.col_base = 0;
  }
  t.flags = flags;

  // Whether a row has a centre inside the triangle and the viewport's columns: most triangles
  // have one in their first row.
  for (int32_t r = first; r <= last; ++r) {
    int32_t a, b;  // the long edge's column, the short edge's
    if (fits) {
      const int ss = t.short_side();
      a = DivideEdge(t.side_edge(1 - ss), t.col_base, r - first).column();
      b = r <= mid ? DivideEdge(t.side_edge(ss), t.col_base, r - first).column()
                   : DivideEdge(t.bottom, t.col_base, r - mid - 1).column();
    } else {
      a = wide_column(v, ActiveTriangle::kLong, r);
      b = wide_column(v, r <= mid ? ActiveTriangle::kTop : ActiveTriangle::kBottom, r);
    }
    const int32_t left = long_left ? a : b, right = long_left ? b : a;
    if (left < width && right > 0 && left < right) return true;
  }
  return false;
}

PickedEdge wide_edge(const ScreenVertex* const v[3], int which, int32_t r, int32_t r_last) {
  const ScreenVertex &a = edge_start(v, which), &b = edge_end(v, which);
  const int64_t dy = int64_t{b.y} - a.y;
  const int64_t q = edge_numerator(a.x, a.y, b.x, b.y, 0, r);
  // The columns at both ends of the rows bound every column between (an edge is straight):
  // relative to the smaller, Q stays below (31 |dx| / dy + 2) dy < 2^29.
  const int32_t c1 = edge_column(q, dy);
  const int32_t c2 = edge_column(edge_numerator(a.x, a.y, b.x, b.y, 0, r_last), dy);
  const int32_t cb = std::min(c1, c2);
  PickedEdge p;
  p.cb = cb;
  p.e.q = static_cast<uint32_t>(static_cast<uint64_t>(q - int64_t{cb} * dy));
  p.e.dx = b.x - a.x;
  p.e.dy = static_cast<uint32_t>(dy);
  return p;
}

}  // namespace lr
