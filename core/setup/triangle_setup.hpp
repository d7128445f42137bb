// Triangle setup: the planes of a binned triangle's attributes, made when its first strip is
// reached (its rows and edges: triangle_rows.hpp). The textured and Phong families use
// setup_planes; the untextured family its own setup (untextured_setup.hpp) on the same planes.
//
// Attribute planes live on the pixel lattice: A(c, r) = base + gx c + gy r in uint32, modulo
// 2^32, with gradients rounded once: every evaluation, direct or stepped, is exact. Error and
// bounds: docs/numerics.md#attribute-plane-equations.
//
// Attributes (all unsigned, ranges at vertices):
//   z    window depth x 65535 x 2^16, [0, 65535 x 2^16]        (screen-linear)
//   q    w_min / w in Q1.30, (0, 2^30]                            (perspective: 1/w, normalised)
//   cq_i colour channel i (Q1.15) times q, Q1.30, [0, q]          (perspective colours)
//   c_i  colour channel i, Q1.15 scaled by 2^15 = Q2.30, [0, 2^30] (affine colours)
// Phong triangles (signed values stored with a bias of 2^31 so that the planes stay unsigned):
//   c_i  normal component i (Q1.30) times q, in Q1.30: |value| <= q <= 2^30
//   position_i world position component i relative to org (Q16.16, clamped to int32) times q,
//        shifted right by m_p (the bit length of the largest relative value): |value| < 2^30
//   tan_i tangent component i (Q1.14 << 16) times q: |value| <= 2^30
// Needles thinner than 1/256 pixel get constant attributes (the vertex mean).
#pragma once

#include <cstdint>

#include "lineraster/core/output/color.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/texture/texture.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"
#include "lineraster/core/vertex/surface_vertex.hpp"

namespace lr {

// Per-pixel lighting attributes of a Phong triangle.
struct PhongSetup {
  const SurfaceVertex* s[3] = {nullptr, nullptr, nullptr};  // nullptr: not a Phong triangle
  bool negate = false;    // back face of a two-sided draw: negated normals
  bool position = false;  // position planes
  bool tangent = false;   // tangent planes (normal maps)
};

// How texture coordinates and colours of a textured triangle are laid out.
struct TextureSetup {
  const Texture* texture = nullptr;                      // nullptr: untextured
  const TexVertex* tv[3] = {nullptr, nullptr, nullptr};  // the vertices' coordinates, colours
  bool perspective = true;  // planes of a * q (exact and span modes) or of a (affine)
  bool colors = true;       // modulate: primary and secondary colour planes
  bool flat = false;        // constant colours flat_primary / flat_secondary
  Color15 flat_primary{}, flat_secondary{};
  Wrap wrap_s = Wrap::kRepeat, wrap_t = Wrap::kRepeat;
};

struct SetupInput {
  const ScreenVertex* v[3];
  ColorPlanes colors;
  bool depth;
  TextureSetup tex;
  PhongSetup phong;
};

// The attribute planes of a textured or Phong triangle of non-zero area (its rows and edges are
// setup_rows', core/setup/triangle_rows.hpp: the strip loop sets up no planes for a triangle
// whose rows cover no pixel centre; untextured triangles: untextured_setup.hpp). Returns the
// colour planes it made (in.colors).
// kTexture and kPhong: whether it sets up texture and Phong planes at all. A renderer whose
// spans have neither family links neither routine (the front end refuses such draws before
// setup); kPhong needs kTexture (Phong's maps use the texture planes).
template <bool kTexture, bool kPhong>
ColorPlanes setup_planes(const SetupInput& in, ActiveTriangle& out);

// What every plane of one triangle shares (docs/numerics.md#attribute-plane-equations). Most
// triangles take the short path: one normalised reciprocal of twice the area and four edge
// coefficients k = 256 e / |D| in a shared fixed-point format, so that a gradient is two 64-bit
// products and a shift. The rest (|D| >= 2^32, or long needles whose error bound that format
// does not meet) take the exact path: a 64-bit reciprocal and round(256 n / |D|) exactly.
// The short path's limit on 2 bm + sh (bm the bit length of the largest edge component, sh the
// leading zeros of |D| < 2^32): its error is below 9 x 2^(2 bm + sh - 30) units, 1,152 at the
// limit.
inline constexpr int kFastPlaneLimit = 37;

struct PlaneBasis {
  int32_t x0 = 0, y0 = 0;  // vertex 0, subpixels (|x0|, |y0| < 2^22)
  bool fast = false;       // the short path
  // Short path: K = round(256 e 2^f / |D|) for e = ey2, -ey1 (x) and -ex2, ex1 (y), signs flipped
  // when the signed area is negative; |K| <= 2^29 by the choice of f, in [16, 51].
  int32_t kx1 = 0, kx2 = 0, ky1 = 0, ky2 = 0;
  uint8_t f = 0;
  // Vertex 0 split into its pixel (c0, r0) and the offset of that pixel's centre from it,
  // (fx, fy) in (-128, 128] subpixels.
  int32_t fx = 0, fy = 0;
  uint32_t c0 = 0, r0 = 0;
  // Exact path: edges from vertex 0, |twice the area| (< 2^47), its sign, and
  // floor((2^64 - 1) / area) (0 when the area is 0).
  int64_t ex1 = 0, ey1 = 0, ex2 = 0, ey2 = 0;
  int64_t area = 0;
  bool flip = false;
  uint64_t inv = 0;
  explicit PlaneBasis(const ScreenVertex* const v[3]);
};

// The texture planes of a textured triangle (part of setup_triangle). q: the vertices' Q1.30
// perspective factors (used when ts.perspective).
void setup_texture(const TextureSetup& ts, const ScreenVertex* const v[3],
                   const TexVertex* const tv[3], const PlaneBasis& pb, const uint32_t q[3],
                   ActiveTriangle& t);

// q = round(w_min 2^30 / w) in Q1.30 for w_min <= w, at least 1 (exposed for tests): a 2-by-1
// division by a normalised reciprocal instead of a 64-bit division, the same value.
uint32_t perspective_factor(uint32_t wmin, uint32_t w);

// The plane through three vertex values (exposed for tests; the second form builds the basis).
Plane make_plane(const PlaneBasis& pb, const uint32_t a[3]);
Plane make_plane(const ScreenVertex* const v[3], const uint32_t a[3]);

}  // namespace lr
