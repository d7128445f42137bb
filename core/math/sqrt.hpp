// Integer square roots used by vector normalisation and the camera.
#pragma once

#include <cstdint>

namespace lr {

// floor(sqrt(v)) for any uint64, exact (digit-by-digit, 32 iterations, no division).
constexpr uint32_t isqrt64(uint64_t v) {
  uint64_t rem = v, root = 0;
  uint64_t bit = uint64_t{1} << 62;
  while (bit > rem) bit >>= 2;
  while (bit != 0) {
    if (rem >= root + bit) {
      rem -= root + bit;
      root = (root >> 1) + bit;
    } else {
      root >>= 1;
    }
    bit >>= 2;
  }
  return static_cast<uint32_t>(root);
}

}  // namespace lr
