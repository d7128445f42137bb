// x^s for the specular term, from two tables generated at compile time: log2 of the mantissa
// (Q8.24) and exp2 of the fraction (Q1.30), each with 2^kBits + 1 entries and linear
// interpolation.
//
// x: Q1.30 in [0, 2^30] (N.H of two Q1.30 unit vectors). s: shininess in Q8.8, [0, 128].
// Result: Q1.15 in [0, 32768]. log2(x) >= -30 fits Q8.24; s * log2(x) >= -3840 stays in int64.
// Error per table size: docs/numerics.md#specular-power-xs (checked by tests/core/math_test.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "lineraster/core/math/fixed.hpp"

namespace lr {

namespace detail {

// Compile-time natural log and exp (series), only ever evaluated by the compiler.
consteval double ct_ln(double x) {  // x in [1, 2]
  double y = (x - 1) / (x + 1), y2 = y * y, term = y, sum = 0;
  for (int k = 1; k < 80; k += 2) {
    sum += term / k;
    term *= y2;
  }
  return 2 * sum;
}
consteval double ct_exp(double x) {  // |x| <= 1
  double term = 1, sum = 1;
  for (int k = 1; k < 30; ++k) {
    term *= x / k;
    sum += term;
  }
  return sum;
}
inline constexpr double kLn2 = 0.69314718055994530942;

template <int kBits>
consteval std::array<int32_t, (size_t{1} << kBits) + 1> make_log2_table() {  // log2(1 + i/N), Q24
  std::array<int32_t, (size_t{1} << kBits) + 1> t{};
  for (int i = 0; i <= (1 << kBits); ++i)
    t[static_cast<size_t>(i)] =
        // Positive table values: adding 0.5 and truncating is round-half-up, as intended.
        // NOLINTNEXTLINE(bugprone-incorrect-roundings)
        static_cast<int32_t>(ct_ln(1.0 + double(i) / (1 << kBits)) / kLn2 * 16777216.0 + 0.5);
  return t;
}
template <int kBits>
consteval std::array<uint32_t, (size_t{1} << kBits) + 1> make_exp2_table() {  // 2^(-j/N), Q1.30
  std::array<uint32_t, (size_t{1} << kBits) + 1> t{};
  for (int j = 0; j <= (1 << kBits); ++j)
    t[static_cast<size_t>(j)] =
        // Positive table values: adding 0.5 and truncating is round-half-up, as intended.
        // NOLINTNEXTLINE(bugprone-incorrect-roundings)
        static_cast<uint32_t>(ct_exp(-kLn2 * j / (1 << kBits)) * 1073741824.0 + 0.5);
  return t;
}

}  // namespace detail

template <int kLogBits = 8, int kExpBits = 8>
struct PowTable {
  static_assert(kLogBits >= 2 && kLogBits <= 12 && kExpBits >= 2 && kExpBits <= 12);
  static constexpr auto kLog2 = detail::make_log2_table<kLogBits>();
  static constexpr auto kExp2 = detail::make_exp2_table<kExpBits>();
  static constexpr size_t kBytes = sizeof(kLog2) + sizeof(kExp2);

  // log2(x) in Q8.24 for x in (0, 2^30] (Q1.30): in [-30, 0].
  static constexpr int32_t log2_q24(uint32_t x) {
    int top = 31 - clz32(x);       // bit index of the leading one, 0..30
    uint32_t m = x << (31 - top);  // leading one at bit 31; the 31 bits below are the fraction
    uint32_t frac = m & 0x7FFFFFFFu;
    uint32_t idx = frac >> (31 - kLogBits);
    uint32_t rem = (frac >> (31 - kLogBits - 16)) & 0xFFFFu;  // next 16 bits
    int32_t a = kLog2[idx], b = kLog2[idx + 1];
    int32_t lm = a + static_cast<int32_t>((int64_t{b - a} * rem) >> 16);
    return lm + (top - 30) * (1 << 24);
  }

  // 2^y for y <= 0 in Q8.24, result Q1.15.
  static constexpr uint32_t exp2_q15(int64_t y) {
    int64_t ny = -y;
    int64_t n = ny >> 24;
    if (n >= 16) return 0;
    uint32_t f = static_cast<uint32_t>(ny & 0xFFFFFF);
    uint32_t idx = f >> (24 - kExpBits);
    uint32_t rem = (f << kExpBits) & 0xFFFFFFu;  // fraction between entries, Q24
    uint32_t a = kExp2[idx], b = kExp2[idx + 1];
    uint32_t e = a - static_cast<uint32_t>((uint64_t{a - b} * rem) >> 24);  // Q1.30
    return static_cast<uint32_t>(round_shift(int64_t{e}, 15 + static_cast<int>(n)));
  }

  // x^s: x Q1.30 in [0, 2^30], s Q8.8 in [0, 128 * 256]. pow(0, 0) = 1 as GL has it.
  static constexpr uint32_t pow_q15(uint32_t x, uint32_t s_q8) {
    if (s_q8 == 0) return 1u << 15;
    if (x == 0) return 0;
    if (x >= (1u << 30)) return 1u << 15;
    int64_t y = (int64_t{log2_q24(x)} * s_q8) >> 8;
    return exp2_q15(y);
  }
};

using DefaultPowTable = PowTable<8, 8>;

}  // namespace lr
