// Filling a strip buffer with one value (the background, the cleared depth): the cheapest way the
// C library offers, since an empty strip costs nothing else. memset when every byte of the value
// is the same (black, white, a cleared 16-bit depth of 0xFFFF), else copies that double what is
// already filled (memcpy moves a word or more per instruction, a loop of 16-bit stores one
// pixel).
#pragma once

#include <cstddef>
#include <cstring>
#include <type_traits>

namespace lr {

template <class T>
void fill_pixels(T* p, size_t n, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (n == 0) return;
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  bool same = true;
  for (size_t i = 1; i < sizeof(T); ++i) same = same && bytes[i] == bytes[0];
  if (same) {
    std::memset(static_cast<void*>(p), bytes[0], n * sizeof(T));
    return;
  }
  p[0] = value;
  for (size_t done = 1; done < n;) {
    const size_t c = done < n - done ? done : n - done;
    std::memcpy(static_cast<void*>(p + done), static_cast<const void*>(p), c * sizeof(T));
    done += c;
  }
}

}  // namespace lr
