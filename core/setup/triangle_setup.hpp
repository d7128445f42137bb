// Triangle setup: what a binned triangle becomes when its first strip is reached — edge walkers
// for its rows and the planes of its attributes.
//
// Attribute planes live on the pixel lattice: A(c, r) = base + gx * c + gy * r for the pixel
// in column c of row r, evaluated in uint32 arithmetic modulo 2^32. The gradients are rounded
// to integers once; modular arithmetic then makes every evaluation (direct, or stepped along a
// span) give exactly the value of that rounded plane, with no drift and no overflow trap,
// wherever the true value lies in the attribute's range. Error against the exact plane: half a
// unit per pixel of distance from the top vertex (< 2^13 units anywhere in the guard band).
//
// Attributes (all unsigned, ranges at vertices):
//   z    window depth x 65535 x 2^16, [0, 65535 x 2^16]        (screen-linear)
//   q    w_min / w in Q1.30, (0, 2^30]                            (perspective: 1/w, normalised)
//   cq_i colour channel i (Q1.15) times q, Q1.30, [0, q]          (perspective colours)
//   c_i  colour channel i, Q1.15 scaled by 2^15 = Q2.30, [0, 2^30] (affine colours)
// Phong triangles (signed values stored with a bias of 2^31 so that the planes stay unsigned):
//   c_i  normal component i (Q1.30) times q, in Q1.30: |value| <= q <= 2^30
//   spec_i world position component i relative to org (Q16.16, clamped to int32) times q,
//        shifted right by m_p (the bit length of the largest relative value): |value| < 2^30
//   tan_i tangent component i (Q1.14 << 16) times q: |value| <= 2^30
// Gradient numerators are < 2^57; gradients beyond 2^38 per pixel only occur for needles
// thinner than 1/256 pixel: such a triangle gets constant attributes (the vertex mean).
#pragma once

#include <cstdint>

#include "core/output/color.hpp"
#include "core/setup/edge.hpp"
#include "core/vertex/screen_vertex.hpp"
#include "core/vertex/surface_vertex.hpp"
#include "core/texture/texture.hpp"

namespace lr {

struct Plane {
  uint32_t base = 0, gx = 0, gy = 0;
  uint32_t at(int32_t c, int32_t r) const {
    return base + gx * static_cast<uint32_t>(c) + gy * static_cast<uint32_t>(r);
  }
};

enum class ColorPlanes : uint8_t { kNone, kPerspective, kAffine };

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
  Plane c[3];
  // Textured triangles. s, t: texel coordinates of level 0 in Q.8 relative to the triangle's
  // own origin (off_s, off_t; see setup_texture), as s * q >> m_s (perspective) or s << m_s
  // (affine).
  Plane s, t;
  Plane spec[3];  // secondary colour, in the format of c
  int32_t off_s = 0, off_t = 0;
  uint8_t m_s = 0, m_t = 0;
  // Textured, modulated: the colours are the same at the three vertices; c[i].base and
  // spec[i].base hold them (Q1.15) and there are no colour planes.
  bool const_colors = false;
  // Phong triangles: tangent planes, the position planes' origin (world Q16.16) and shift, and
  // the bitangent's handedness (+-16384).
  uint8_t m_p = 0;
  int16_t handedness = 0;
  Plane tan[3];
  int32_t org[3] = {0, 0, 0};
};

inline constexpr uint32_t kPlaneBias = 1u << 31;
// A biased signed plane value back to int32.
constexpr int32_t unbias(uint32_t v) {
  return static_cast<int32_t>(v - kPlaneBias);
}

// Per-pixel lighting attributes of a Phong triangle.
struct PhongSetup {
  const SurfaceVertex* s[3] = {nullptr, nullptr, nullptr};  // nullptr: not a Phong triangle
  bool negate = false;    // back face of a two-sided draw: negated normals
  bool position = false;  // position planes
  bool tangent = false;   // tangent planes (normal maps)
};

// How texture coordinates and colours of a textured triangle are laid out.
struct TextureSetup {
  const Texture* texture = nullptr;  // nullptr: untextured
  bool perspective = true;           // planes of a * q (exact and span modes) or of a (affine)
  bool colors = true;                // modulate: primary and secondary colour planes
  bool flat = false;                 // constant colours flat_primary / flat_secondary
  Color15 flat_primary{}, flat_secondary{};
  Wrap wrap_s = Wrap::kRepeat, wrap_t = Wrap::kRepeat;
};

struct SetupInput {
  const ScreenVertex* v[3];
  ColorPlanes colors;
  bool depth;
  TextureSetup tex;
  PhongSetup phong;
  bool affine_colors_ok = false;  // the renderer links the affine colour routine (kPerspective
                                  // triangles may get affine planes: ActiveTriangle::colors)
  int32_t first_row;  // first row to draw (>= the triangle's own first row), viewport clamped
  int32_t last_row;   // inclusive
};

// Fills `out` (except index/draw/flat). The triangle must have non-zero area.
void setup_triangle(const SetupInput& in, ActiveTriangle& out);

// What every plane of one triangle shares: its edges from vertex 0 (subpixels), twice its area
// (|area| < 2^47 inside the guard band) and a reciprocal of the area, so that each of the
// triangle's gradients costs multiplications instead of 64-bit divisions (one division per
// triangle: on Cortex-M a 64-bit division is a libgcc call of about 100 instructions).
struct PlaneBasis {
  int64_t x0 = 0, y0 = 0, ex1 = 0, ey1 = 0, ex2 = 0, ey2 = 0;
  int64_t area = 0;   // |twice the signed area|, subpixels^2
  bool flip = false;  // the signed area was negative
  uint64_t inv = 0;   // floor((2^64 - 1) / area); 0 when area == 0
  explicit PlaneBasis(const ScreenVertex* const v[3]);
};

// The texture planes of a textured triangle (part of setup_triangle). q: the vertices' Q1.30
// perspective factors (used when ts.perspective).
void setup_texture(const TextureSetup& ts, const ScreenVertex* const v[3], const PlaneBasis& pb,
                   const uint32_t q[3], ActiveTriangle& t);

// The plane through three vertex values (exposed for tests; the second form builds the basis).
Plane make_plane(const PlaneBasis& pb, const uint32_t a[3]);
Plane make_plane(const ScreenVertex* const v[3], const uint32_t a[3]);

}  // namespace lr
