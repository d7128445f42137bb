// Span routines: fill one row of one triangle between its edges.
//
// One routine per state (depth test on/off x colour planes none/perspective/affine), each a
// template instance with no per-pixel branch on state; the table of a renderer's
// SpanSet holds the instances its states select (span_state.hpp). Per pixel: depth test
// first, then colour, then the write. Returns the number of pixels written.
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

template <class PF>
using SpanFn = uint32_t (*)(const ActiveTriangle& t, typename PF::Storage* px, uint16_t* depth,
                            int32_t col, int32_t row, int32_t count);

template <class PF, bool kDepth, ColorPlanes kColors>
uint32_t fill_span(const ActiveTriangle& t, typename PF::Storage* px, uint16_t* depth, int32_t col,
                   int32_t row, int32_t count) {
  uint32_t z = 0, dz = 0;
  if constexpr (kDepth) {
    z = detail::depth_start(t.z, col, row);
    dz = t.z.gx;
  }
  uint32_t q = 0, dq = 0;
  std::array<uint32_t, 3> c{}, dc{};
  if constexpr (kColors != ColorPlanes::kNone) {
    for (int k = 0; k < 3; ++k) {
      c[static_cast<size_t>(k)] = t.c[k].at(col, row);
      dc[static_cast<size_t>(k)] = t.c[k].gx;
    }
  }
  if constexpr (kColors == ColorPlanes::kPerspective) {
    q = t.q.at(col, row);
    dq = t.q.gx;
  }
  typename PF::Storage flat{};
  if constexpr (kColors == ColorPlanes::kNone)
    flat = PF::encode(Rgb8{static_cast<uint8_t>(t.q.base), static_cast<uint8_t>(t.q.base >> 8),
                           static_cast<uint8_t>(t.q.base >> 16)});

  uint32_t written = 0;
  for (int32_t i = 0; i < count; ++i) {
    bool pass = true;
    if constexpr (kDepth) {
      pass = detail::depth_pass(z, depth[i]);
      z += dz;
    }
    if (pass) {
      if constexpr (kColors == ColorPlanes::kNone) {
        px[i] = flat;
      } else if constexpr (kColors == ColorPlanes::kPerspective) {
        detail::Reciprocal rc(q);
        px[i] = PF::encode15(rc.apply(c[0]), rc.apply(c[1]), rc.apply(c[2]));
      } else {
        px[i] =
            PF::encode15(detail::affine15(c[0]), detail::affine15(c[1]), detail::affine15(c[2]));
      }
      ++written;
    }
    if constexpr (kColors != ColorPlanes::kNone) {
      c[0] += dc[0];
      c[1] += dc[1];
      c[2] += dc[2];
    }
    if constexpr (kColors == ColorPlanes::kPerspective) q += dq;
  }
  return written;
}

// The untextured family (dispatch.hpp): fill_span per (depth test, colour planes).
template <class PF>
struct UntexturedSpans {
  using Layout = UntexturedLayout;
  using Fn = SpanFn<PF>;
  static constexpr auto kUsed = &UsedRoutines::untextured;
  template <bool kDepth, ColorPlanes kColors>
  static constexpr Fn routine() {
    return &fill_span<PF, kDepth, kColors>;
  }
};

// The routines of a set, generated from the template and the state space (span_state.hpp).
template <class PF, SpanSet kSet = kAllSpans>
inline constexpr std::array<SpanFn<PF>, kUntexturedRoutines> kSpanTable =
    make_table<UntexturedSpans<PF>, kSet>();

template <class PF, SpanSet kSet = kAllSpans>
constexpr SpanFn<PF> span_routine(bool depth, ColorPlanes colors) {
  return kSpanTable<PF, kSet>[untextured_index(depth, colors)];
}

}  // namespace lr
