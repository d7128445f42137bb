// The strip clear by hand (core/raster/strip_fill.hpp: word stores, two STMs a loop) against its
// portable form (memset, or memcpy doubling) for 16- and 32-bit pixels: every count from 0 to
// 700, every start address within a word, values whose bytes are equal and not, with guard
// bytes before and after that must stay untouched. Returns the number of cases that differ.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <initializer_list>

#include "lineraster/core/raster/strip_fill.hpp"

namespace lr::fw::fill {

#ifdef LR_FILL_BY_HAND
constexpr bool kFillByHand = true;

struct Result {
  uint32_t cases = 0;
  uint32_t differing = 0;
};

template <class T>
void check(Result& r, T value) {
  constexpr size_t kMax = 700;
  alignas(4) static unsigned char a[(kMax + 8) * sizeof(T)], b[sizeof a];
  for (size_t offset = 0; offset < 4; offset += alignof(T) < 2 ? 1 : alignof(T)) {
    for (size_t n = 0; n <= kMax; ++n) {
      std::memset(a, 0xA5, sizeof a);
      std::memset(b, 0xA5, sizeof b);
      // (the pixel buffers of the core are arrays of T: the stores go through T pointers)
      T* pa = reinterpret_cast<T*>(a + sizeof(T) + offset);
      T* pb = reinterpret_cast<T*>(b + sizeof(T) + offset);
      fill_pixels_by_hand(pa, n, value);
      fill_pixels_c(pb, n, value);
      ++r.cases;
      if (std::memcmp(a, b, sizeof a) != 0) ++r.differing;
    }
  }
}

inline Result run() {
  Result r;
  for (uint16_t v : {uint16_t{0xFFFF}, uint16_t{0x1234}, uint16_t{0x0000}, uint16_t{0xF81F}})
    check<uint16_t>(r, v);
  for (uint32_t v : {0xFFFFFFFFu, 0x00123456u, 0x80808080u}) check<uint32_t>(r, v);
  return r;
}
#else
constexpr bool kFillByHand = false;
struct Result {
  uint32_t cases = 0;
  uint32_t differing = 0;
};
inline Result run() {
  return {};
}
#endif

}  // namespace lr::fw::fill
