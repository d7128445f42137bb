// Reciprocals of normalised divisors, exact and therefore identical on every core: where the
// core divides in hardware (or on a host) they are one division; on cores without a 32-bit
// divider (Armv6-M) they come from a 256-entry seed table, one Newton step and an exact
// remainder correction. Derivation and bounds: docs/numerics.md#normalised-reciprocals.
//
//   recip16(d)  d in [2^15, 2^16): floor((2^32 - 1) / d), in (2^16, 2^17]
//   recip32(d)  d in [2^31, 2^32): floor((2^64 - 1) / d) - 2^32, in [0, 2^32) (the "inverse
//               limb" of a 2-by-1 division)
//   divide_2by1(n, d, recip32(d))  floor(n / d) and its remainder for n < d 2^32: two multiplies
//               and at most two corrections instead of a 64-bit division
//   divide_small(n, small_divisor(d, j))  floor(n / d) for d in [2^14, 2^24], n <= 2^31 and
//               n < 2^15 d (the textured span's per-pixel division): one recip16 shared by the
//               divisions of a pixel, then a 32-bit multiply and a few corrections each
//   recip_q61(d)  d in [2^31, 2^32): 2^61 / d within 2 units (relative 2^-28), in
//               (2^29 - 2, 2^30 + 2): not exact, but the same integers on every core (one
//               recip16 and one Newton step in high-word products): the vertex stage's 1 / w
#pragma once

#include <array>
#include <cstdint>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/wide_mul.hpp"

namespace lr {

constexpr uint32_t recip16(uint32_t d);
constexpr uint32_t recip32(uint32_t d);

struct Quotient32 {
  uint32_t q;  // floor(n / d)
  uint32_t r;  // n - q d, in [0, d)
};
constexpr Quotient32 divide_2by1(uint64_t n, uint32_t d, uint32_t v);
constexpr uint32_t recip_q61(uint32_t d);

// A divisor in [2^14, 2^24] prepared for divide_small: on cores with a divider just d.
struct SmallDivisor {
  uint32_t d;  // the divisor
  uint32_t v;  // floor((2^32 - 1) / dn), dn = floor(d / 2^j) 2^k in [2^15, 2^16]
  int j;       // the caller's shift: floor(d / 2^j) in [2^14, 2^16]
  int k;       // 1 when floor(d / 2^j) < 2^15, else 0
};
// j: a shift with floor(d / 2^j) in [2^14, 2^16], known to the caller for a run of divisors
// (the span's chunk).
constexpr SmallDivisor small_divisor(uint32_t d, int j);
constexpr uint32_t divide_small(uint32_t n, const SmallDivisor& s);

// ---- Implementation --------------------------------------------------------------------------

namespace detail {

// Seed i: 2^32 / (the middle of the divisors with top bits 256 + i), relative error < 2^-9.
consteval std::array<uint32_t, 256> make_recip_seeds() {
  std::array<uint32_t, 256> s{};
  for (uint32_t i = 0; i < 256; ++i) {
    const uint64_t mid = (uint64_t{256 + i} << 7) + 64;
    s[i] = static_cast<uint32_t>((uint64_t{1} << 32) / mid);
  }
  return s;
}
inline constexpr std::array<uint32_t, 256> kRecipSeeds = make_recip_seeds();

// The table path of recip16, on every core (tests compare it with the division for every d).
constexpr uint32_t recip16_table(uint32_t d) {
  uint32_t x = kRecipSeeds[(d >> 7) - 256];
  // e = 2^32 - d x in (-2^23, 2^23): wrapping arithmetic gives it exactly. The Newton step
  // x + x e / 2^32 in 32-bit products of shortened factors (|x / 4 * e / 512| < 2^30).
  const auto e = static_cast<int32_t>(0u - d * x);
  x = static_cast<uint32_t>(static_cast<int32_t>(x) +
                            ((static_cast<int32_t>(x >> 2) * (e >> 9)) >> 21));
  // x is now within a few units of the quotient: the remainder (2^32 - 1) - d x is small, and
  // exact in wrapping 32-bit arithmetic.
  auto rem = static_cast<int32_t>(0xFFFFFFFFu - d * x);
  while (rem < 0) {
    --x;
    rem += static_cast<int32_t>(d);
  }
  while (rem >= static_cast<int32_t>(d)) {
    ++x;
    rem -= static_cast<int32_t>(d);
  }
  return x;
}

// recip32 from recip16 of the divisor's top half: one Newton step in 64-bit products, then an
// exact correction (tests compare it with the 64-bit division). A call where the code is built
// for size (one copy, not one per caller).
LR_SIZE_NOINLINE constexpr uint32_t recip32_newton(uint32_t d) {
  // X0 = 2^48 / (d >> 16) within 2^-15 of 2^64 / d (relative), below 2^33 + 2^16.
  uint64_t x = uint64_t{recip16(d >> 16)} << 16;
  // E = 2^64 - d X0, |E| < 2^50, exact in wrapping 64-bit arithmetic; X0 / 2 * E / 2^19 < 2^63.
  const auto e = static_cast<int64_t>(uint64_t{0} - uint64_t{d} * x);
  x = static_cast<uint64_t>(static_cast<int64_t>(x) +
                            ((static_cast<int64_t>(x >> 1) * (e >> 19)) >> 44));
  auto rem = static_cast<int64_t>(~uint64_t{0} - uint64_t{d} * x);
  while (rem < 0) {
    --x;
    rem += d;
  }
  while (rem >= static_cast<int64_t>(d)) {
    ++x;
    rem -= d;
  }
  return static_cast<uint32_t>(x - (uint64_t{1} << 32));
}

constexpr SmallDivisor small_divisor_table(uint32_t d, int j) {
  const uint32_t dh = d >> j;
  if (dh == (1u << 16)) return {d, 0xFFFFu, j, 0};
  const int k = dh < (1u << 15) ? 1 : 0;
  return {d, recip16_table(dh << k), j, k};
}

// With n' = floor(n / 2^j) 2^k < 2^31 and a = n' / 2^16 < 2^15: a v < 2^32, and the estimate
// a v / 2^16 is within a few units of floor(n / d) (docs/numerics.md#normalised-reciprocals);
// the exact remainder n - q d, signed (|n - q d| < 2^31), corrects it.
constexpr uint32_t divide_small_table(uint32_t n, const SmallDivisor& s) {
  const uint32_t nn = (n >> s.j) << s.k;
  uint32_t q = ((nn >> 16) * s.v) >> 16;
  uint32_t r = n - q * s.d;
  while (static_cast<int32_t>(r) < 0) {
    --q;
    r += s.d;
  }
  while (r >= s.d) {
    ++q;
    r -= s.d;
  }
  return q;
}

}  // namespace detail

constexpr SmallDivisor small_divisor(uint32_t d, [[maybe_unused]] int j) {
#if defined(__arm__) && !defined(__ARM_FEATURE_IDIV)
  return detail::small_divisor_table(d, j);
#else
  return {d, 0, 0, 0};
#endif
}

constexpr uint32_t divide_small(uint32_t n, const SmallDivisor& s) {
#if defined(__arm__) && !defined(__ARM_FEATURE_IDIV)
  return detail::divide_small_table(n, s);
#else
  return n / s.d;
#endif
}

constexpr uint32_t recip16(uint32_t d) {
#if defined(__arm__) && !defined(__ARM_FEATURE_IDIV)
  return detail::recip16_table(d);
#else
  return 0xFFFFFFFFu / d;
#endif
}

constexpr uint32_t recip32(uint32_t d) {
#if defined(__arm__)
  return detail::recip32_newton(d);
#else
  return static_cast<uint32_t>(~uint64_t{0} / d - (uint64_t{1} << 32));
#endif
}

constexpr Quotient32 divide_2by1(uint64_t n, uint32_t d, uint32_t v) {
  const auto n1 = static_cast<uint32_t>(n >> 32), n0 = static_cast<uint32_t>(n);
  // q = v n1 + (n1 + 1) 2^32 + n0, its high word the candidate quotient (at most one too
  // large or one too small; Moeller and Granlund 2011, the 2-by-1 division).
  const uint64_t p = uint64_t{v} * n1 + ((uint64_t{n1} + 1) << 32) + n0;
  auto q1 = static_cast<uint32_t>(p >> 32);
  const auto q0 = static_cast<uint32_t>(p);
  uint32_t r = n0 - q1 * d;
  if (r > q0) {
    --q1;
    r += d;
  }
  if (r >= d) {
    ++q1;
    r -= d;
  }
  return {q1, r};
}

namespace detail {

// recip_q61 in 32-bit products for cores without a 64-bit one, the same integer. With
// r = recip16(dh) (dh = d / 2^16, dl = d mod 2^16; r = 2^16 rh + rl, rh in {1, 2}) and
// x0 = r 2^13: floor(d x0 / 2^32) = floor((dh r + floor(dl r / 2^16)) / 8), where dh r <= 2^32 - 1
// (r's definition), floor(dl r / 2^16) = dl rh + floor(dl rl / 2^16), and the sum may carry; and
// floor(x0 8 eh / 2^32) = floor(r eh / 2^16) = rh eh + floor(rl eh / 2^16) (|rl eh| < 2^31).
constexpr uint32_t recip_q61_split(uint32_t d) {
  const uint32_t dh = d >> 16, dl = d & 0xFFFFu;
  const uint32_t r = recip16(dh);
  const uint32_t rh = r >> 16, rl = r & 0xFFFFu;
  const uint32_t dlr = dl * rh + ((dl * rl) >> 16);  // floor(dl r / 2^16) < 2^17
  // dh r + dlr may pass 2^32 (it is about 2^32 (1 + eps)): its carry is bit 29 of the result.
  const uint32_t sum = dh * r + dlr;
  const uint32_t hi = (sum >> 3) | (sum < dlr ? 1u << 29 : 0u);  // floor(d x0 / 2^32)
  const auto eh = static_cast<int32_t>((1u << 29) - hi);
  const int32_t corr = static_cast<int32_t>(rh) * eh + ((static_cast<int32_t>(rl) * eh) >> 16);
  return (r << 13) + static_cast<uint32_t>(corr);
}

}  // namespace detail

// y = 2^61 / d. x0 = recip16(d / 2^16) 2^13 = y (1 + eps) with eps in (-2^-16, 2^-15]: d / 2^16
// is d's top half (at most 2^-15 below d / 2^16) and recip16 floors (by less than 2^-16). The
// Newton step x0 + x0 e / 2^61 with e = 2^61 - d x0 gives y (1 - eps^2), within one unit of y.
// Here e is taken in units of 2^32: eh = 2^29 - floor(d x0 / 2^32) = ceil(e / 2^32), |eh| <= 2^14 +
// 1, so x0 eh / 2^29 exceeds x0 e / 2^61 by less than x0 / 2^29 <= 2 units, and the product's floor
// takes at most one: x1 is in [y - 2, y + 2) (docs/numerics.md#projection-and-snapping;
// tests/core/math_test.cpp checks it).
constexpr uint32_t recip_q61(uint32_t d) {
  if constexpr (kSplitWideProducts) return detail::recip_q61_split(d);
  const uint32_t x0 = recip16(d >> 16) << 13;
  const auto eh = static_cast<int32_t>((1u << 29) - mul_hi_u(d, x0));
  return static_cast<uint32_t>(static_cast<int32_t>(x0) + mul_hi(static_cast<int32_t>(x0), eh * 8));
}

}  // namespace lr
