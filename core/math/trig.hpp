// Sine and cosine of angles in degrees, in fixed point, from a table generated at compile time.
//
// Angles are Fixed degrees (Q16.16, any value: reduced modulo 360 exactly in integers).
// Results are Fixed in [-1, 1]. The table holds sin over [0, 90] degrees in kTrigSteps + 1
// entries (Q1.30); linear interpolation between entries stays under half a Q16.16 unit
// (docs/numerics.md#sine-and-cosine).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "lineraster/core/math/fixed.hpp"

namespace lr {

Fixed sin_deg(Fixed degrees);
Fixed cos_deg(Fixed degrees);

namespace detail {

inline constexpr int kTrigSteps = 256;

// Compile-time sine by Taylor series on [0, pi/2]; only ever evaluated by the compiler.
consteval double ct_sin(double x) {
  double term = x, sum = x;
  for (int n = 1; n < 20; ++n) {
    term *= -x * x / ((2.0 * n) * (2.0 * n + 1.0));
    sum += term;
  }
  return sum;
}

consteval std::array<int32_t, kTrigSteps + 1> make_sin_table() {
  std::array<int32_t, kTrigSteps + 1> t{};
  constexpr double kHalfPi = 1.57079632679489661923;
  for (int i = 0; i <= kTrigSteps; ++i) {
    double s = ct_sin(kHalfPi * i / kTrigSteps);
    // Positive table values: adding 0.5 and truncating is round-half-up, as intended.
    // NOLINTNEXTLINE(bugprone-incorrect-roundings)
    t[static_cast<size_t>(i)] = static_cast<int32_t>(s * (1 << 30) + 0.5);
  }
  return t;
}

inline constexpr std::array<int32_t, kTrigSteps + 1> kSinTable = make_sin_table();

}  // namespace detail
}  // namespace lr
