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

// Sine and cosine in Q1.30 (in [-2^30, 2^30]), within a few units of 2^-30 of the exact values
// (docs/numerics.md#sine-and-cosine): the angle reduced exactly to [0, 45] degrees, turned into
// radians in Q2.30 and the Taylor polynomials to x^11 and x^12 evaluated in Q2.30 (the terms
// left out are below 2^-31 there; every product of two Q2.30 values below 2^31 is below 2^62).
// For the matrices of fine transforms (rotate_x_fine ..., perspective_fine).
struct SinCos30 {
  int32_t sin, cos;
};
SinCos30 sin_cos_q30(Fixed degrees);

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

// The Taylor coefficients of sin (x^3 ... x^11) and cos (x^2 ... x^12) in Q1.30, rounded.
consteval int32_t q30(double v) {
  const double s = v * (1 << 30);
  return static_cast<int32_t>(s < 0 ? s - 0.5 : s + 0.5);
}
consteval std::array<int32_t, 5> make_sin_coefficients() {
  std::array<int32_t, 5> c{};
  double f = 1.0;
  for (int k = 1; k <= 5; ++k) {
    f *= -1.0 / ((2.0 * k) * (2.0 * k + 1.0));  // (-1)^k / (2k + 1)!
    c[static_cast<size_t>(k - 1)] = q30(f);
  }
  return c;
}
consteval std::array<int32_t, 6> make_cos_coefficients() {
  std::array<int32_t, 6> c{};
  double f = 1.0;
  for (int k = 1; k <= 6; ++k) {
    f *= -1.0 / ((2.0 * k - 1.0) * (2.0 * k));  // (-1)^k / (2k)!
    c[static_cast<size_t>(k - 1)] = q30(f);
  }
  return c;
}
inline constexpr std::array<int32_t, 5> kSinCoefficients = make_sin_coefficients();
inline constexpr std::array<int32_t, 6> kCosCoefficients = make_cos_coefficients();

}  // namespace detail
}  // namespace lr
