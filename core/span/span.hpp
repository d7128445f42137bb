// What the span routines share: the perspective-correct channel's reciprocal, the depth test of
// the full-scale depth planes (textured and Phong), the affine channel's clamp. The spans
// themselves: untextured_span.hpp, tex_span.hpp, phong_span.hpp; every family's routines are
// template instances with no per-pixel branch on state, in tables of the renderer's SpanSet
// (span_state.hpp, dispatch.hpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "lineraster/core/math/saturate.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/span/dispatch.hpp"
#include "lineraster/core/span/span_state.hpp"

namespace lr {

namespace detail {

// Perspective-correct channel value cq / q in Q1.15 with a 17-bit normalised reciprocal
// (relative error below 2^-14: docs/numerics.md#perspective-correct-attributes).
struct Reciprocal {
  int shift;
  uint32_t r;
  int32_t q;
  explicit Reciprocal(uint32_t plane_q) {
    int32_t qi = static_cast<int32_t>(plane_q);
    q = qi < 1 ? 1 : qi;  // plane rounding can only take q below 1 for extreme w ratios
    shift = clz32(static_cast<uint32_t>(q));
    uint32_t qn = static_cast<uint32_t>(q) << shift;
    r = 0xFFFFFFFFu / (qn >> 16);
  }
  uint32_t apply(uint32_t plane_cq) const {
    int32_t v = static_cast<int32_t>(plane_cq);
    v = v < 0 ? 0 : v > q ? q : v;
    return clamp_c15(static_cast<int32_t>((((static_cast<uint32_t>(v) << shift) >> 17) * r) >> 16));
  }
};

// The depth plane's value at a span's first pixel, plus the half that rounds it to 16 bits
// (stepping the sum modulo 2^32 rounds every pixel's value: depth_pass).
inline uint32_t depth_start(const Plane& z, int32_t col, int32_t row) {
  return z.at(col, row) + (1u << 15);
}

// The depth test (LESS) and write of one pixel: z is the depth plane's value (kDepthMax scale)
// plus 2^15 (depth_start).
inline bool depth_pass(uint32_t z, uint16_t& stored) {
  const auto d = static_cast<uint16_t>(z >> 16);
  const bool pass = d < stored;
  if (pass) stored = d;
  return pass;
}

// An affine colour plane's value (Q2.30) as a Q1.15 channel, clamped to [0, 1 - 2^-15]: one
// USAT on Armv7-M, and the same 8-bit level as clamping to [0, 1].
constexpr uint32_t affine15(uint32_t plane_c) {
  return usat_asr<Color15::kFracBits, 15>(static_cast<int32_t>(plane_c));
}
static_assert(to_byte(Color15::kOne - 1) == to_byte(Color15::kOne));

}  // namespace detail

}  // namespace lr
