#include "lineraster/core/math/trig.hpp"

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

}  // namespace lr
