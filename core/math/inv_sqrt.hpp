// Inverse square root from a table generated at compile time, for renormalising interpolated
// normals per pixel (and the sphere-map and tangent-frame vectors) without a square root or a
// division.
//
// f in [1, 4) (a sum of squares scaled by a power of 4) is looked up by its top kBits bits
// (3 * 2^(kBits - 2) entries of 1/sqrt in Q1.30), then kNewton Newton steps in 64-bit
// integers. The default (8 bits, one step) keeps a unit vector's length within 2^-15 of 1. Error
// per size: docs/numerics.md#inverse-square-root-table-and-newton-step (checked by
// tests/core/phong_test.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/vec.hpp"

namespace lr {

namespace detail {

consteval double ct_sqrt(double v) {
  double g = v > 1 ? v : 1;
  for (int k = 0; k < 60; ++k) g = 0.5 * (g + v / g);
  return g;
}

// 1/sqrt over 3 * 2^(kBits - 2) buckets of [1, 4), Q1.30: the value with equal relative error
// against 1/sqrt at both ends of its bucket.
template <int kBits>
consteval std::array<uint32_t, (size_t{3} << (kBits - 2))> make_inv_sqrt_table() {
  std::array<uint32_t, (size_t{3} << (kBits - 2))> t{};
  const double step = 1.0 / double(size_t{1} << (kBits - 2));
  for (size_t i = 0; i < t.size(); ++i) {
    const double lo = 1.0 + double(i) * step, hi = lo + step;
    // Positive table values: adding 0.5 and truncating is round-half-up, as intended.
    // NOLINTNEXTLINE(bugprone-incorrect-roundings)
    t[i] = static_cast<uint32_t>(2.0 / (ct_sqrt(lo) + ct_sqrt(hi)) * 1073741824.0 + 0.5);
  }
  return t;
}

}  // namespace detail

template <int kBits, int kNewton>
struct InvSqrtTable {
  static_assert(kBits >= 3 && kBits <= 12, "table of 6 to 3072 entries");
  static_assert(kNewton >= 0 && kNewton <= 2);
  static constexpr size_t kEntries = size_t{3} << (kBits - 2);

  // 1/sqrt(f) for f = x / 2^30 in [1, 4) (x in [2^30, 2^32)), Q1.30.
  static constexpr uint32_t rsqrt_q30(uint32_t x) {
    const size_t i = (x >> (32 - kBits)) - (size_t{1} << (kBits - 2));
    int64_t y = kTable[i];
    for (int k = 0; k < kNewton; ++k) {
      const int64_t y2 = (y * y) >> 30;                                  // <= 2^30
      const int64_t t = (int64_t{3} << 30) - ((int64_t{x} * y2) >> 30);  // ~2^31
      y = (y * t) >> 31;                                                 // < 2^62 before the shift
    }
    return static_cast<uint32_t>(y);
  }

  // Normalises (x, y, z), any common scale with |components| < 2^62, to a Q1.30 unit vector.
  // Returns false (out unchanged) for the zero vector.
  static constexpr bool normalize(int64_t x, int64_t y, int64_t z, Unit30& out) {
    uint64_t m = abs64(x) | abs64(y) | abs64(z);
    if (m == 0) return false;
    // Largest magnitude into [2^29, 2^30): the sum of squares is in [2^58, 3 * 2^60).
    const int top = 63 - clz64(m);
    if (top >= 30) {
      const int s = top - 29;
      x >>= s;
      y >>= s;
      z >>= s;
    } else if (top < 29) {
      const int s = 29 - top;
      x = static_cast<int64_t>(static_cast<uint64_t>(x) << s);
      y = static_cast<int64_t>(static_cast<uint64_t>(y) << s);
      z = static_cast<int64_t>(static_cast<uint64_t>(z) << s);
    }
    const uint64_t len2 =
        static_cast<uint64_t>(x * x) + static_cast<uint64_t>(y * y) + static_cast<uint64_t>(z * z);
    // len2 = f 4^j with f in [1, 4): j = 29 or 30. 1/len = rsqrt(f) 2^-j.
    const int e = 63 - clz64(len2);
    const int j = e >> 1;
    const auto f = static_cast<uint32_t>(len2 >> (2 * j - 30));  // [2^30, 2^32)
    const int64_t r = rsqrt_q30(f);
    // |component| < 2^30 and r <= 2^30: products below 2^60.
    out.x = static_cast<int32_t>((x * r) >> j);
    out.y = static_cast<int32_t>((y * r) >> j);
    out.z = static_cast<int32_t>((z * r) >> j);
    return true;
  }

 private:
  static constexpr std::array<uint32_t, kEntries> kTable = detail::make_inv_sqrt_table<kBits>();
};

using DefaultInvSqrt = InvSqrtTable<8, 1>;

}  // namespace lr
