#include "lineraster/core/math/trig.hpp"

#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/math/wide_divide.hpp"

namespace lr {
namespace {

constexpr int64_t kQuarterTurn = int64_t{90} << Fixed::kFracBits;  // 90 degrees, Q16.16

// sin of an angle in [0, 90] degrees given in Q16.16 (as int64), returned in Q16.16.
int32_t sin_quadrant(int64_t a) {
  // Position in table steps with 16 fractional bits: a * kTrigSteps / 90deg. a in [0, 90deg]:
  // the numerator is below 2^47 and the quotient at most kTrigSteps 2^16, one 64-by-32 division.
  const int64_t pos = divide_64by32(static_cast<uint64_t>(a) * detail::kTrigSteps * Fixed::kOne,
                                    static_cast<uint32_t>(kQuarterTurn))
                          .q;
  auto i = static_cast<size_t>(pos >> Fixed::kFracBits);
  int64_t frac = pos & (Fixed::kOne - 1);
  int64_t s0 = detail::kSinTable[i];
  int64_t s1 = i + 1 <= static_cast<size_t>(detail::kTrigSteps) ? detail::kSinTable[i + 1] : s0;
  int64_t s = s0 + (((s1 - s0) * frac) >> Fixed::kFracBits);  // Q1.30
  return static_cast<int32_t>(round_shift(s, 30 - Fixed::kFracBits));
}

}  // namespace

Fixed sin_deg(Fixed degrees) {
  constexpr int64_t kFullTurn = 4 * kQuarterTurn;
  int64_t a = degrees.raw % static_cast<int32_t>(kFullTurn);  // 360deg < 2^31: in 32 bits
  if (a < 0) a += kFullTurn;
  int32_t sign = 1;
  if (a >= 2 * kQuarterTurn) {  // sin(a) = -sin(a - 180)
    a -= 2 * kQuarterTurn;
    sign = -1;
  }
  if (a > kQuarterTurn) a = 2 * kQuarterTurn - a;  // sin(a) = sin(180 - a)
  return Fixed::from_raw(sign * sin_quadrant(a));
}

Fixed cos_deg(Fixed degrees) {
  return sin_deg(degrees + Fixed::from_int(90));
}

namespace {

// a b 2^-30 rounded, a and b Q2.30 below 2^31 in magnitude: the product below 2^62.
int64_t mul30(int64_t a, int64_t b) {
  return shift_rounded(a * b, 30);
}

// sin and cos of x radians, x in [0, pi/4] in Q2.30: Horner in x^2 (below 0.62, so every
// partial sum of the series stays below 1 in magnitude: all values below 2^31).
SinCos30 sin_cos_octant(int64_t x) {
  const int64_t x2 = mul30(x, x);
  int64_t p = detail::kSinCoefficients[4];
  for (int k = 3; k >= 0; --k) p = detail::kSinCoefficients[static_cast<size_t>(k)] + mul30(x2, p);
  const int64_t s = x + mul30(x, mul30(x2, p));
  int64_t q = detail::kCosCoefficients[5];
  for (int k = 4; k >= 0; --k) q = detail::kCosCoefficients[static_cast<size_t>(k)] + mul30(x2, q);
  const int64_t c = (int64_t{1} << 30) + mul30(x2, q);
  return {static_cast<int32_t>(s), static_cast<int32_t>(c)};
}

}  // namespace

SinCos30 sin_cos_q30(Fixed degrees) {
  // The angle in [0, 360) degrees (Q16.16, exact), its quadrant and the angle r in [0, 90).
  int32_t a = degrees.raw % static_cast<int32_t>(4 * kQuarterTurn);
  if (a < 0) a += static_cast<int32_t>(4 * kQuarterTurn);
  int quadrant = 0;
  while (a >= kQuarterTurn) {
    a -= static_cast<int32_t>(kQuarterTurn);
    ++quadrant;
  }
  // Above 45 degrees, the complement: sin r = cos(90 - r). r' in [0, 45] degrees is below 2^22
  // (Q16.16); times pi / 180 in Q0.44 (below 2^39) it is below 2^61, in Q2.30 after the shift.
  const bool upper = a > kQuarterTurn / 2;
  const int64_t r = upper ? kQuarterTurn - a : a;
  constexpr int64_t kRadiansPerDegreeQ44 = 307041569098;  // round(pi / 180 2^44)
  const SinCos30 o = sin_cos_octant(shift_rounded(r * kRadiansPerDegreeQ44, 30));
  const int32_t s = upper ? o.cos : o.sin, c = upper ? o.sin : o.cos;
  switch (quadrant) {
    case 0:
      return {s, c};
    case 1:
      return {c, -s};
    case 2:
      return {-s, -c};
    default:
      return {-c, s};
  }
}

}  // namespace lr
