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
// spills in it); on Armv6-M lane_span runs this loop by hand (eight low registers: GCC 12 spills
// the steps and rebuilds the masks per pixel). firmware/span_check compares both with their C
// twins pixel for pixel on the targets, tests/core/lane_rows_test.cpp the C twin with the
// generic row loop and this loop with a direct evaluation of the planes.
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
      // The 17 bits of z >> 15 against the stored 16 (the same for half depths below 2^31, as
      // the planes' are; so for every z, as the loops by hand compare).
      const uint32_t d = z >> 15;
      pass = d < depth[i];
      if (pass) depth[i] = static_cast<uint16_t>(d);
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

#if defined(__thumb__) && !defined(__thumb2__)
inline constexpr bool kLaneSpanAsm = true;  // Armv6-M
#else
inline constexpr bool kLaneSpanAsm = false;
#endif
// Armv7-M where code size comes first (-Os): the shared row walk calls the span out of line
// there, and lanes triangles take it instead of their whole visit by hand (lane_rows.hpp).
// Elsewhere the C loop (inlined into a row walk, its twelve registers are more than GCC 12 finds
// on every core).
#if defined(__thumb2__) && defined(__OPTIMIZE_SIZE__)
inline constexpr bool kLaneSpanAsmV7 = true;
#else
inline constexpr bool kLaneSpanAsmV7 = false;
#endif

namespace detail {
// The loop with the depth test by hand on Armv6-M (n > 0). Low registers: the pixels' and the
// depths' ends, the byte index from -2n up to 0, z, br and two temporaries; high: g and the
// three steps (ADD takes them directly), the rejected count. Per written pixel 21 instructions
// (22 with the byte swap), per rejected one 12. In unified syntax (GCC passes Armv6-M inline
// assembly in divided syntax, and expects it back so).
#if defined(__thumb__) && !defined(__thumb2__)
template <bool kSwap>
[[gnu::always_inline]] inline uint32_t lane_span_v6m(uint16_t* px, uint16_t* depth, int32_t n,
                                                     uint32_t z, uint32_t dz, uint32_t br,
                                                     uint32_t dbr, uint32_t g, uint32_t dg) {
  uint16_t* const pe = px + n;
  uint16_t* const de = depth + n;
  int32_t i = -2 * n;
  register uint32_t rg asm("r8") = g;
  register uint32_t rdz asm("r9") = dz;
  register uint32_t rdbr asm("r10") = dbr;
  register uint32_t rdg asm("r11") = dg;
  register uint32_t rej asm("r12") = 0;
  uint32_t t1, t2;
#define LR_LANE_SPAN_V6M(SWAP)                                                                  \
  asm volatile(                                                                                 \
      ".syntax unified\n\t"                                                                     \
      "b      1f\n\t"                                                                           \
      "3:\n\t"                                                                                  \
      "mov    %[t1], %[rej]\n\t"                                                                \
      "adds   %[t1], #1\n\t"                                                                    \
      "mov    %[rej], %[t1]\n\t"                                                                \
      "b      2f\n\t"                                                                           \
      "1:\n\t"                                                                                  \
      "lsrs   %[t1], %[z], #15\n\t"                                                             \
      "ldrh   %[t2], [%[de], %[i]]\n\t"                                                         \
      "cmp    %[t2], %[t1]\n\t"                                                                 \
      "bls    3b\n\t"                                                                           \
      "strh   %[t1], [%[de], %[i]]\n\t"                                                         \
      "lsrs   %[t1], %[br], #27\n\t"                                                            \
      "mov    %[t2], %[g]\n\t"                                                                  \
      "lsrs   %[t2], %[t2], #26\n\t"                                                            \
      "lsls   %[t2], %[t2], #5\n\t"                                                             \
      "orrs   %[t1], %[t2]\n\t"                                                                 \
      "lsls   %[t2], %[br], #16\n\t"                                                            \
      "lsrs   %[t2], %[t2], #27\n\t"                                                            \
      "lsls   %[t2], %[t2], #11\n\t"                                                            \
      "orrs   %[t1], %[t2]\n\t" SWAP                                                            \
      "strh   %[t1], [%[pe], %[i]]\n\t"                                                         \
      "2:\n\t"                                                                                  \
      "add    %[z], %[dz]\n\t"                                                                  \
      "add    %[br], %[dbr]\n\t"                                                                \
      "add    %[g], %[dg]\n\t"                                                                  \
      "adds   %[i], #2\n\t"                                                                     \
      "bne    1b\n\t"                                                                           \
      ".syntax divided\n\t"                                                                     \
      : [i] "+l"(i), [z] "+l"(z), [br] "+l"(br), [g] "+h"(rg), [rej] "+h"(rej), [t1] "=&l"(t1), \
        [t2] "=&l"(t2)                                                                          \
      : [pe] "l"(pe), [de] "l"(de), [dz] "h"(rdz), [dbr] "h"(rdbr), [dg] "h"(rdg)               \
      : "cc", "memory")
  if constexpr (kSwap)
    LR_LANE_SPAN_V6M("rev16  %[t1], %[t1]\n\t");
  else
    LR_LANE_SPAN_V6M("");
#undef LR_LANE_SPAN_V6M
  return rej;
}
#else
// Declared only: lane_span never calls it on other cores.
template <bool kSwap>
uint32_t lane_span_v6m(uint16_t* px, uint16_t* depth, int32_t n, uint32_t z, uint32_t dz,
                       uint32_t br, uint32_t dbr, uint32_t g, uint32_t dg);
#endif

// The same loop on Armv7-M at -Os (n > 0): the index from -n up to 0 scales itself in the
// addresses, the lanes pack with the modified immediates. Per written pixel 15 instructions (16
// with the byte swap), per rejected one 8.
#if defined(__thumb2__) && defined(__OPTIMIZE_SIZE__)
template <bool kSwap>
[[gnu::always_inline]] inline uint32_t lane_span_v7m(uint16_t* px, uint16_t* depth, int32_t n,
                                                     uint32_t z, uint32_t dz, uint32_t br,
                                                     uint32_t dbr, uint32_t g, uint32_t dg) {
  uint16_t* const pe = px + n;
  uint16_t* const de = depth + n;
  int32_t i = -n;
  uint32_t rej = 0, t1, t2;
#define LR_LANE_SPAN_V7M(SWAP)                                                                 \
  asm volatile(                                                                                \
      "1:\n\t"                                                                                 \
      "ldrh   %[t2], [%[de], %[i], lsl #1]\n\t"                                                \
      "cmp    %[t2], %[z], lsr #15\n\t"                                                        \
      "bls    3f\n\t"                                                                          \
      "lsrs   %[t1], %[z], #15\n\t"                                                            \
      "strh   %[t1], [%[de], %[i], lsl #1]\n\t"                                                \
      "and    %[t1], %[br], #0xF800F800\n\t"                                                   \
      "orr    %[t1], %[t1], %[t1], lsr #27\n\t"                                                \
      "and    %[t2], %[g], #0xFC000000\n\t"                                                    \
      "orr    %[t1], %[t1], %[t2], lsr #21\n\t" SWAP                                           \
      "strh   %[t1], [%[pe], %[i], lsl #1]\n\t"                                                \
      "2:\n\t"                                                                                 \
      "add    %[z], %[dz]\n\t"                                                                 \
      "add    %[br], %[dbr]\n\t"                                                               \
      "add    %[g], %[dg]\n\t"                                                                 \
      "adds   %[i], #1\n\t"                                                                    \
      "bne    1b\n\t"                                                                          \
      "b      4f\n\t"                                                                          \
      "3:\n\t"                                                                                 \
      "adds   %[rej], #1\n\t"                                                                  \
      "b      2b\n\t"                                                                          \
      "4:\n\t"                                                                                 \
      : [i] "+r"(i), [z] "+r"(z), [br] "+r"(br), [g] "+r"(g), [rej] "+r"(rej), [t1] "=&r"(t1), \
        [t2] "=&r"(t2)                                                                         \
      : [pe] "r"(pe), [de] "r"(de), [dz] "r"(dz), [dbr] "r"(dbr), [dg] "r"(dg)                 \
      : "cc", "memory")
  if constexpr (kSwap)
    LR_LANE_SPAN_V7M("rev16  %[t1], %[t1]\n\t");
  else
    LR_LANE_SPAN_V7M("");
#undef LR_LANE_SPAN_V7M
  return rej;
}
#else
// Declared only: lane_span never calls it on other cores.
template <bool kSwap>
uint32_t lane_span_v7m(uint16_t* px, uint16_t* depth, int32_t n, uint32_t z, uint32_t dz,
                       uint32_t br, uint32_t dbr, uint32_t g, uint32_t dg);
#endif
}  // namespace detail

// The loop of the renderer's span: by hand on Armv6-M (Armv7-M at -Os) with the depth test for the
// RGB565 formats (whose from_value is the value or its byte swap), lane_span_portable elsewhere.
template <class PF, bool kDepth>
[[gnu::always_inline]] inline uint32_t lane_span(typename PF::Storage* px, uint16_t* depth,
                                                 int32_t n, uint32_t z, uint32_t dz, uint32_t br,
                                                 uint32_t dbr, uint32_t g, uint32_t dg) {
  if constexpr ((kLaneSpanAsm || kLaneSpanAsmV7) && kDepth && kRgb565Lanes<PF>) {
    constexpr unsigned kProbe = PF::from_value(0x1234u);
    if constexpr (kProbe == 0x1234u || kProbe == 0x3412u) {
      if (n <= 0) return 0;
      if constexpr (kLaneSpanAsmV7)
        return detail::lane_span_v7m<kProbe == 0x3412u>(reinterpret_cast<uint16_t*>(px), depth, n,
                                                        z, dz, br, dbr, g, dg);
      else
        return detail::lane_span_v6m<kProbe == 0x3412u>(reinterpret_cast<uint16_t*>(px), depth, n,
                                                        z, dz, br, dbr, g, dg);
    }
  }
  return lane_span_portable<PF, kDepth>(px, depth, n, z, dz, br, dbr, g, dg);
}

}  // namespace lr
