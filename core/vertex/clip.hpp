// Clipping in homogeneous (clip) space: near and far planes, a guard band at the sides, and
// w >= 2^-16. The guard band keeps snapped coordinates small (see screen_vertex.hpp) while
// triangles that reach far outside the viewport keep their exact edges: the band is at
// |x_ndc| <= G_x with G_x = max(1, 8192 / width), likewise for y.
//
// Clip coordinates (Q28.28 int64) beyond 2^47 in magnitude (|coordinate| >= 2^19) are outside
// the range the clipper can evaluate without overflow (G * w < 2^60): triangles using such a
// vertex are rejected and counted, never drawn wrong.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/vertex/surface_vertex.hpp"

namespace lr {

enum ClipPlane : uint8_t {
  kClipNear = 1 << 0,
  kClipFar = 1 << 1,
  kClipLeft = 1 << 2,
  kClipRight = 1 << 3,
  kClipBottom = 1 << 4,
  kClipTop = 1 << 5,
  kClipW = 1 << 6,
  kClipOutOfRange = 1 << 7,  // not a plane: the vertex cannot be clipped safely
};
inline constexpr int kClipPlanes = 7;
inline constexpr int kMaxClipVertices = 3 + kClipPlanes;

struct GuardBand {
  int32_t gx = 1, gy = 1;  // guard factors in NDC units
};

struct ClipVertex {
  ClipCoord p;
  Color15 color;
  Color15 spec;
  int32_t u = 0, v = 0;     // texture coordinates, Q12.20
  SurfaceVertex surface{};  // per-pixel lighting: interpolated linearly like the colours
  // 1 + a corner of the input triangle (1..3), or 0: a point made by clipping (0 by default,
  // so that the front end's clip buffers are zero bytes and a static renderer goes to .bss). A
  // corner's side of each plane is its outcode's, the vertex stage's decision, so that a corner
  // kept by the clipper is the vertex its unclipped neighbours use; a made point's is its
  // distance's sign.
  uint8_t corner = 0;
  uint8_t outcode = 0;  // a corner's
};

uint8_t outcode(const ClipCoord& c, GuardBand g);

// Clips the convex polygon poly[0..n) against the planes in `planes`; returns the new vertex
// count (0: nothing left), the polygon in poly (the corners it keeps keep their `corner`).
// `scratch` holds each plane's output (the caller owns both: the front end keeps them in its
// object, not on the stack). Intersections are always computed from the inside vertex towards the
// outside one, so an edge shared by two triangles is cut at the same point in both (no cracks after
// clipping). kAttributes: the points it makes carry the texture coordinates, the specular colour
// and the surface too (textured and Phong draws); without, only the position and the colour, the
// rest zero (a renderer without textured or Phong spans links no code for them:
// FrontEndRoutines::clip).
using ClipPolygon = std::span<ClipVertex, kMaxClipVertices>;
template <bool kAttributes = true>
int clip_polygon(ClipPolygon poly, ClipPolygon scratch, int n, uint8_t planes, GuardBand g);
extern template int clip_polygon<true>(ClipPolygon, ClipPolygon, int, uint8_t, GuardBand);
extern template int clip_polygon<false>(ClipPolygon, ClipPolygon, int, uint8_t, GuardBand);

// The clipper's memory: a polygon and its scratch (the caller keeps them off the stack).
struct ClipBuffers {
  std::array<ClipVertex, kMaxClipVertices> polygon{};
  std::array<ClipVertex, kMaxClipVertices> scratch{};
};

}  // namespace lr
