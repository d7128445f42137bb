// Fixed-point scalars and the integer helpers every stage shares.
//
// Fixed: Q16.16 in an int32 (raw / 65536). Range [-32768, 32768), resolution 2^-16 (1.5e-5).
// Used for model and world coordinates, matrix entries and camera parameters. Products are
// formed in 64 bits (|a*b| < 2^62 for any two int32) and rounded back, so multiplication cannot
// overflow the intermediate; a result outside the Q16.16 range saturates (see mul()).
#pragma once

#include <compare>
#include <cstdint>
#include <limits>

// [[gnu::noinline]] where the code is built for size (-Os), nothing elsewhere: for small
// helpers that GCC would otherwise inline into every caller there (one copy of each instead).
#if defined(__OPTIMIZE_SIZE__)
#define LR_SIZE_NOINLINE [[gnu::noinline]]
#else
#define LR_SIZE_NOINLINE
#endif

namespace lr {

struct Fixed {
  static constexpr int kFracBits = 16;
  static constexpr int32_t kOne = int32_t{1} << kFracBits;

  int32_t raw = 0;

  static constexpr Fixed from_raw(int32_t r) { return Fixed{r}; }
  static constexpr Fixed from_int(int32_t i) { return Fixed{i * kOne}; }
  // Ratio n/d rounded to nearest; d > 0.
  static constexpr Fixed ratio(int32_t n, int32_t d);
  // Only at compile time, so that no floating point reaches a target without an FPU.
  static consteval Fixed from_double(double v) {
    return Fixed{static_cast<int32_t>(v * kOne + (v >= 0 ? 0.5 : -0.5))};
  }

  friend constexpr Fixed operator+(Fixed a, Fixed b) { return Fixed{a.raw + b.raw}; }
  friend constexpr Fixed operator-(Fixed a, Fixed b) { return Fixed{a.raw - b.raw}; }
  friend constexpr Fixed operator-(Fixed a) { return Fixed{-a.raw}; }
  friend constexpr bool operator==(Fixed a, Fixed b) = default;
  friend constexpr auto operator<=>(Fixed a, Fixed b) = default;
};

// Saturates an int64 into int32.
constexpr int32_t saturate32(int64_t v) {
  if (v > std::numeric_limits<int32_t>::max()) return std::numeric_limits<int32_t>::max();
  if (v < std::numeric_limits<int32_t>::min()) return std::numeric_limits<int32_t>::min();
  return static_cast<int32_t>(v);
}

// Arithmetic shift right with rounding to nearest (ties towards +infinity), for int64.
constexpr int64_t round_shift(int64_t v, int s) {
  return (v + (int64_t{1} << (s - 1))) >> s;
}

// Floor and ceiling of n / d for d > 0, exact for all int64 n.
constexpr int64_t floor_div(int64_t n, int64_t d) {
  int64_t q = n / d;
  return (n % d != 0 && n < 0) ? q - 1 : q;
}
constexpr int64_t ceil_div(int64_t n, int64_t d) {
  int64_t q = n / d;
  return (n % d != 0 && n > 0) ? q + 1 : q;
}
// n / d rounded to nearest (ties away from zero), d > 0.
constexpr int64_t round_div(int64_t n, int64_t d) {
  return n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d);
}

// Q16.16 product, rounded, saturated to the Q16.16 range.
constexpr Fixed mul(Fixed a, Fixed b) {
  return Fixed{saturate32(round_shift(int64_t{a.raw} * b.raw, Fixed::kFracBits))};
}
// Q16.16 quotient, rounded; b != 0. Saturates.
constexpr Fixed div(Fixed a, Fixed b) {
  int64_t n = int64_t{a.raw} * Fixed::kOne;
  int64_t d = b.raw;
  if (d < 0) {
    n = -n;
    d = -d;
  }
  return Fixed{saturate32(round_div(n, d))};
}
constexpr Fixed Fixed::ratio(int32_t n, int32_t d) {
  return Fixed{saturate32(round_div(int64_t{n} * kOne, d))};
}

// Number of leading zero bits of a non-zero value; portable and constexpr (GCC lowers the
// builtin to CLZ where the core has it).
constexpr int clz32(uint32_t v) {
  return __builtin_clz(v);
}
// clz64 and abs64 are calls where the code is built for size: each is a few instructions on a
// 32-bit core, inlined in dozens of places (0.3 KB of the Gouraud renderer at -Os on Cortex-M4F).
LR_SIZE_NOINLINE constexpr int clz64(uint64_t v) {
  return __builtin_clzll(v);
}

// Magnitude of an int64 as uint64, defined for INT64_MIN too.
LR_SIZE_NOINLINE constexpr uint64_t abs64(int64_t v) {
  return v < 0 ? uint64_t{0} - static_cast<uint64_t>(v) : static_cast<uint64_t>(v);
}

}  // namespace lr
