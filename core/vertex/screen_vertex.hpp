// A vertex after the vertex stage: projected, snapped, lit. One per mesh vertex of each draw,
// plus those made by clipping. 24 bytes: what every draw reads of a vertex. Textured draws keep
// their texture coordinates and secondary colour apart (TexVertex), Phong draws their surface
// (SurfaceVertex), each in a store of its own indexed like the vertex store.
#pragma once

#include <cstdint>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/output/color.hpp"

namespace lr {

inline constexpr int kSubpixelBits = 8;                   // docs/conventions.md#coordinates
inline constexpr int32_t kSubpixel = 1 << kSubpixelBits;  // subpixels per pixel
inline constexpr int32_t kHalfPixel = kSubpixel / 2;

// First row whose centre lies strictly below y (subpixels): rows with centre in (y, ...].
// (y within the coordinate budget, |y| < 2^23: y - 128 stays in int32; >> floors.)
constexpr int32_t first_row_below(int32_t y) {
  return ((y - kHalfPixel) >> kSubpixelBits) + 1;
}
// Last row whose centre lies at or above y: rows with centre in (..., y].
constexpr int32_t last_row_at_or_above(int32_t y) {
  return (y - kHalfPixel) >> kSubpixelBits;
}

// Largest viewport side. Guard-band clipping keeps every snapped coordinate within
// [-8192 - W/2, 8192 + W/2] pixels, so |x|, |y| < 2^14 pixels = 2^22 subpixels and edge deltas
// are < 2^23: edge products (delta x delta) stay below 2^46 and attribute gradient numerators
// (2^32 attribute range x 2^23 x 2) below 2^57 — all inside int64.
inline constexpr int kMaxViewport = 4096;

// Window depth in [0, 1] scaled by 65535 * 2^16 (uint32): the 16-bit depth buffer value is
// (z + 2^15) >> 16 = round(depth * 65535). The 16 fraction bits absorb the plane's rounding.
inline constexpr uint32_t kDepthMax = 65535u << 16;

struct ScreenVertex {
  int32_t x = 0, y = 0;  // display position in subpixels (Q.8), y down; valid when outcode == 0
  uint32_t z = 0;        // window depth, scaled as kDepthMax above
  uint32_t w = 0;        // clip-space w, Q16.16 (perspective correction); draw_screen reads
                         // 0 as 1.0. All-zero defaults keep static stores in .bss.
  Color15 color{};       // lit or given colour (the primary colour when textured and lit)
  uint8_t outcode = 0;   // clip planes this vertex is outside of (0: projected fields valid)
  uint8_t color_pending = 0;  // vertex stage: 1 while its colour waits for the first triangle
                              // that is drawn with it (lit Gouraud: vertices are lit lazily)
};
static_assert(sizeof(ScreenVertex) == 24);

// A band's vertex compaction (front end) numbers the vertices it keeps in the two bytes above:
// a kept vertex is projected (outcode 0) and lit (nothing pending), so both are free then.
constexpr uint16_t link_of(const ScreenVertex& v) {
  return static_cast<uint16_t>(v.outcode | v.color_pending << 8);
}
constexpr void set_link(ScreenVertex& v, uint16_t link) {
  v.outcode = static_cast<uint8_t>(link);
  v.color_pending = static_cast<uint8_t>(link >> 8);
}

// What a textured vertex has besides its ScreenVertex (and what a Phong draw with a texture or
// a normal map reads: the coordinates). 16 bytes; in FrameStorage::tex_vertices, indexed like
// the vertex store, so that untextured frames pay no RAM for it.
struct TexVertex {
  int32_t u = 0, v = 0;  // texture coordinates, Q12.20 (TexCoord)
  Color15 spec{};        // secondary (specular) colour of textured, lit draws; else 0
  uint16_t reserved = 0;
  friend constexpr bool operator==(const TexVertex&, const TexVertex&) = default;
};
static_assert(sizeof(TexVertex) == 16);

// Twice the signed area of the triangle (a, b, c) on the display, from the snapped subpixel
// positions (subpixels^2): (b - a) x (c - a). |area| < 2^47 inside the guard band, exact in int64.
constexpr int64_t signed_area2(const ScreenVertex& a, const ScreenVertex& b,
                               const ScreenVertex& c) {
  return (int64_t{b.x} - a.x) * (int64_t{c.y} - a.y) - (int64_t{c.x} - a.x) * (int64_t{b.y} - a.y);
}

// Facing, GL's default (glFrontFace(GL_CCW)): a triangle is front-facing when its vertices run
// counter-clockwise in NDC, where y points up. The display's y points down, which mirrors the
// winding: counter-clockwise in NDC is clockwise on the display, a negative signed_area2.
// A zero area is neither front- nor back-facing (such triangles cover no pixel and are culled).
constexpr bool front_facing(int64_t area2) {
  return area2 < 0;
}
constexpr bool back_facing(int64_t area2) {
  return area2 > 0;
}

}  // namespace lr
