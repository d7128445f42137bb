// One plane of a small untextured triangle (setup_untextured_triangle's 32-bit path,
// docs/numerics.md#untextured-planes) from exact numerators: the two cross products of an
// attribute's vertex differences with the triangle's (normalised) edges, each times one signed
// reciprocal of the area chosen per triangle and plane kind, and two high-word products for the
// offset of vertex 0 from its reference pixel's centre; a power of two only where the plane's
// units need more bits than the product has (green, depth of slivers), as a left shift.
#pragma once

#include <cstdint>

#include "lineraster/core/math/wide_mul.hpp"
#include "lineraster/core/setup/active_triangle.hpp"

namespace lr {

// The basis: the edges times 2^(14 - bm) (|E| < 2^14: a difference below 2^16 times one stays
// below 2^30), the offset of vertex 0 from the centre of its reference pixel (c0, r0) in
// subpixels times 2^24, and that pixel.
struct SmallBasis {
  int32_t e1x = 0, e1y = 0, e2x = 0, e2y = 0;
  int32_t fx = 0, fy = 0;
  uint32_t c0 = 0, r0 = 0;
};

// A plane kind's factor: the signed reciprocal scaled so that mul_hi(n, r) is the gradient
// times 2^-left (|r| <= 2^31, left in [0, 31)).
struct PlaneScale {
  int32_t r = 0;
  int left = 0;
};
// From the reciprocal rc (the product's gradient times 2^s in the plane's units): s <= 0 shifts
// rc right (its precision drops, the products' stays), s > 0 shifts the products left.
constexpr PlaneScale plane_scale(int32_t rc, int s) {
  return s >= 0 ? PlaneScale{rc, s} : PlaneScale{rc >> (-s < 31 ? -s : 31), 0};
}

// The plane whose vertex differences are d1, d2 (vertex 1 and 2 minus vertex 0, |d| <= 2^16)
// and whose value at vertex 0 is a0: gradients (floored, times 2^left), the base at pixel
// (0, 0) modulo 2^32.
inline void small_plane(const SmallBasis& b, int32_t d1, int32_t d2, uint32_t a0,
                        const PlaneScale& sc, Plane& pl) {
  // Exact: |d E| < 2^30, so each numerator is below 2^31.
  const int32_t nx = d1 * b.e2y - d2 * b.e1y;
  const int32_t ny = d2 * b.e1x - d1 * b.e2x;
  const int32_t px = mul_hi(nx, sc.r), py = mul_hi(ny, sc.r);  // |p| <= 2^30
  const int32_t off = mla_hi(px, b.fx, mul_hi(py, b.fy));      // (px fx + py fy) / 256
  const uint32_t gx = static_cast<uint32_t>(px) << sc.left;
  const uint32_t gy = static_cast<uint32_t>(py) << sc.left;
  pl.gx = gx;
  pl.gy = gy;
  pl.base = a0 + (static_cast<uint32_t>(off) << sc.left) - gx * b.c0 - gy * b.r0;
}

}  // namespace lr
