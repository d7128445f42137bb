// The binned triangle: a triangle that passed culling, in the edge table until the strip loop
// reaches its first strip. It refers to its vertices in the vertex store; its draw is the one
// whose vertices those are (each draw's vertices are one range of the store, in draw order:
// DrawRecord::first_vertex), and a flat-shaded triangle's colours are in a store of their own,
// indexed like the triangles, so that a Gouraud triangle is 8 bytes.
#pragma once

#include <cstddef>
#include <cstdint>

#include "lineraster/core/output/color.hpp"

namespace lr {

inline constexpr uint16_t kNoTriangle = 0xFFFF;
inline constexpr size_t kMaxStoreEntries = 0xFFFF;  // indices are uint16; 0xFFFF = none

// 8 bytes, word-aligned (the front end's lane stores one with a doubleword store).
struct alignas(4) BinnedTriangle {
  uint16_t v[3];  // vertex store indices, topmost first (store_binned() below)
  uint16_t next;  // next triangle of the same bucket (lists are built by prepending, so
                  // they run from the latest submission to the earliest)
};
static_assert(sizeof(BinnedTriangle) == 8);

// The order in which binning stores a triangle's vertices (a, b, c as submitted; dy1 = yb - ya,
// dy2 = yc - ya in subpixels): the rotation of (a, b, c) that puts the topmost first (of a tie,
// the earliest of a, b, c), so that the winding stays and setup sorts the other two with one
// compare (sort_below_top in core/setup/triangle_rows.hpp: the later swapped when it lies
// strictly above). That sorts as sort_by_y sorts (a, b, c) except where b is on top and a is
// level with c: sort_by_y(a, b, c) gives (b, a, c), the rotation (b, c, a) (a flat bottom whose
// two corners come in the other order).
template <class T>
constexpr void store_top_first(T (&v)[3], T a, T b, T c, int32_t dy1, int32_t dy2) {
  if (dy1 <= dy2 && dy1 < 0) {  // b on top
    v[0] = b;
    v[1] = c;
    v[2] = a;
  } else if (dy2 < dy1 && dy2 < 0) {  // c on top
    v[0] = c;
    v[1] = a;
    v[2] = b;
  } else {
    v[0] = a;
    v[1] = b;
    v[2] = c;
  }
}

// The order sorted by y (topmost first, then the other two as sort_below_top orders them): the
// rotation above with sort_below_top's compare made here, on dy1 and dy2. Setup's hand-made lanes
// block (kBinnedSorted) then needs no compare of its own; the winding is lost.
template <class T>
constexpr void store_sorted(T (&v)[3], T a, T b, T c, int32_t dy1, int32_t dy2) {
  if (dy1 <= dy2 && dy1 < 0) {  // b on top; a strictly above c: (b, a, c)
    v[0] = b;
    v[1] = dy2 > 0 ? a : c;
    v[2] = dy2 > 0 ? c : a;
  } else if (dy2 < dy1 && dy2 < 0) {  // c on top; b strictly above a: (c, b, a)
    v[0] = c;
    v[1] = dy1 < 0 ? b : a;
    v[2] = dy1 < 0 ? a : b;
  } else {  // a on top; c strictly above b: (a, c, b)
    v[0] = a;
    v[1] = dy2 < dy1 ? c : b;
    v[2] = dy2 < dy1 ? b : c;
  }
}

// Whether binning stores vertices sorted (store_sorted): where the front end's bin lane is made by
// hand (kBinLaneAsm in bin_lane.hpp: Thumb-2 with the DSP extension, not at -Os), which covers
// every target of setup's hand-made lanes block (kSmallPlanesByHand in
// core/setup/untextured_setup.hpp, which reads the vertices as binned), for the triangles of every
// draw that block may take (untextured, colour planes, not Phong: sorts_for_lanes in
// draw_record.hpp; the lane sorts all it takes). Elsewhere the rotation (store_top_first); setup
// without the block sorts with one compare either way; two-sided Phong reads the winding.
#if defined(__thumb2__) && defined(__ARM_FEATURE_DSP) && !defined(__OPTIMIZE_SIZE__)
inline constexpr bool kBinnedSorted = true;
#else
inline constexpr bool kBinnedSorted = false;
#endif

// The order binning stores: store_sorted where kBinnedSorted and `sorted`, else the rotation.
template <class T>
constexpr void store_binned(T (&v)[3], T a, T b, T c, int32_t dy1, int32_t dy2,
                            bool sorted = true) {
  if (kBinnedSorted && sorted)
    store_sorted(v, a, b, c, dy1, dy2);
  else
    store_top_first(v, a, b, c, dy1, dy2);
}

// A flat-shaded triangle's colours (FrameStorage::triangle_colors, one per binned triangle):
// lit by its face normal or its provoking vertex's, the primary colour (of the texture's
// modulation when textured) and the secondary one (textured, lit, separate specular). 6 bytes.
struct TriangleColors {
  Rgb8 primary;
  Rgb8 secondary;
};
static_assert(sizeof(TriangleColors) == 6);

}  // namespace lr
