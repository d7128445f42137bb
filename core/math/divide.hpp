// Exact integer division by one divisor many times: one reciprocal, then a multiply-high and a
// remainder correction per quotient, instead of a 64-bit division each (a library call on
// 32-bit Arm).
#pragma once

#include <cstdint>

namespace lr {

// High 64 bits of a 64 x 64-bit product: one instruction where the compiler has a 128-bit type
// (x86-64, AArch64), else from 32-bit halves (32-bit Arm). The same exact value either way.
constexpr uint64_t mul_hi(uint64_t a, uint64_t b) {
#if defined(__SIZEOF_INT128__)
  return static_cast<uint64_t>((static_cast<unsigned __int128>(a) * b) >> 64);
#else
  const uint64_t al = static_cast<uint32_t>(a), ah = a >> 32;
  const uint64_t bl = static_cast<uint32_t>(b), bh = b >> 32;
  const uint64_t ll = al * bl, lh = al * bh, hl = ah * bl, hh = ah * bh;
  const uint64_t mid = (ll >> 32) + static_cast<uint32_t>(lh) + static_cast<uint32_t>(hl);
  return hh + (lh >> 32) + (hl >> 32) + (mid >> 32);
#endif
}

// floor(n / d) for a fixed d > 0 and any n < 2^63, bit for bit the quotient of a division
// (at most two corrections: docs/numerics.md#one-division-many-quotients).
class Divider {
 public:
  constexpr explicit Divider(uint64_t d) : d_(d), inv_(~uint64_t{0} / d) {}
  constexpr uint64_t quotient(uint64_t n) const {
    uint64_t q = mul_hi(n, inv_);
    uint64_t r = n - q * d_;
    while (r >= d_) {  // at most twice
      ++q;
      r -= d_;
    }
    return q;
  }
  constexpr uint64_t divisor() const { return d_; }
  constexpr uint64_t reciprocal() const { return inv_; }

 private:
  uint64_t d_, inv_;
};

}  // namespace lr
