// The active triangle: what triangle setup makes of a binned triangle when the strip loop
// reaches its first strip, and what the row loops and span routines read, in place. Written once
// at setup and never changed afterwards: each strip visit picks the triangle up at its own first
// row from the edges' records (core/setup/row_edge.hpp), whatever strip came before and whoever
// drew it, so strips can be skipped, drawn in passes or (later) shared between cores.
//
// Every family has the same rows, edges and row loop (resolved at setup: one call per triangle
// and strip visit) and the same five planes; what the planes hold is the family's:
//   untextured:  core/setup/untextured_setup.hpp (z, and the colours by kind)
//   textured, Phong: core/setup/triangle_setup.hpp (z, q, c), with the further planes of their
//                slot in ActiveExtra
#pragma once

#include <cstdint>

#include "lineraster/core/setup/row_edge.hpp"

namespace lr {

// An attribute on the pixel lattice: A(c, r) = base + gx * c + gy * r, modulo 2^32.
struct Plane {
  uint32_t base = 0, gx = 0, gy = 0;
  uint32_t at(int32_t c, int32_t r) const {
    return base + gx * static_cast<uint32_t>(c) + gy * static_cast<uint32_t>(r);
  }
};

// The planes of the textured and Phong families: in a store of their own
// (FrameStorage::active_extra), one per active slot, so that untextured frames pay no RAM for
// them. 124 bytes.
struct ActiveExtra {
  // s, t: texel coordinates of level 0 in Q.8 relative to the triangle's own origin (off_s,
  // off_t; see setup_texture), as s * q >> m_s (perspective) or s << m_s (affine).
  Plane s, t;
  // Three more planes, used by one family each: a textured triangle's secondary colour, a
  // Phong triangle's world position.
  union Extra {
    Plane spec[3];      // textured: secondary colour, in the format of ActiveTriangle::c
    Plane position[3];  // Phong: world position relative to org, shifted right by m_p
    constexpr Extra() : spec{} {}
  } extra;
  int32_t off_s = 0, off_t = 0;
  uint8_t m_s = 0, m_t = 0;
  // Textured, modulated: the colours are the same at the three vertices; c[i].base and
  // extra.spec[i].base hold them (Q1.15) and there are no colour planes.
  bool const_colors = false;
  // Phong triangles: tangent planes, the position planes' origin (world Q16.16) and shift, and
  // the bitangent's handedness (+-16384).
  uint8_t m_p = 0;
  int16_t handedness = 0;
  Plane tan[3];
  int32_t org[3] = {0, 0, 0};
};

struct StripRows;  // one strip as the row loops see it (core/raster/row_loop.hpp)
struct ActiveTriangle;
// A row loop: draws the triangle's rows of one strip (one call per triangle and strip visit).
using RowFn = void (*)(const ActiveTriangle& t, StripRows& strip);

struct ActiveTriangle {
  // The edges of the rows down to mid_row, left and right (one of them the long edge, from the
  // top vertex to the bottom one, the other the top edge, to the middle vertex), relative to
  // col_base at first_row, in the order a row loop reads them: Q, dx, dy (row_edge.hpp).
  uint32_t edge_q[2] = {0, 0};
  int32_t edge_dx[2] = {0, 0};
  uint32_t edge_dy[2] = {0, 0};  // (zero-initialised: active stores go to .bss)
  // The bottom edge (middle to bottom vertex), which replaces the top edge after mid_row; its
  // record at row mid_row + 1. A flat top or bottom has a record no row reads.
  RowEdge bottom;
  int16_t first_row = 0;  // first row to draw: the edges' reference row
  int16_t mid_row = 0;    // last row drawn with the top edge (first_row - 1 when none is)
  int16_t last_row = 0;   // last row to draw (inclusive, clamped to the viewport)
  int16_t col_base = 0;   // the edges' column base
  uint16_t index = 0;     // binned triangle index: submission order
  uint8_t draw = 0;       // draw record of the triangle's state (read by textured and Phong rows)
  uint8_t flags = 0;      // kBottomRight, kWideEdges, kInside
  // The top and bottom edges are the right ones (the middle vertex lies right of the long edge).
  static constexpr uint8_t kBottomRight = 1;
  // The edges do not fit the records' 32 bits on every row (huge guard-band triangles): each
  // strip visit picks them up from the vertices (wide_edge, core/setup/triangle_rows.hpp).
  static constexpr uint8_t kWideEdges = 2;
  // Every span lies in the columns [0, width) unclamped (col_base is 0).
  static constexpr uint8_t kInside = 4;
  // The three edges by their vertices (wide_edge): top to bottom, top to middle, middle to
  // bottom.
  static constexpr int kLong = 0, kTop = 1, kBottom = 2;
  // The side (0 left, 1 right) of the top and bottom edges.
  int short_side() const { return flags & kBottomRight; }
  // The record of the left (0) or right (1) edge of the rows down to mid_row.
  RowEdge side_edge(int side) const { return RowEdge{edge_q[side], edge_dx[side], edge_dy[side]}; }
  RowFn rows = nullptr;  // the row loop of the triangle's family and state
  Plane z;
  Plane c[3];  // right after z: a row loop reads z, c[0] and c[1] as one block
  Plane q;
  // Textured and Phong triangles: their slot's planes. The others' rows never read it (nor draw):
  // the strip loop's lanes setup stores neither (the other untextured setups store both).
  ActiveExtra* ext = nullptr;
};
static_assert(sizeof(ActiveExtra) == 124);
static_assert(sizeof(ActiveTriangle) == (sizeof(uintptr_t) == 4 ? 116 : 128));  // 116 B on Cortex-M

inline constexpr uint32_t kPlaneBias = 1u << 31;
// A biased signed plane value back to int32.
constexpr int32_t unbias(uint32_t v) {
  return static_cast<int32_t>(v - kPlaneBias);
}

}  // namespace lr
