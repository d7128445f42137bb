// Triangle setup of the untextured family (flat, Gouraud with affine or perspective-correct
// colours, depth test on or off): the planes of a triangle whose rows and edges setup_rows made.
//
// Planes come from one reciprocal of twice the area and 32-bit products: four coefficients per
// triangle (the barycentric gradients scaled by a per-triangle power of two), then per attribute
// two high-word products per gradient and a shift (docs/numerics.md#untextured-planes). That
// short path holds for triangles within 4096 pixels whose aspect keeps its error bound; the
// rest (long needles, giants) take the exact wide path of make_plane (triangle_setup.hpp),
// counted in FrameStats::triangles_wide.
//
// What the ActiveTriangle's planes hold (kind: UntexturedKind; all uint32, modular):
//   z       window depth x 65535 x 2^15 ("half depth"), [0, 65535 x 2^15], plus 2^14 (in the
//           base): the 16-bit depth is z >> 15, rounded
//   kFlat   c[0].base: the triangle's pixel, as the pixel format stores it (PixelBits)
//   kLanes  (RGB565 pixel formats) each colour a level plus half a level in its top bits,
//           channel in [0, 1]: c[0] blue and red as the 16-bit lanes of one plane (blue high),
//           31 x channel x 2^11 + 2^10 (a 5-bit level in the lane's top five bits); c[1] green,
//           63 x channel x 2^26 + 2^25 (a 6-bit level in the top six bits). The lanes stay in
//           [0, 2^16) on every pixel of the triangle (errors below 2^7 lane units:
//           docs/numerics.md#untextured-planes), so adding the packed gradient steps both.
//   kAffine c[i]: channel i, Q1.15 x 2^15 (Q2.30), [0, 2^30]
//   kPerspective q: w_min / w in Q1.30, (0, 2^30]; c[i]: channel i (Q1.15) times q, Q1.30
#pragma once

#include <cstdint>

#include "lineraster/core/binning/binned_triangle.hpp"
#include "lineraster/core/lighting/one_hue.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr {

// The span a triangle of the family gets (its row loop: core/raster/untextured_rows.hpp).
enum class UntexturedKind : uint8_t { kFlat, kPerspective, kAffine, kLanes };
inline constexpr int kUntexturedKinds = 4;

// The affine colour test's bound for a pixel format (docs/numerics.md#when-screen-linear-colours-
// are-close-enough): affine colours are taken when (w_max - w_min) x D <= bound x w_min, D the
// largest difference of a channel (Q1.15) between two vertices, green's counted green_weight
// times. Half an output step of the format: 256 and 1 for 8-bit channels (half a level),
// 2,080 and 2 for RGB565 (half a 5-bit step for red and blue, half a 6-bit step for green).
// quick_shift: a test first that needs no colour: (w_max - w_min) 2^quick_shift <= w_min
// implies the bound for any colours (2^quick_shift x bound >= 2^15 x green_weight).
struct AffineBound {
  uint32_t bound = 256;
  uint32_t green_weight = 1;
  int quick_shift = 7;
};
inline constexpr AffineBound kAffineBound8{256, 1, 7};
inline constexpr AffineBound kAffineBound565{2080, 2, 5};
static_assert((kAffineBound8.bound << kAffineBound8.quick_shift) >=
              (Color15::kOne * kAffineBound8.green_weight));
static_assert((kAffineBound565.bound << kAffineBound565.quick_shift) >=
              (Color15::kOne * kAffineBound565.green_weight));

struct UntexturedInput {
  ColorPlanes colors = ColorPlanes::kNone;  // the draw's: kNone is flat
  bool depth = true;                        // a depth plane
  bool lanes = false;                       // the pixel format has the RGB565 lane span (kLanes)
  bool affine_ok = false;  // a kPerspective triangle may get affine planes (routine linked)
  AffineBound affine{};
  uint32_t flat_pixel = 0;  // kFlat: the pixel, as PixelBits stores it
  // Most triangles are lanes triangles with depth (lanes_first_of): where kSmallPlanesByHand,
  // their rows and planes are made in one step, before the affine colour test.
  bool lanes_first = false;
  // A draw whose colours are one hue (DrawRecord::hue): its small lanes triangles' red and blue
  // planes are made from green's differences (docs/numerics.md#one-hue).
  OneHue hue{};
};
// What UntexturedInput::lanes_first should be for the rest of the input.
// (LanesSetup's block tests kAffineBound565 itself: lanes are RGB565 pixels.)
constexpr bool lanes_first_of(const UntexturedInput& in) {
  return in.lanes && in.depth &&
         (in.colors == ColorPlanes::kAffine ||
          (in.colors == ColorPlanes::kPerspective && in.affine_ok &&
           in.affine.bound == kAffineBound565.bound &&
           in.affine.green_weight == kAffineBound565.green_weight &&
           in.affine.quick_shift == kAffineBound565.quick_shift));
}

struct UntexturedSetup {
  UntexturedKind kind;
  bool wide;  // the planes took the exact wide path
};

// The rows a triangle may be drawn on: from the later of its own first row and first_min, to
// the earlier of its own last row and last_max; columns [0, width).
struct RowWindow {
  int32_t first_min = 0;
  int32_t last_max = 0;
  int32_t width = 0;
};

// What setup_untextured_triangle made, in one word (returned in a register): bit 0 pixels (0: a
// sliver, whose rows cover no pixel centre; no planes were made), bits 1-2 the kind, bit 3 wide.
class UntexturedTriangle {
 public:
  static constexpr UntexturedTriangle sliver() { return UntexturedTriangle(0); }
  static constexpr UntexturedTriangle made(UntexturedKind kind, bool wide) {
    return UntexturedTriangle(1u | static_cast<uint32_t>(kind) << 1 | (wide ? 8u : 0u));
  }
  constexpr bool pixels() const { return (bits_ & 1u) != 0; }
  constexpr UntexturedKind kind() const { return static_cast<UntexturedKind>((bits_ >> 1) & 3u); }
  constexpr bool wide() const { return (bits_ & 8u) != 0; }
  // 2 kind: the offset of the kind's row loop from kFlat's (untextured_row_index).
  constexpr uint32_t row_offset() const { return bits_ & 6u; }
  constexpr bool operator==(const UntexturedTriangle&) const = default;

 private:
  constexpr explicit UntexturedTriangle(uint32_t bits) : bits_(bits) {}
  uint32_t bits_;
};
static_assert(kUntexturedKinds <= 4);

// The whole setup of an untextured triangle (vertices v sorted by y, non-zero area): rows,
// edges (setup_rows) and planes. Triangles within 64 pixels take one path in 32-bit arithmetic
// for all of it; the others setup_rows and setup_untextured. Where code size comes first (-Os),
// setup_rows makes every triangle's rows (the same records and pixels: exact either way).
UntexturedTriangle setup_untextured_triangle(const ScreenVertex* const v[3], const RowWindow& w,
                                             const UntexturedInput& in, ActiveTriangle& t);

// The planes of the triangle with vertices v sorted by y (setup_rows' order: vertex 0 is the
// top one) and non-zero area.
UntexturedSetup setup_untextured(const ScreenVertex* const v[3], const UntexturedInput& in,
                                 ActiveTriangle& t);

// Whether the screen-linear colours of the triangle are within the bound of perspective-correct
// ones everywhere in it (exposed for tests).
bool affine_within(const ScreenVertex* const v[3], const AffineBound& b);

// The short path's shared part (exposed for tests): the barycentric gradients of the triangle
// (vertex 0's) as k = 256 e / D x 2^T, |k| <= 2^30, with T = 21 - bm + L (bm the bit length of
// the largest edge component, L that of |D|), and vertex 0's pixel and offset.
struct FastBasis {
  int32_t kx1 = 0, kx2 = 0, ky1 = 0, ky2 = 0;
  int32_t p = 0;       // 11 + bm - L: a plane whose differences are scaled by 2^u shifts by p - u
  int32_t spread = 0;  // 2 bm - L: how far the triangle is from well-shaped (log2 of aspect + 1)
  int32_t bm = 0;
  int32_t fx = 0, fy = 0;   // (128 - (x0 & 255)) << 23 and the same for y
  uint32_t c0 = 0, r0 = 0;  // vertex 0's pixel
};
// False when the triangle is too large for the short path (an edge component of 2^20 subpixels
// or more) or its spread exceeds `max_spread`.
bool fast_basis(const ScreenVertex* const v[3], int max_spread, FastBasis& b);
// The plane through vertex values a (each in [0, 2^31)), their differences scaled by 2^u
// (u >= -1, |a_i - a_0| 2^u < 2^30 + 1).
Plane fast_plane(const FastBasis& b, const int32_t a[3], int u);

// The rows, edges and flags of a triangle (setup_untextured_triangle's first step, v sorted by
// y): kSlow when it is not small (an edge component of 2^kSmallEdgeBits subpixels or more) or
// has no row in the window, nothing made; else t's rows and edges as setup_rows makes them, d
// twice its signed area and m the OR of its edge components' magnitudes, and kPixels when |d| is
// kSurelyPixelsArea2 or more (untested) or the middle vertex's row (or the first) has a pixel
// centre in [0, width), kLaterRows when only a later row may. Exposed for tests.
// LanesSetup's block, which tests the later rows itself, gives kNoPixels for a triangle none of
// whose rows in the window has a pixel centre in [0, width) (small_rows never does).
struct SmallRows {
  static constexpr uint8_t kSlow = 0, kPixels = 1, kLaterRows = 2, kNoPixels = 3;
  int32_t d = 0;
  uint32_t m = 0;
  uint8_t result = kSlow;
};
// Twice the area (subpixels squared: 2^19 is four pixels) from which small_rows does not test
// for a pixel centre: such triangles hardly ever lack one, so over them the test (about 25
// instructions by hand) costs more than the planes of the rare one without (its rows then draw
// nothing; it counts as set up, not as without pixels). |d| is taken as d ^ (d >> 31) (one less
// for negative d).
inline constexpr uint32_t kSurelyPixelsArea2 = 1u << 17;
constexpr bool surely_pixels(int32_t d) {
  return static_cast<uint32_t>(d ^ (d >> 31)) >= kSurelyPixelsArea2;
}
SmallRows small_rows(const ScreenVertex* const v[3], const RowWindow& w, ActiveTriangle& t);
// The same by hand where the core divides in one instruction (kSmallRowsByHand: Armv7-M, not at
// -Os); elsewhere small_rows itself.
#if defined(__thumb2__) && defined(__ARM_FEATURE_IDIV) && !defined(__OPTIMIZE_SIZE__)
inline constexpr bool kSmallRowsByHand = true;
#else
inline constexpr bool kSmallRowsByHand = false;
#endif
SmallRows small_rows_by_hand(const ScreenVertex* const v[3], const RowWindow& w, ActiveTriangle& t);

// The planes of a small triangle (setup_untextured_triangle's: edges below 2^kSmallEdgeBits
// subpixels, d twice its signed area, m the OR of its edge components' magnitudes) of the kind
// given (not kPerspective), with v sorted by y and its rows already set up; false (t's planes
// unspecified) when its spread or its depth differences (above kSmallMaxDepthBits) need
// setup_untextured. Exposed for tests.
bool small_planes(const ScreenVertex* const v[3], int32_t d, uint32_t m, const UntexturedInput& in,
                  UntexturedKind kind, ActiveTriangle& t);
// small_planes' integers for kLanes with depth, by hand where the core has SMMUL/SMMLA
// (kSmallPlanesByHand: Armv7E-M with a divide instruction, not at -Os); elsewhere it makes nothing
// and returns false. Binning stores the vertices sorted there (kBinnedSorted).
#if defined(__thumb2__) && defined(__ARM_FEATURE_DSP) && defined(__ARM_FEATURE_IDIV) && \
    !defined(__OPTIMIZE_SIZE__)
inline constexpr bool kSmallPlanesByHand = true;
#else
inline constexpr bool kSmallPlanesByHand = false;
#endif
static_assert(!kSmallPlanesByHand || kBinnedSorted);
bool small_lanes_planes_by_hand(const ScreenVertex* const v[3], int32_t d, uint32_t m,
                                const UntexturedInput& in, ActiveTriangle& t);
// small_rows_by_hand and, when its result is kPixels, small_lanes_planes_by_hand in one call
// (one block of hand-made code where kSmallPlanesByHand): whether the planes were made (false
// elsewhere: there only the rows are made).
bool small_lanes_triangle_by_hand(const ScreenVertex* const v[3], const RowWindow& w,
                                  const UntexturedInput& in, ActiveTriangle& t, SmallRows& rows);

// setup_untextured_triangle for the triangles of one strip whose draw has lanes_first: what
// stays the same between them (the window, the input, the vertex store) given once, then one call
// per triangle from its three vertex indices (as binned: sorted by y where kBinnedSorted, else
// top first and the other two sorted here by sort_below_top). Where
// kSmallPlanesByHand, vertex fetch, rows, planes and the affine colour test's quick part
// are one block of hand-made code (the rest, rare, as setup_untextured_triangle does it); the
// same result and record as sort_by_y and setup_untextured_triangle everywhere. w and in must
// outlive the calls (the strip loop's setup context holds them).
// The words of the hand-made setup blocks' frame (untextured_setup.cpp).
inline constexpr size_t kLanesFrameWords = 35;
class LanesSetup {
 public:
  // (w's first_min, last_max and width are read here: prepare again when they change.) A lanes
  // triangle's record gets lanes_rows as its row loop (t.rows) here; the other kinds' are the
  // caller's to set.
  void prepare(const RowWindow& w, const UntexturedInput& in, const ScreenVertex* vertices,
               RowFn lanes_rows = nullptr);
  UntexturedTriangle set_up(const uint16_t index[3], ActiveTriangle& t) {
    constexpr UntexturedTriangle kLanes = UntexturedTriangle::made(UntexturedKind::kLanes, false);
    if constexpr (kSmallPlanesByHand) {  // 32-bit addresses
      const uint32_t status = block(frame_, t, index);
      if (status == 1) [[likely]]  // a lanes triangle, rows, planes and t.rows made
        return kLanes;
      if (status == 4) return UntexturedTriangle::sliver();  // no row has a pixel centre
    }
    const UntexturedTriangle u = rest(index, t);
    if (u == kLanes) t.rows = lanes_rows_;
    return u;
  }

 private:
  // The hand-made block where kSmallPlanesByHand (nothing elsewhere: 0), and what remains after
  // it. t and index go in registers; 1 is its usual result (rows and planes made), 4 a sliver
  // (no row of the window has a pixel centre in [0, width): its rows made, no planes).
  static uint32_t block(uint32_t* frame, ActiveTriangle& t, const uint16_t index[3]);
  UntexturedTriangle rest(const uint16_t index[3], ActiveTriangle& t);

  const RowWindow* w_ = nullptr;
  const UntexturedInput* in_ = nullptr;
  RowFn lanes_rows_ = nullptr;
  const ScreenVertex* vertices_ = nullptr;
  uint32_t frame_[kLanesFrameWords] = {};  // the hand-made block's frame (untextured_setup.cpp)
};

// What the strip loop keeps of LanesSetup where it is not by hand, or where the renderer draws
// no lanes triangle: nothing (its setup context stays small).
struct NoLanesSetup {
  static void prepare(const RowWindow& /*w*/, const UntexturedInput& /*in*/,
                      const ScreenVertex* /*vertices*/, RowFn /*lanes_rows*/ = nullptr) {}
  static UntexturedTriangle set_up(const uint16_t /*index*/[3], ActiveTriangle& /*t*/) {
    return UntexturedTriangle::sliver();
  }
};

// The short path's limits (docs/numerics.md#untextured-planes): the largest edge component, the
// spread of affine and flat triangles and of perspective ones, and the depth plane's spread plus
// the bit length of its largest vertex difference.
inline constexpr int kFastMaxEdgeBits = 20;
inline constexpr int kFastMaxSpread = 10;
inline constexpr int kFastMaxSpreadPerspective = 6;
inline constexpr int kFastMaxDepthSpread = 35;
// The small path's depth plane: vertex differences of at most this many bits (2^26 half units,
// 1/32 of the depth range), of which it keeps the top 16 (docs/numerics.md#untextured-planes).
inline constexpr int kSmallMaxDepthBits = 26;
// Lanes: edge components below 2^15 subpixels (128 pixels), so that the lanes' rounding stays
// below 2^7 lane units everywhere in the triangle (an eighth of a 6-bit level).
inline constexpr int kLanesMaxEdgeBits = 15;
// Triangles whose edge components are below 2^kSmallEdgeBits subpixels (64 pixels) are set up
// in 32-bit arithmetic throughout (setup_untextured_triangle).
inline constexpr int kSmallEdgeBits = 14;
static_assert(kSmallEdgeBits <= kLanesMaxEdgeBits && kSmallEdgeBits <= kFastMaxEdgeBits);

}  // namespace lr
