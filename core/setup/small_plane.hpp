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
// (0, 0) modulo 2^32. px, py: the unshifted products, gx 2^-left and gy 2^-left (|p| <= 2^30).
inline void small_plane(const SmallBasis& b, int32_t d1, int32_t d2, uint32_t a0,
                        const PlaneScale& sc, Plane& pl, int32_t& px, int32_t& py) {
  // Exact: |d E| < 2^30, so each numerator is below 2^31.
  const int32_t nx = d1 * b.e2y - d2 * b.e1y;
  const int32_t ny = d2 * b.e1x - d1 * b.e2x;
  px = mul_hi(nx, sc.r);
  py = mul_hi(ny, sc.r);
  const int32_t off = mla_hi(px, b.fx, mul_hi(py, b.fy));  // (px fx + py fy) / 256
  const uint32_t gx = static_cast<uint32_t>(px) << sc.left;
  const uint32_t gy = static_cast<uint32_t>(py) << sc.left;
  pl.gx = gx;
  pl.gy = gy;
  pl.base = a0 + (static_cast<uint32_t>(off) << sc.left) - gx * b.c0 - gy * b.r0;
}
inline void small_plane(const SmallBasis& b, int32_t d1, int32_t d2, uint32_t a0,
                        const PlaneScale& sc, Plane& pl) {
  int32_t px, py;
  small_plane(b, d1, d2, a0, sc, pl, px, py);
}

// The red and blue lanes of a one-hue triangle (docs/numerics.md#one-hue) from green's unshifted
// products px, py and left shift: each lane's products are mul_hi(p, K 2^e), e = left - 14 (K
// shifted right when e < 0, the products left when e > 0), red in the low lane; a0 the packed
// lanes at vertex 0. The same integers as small_lanes_planes_by_hand.
inline void hue_lanes(const SmallBasis& b, int32_t px, int32_t py, int green_left,
                      const int32_t (&hue)[2], uint32_t a0, Plane& pl) {
  const int e = green_left - 14;
  const PlaneScale r = plane_scale(hue[0], e), bl = plane_scale(hue[1], e);
  const int32_t rx = mul_hi(px, r.r), ry = mul_hi(py, r.r);
  const int32_t bx = mul_hi(px, bl.r), by = mul_hi(py, bl.r);
  const uint32_t off = static_cast<uint32_t>(mla_hi(rx, b.fx, mul_hi(ry, b.fy))) +
                       (static_cast<uint32_t>(mla_hi(bx, b.fx, mul_hi(by, b.fy))) << 16);
  const uint32_t gx = static_cast<uint32_t>(rx) + (static_cast<uint32_t>(bx) << 16);
  const uint32_t gy = static_cast<uint32_t>(ry) + (static_cast<uint32_t>(by) << 16);
  pl.gx = gx << r.left;
  pl.gy = gy << r.left;
  pl.base = a0 + ((off - gx * b.c0 - gy * b.r0) << r.left);
}

}  // namespace lr
