// The active triangle: what triangle setup makes of a binned triangle when the strip loop
// reaches its first strip, and what the span routines read. Edge walkers for its rows and the
// planes of its attributes (the formats of the planes: triangle_setup.hpp).
#pragma once

#include <cstdint>

#include "lineraster/core/output/color.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/setup/edge.hpp"

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

struct ActiveTriangle {
  EdgeWalker long_edge;    // top vertex to bottom vertex
  EdgeWalker short_edge;   // the short edge of the current row (top, then bottom)
  EdgeWalker bottom_edge;  // middle vertex to bottom vertex, positioned at row mid_row + 1
  int16_t row = 0;         // next row to draw
  int16_t mid_row = 0;     // last row drawn with the top short edge
  int16_t last_row = 0;    // last row to draw (inclusive, clamped to the viewport)
  uint16_t index = 0;      // binned triangle index: submission order
  bool long_is_left = false;
  uint8_t draw = 0;  // draw record of the triangle's state
  // The colour planes this triangle has: the draw's, except that a perspective-correct draw's
  // triangle gets affine planes when they are within half an 8-bit level of it (setup_triangle).
  ColorPlanes colors = ColorPlanes::kNone;
  Rgb8 flat{};  // colour of flat-shaded triangles
  Plane z;
  Plane q;
  Plane c[3];  // colour channels; Phong: the normal's components
  // Textured and Phong triangles: their slot's planes (nullptr for the others).
  ActiveExtra* ext = nullptr;
};
static_assert(sizeof(ActiveExtra) == 124);
static_assert(sizeof(ActiveTriangle) == 136 + sizeof(uintptr_t));  // 140 B on Cortex-M

inline constexpr uint32_t kPlaneBias = 1u << 31;
// A biased signed plane value back to int32.
constexpr int32_t unbias(uint32_t v) {
  return static_cast<int32_t>(v - kPlaneBias);
}

// Walks the triangle's rows from t.row up to `end` (inclusive): row(r) for each, then both edges
// step to the next row; at the middle vertex the short edge becomes the bottom edge. Leaves t.row
// at the first row not walked. The one place rows are stepped: drawing a strip passes the span
// work as `row`, skipping an unchanged strip passes nothing.
template <class RowFn>
[[gnu::always_inline]] inline void walk_rows(ActiveTriangle& t, int end, RowFn&& row) {
  int r = t.row;
  for (; r <= end; ++r) {
    if (r == t.mid_row + 1) t.short_edge = t.bottom_edge;
    row(r);
    t.long_edge.step();
    t.short_edge.step();
  }
  t.row = static_cast<int16_t>(r);
}

// Whether a row from t.row up to `end` (inclusive) has a pixel centre inside the triangle and
// inside columns [0, width): walk_rows' stepping on copies of the edges, up to the first such row
// (most triangles have one in their first row, which needs no copies).
inline bool has_pixels(const ActiveTriangle& t, int end, int32_t width) {
  const bool long_left = t.long_is_left;
  auto inside = [long_left, width](const EdgeWalker& long_edge, const EdgeWalker& short_edge) {
    const int32_t a = long_edge.column(), b = short_edge.column();
    const int32_t left = long_left ? a : b, right = long_left ? b : a;
    return left < width && right > 0 && left < right;
  };
  const int bottom = t.mid_row + 1;
  int r = t.row;
  if (r <= end && r != bottom && inside(t.long_edge, t.short_edge)) return true;
  EdgeWalker long_edge = t.long_edge, short_edge = t.short_edge;
  for (; r <= end; ++r) {
    if (r == bottom) short_edge = t.bottom_edge;
    if (inside(long_edge, short_edge)) return true;
    long_edge.step();
    short_edge.step();
  }
  return false;
}

}  // namespace lr
