// Filling a strip buffer with one value (the background, the cleared depth): an empty strip costs
// nothing else, and every strip is cleared, so this is the frame's fixed cost. On Thumb-2 cores
// the 16- and 32-bit pixels are stored a word at a time by hand: two STMs of eight registers a
// loop, 64 bytes in four instructions, where newlib's memset stores about 8 bytes an instruction
// and the memcpy doubling below about 3 (a 320 x 8 RGB565 strip and its depth: about 2,400
// instructions by the C library, about 650 by hand); on Armv6-M two STMs of four registers.
// Elsewhere, and for other pixel sizes: memset when every byte of the value is the same (black,
// white, a cleared 16-bit depth of 0xFFFF), else copies that double what is already filled.
// firmware/span_check checks that both ways store the same bytes (fill_check.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace lr {

// The portable way: the C library's memset or memcpy.
template <class T>
void fill_pixels_c(T* p, size_t n, const T& value) {
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

#if defined(__thumb__) && !defined(__OPTIMIZE_SIZE__) && \
    (defined(__thumb2__) || __ARM_ARCH_ISA_THUMB == 1)
#define LR_FILL_BY_HAND 1
// n words of w from p (word-aligned): a loop of two STMs by hand (eight registers each on
// Thumb-2, 64 bytes a loop; four on Armv6-M, whose STM takes only r0-r7: 32 bytes a loop), then
// the rest one word at a time. The stores go through the asm (a "memory" clobber), so no C object
// is written as another type.
inline void fill_words_by_hand(void* p, size_t n, uint32_t w) {
  register void* d asm("r0") = p;
  register uint32_t a asm("r2") = w, b asm("r3") = w, c asm("r4") = w, e asm("r5") = w;
#ifdef __thumb2__
  constexpr size_t kLoopWords = 16;
  register size_t loops asm("r1") = n / kLoopWords;
  size_t rest = n % kLoopWords;
  register uint32_t f asm("r6") = w, g asm("r8") = w, h asm("r10") = w, k asm("r12") = w;
  asm volatile(
      "cbz     %[loops], 2f\n\t"
      "1:\n\t"
      "stmia   %[d]!, {r2, r3, r4, r5, r6, r8, r10, r12}\n\t"
      "stmia   %[d]!, {r2, r3, r4, r5, r6, r8, r10, r12}\n\t"
      "subs    %[loops], %[loops], #1\n\t"
      "bne     1b\n\t"
      "2:\n\t"
      "cmp     %[rest], #0\n\t"
      "beq     4f\n\t"
      "3:\n\t"
      "stmia   %[d]!, {r2}\n\t"
      "subs    %[rest], %[rest], #1\n\t"
      "bne     3b\n\t"
      "4:\n\t"
      : [d] "+r"(d), [loops] "+r"(loops), [rest] "+r"(rest)
      : "r"(a), "r"(b), "r"(c), "r"(e), "r"(f), "r"(g), "r"(h), "r"(k)
      : "memory", "cc");
#else
  constexpr size_t kLoopWords = 8;
  register size_t loops asm("r1") = n / kLoopWords;
  size_t rest = n % kLoopWords;
  asm volatile(
      ".syntax unified\n\t"  // (GCC passes Armv6-M asm in divided syntax and expects it back)
      "cmp     %[loops], #0\n\t"
      "beq     2f\n\t"
      "1:\n\t"
      "stmia   %[d]!, {r2, r3, r4, r5}\n\t"
      "stmia   %[d]!, {r2, r3, r4, r5}\n\t"
      "subs    %[loops], %[loops], #1\n\t"
      "bne     1b\n\t"
      "2:\n\t"
      "cmp     %[rest], #0\n\t"
      "beq     4f\n\t"
      "3:\n\t"
      "stmia   %[d]!, {r2}\n\t"
      "subs    %[rest], %[rest], #1\n\t"
      "bne     3b\n\t"
      "4:\n\t"
      ".syntax divided\n\t"
      : [d] "+l"(d), [loops] "+l"(loops), [rest] "+l"(rest)
      : "l"(a), "l"(b), "l"(c), "l"(e)
      : "memory", "cc");
#endif
}

// fill_pixels by hand: 2- and 4-byte pixels (an odd 16-bit pixel at either end alone).
template <class T>
void fill_pixels_by_hand(T* p, size_t n, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  if constexpr (sizeof(T) != 2 && sizeof(T) != 4) {
    fill_pixels_c(p, n, value);
  } else {
    if (n == 0) return;
    if ((reinterpret_cast<uintptr_t>(p) & (sizeof(T) - 1)) != 0) {
      fill_pixels_c(p, n, value);  // (not even aligned to its own size: no word stores)
      return;
    }
    if (sizeof(T) == 2 && (reinterpret_cast<uintptr_t>(p) & 2) != 0) {
      *p++ = value;
      --n;
    }
    uint32_t w;
    if constexpr (sizeof(T) == 2) {
      std::memcpy(&w, &value, 2);
      std::memcpy(reinterpret_cast<unsigned char*>(&w) + 2, &value, 2);
    } else {
      std::memcpy(&w, &value, 4);
    }
    const size_t words = n * sizeof(T) / 4;
    fill_words_by_hand(p, words, w);
    if (sizeof(T) == 2 && (n & 1) != 0) p[n - 1] = value;
  }
}
#endif

// Fills n pixels from p with value.
template <class T>
void fill_pixels(T* p, size_t n, const T& value) {
#ifdef LR_FILL_BY_HAND
  fill_pixels_by_hand(p, n, value);
#else
  fill_pixels_c(p, n, value);
#endif
}

}  // namespace lr
