// Triangle edges as the row loop walks them: the first pixel column at or right of an edge on a
// row, exact on every row, from one record that any row can be picked up from.
//
// For an edge from (xa, ya) to (xb, yb), ya < yb (subpixels, y down), dx = xb - xa, dy = yb - ya,
// and the row r (centre yc = 256 r + 128), the first column whose centre is at or right of the
// edge is
//   c(r) = ceil((xa - 128 + dx (yc - ya) / dy) / 256) = floor(Q(r) / dy),
//   Q(r) = floor(((xa - 128) dy + dx (yc - ya) + 256 dy - 1) / 256),   Q(r + 1) = Q(r) + dx
// (docs/numerics.md#edge-columns). A left edge includes a centre exactly on it, a right edge
// excludes it: the fill rule (docs/raster-rules.md).
//
// RowEdge keeps Q relative to a column base cb, Q(r) - cb dy, at the triangle's reference row, in
// uint32 modulo 2^32: picking the edge up at any row is one multiply-add, and the value is exact
// wherever the true one lies in [0, 2^32) (every row of a triangle whose edges pass
// edges_fit(); the others are picked up per strip visit from their vertices: wide_edge).
// Two ways to walk it, the same columns: DivideEdge (one division per row, for cores with a
// divider) and DdaEdge (an exact DDA: two divisions per pick-up, none per row, for Armv6-M).
#pragma once

#include <cstdint>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr {

struct RowEdge {
  uint32_t q = 0;   // Q(r_ref) - cb dy, modulo 2^32
  int32_t dx = 0;   // xb - xa, |dx| < 2^23: Q's step per row
  uint32_t dy = 0;  // yb - ya in (0, 2^23); 1 for an edge no row uses (kUnusedEdge)
};
// The record of a flat top or bottom edge, which no row uses but a pick-up may divide by.
inline constexpr RowEdge kUnusedEdge{0, 0, 1};

// Q(r) of the edge (xa, ya)-(xb, yb) relative to column base cb, exact in int64 (|Q| < 2^39
// inside the coordinate budget).
constexpr int64_t edge_numerator(int32_t xa, int32_t ya, int32_t xb, int32_t yb, int32_t cb,
                                 int32_t r) {
  const int64_t dy = int64_t{yb} - ya;
  const int64_t yc = int64_t{r} * kSubpixel + kHalfPixel;
  const int64_t p = (int64_t{xa} - kHalfPixel - int64_t{cb} * kSubpixel) * dy +
                    (int64_t{xb} - xa) * (yc - ya) + kSubpixel * dy - 1;
  return p >> kSubpixelBits;  // floor
}

// The record of an edge that rows use (ya < yb), at reference row r_ref, relative to cb.
constexpr RowEdge make_row_edge(int32_t xa, int32_t ya, int32_t xb, int32_t yb, int32_t cb,
                                int32_t r_ref) {
  RowEdge e;
  e.q = static_cast<uint32_t>(static_cast<uint64_t>(edge_numerator(xa, ya, xb, yb, cb, r_ref)));
  e.dx = xb - xa;
  e.dy = static_cast<uint32_t>(yb - ya);
  return e;
}

// floor(a / b) for b > 0 in int32 (C's division truncates).
constexpr int32_t floor_div32(int32_t a, int32_t b) {
  const int32_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

// An edge walked with one exact division per row: Q relative to the base, stepped by dx.
class DivideEdge {
 public:
  // At the row k rows below the record's reference row; cb the base the record is relative to.
  DivideEdge(const RowEdge& e, int32_t cb, int32_t k)
      : q_(e.q + static_cast<uint32_t>(e.dx) * static_cast<uint32_t>(k)),
        dx_(static_cast<uint32_t>(e.dx)),
        dy_(e.dy),
        cb_(cb) {}
  int32_t column() const { return cb_ + static_cast<int32_t>(q_ / dy_); }
  void step() { q_ += dx_; }

 private:
  uint32_t q_, dx_, dy_;
  int32_t cb_;
};

// The same columns from an exact DDA: the column and the remainder of Q / dy, stepped by the
// quotient and remainder of dx / dy. Two divisions when picked up, none per row.
class DdaEdge {
 public:
  [[gnu::always_inline]] DdaEdge(const RowEdge& e, int32_t cb, int32_t k) : dy_(e.dy) {
    const uint32_t q = e.q + static_cast<uint32_t>(e.dx) * static_cast<uint32_t>(k);
    col_ = cb + static_cast<int32_t>(q / dy_);
    rem_ = q % dy_;
    const auto dy = static_cast<int32_t>(dy_);
    // Steep edges (|dx| < dy, about half of them) step by 0 or -1 columns: no division.
    if (e.dx >= 0 && e.dx < dy)
      sq_ = 0;
    else if (e.dx < 0 && -e.dx <= dy)
      sq_ = -1;
    else
      sq_ = floor_div32(e.dx, dy);
    sr_ = static_cast<uint32_t>(e.dx - sq_ * dy);  // in [0, dy): sq dy >= dx - dy > -2^24
  }
  int32_t column() const { return col_; }
  // rem + sr < 2 dy < 2^24: one correction.
  void step() {
    col_ += sq_;
    rem_ += sr_;
    if (rem_ >= dy_) {
      rem_ -= dy_;
      ++col_;
    }
  }

 private:
  int32_t col_;
  uint32_t rem_;
  int32_t sq_;
  uint32_t sr_, dy_;
};

// The walker of this core: a division per row where the core divides in one instruction (and
// on hosts), the DDA on Armv6-M, whose division is a library call.
#if defined(__arm__) && !defined(__ARM_FEATURE_IDIV)
using RowEdgeWalker = DdaEdge;
#else
using RowEdgeWalker = DivideEdge;
#endif

}  // namespace lr
