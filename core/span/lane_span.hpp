// The Gouraud span of RGB565 pixel formats: colours stepped as 16-bit lanes and packed to
// RGB565 without a table, depth tested per pixel.
//
// Registers (untextured_setup.hpp, kLanes): br holds blue in its high lane and red in its low
// lane, each a 5-bit level in the lane's top five bits (rounded); g holds green's 6-bit level in
// its top six bits (26 bits below it). One add steps both lanes of br (the low lane never leaves
// [0, 2^16) inside a triangle, so nothing carries between them), and
//   t = br & 0xF800F800;  pixel = t | t >> 27 | (g & 0xFC000000) >> 21
// puts red in bits 11..15 and blue in bits 0..4 in place. z is the half-depth plane plus 2^14.
//
// lane_span_portable is the loop in C. On Armv7E-M the whole strip visit of a lanes triangle
// (edges, spans and this loop) runs with its registers allocated by hand (lane_rows.hpp: GCC 12
// spills in it); firmware/span_check compares it with its C twin pixel for pixel on the target,
// tests/core/lane_rows_test.cpp the C twin with the generic row loop and this loop with a
// direct evaluation of the planes.
#pragma once

#include <cstddef>
#include <cstdint>

namespace lr {

// An RGB565 pixel format (Rgb565Be, or one storing the same value natively): 16-bit pixels
// whose from_value takes the RGB565 value.
template <class PF>
inline constexpr bool kRgb565Lanes = requires {
  PF::from_value(0u);
}
&&sizeof(typename PF::Storage) == 2;

// The RGB565 value of the lane registers.
constexpr uint32_t lanes565(uint32_t br, uint32_t g) {
  const uint32_t t = br & 0xF800F800u;
  return (t | t >> 27 | (g & 0xFC000000u) >> 21) & 0xFFFFu;
}

// Fills px[0..n) (and depth with kDepth), returns the pixels the depth test rejected.
template <class PF, bool kDepth>
inline uint32_t lane_span_portable(typename PF::Storage* px, uint16_t* depth, int32_t n, uint32_t z,
                                   uint32_t dz, uint32_t br, uint32_t dbr, uint32_t g,
                                   uint32_t dg) {
  uint32_t rejected = 0;
  for (int32_t i = 0; i < n; ++i) {
    bool pass = true;
    if constexpr (kDepth) {
      const auto d = static_cast<uint16_t>(z >> 15);
      pass = d < depth[i];
      if (pass) depth[i] = d;
      z += dz;
    }
    if (pass)
      px[i] = PF::from_value(lanes565(br, g));
    else
      ++rejected;
    br += dbr;
    g += dg;
  }
  return rejected;
}

}  // namespace lr
