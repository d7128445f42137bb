// Exact scanline stepping of one triangle edge: an integer DDA with an error term.
//
// For an edge from (xa, ya) to (xb, yb), ya < yb, in subpixels (y down), and the pixel row r
// (centre yc = 256 r + 128), the walker holds X = ceil(x(yc) - 128): the smallest subpixel
// position whose pixel-centre test passes. column() = ceil(X / 256) gives both ends of a span:
// a left edge includes a centre exactly on it, a right edge excludes it (the fill rule:
// docs/raster-rules.md). |X| < 2^22 and 0 < dy < 2^23, so the walker is int32; setup uses
// int64. Invariant, proof and bounds: docs/numerics.md#edge-stepping-the-dda.
#pragma once

#include <cstdint>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr {

struct EdgeWalker {
  int32_t x;       // X for the current row
  int32_t err;     // e, in [0, dy)
  int32_t step_q;  // floor(256 dx / dy)
  int32_t step_r;  // 256 dx - step_q dy
  int32_t dy;

  // Positions the walker on row `row` (any row; the edge line is extended beyond its ends).
  // Only m = dx (yc - ya) is divided, in 32 bits when it fits (every small triangle), else in
  // 64 bits; 256 dx always fits (docs/numerics.md#edge-stepping-the-dda).
  void init(int32_t xa, int32_t ya, int32_t xb, int32_t yb, int32_t row) {
    const int32_t ddy = yb - ya;  // (0, 2^23)
    const int32_t ddx = xb - xa;  // |ddx| < 2^23
    const int64_t yc = int64_t{row} * kSubpixel + kHalfPixel;
    const int64_t m = int64_t{ddx} * (yc - ya);
    int64_t c;
    if (m >= INT32_MIN && m <= INT32_MAX) {
      const auto m32 = static_cast<int32_t>(m);
      c = m32 / ddy + (m32 % ddy > 0 ? 1 : 0);
    } else {
      c = ceil_div(m, ddy);
    }
    x = static_cast<int32_t>(int64_t{xa} - kHalfPixel + c);
    err = static_cast<int32_t>(c * ddy - m);
    const int32_t s = ddx * kSubpixel;
    int32_t q = s / ddy, r = s % ddy;  // q * ddy itself may not fit: keep to the remainder
    if (r < 0) {
      --q;
      r += ddy;
    }
    step_q = q;
    step_r = r;
    dy = ddy;
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

}  // namespace lr
