// 64-bit divisions in 32-bit pieces, exact (the same integers as C's division): where the
// quotient fits 32 bits, one 2-by-1 division by a normalised reciprocal (reciprocal.hpp), so
// that the renderer links no C library 64-bit division (on 32-bit Arm __aeabi_ldivmod,
// __aeabi_uldivmod and __udivmoddi4: 0.9 KB of flash at -Os).
//
//   divide_64by32(n, d)  floor(n / d) and n mod d for d > 0 and n < d 2^32 (quotient < 2^32)
//   reciprocal64(d)      floor((2^64 - 1) / d) for d > 0 (any quotient: two or one of the above)
#pragma once

#include <cstdint>
#include <type_traits>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/reciprocal.hpp"

namespace lr {

constexpr Quotient32 divide_64by32(uint64_t n, uint32_t d);
uint64_t reciprocal64(uint64_t d);

// ---- Implementation --------------------------------------------------------------------------

namespace detail {

// The 2-by-1 division of n 2^s by d 2^s (d 2^s in [2^31, 2^32)): the same quotient, the
// remainder 2^s times n mod d; n < d 2^32 keeps n 2^s below 2^64 and the quotient below 2^32.
// recip32_newton on every core, so that the host's tests check the Arm path's integers.
[[gnu::always_inline]] constexpr Quotient32 divide_64by32_2by1(uint64_t n, uint32_t d) {
  const int s = clz32(d);
  const uint32_t dn = d << s;
  const Quotient32 qr = divide_2by1(n << s, dn, recip32_newton(dn));
  return {qr.q, qr.r >> s};
}

// One out-of-line copy (wide_divide.cpp) for the callers on 32-bit Arm.
Quotient32 divide_64by32_call(uint64_t n, uint32_t d);

}  // namespace detail

constexpr Quotient32 divide_64by32(uint64_t n, uint32_t d) {
#if defined(__arm__)
  if (!std::is_constant_evaluated()) return detail::divide_64by32_call(n, d);
#endif
  return {static_cast<uint32_t>(n / d), static_cast<uint32_t>(n % d)};
}

}  // namespace lr
