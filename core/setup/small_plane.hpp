// One plane of a small untextured triangle (setup_untextured_triangle's 32-bit path,
// docs/numerics.md#untextured-planes) from the triangle's basis and an attribute's two vertex
// differences: two high-word products per gradient, two for the offset of vertex 0 from its
// reference pixel's centre, a per-triangle power of two, and the value at pixel (0, 0).
//
// The C form of every core; on Armv7E-M the lanes planes with depth are made by hand instead
// (small_lanes_planes_by_hand, untextured_setup.cpp: the same integers; an asm block per plane
// step alone made the setup longer, GCC 12 then kept the basis and the shifts in memory).
#pragma once

#include <cstdint>

#include "lineraster/core/math/wide_mul.hpp"
#include "lineraster/core/setup/active_triangle.hpp"

namespace lr {

// The basis: the barycentric gradients of vertices 1 and 2 scaled by a per-triangle power of
// two (|k| <= 2^30, as FastBasis's), the offset of vertex 0 from the centre of its reference
// pixel (c0, r0) in subpixels times 2^24, and that pixel. Read from memory by the plane step.
struct SmallBasis {
  int32_t kx1 = 0, kx2 = 0, ky1 = 0, ky2 = 0;
  int32_t fx = 0, fy = 0;
  uint32_t c0 = 0, r0 = 0;
};

// 2^s as a left shift, a right shift and the right shift's rounding half (0 for none); left in
// [0, 31), right in [0, 31].
struct PlaneShift {
  int32_t left = 0, right = 0, half = 0;
};
constexpr PlaneShift plane_shift(int s) {
  const int32_t left = s > 0 ? s : 0;
  const int32_t right = s >= 0 ? 0 : s < -31 ? 31 : -s;
  // In unsigned arithmetic, since right reaches 31 (the depth plane of a small triangle with
  // (nearly) one depth): as int32, 2^31 >> 1 is -2^30, which made every scaled value -1.
  return {left, right, static_cast<int32_t>((1u << right) >> 1)};
}

// The plane whose normalised vertex differences are n1, n2 (vertex 1 and 2 minus vertex 0,
// |n| <= 2^30) and whose value at vertex 0 is a0: gradients 2^s times the products' (rounded),
// the base at pixel (0, 0) modulo 2^32.
inline void small_plane(const SmallBasis& b, int32_t n1, int32_t n2, uint32_t a0,
                        const PlaneShift& sh, Plane& pl) {
  const int32_t gx = mla_hi(n1, b.kx1, mul_hi(n2, b.kx2));
  const int32_t gy = mla_hi(n1, b.ky1, mul_hi(n2, b.ky2));
  const int32_t off = mla_hi(gx, b.fx, mul_hi(gy, b.fy));  // (gx fx + gy fy) / 256
  const auto scale = [&sh](int32_t x) {
    return static_cast<uint32_t>(
        (static_cast<int32_t>(static_cast<uint32_t>(x) << sh.left) + sh.half) >> sh.right);
  };
  const uint32_t ugx = scale(gx), ugy = scale(gy);
  pl.gx = ugx;
  pl.gy = ugy;
  pl.base = a0 + scale(off) - ugx * b.c0 - ugy * b.r0;
}

}  // namespace lr
