// Fixed-point vectors.
//
// Vec3: three Fixed (Q16.16) — positions and directions in model, world and eye space,
//       |component| < 32768 units.
// Normal16: a unit vector in Q1.14 per component (16384 = 1.0), 6 bytes: how meshes store
//       normals (in flash). |component| <= 1 so 16384 always fits in int16.
// Unit30: a unit vector in Q1.30 per component (2^30 = 1.0): the working format of lighting.
#pragma once

#include <cstdint>
#include <type_traits>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/sqrt.hpp"
#include "lineraster/core/math/wide_divide.hpp"

namespace lr {

struct Vec3 {
  Fixed x, y, z;
  friend constexpr bool operator==(const Vec3&, const Vec3&) = default;
};

struct Normal16 {
  int16_t x = 0, y = 0, z = 0;
  static constexpr int kFracBits = 14;
  friend constexpr bool operator==(const Normal16&, const Normal16&) = default;
};

// A tangent for normal mapping: the direction of increasing u on the surface, unit Q1.14 like
// Normal16, and w = +-1 (Q1.14: +-16384): the bitangent is w * cross(normal, tangent).
struct Tangent16 {
  int16_t x = 0, y = 0, z = 0, w = 16384;
  static constexpr int kFracBits = 14;
  friend constexpr bool operator==(const Tangent16&, const Tangent16&) = default;
};

struct Unit30 {
  int32_t x = 0, y = 0, z = 0;
  static constexpr int kFracBits = 30;
};

constexpr Vec3 operator+(Vec3 a, Vec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
constexpr Vec3 operator-(Vec3 a, Vec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}

// Dot product of Q16.16 vectors in Q32.30 (int64): each product (< 2^62) is shifted by 2
// first, so the sum of three stays below 2^62.
constexpr int64_t dot_q30(Vec3 a, Vec3 b) {
  return ((int64_t{a.x.raw} * b.x.raw) >> 2) + ((int64_t{a.y.raw} * b.y.raw) >> 2) +
         ((int64_t{a.z.raw} * b.z.raw) >> 2);
}

namespace detail {
constexpr bool normalize_unit30_body(int64_t x, int64_t y, int64_t z, Unit30& out) {
  uint64_t m = abs64(x) | abs64(y) | abs64(z);
  if (m == 0) return false;
  // Bring the largest magnitude into [2^29, 2^30): squares then sum below 3 * 2^60.
  int top = 63 - clz64(m);
  if (top >= 30) {
    int s = top - 29;
    x >>= s;
    y >>= s;
    z >>= s;
  } else if (top < 29) {
    int s = 29 - top;
    x = static_cast<int64_t>(static_cast<uint64_t>(x) << s);
    y = static_cast<int64_t>(static_cast<uint64_t>(y) << s);
    z = static_cast<int64_t>(static_cast<uint64_t>(z) << s);
  }
  uint64_t len2 =
      static_cast<uint64_t>(x * x) + static_cast<uint64_t>(y * y) + static_cast<uint64_t>(z * z);
  // len in [2^28, 2^31): 30 fractional bits of each quotient need x * 2^30 < 2^60.
  const uint32_t len = isqrt64(len2);
  if (len == 0) return false;
  // round_div(c 2^30, len) (half away from zero) as |c| 2^30 + floor(len / 2) over len with c's
  // sign, in one 64-by-32 division: |c| <= len (len = floor(sqrt(x^2 + y^2 + z^2))), so the
  // numerator is below len 2^32 and the quotient at most 2^30.
  auto unit = [len](int64_t c) {
    const uint32_t q = divide_64by32((abs64(c) << 30) + (len >> 1), len).q;
    return c < 0 ? -static_cast<int32_t>(q) : static_cast<int32_t>(q);
  };
  out.x = unit(x);
  out.y = unit(y);
  out.z = unit(z);
  return true;
}
}  // namespace detail

// Normalises the vector (x, y, z), given in any common fixed-point scale, to a Q1.30 unit vector.
// Returns false (and leaves `out` unchanged) for the zero vector. At run time one out-of-line
// copy (vec.cpp): the body is 0.7 KB of flash, and each translation unit made its own.
bool normalize_unit30_call(int64_t x, int64_t y, int64_t z, Unit30& out);
constexpr bool normalize_unit30(int64_t x, int64_t y, int64_t z, Unit30& out) {
  if (std::is_constant_evaluated()) return detail::normalize_unit30_body(x, y, z, out);
  return normalize_unit30_call(x, y, z, out);
}

constexpr Vec3 to_vec3(Unit30 u) {
  return {Fixed::from_raw(static_cast<int32_t>(round_shift(u.x, 14))),
          Fixed::from_raw(static_cast<int32_t>(round_shift(u.y, 14))),
          Fixed::from_raw(static_cast<int32_t>(round_shift(u.z, 14)))};
}

// Unit vector of a Q16.16 vector; the zero vector stays zero.
constexpr Vec3 normalize(Vec3 v) {
  Unit30 u;
  if (!normalize_unit30(v.x.raw, v.y.raw, v.z.raw, u)) return v;
  return to_vec3(u);
}

// Cross product in Q16.16, computed in 64 bits and saturated.
constexpr Vec3 cross(Vec3 a, Vec3 b) {
  auto c = [](int32_t p, int32_t q, int32_t r, int32_t s) {
    return Fixed::from_raw(saturate32(round_shift(int64_t{p} * q - int64_t{r} * s, 16)));
  };
  return {c(a.y.raw, b.z.raw, a.z.raw, b.y.raw), c(a.z.raw, b.x.raw, a.x.raw, b.z.raw),
          c(a.x.raw, b.y.raw, a.y.raw, b.x.raw)};
}

}  // namespace lr
