// A vertex after the vertex stage: projected, snapped, lit. One per mesh vertex of each draw,
// plus those made by clipping. 40 bytes.
#pragma once

#include <cstdint>

#include "core/output/color.hpp"

namespace lr {

inline constexpr int kSubpixelBits = 8;                   // DESIGN.md §3 default
inline constexpr int32_t kSubpixel = 1 << kSubpixelBits;  // subpixels per pixel
inline constexpr int32_t kHalfPixel = kSubpixel / 2;

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
  int32_t u = 0, v = 0;  // texture coordinates, Q12.20 (TexCoord)
  Color15 color{};       // lit or given colour (the primary colour when textured and lit)
  Color15 spec{};        // secondary (specular) colour of textured, lit draws; else 0
  uint8_t outcode = 0;   // clip planes this vertex is outside of (0: projected fields valid)
  uint8_t unlit = 0;     // vertex stage: 1 while its colour waits for its first drawn triangle
};
static_assert(sizeof(ScreenVertex) == 40);

}  // namespace lr
