// The spans of the untextured family: one row of one triangle between its edges, from the
// planes of untextured_setup.hpp at the span's first pixel, stepped along it. Per pixel the
// depth test first (16-bit LESS with write), then the colour and the write. Each returns the
// pixels the depth test rejected (the row loop counts the written ones from that).
//
//   kFlat         one pixel for the whole triangle
//   kLanes        RGB565 formats: blue and red as 16-bit lanes of one register and green in
//                 another, each stepped by one add and packed to RGB565 without a table
//                 (core/span/lane_span.hpp: the loop, and its Armv7E-M form)
//   kAffine       three Q2.30 channel planes, clamped to Q1.15
//   kPerspective  the channels times q over q, one 17-bit reciprocal per pixel
#pragma once

#include <cstdint>
#include <cstring>

#include "lineraster/core/output/color.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/setup/untextured_setup.hpp"
#include "lineraster/core/span/lane_span.hpp"
#include "lineraster/core/span/span.hpp"

namespace lr {

// A pixel as the bits of a uint32 (a flat triangle's colour in its plane) and back.
template <class PF>
uint32_t pixel_bits(typename PF::Storage p) {
  static_assert(sizeof(p) <= sizeof(uint32_t));
  uint32_t b = 0;
  std::memcpy(&b, &p, sizeof(p));
  return b;
}
template <class PF>
typename PF::Storage from_pixel_bits(uint32_t b) {
  typename PF::Storage p{};
  std::memcpy(static_cast<void*>(&p), &b, sizeof(p));
  return p;
}

// Q1.15 channels in [0, 1] as a pixel: RGB565 formats round each to its 5 or 6 bits
// (round(31 c), round(63 c): the lanes' rounding), the others through PF::encode15.
template <class PF>
typename PF::Storage pack15(uint32_t r15, uint32_t g15, uint32_t b15) {
  if constexpr (kRgb565Lanes<PF>) {
    constexpr uint32_t kHalf = Color15::kOne / 2;
    const uint32_t r5 = (r15 * 31 + kHalf) >> Color15::kFracBits;
    const uint32_t g6 = (g15 * 63 + kHalf) >> Color15::kFracBits;
    const uint32_t b5 = (b15 * 31 + kHalf) >> Color15::kFracBits;
    return PF::from_value((r5 << 11) | (g6 << 5) | b5);
  } else {
    return PF::encode15(r15, g15, b15);
  }
}

namespace detail {
// The depth test (LESS) and write of one pixel with half depth z (the plane's value, whose base
// holds the 2^14 that rounds it to 16 bits: untextured_setup.hpp).
inline bool half_depth_pass(uint32_t z, uint16_t& stored) {
  const auto d = static_cast<uint16_t>(z >> 15);
  const bool pass = d < stored;
  if (pass) stored = d;
  return pass;
}
}  // namespace detail

// persp: for kPerspective, whether the triangle is one (else kAffine's span: one routine for
// both where the code is built for size, untextured_rows.hpp); the kind's own value elsewhere.
template <class PF, bool kDepth, UntexturedKind kKind>
[[gnu::always_inline]] inline uint32_t untextured_span(const ActiveTriangle& t,
                                                       typename PF::Storage* px, uint16_t* depth,
                                                       int32_t col, int32_t row, int32_t count,
                                                       bool persp = kKind ==
                                                                    UntexturedKind::kPerspective) {
  uint32_t z = 0, dz = 0;
  if constexpr (kDepth) {
    z = t.z.at(col, row);
    dz = t.z.gx;
  }
  if constexpr (kKind == UntexturedKind::kLanes) {
    return lane_span<PF, kDepth>(px, depth, count, z, dz, t.c[0].at(col, row), t.c[0].gx,
                                 t.c[1].at(col, row), t.c[1].gx);
  } else {
    uint32_t c[3] = {}, dc[3] = {}, q = 0, dq = 0;
    if constexpr (kKind != UntexturedKind::kFlat) {
      for (int k = 0; k < 3; ++k) {
        c[k] = t.c[k].at(col, row);
        dc[k] = t.c[k].gx;
      }
    }
    if (kKind == UntexturedKind::kPerspective && persp) {
      q = t.q.at(col, row);
      dq = t.q.gx;
    }
    const typename PF::Storage flat = from_pixel_bits<PF>(t.c[0].base);
    uint32_t rejected = 0;
    for (int32_t i = 0; i < count; ++i) {
      bool pass = true;
      if constexpr (kDepth) {
        pass = detail::half_depth_pass(z, depth[i]);
        z += dz;
      }
      if (pass) {
        if constexpr (kKind == UntexturedKind::kFlat) {
          px[i] = flat;
        } else if (kKind == UntexturedKind::kPerspective && persp) {
          const detail::Reciprocal rc(q);
          px[i] = pack15<PF>(rc.apply(c[0]), rc.apply(c[1]), rc.apply(c[2]));
        } else {
          px[i] =
              pack15<PF>(detail::affine15(c[0]), detail::affine15(c[1]), detail::affine15(c[2]));
        }
      } else {
        ++rejected;
      }
      if constexpr (kKind != UntexturedKind::kFlat) {
        c[0] += dc[0];
        c[1] += dc[1];
        c[2] += dc[2];
      }
      if constexpr (kKind == UntexturedKind::kPerspective) q += dq;
    }
    return rejected;
  }
}

}  // namespace lr
