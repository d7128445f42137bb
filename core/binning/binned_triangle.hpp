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
  uint16_t v[3];  // vertex store indices
  uint16_t next;  // next triangle of the same bucket (lists are built by prepending, so
                  // they run from the latest submission to the earliest)
};
static_assert(sizeof(BinnedTriangle) == 8);

// A flat-shaded triangle's colours (FrameStorage::triangle_colors, one per binned triangle):
// lit by its face normal or its provoking vertex's, the primary colour (of the texture's
// modulation when textured) and the secondary one (textured, lit, separate specular). 6 bytes.
struct TriangleColors {
  Rgb8 primary;
  Rgb8 secondary;
};
static_assert(sizeof(TriangleColors) == 6);

}  // namespace lr
