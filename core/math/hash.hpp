// Hashes: FNV-1a (Fowler-Noll-Vo) in 32 and 64 bits, and the word mixer of the strip input
// signatures.
//
// FNV-1a folds one value into the hash as h = (h ^ v) * prime, from a fixed offset basis. The
// reference folds bytes; the strip signatures fold 16- and 32-bit words the same way. For a
// given v the step is a bijection of h (the prime is odd), and for a given h one of v, so two
// sequences that differ in one value always hash differently. Integer arithmetic only: the
// same values on every CPU.
#pragma once

#include <cstdint>

namespace lr {

inline constexpr uint32_t kFnv1a32Offset = 2166136261u;
inline constexpr uint32_t kFnv1a32Prime = 16777619u;
inline constexpr uint64_t kFnv1a64Offset = 0xcbf29ce484222325u;
inline constexpr uint64_t kFnv1a64Prime = 0x100000001b3u;

// One FNV-1a step.
constexpr uint32_t fnv1a32(uint32_t h, uint32_t v) {
  return (h ^ v) * kFnv1a32Prime;
}
constexpr uint64_t fnv1a64(uint64_t h, uint64_t v) {
  return (h ^ v) * kFnv1a64Prime;
}

// FNV-1a of a byte sequence, byte by byte.
struct Fnv1a32 {
  uint32_t value = kFnv1a32Offset;
  constexpr void add(uint8_t byte) { value = fnv1a32(value, byte); }
};
struct Fnv1a64 {
  uint64_t value = kFnv1a64Offset;
  constexpr void add(uint8_t byte) { value = fnv1a64(value, byte); }
};

// An FNV-1a step on a 32-bit word followed by h ^= h >> 13, which brings the high bits (where
// the multiply carries a word's changes) down into the low ones; also a bijection of h.
constexpr uint32_t mix_word(uint32_t h, uint32_t v) {
  const uint32_t x = fnv1a32(h, v);
  return x ^ (x >> 13);
}

}  // namespace lr
