// Exact scanline stepping of one triangle edge: an integer DDA with an error term.
//
// For an edge from (xa, ya) to (xb, yb), ya < yb, in subpixels (y down), and the pixel row r
// (centre yc = 256 r + 128), the walker holds X = ceil(x(yc) - 128): the smallest subpixel
// position whose pixel-centre test passes. The first pixel column on or right of the edge is
// then ceil(X / 256) = (X + 255) >> 8. That one formula gives both ends of a span: a left edge
// includes a centre exactly on it (col >= bound) and a right edge excludes it (col < bound),
// which is the left half of the fill rule (DESIGN.md §4).
//
// Invariant: X * dy - N = e with 0 <= e < dy, where N = (xa - 128) dy + dx (yc - ya). Moving
// one row adds 256 dx to N = step_q * dy + step_r (0 <= step_r < dy). Values: |X| < 2^22,
// 0 < dy < 2^23, so X, e, step_q, step_r and dy are int32; setup uses int64.
#pragma once

#include <cstdint>

#include "core/fixed.hpp"
#include "core/screen_vertex.hpp"

namespace lr {

struct EdgeWalker {
  int32_t x;       // X for the current row
  int32_t err;     // e, in [0, dy)
  int32_t step_q;  // floor(256 dx / dy)
  int32_t step_r;  // 256 dx - step_q dy
  int32_t dy;

  // Positions the walker on row `row` (any row; the edge line is extended beyond its ends).
  void init(int32_t xa, int32_t ya, int32_t xb, int32_t yb, int32_t row) {
    int64_t ddy = int64_t{yb} - ya, ddx = int64_t{xb} - xa;
    int64_t yc = int64_t{row} * kSubpixel + kHalfPixel;
    int64_t n = (int64_t{xa} - kHalfPixel) * ddy + ddx * (yc - ya);
    int64_t xc = ceil_div(n, ddy);
    x = static_cast<int32_t>(xc);
    err = static_cast<int32_t>(xc * ddy - n);
    int64_t s = ddx * kSubpixel;
    int64_t q = floor_div(s, ddy);
    step_q = static_cast<int32_t>(q);
    step_r = static_cast<int32_t>(s - q * ddy);
    dy = static_cast<int32_t>(ddy);
  }

  // Unsigned arithmetic: after a triangle's last row the walker may be stepped once past the
  // edge's end, where X is never used; wrapping there must not be undefined.
  void step() {
    uint32_t ux = static_cast<uint32_t>(x) + static_cast<uint32_t>(step_q);
    err -= step_r;
    if (err < 0) {
      ux += 1;
      err += dy;
    }
    x = static_cast<int32_t>(ux);
  }

  // First pixel column whose centre is at or right of the edge.
  int32_t column() const { return (x + (kSubpixel - 1)) >> kSubpixelBits; }
};

// First row whose centre lies strictly below y (subpixels): rows with centre in (y, ...].
constexpr int32_t first_row_below(int32_t y) {
  return static_cast<int32_t>(floor_div(int64_t{y} - kHalfPixel, kSubpixel)) + 1;
}
// Last row whose centre lies at or above y: rows with centre in (..., y].
constexpr int32_t last_row_at_or_above(int32_t y) {
  return static_cast<int32_t>(floor_div(int64_t{y} - kHalfPixel, kSubpixel));
}

}  // namespace lr
