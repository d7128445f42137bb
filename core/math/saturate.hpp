// Saturating a (shifted) value into a bit range: one USAT or SSAT on cores with the saturation
// instructions (Armv7-M and Armv7E-M, __ARM_FEATURE_SAT), the portable clamp elsewhere. GCC finds
// USAT in the portable form only sometimes (not when it has hoisted the bound into a register).
#pragma once

#include <cstdint>
#include <type_traits>

namespace lr {

// (v >> kShift) (arithmetic) clamped to [0, 2^kBits - 1].
template <int kBits, int kShift>
constexpr uint32_t usat_asr(int32_t v) {
  static_assert(kBits >= 1 && kBits <= 31 && kShift >= 1 && kShift <= 31);
#if defined(__ARM_FEATURE_SAT) && defined(__thumb2__)
  if (!std::is_constant_evaluated()) {
    uint32_t r;
    asm("usat %0, %1, %2, asr %3" : "=r"(r) : "I"(kBits), "r"(v), "I"(kShift));
    return r;
  }
#endif
  const int32_t x = v >> kShift;
  constexpr int32_t kMax = (int32_t{1} << kBits) - 1;
  return x < 0 ? 0u : x > kMax ? static_cast<uint32_t>(kMax) : static_cast<uint32_t>(x);
}

// v clamped to [-2^(kBits - 1), 2^(kBits - 1) - 1]: one SSAT where the core has it.
template <int kBits>
constexpr int32_t saturate_signed(int32_t v) {
  static_assert(kBits >= 1 && kBits <= 32);
#if defined(__ARM_FEATURE_SAT) && defined(__thumb2__)
  if (!std::is_constant_evaluated()) {
    int32_t r;
    asm("ssat %0, %1, %2" : "=r"(r) : "I"(kBits), "r"(v));
    return r;
  }
#endif
  constexpr int32_t kMax = static_cast<int32_t>((uint32_t{1} << (kBits - 1)) - 1);
  return v < -kMax - 1 ? -kMax - 1 : v > kMax ? kMax : v;
}

}  // namespace lr
