#include "lineraster/core/math/wide_divide.hpp"

namespace lr {

Quotient32 detail::divide_64by32_call(uint64_t n, uint32_t d) {
  return divide_64by32_2by1(n, d);
}

uint64_t reciprocal64(uint64_t d) {
  constexpr uint64_t kAll = ~uint64_t{0};
  if ((d >> 32) == 0) {
    // Schoolbook, two 32-bit digits: 2^32 - 1 < d 2^32, and the first remainder r < d makes
    // r 2^32 + 2^32 - 1 < d 2^32.
    const auto d32 = static_cast<uint32_t>(d);
    const Quotient32 hi = divide_64by32(kAll >> 32, d32);
    const Quotient32 lo = divide_64by32((uint64_t{hi.r} << 32) | (kAll >> 32), d32);
    return (uint64_t{hi.q} << 32) | lo.q;
  }
  // d >= 2^32, the quotient below 2^32 (Warren, Hacker's Delight 9-5, divDu): the top 32 bits
  // of d normalised, v in [2^31, 2^32), divide (2^64 - 1) / 2 (< v 2^32); the estimate q, at
  // most one above the quotient after the decrement and at most one below it, is corrected by
  // the exact remainder (2^64 - 1) - q d.
  const int s = clz64(d);  // 0..31
  const auto v = static_cast<uint32_t>((d << s) >> 32);
  uint64_t q = (uint64_t{divide_64by32(kAll >> 1, v).q} << s) >> 31;
  if (q != 0) --q;
  if (kAll - q * d >= d) ++q;
  return q;
}

}  // namespace lr
