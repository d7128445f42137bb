// A plane's error against the exact plane through three vertex values (the plane and untextured
// setup tests): the exact value at a pixel centre in 128-bit integers (tests/reference/int128.hpp
// on 32-bit targets), the core's value taken modulo 2^32 as the core's planes wrap.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <random>

#include "lineraster/core/setup/triangle_setup.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"
#include "tests/reference/int128.hpp"

namespace lr::test {

#if defined(__SIZEOF_INT128__)
__extension__ typedef __int128 i128;
#else
using i128 = ref::Int128;  // 32-bit targets (the armhf test build): the same exact values
#endif

inline uint32_t low_word(const i128& v) {
#if defined(__SIZEOF_INT128__)
  return static_cast<uint32_t>(static_cast<uint64_t>(v));
#else
  return static_cast<uint32_t>(v.lo());
#endif
}

// Plane p's error at pixel (c, r) against the exact plane through the vertex values a, modulo
// 2^32, in units.
inline double plane_error(const ScreenVertex* const v[3], const uint32_t a[3], const Plane& p,
                          int32_t c, int32_t r) {
  const int64_t x0 = v[0]->x, y0 = v[0]->y;
  const int64_t ex1 = v[1]->x - x0, ey1 = v[1]->y - y0, ex2 = v[2]->x - x0, ey2 = v[2]->y - y0;
  const i128 d = i128{ex1} * ey2 - i128{ex2} * ey1;
  const i128 da1 = i128{a[1]} - a[0], da2 = i128{a[2]} - a[0];
  const i128 px = i128{c} * kSubpixel + kHalfPixel - x0, py = i128{r} * kSubpixel + kHalfPixel - y0;
  i128 n = px * (da1 * ey2 - da2 * ey1) + py * (da2 * ex1 - da1 * ex2);
  i128 dd = d;
  if (dd < 0) {
    n = -n;
    dd = -dd;
  }
  i128 t = n / dd, rem = n % dd;  // n = t dd + rem, rem in [0, dd)
  if (rem < 0) {
    t = t - 1;
    rem = rem + dd;
  }
  // got - (a0 + t + rem / dd), the integer part taken modulo 2^32.
  const auto diff = static_cast<int32_t>(p.at(c, r) - a[0] - low_word(t));
  return diff - static_cast<double>(rem) / static_cast<double>(dd);
}

// Calls sample(c, r, distance) at the corners and four random pixel centres of the bounding box
// of v (the pixel centres inside it); distance is |dx| + |dy| in pixels from v[0] to the centre,
// the factor of a plane's gradient error there.
template <class Sample>
void sample_bounding_box(const ScreenVertex* const v[3], std::mt19937_64& rng, Sample&& sample) {
  const int32_t xl = std::min({v[0]->x, v[1]->x, v[2]->x}),
                xh = std::max({v[0]->x, v[1]->x, v[2]->x});
  const int32_t yl = std::min({v[0]->y, v[1]->y, v[2]->y}),
                yh = std::max({v[0]->y, v[1]->y, v[2]->y});
  const int32_t c0 = first_row_below(xl - 1), c1 = last_row_at_or_above(xh);
  const int32_t r0 = first_row_below(yl - 1), r1 = last_row_at_or_above(yh);
  if (c0 > c1 || r0 > r1) return;
  auto at = [&](int32_t c, int32_t r) {
    const double dx = (c * double{kSubpixel} + kHalfPixel - v[0]->x) / kSubpixel;
    const double dy = (r * double{kSubpixel} + kHalfPixel - v[0]->y) / kSubpixel;
    sample(c, r, std::abs(dx) + std::abs(dy));
  };
  at(c0, r0);
  at(c1, r0);
  at(c0, r1);
  at(c1, r1);
  for (int k = 0; k < 4; ++k)
    at(c0 + static_cast<int32_t>(rng() % static_cast<uint64_t>(c1 - c0 + 1)),
       r0 + static_cast<int32_t>(rng() % static_cast<uint64_t>(r1 - r0 + 1)));
}

}  // namespace lr::test
