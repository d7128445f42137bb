// The binned triangle: a triangle that passed culling, in the edge table until the strip loop
// reaches its first strip. It refers to its vertices in the vertex store and to its draw record.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/output/color.hpp"

namespace lr {

inline constexpr uint16_t kNoTriangle = 0xFFFF;
inline constexpr size_t kMaxStoreEntries = 0xFFFF;  // indices are uint16; 0xFFFF = none

// 16 bytes.
struct BinnedTriangle {
  uint16_t v[3];   // vertex store indices
  uint16_t next;   // next triangle of the same bucket (lists are built by prepending, so
                   // they run from the latest submission to the earliest)
  uint8_t draw;    // draw record
  Rgb8 flat;       // flat-shaded colour (the primary colour when textured)
  Rgb8 flat_spec;  // flat-shaded secondary colour of textured, lit draws
  uint8_t reserved;
};
static_assert(sizeof(BinnedTriangle) == 16);

}  // namespace lr
