// Products wider than 32 bits, exact and therefore identical on every core. Where the core has a
// 32 x 32 -> 64 multiply (Armv7-M and later: SMULL, UMULL; hosts) they are one instruction;
// Armv6-M (Cortex-M0/M0+) has only MULS (the low 32 bits), and GCC calls libgcc's 64 x 64
// multiply for any int64 product there, so the high words are built from four 16 x 16 products
// instead (about 15 instructions, no call).
//
//   mul_hi(a, b)       floor(a b / 2^32), signed       (SMMUL where the core has it (the DSP
//                                                      extension), else the high word of SMULL)
//   mla_hi(a, b, acc)  acc + floor(a b / 2^32)         (SMMLA where the core has it (the DSP
//                                                      extension); wraps modulo 2^32 like it)
//   mul_hi_u(a, b)     floor(a b / 2^32), unsigned     (the high word of UMULL)
//   mul_wide(a, b)     a b as int64                    (SMULL)
//
// The split forms (detail::*_split) are plain C: the tests run them on the host against the
// 64-bit products for edge and random operands, which is what makes an Armv6-M frame equal to
// the others bit for bit.
#pragma once

#include <cstdint>
#include <type_traits>

namespace lr {

namespace detail {

// a = ah 2^16 + al, b = bh 2^16 + bl (al, bl in [0, 2^16), ah, bh in [-2^15, 2^15)):
// a b = ah bh 2^32 + (ah bl + al bh) 2^16 + al bl. With al bl = t 2^16 + u, x = ah bl + t
// (|ah bl| <= 2^31 - 2^16 - 2^15 + 1 and t < 2^16: no overflow) = xh 2^16 + xl, and
// y = xl + al bh = yh 2^16 + yl (also inside int32), a b = (ah bh + xh + yh) 2^32 + yl 2^16 + u
// with 0 <= yl 2^16 + u < 2^32: the high word is ah bh + xh + yh exactly.
constexpr int32_t mul_hi_split(int32_t a, int32_t b) {
  const int32_t ah = a >> 16, bh = b >> 16;
  const auto al = static_cast<int32_t>(static_cast<uint32_t>(a) & 0xFFFFu);
  const auto bl = static_cast<int32_t>(static_cast<uint32_t>(b) & 0xFFFFu);
  const uint32_t ll = static_cast<uint32_t>(al) * static_cast<uint32_t>(bl);
  const int32_t x = ah * bl + static_cast<int32_t>(ll >> 16);
  const int32_t y = (x & 0xFFFF) + al * bh;
  return ah * bh + (x >> 16) + (y >> 16);
}

// The same for unsigned operands: every partial product below 2^32, the carries counted.
constexpr uint32_t mul_hi_u_split(uint32_t a, uint32_t b) {
  const uint32_t ah = a >> 16, al = a & 0xFFFFu, bh = b >> 16, bl = b & 0xFFFFu;
  const uint32_t ll = al * bl, lh = al * bh, hl = ah * bl;
  // mid < 3 (2^16 - 1) + ... : (ll >> 16) + (lh & 0xFFFF) + (hl & 0xFFFF) < 3 * 2^16.
  const uint32_t mid = (ll >> 16) + (lh & 0xFFFFu) + (hl & 0xFFFFu);
  return ah * bh + (lh >> 16) + (hl >> 16) + (mid >> 16);
}

// a b as int64 from the high word and the low word (MULS gives the low word exactly).
constexpr int64_t mul_wide_split(int32_t a, int32_t b) {
  const uint32_t lo = static_cast<uint32_t>(a) * static_cast<uint32_t>(b);
  return static_cast<int64_t>(
      (static_cast<uint64_t>(static_cast<uint32_t>(mul_hi_split(a, b))) << 32) | lo);
}

}  // namespace detail

// An int32 as its halves, v = h 2^16 + l with l in [0, 2^16): what the split products use. A
// value that meets many products (a matrix entry, a reciprocal) is split once.
struct Halves {
  int32_t h;
  uint32_t l;
};
constexpr Halves halves(int32_t v) {
  return {v >> 16, static_cast<uint32_t>(v) & 0xFFFFu};
}
// mul_hi from split operands: detail::mul_hi_split's arithmetic, exact (the same integer).
constexpr int32_t mul_hi_halves(Halves a, Halves b) {
  const uint32_t ll = a.l * b.l;
  const int32_t x = a.h * static_cast<int32_t>(b.l) + static_cast<int32_t>(ll >> 16);
  const int32_t y = (x & 0xFFFF) + static_cast<int32_t>(a.l) * b.h;
  return a.h * b.h + (x >> 16) + (y >> 16);
}

#if defined(__ARM_ARCH_6M__)
inline constexpr bool kSplitWideProducts = true;
#else
inline constexpr bool kSplitWideProducts = false;
#endif

// On Armv7-M the products are written out as the instructions: GCC 12 keeps the sign words of
// 64-bit products it has hoisted and multiplies 64 x 64 in four instructions where one does.
constexpr int32_t mul_hi(int32_t a, int32_t b) {
  if constexpr (kSplitWideProducts) return detail::mul_hi_split(a, b);
#if defined(__thumb2__)
  if (!std::is_constant_evaluated()) {
    int32_t r;
#if defined(__ARM_FEATURE_DSP)
    asm("smmul %0, %1, %2" : "=r"(r) : "r"(a), "r"(b));
#else
    int32_t lo;
    asm("smull %0, %1, %2, %3" : "=r"(lo), "=r"(r) : "r"(a), "r"(b));
#endif
    return r;
  }
#endif
  return static_cast<int32_t>((int64_t{a} * b) >> 32);
}

constexpr int32_t mla_hi(int32_t a, int32_t b, int32_t acc) {
#if defined(__thumb2__) && defined(__ARM_FEATURE_DSP)
  if (!std::is_constant_evaluated()) {
    int32_t r;
    asm("smmla %0, %1, %2, %3" : "=r"(r) : "r"(a), "r"(b), "r"(acc));
    return r;
  }
#endif
  return static_cast<int32_t>(static_cast<uint32_t>(acc) + static_cast<uint32_t>(mul_hi(a, b)));
}

constexpr uint32_t mul_hi_u(uint32_t a, uint32_t b) {
  if constexpr (kSplitWideProducts) return detail::mul_hi_u_split(a, b);
#if defined(__thumb2__)
  if (!std::is_constant_evaluated()) {
    uint32_t lo, hi;
    asm("umull %0, %1, %2, %3" : "=r"(lo), "=r"(hi) : "r"(a), "r"(b));
    return hi;
  }
#endif
  return static_cast<uint32_t>((uint64_t{a} * b) >> 32);
}

constexpr int64_t mul_wide(int32_t a, int32_t b) {
  if constexpr (kSplitWideProducts) return detail::mul_wide_split(a, b);
  return int64_t{a} * b;
}

}  // namespace lr
