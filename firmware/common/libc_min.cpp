// The C library functions that compiled code calls without asking: memcpy, memmove, memset,
// memcmp (GCC emits them for struct copies, zeroing, std::fill of a byte pattern,
// std::string_view comparison) and strlen (std::string_view from a C string, when not folded at
// compile time, e.g. at -O0). The firmware links no C library (-nostdlib): this is
// all of it, so that nothing can pull in malloc, stdio or the C library's startup.
//
// Built with -fno-tree-loop-distribute-patterns -fno-builtin (see firmware/CMakeLists.txt):
// otherwise GCC recognises these loops and turns them into calls to themselves.
#include <cstddef>
#include <cstdint>

namespace {

constexpr std::uintptr_t kWordMask = sizeof(std::uint32_t) - 1;

bool word_aligned(const void* p) {
  return (reinterpret_cast<std::uintptr_t>(p) & kWordMask) == 0;
}

}  // namespace

extern "C" {

void* memcpy(void* __restrict dst, const void* __restrict src, std::size_t n) {
  auto* d = static_cast<unsigned char*>(dst);
  const auto* s = static_cast<const unsigned char*>(src);
  if (word_aligned(d) && word_aligned(s)) {
    // May alias anything: memcpy's words are not objects of type uint32_t.
    using Word [[gnu::may_alias]] = std::uint32_t;
    auto* dw = reinterpret_cast<Word*>(d);
    const auto* sw = reinterpret_cast<const Word*>(s);
#if defined(__arm__)
    // Strip clears of a background whose bytes differ copy what is filled: 32 bytes per two
    // LDM/STM pairs of four low registers (all that Armv6-M has for them).
    for (; n >= 32; n -= 32) {
      asm volatile(
          "ldmia %1!, {r2, r3, r4, r5}\n\tstmia %0!, {r2, r3, r4, r5}\n\t"
          "ldmia %1!, {r2, r3, r4, r5}\n\tstmia %0!, {r2, r3, r4, r5}"
          : "+l"(dw), "+l"(sw)
          :
          : "r2", "r3", "r4", "r5", "memory");
    }
#endif
    for (; n >= 16; n -= 16) {
      dw[0] = sw[0];
      dw[1] = sw[1];
      dw[2] = sw[2];
      dw[3] = sw[3];
      dw += 4;
      sw += 4;
    }
    for (; n >= 4; n -= 4) *dw++ = *sw++;
    d = reinterpret_cast<unsigned char*>(dw);
    s = reinterpret_cast<const unsigned char*>(sw);
  }
  while (n--) *d++ = *s++;
  return dst;
}

void* memmove(void* dst, const void* src, std::size_t n) {
  auto* d = static_cast<unsigned char*>(dst);
  const auto* s = static_cast<const unsigned char*>(src);
  if (reinterpret_cast<std::uintptr_t>(d) - reinterpret_cast<std::uintptr_t>(s) >= n) {
    // No overlap that a forward copy would spoil (d before s, or d at or after s + n).
    while (n--) *d++ = *s++;
  } else {
    d += n;
    s += n;
    while (n--) *--d = *--s;
  }
  return dst;
}

void* memset(void* dst, int c, std::size_t n) {
  auto* d = static_cast<unsigned char*>(dst);
  const auto byte = static_cast<unsigned char>(c);
  while (n > 0 && !word_aligned(d)) {
    *d++ = byte;
    --n;
  }
  using Word [[gnu::may_alias]] = std::uint32_t;
  const Word pattern = 0x01010101u * byte;
  auto* dw = reinterpret_cast<Word*>(d);
#if defined(__arm__)
  // Strip clears are most of what memset does here: 64 bytes per four STMs (Armv6-M stores only
  // low registers, hence four of them, named so that the list is in ascending order).
  register Word p2 asm("r2") = pattern;
  register Word p3 asm("r3") = pattern;
  register Word p4 asm("r4") = pattern;
  register Word p5 asm("r5") = pattern;
  for (; n >= 64; n -= 64) {
    asm volatile(
        "stmia %0!, {%1, %2, %3, %4}\n\tstmia %0!, {%1, %2, %3, %4}\n\t"
        "stmia %0!, {%1, %2, %3, %4}\n\tstmia %0!, {%1, %2, %3, %4}"
        : "+l"(dw)
        : "l"(p2), "l"(p3), "l"(p4), "l"(p5)
        : "memory");
  }
#endif
  for (; n >= 16; n -= 16) {
    dw[0] = pattern;
    dw[1] = pattern;
    dw[2] = pattern;
    dw[3] = pattern;
    dw += 4;
  }
  for (; n >= 4; n -= 4) *dw++ = pattern;
  d = reinterpret_cast<unsigned char*>(dw);
  while (n--) *d++ = byte;
  return dst;
}

int memcmp(const void* a, const void* b, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(a);
  const auto* q = static_cast<const unsigned char*>(b);
  for (; n > 0; --n, ++p, ++q) {
    if (*p != *q) return *p < *q ? -1 : 1;
  }
  return 0;
}

std::size_t strlen(const char* s) {
  const char* p = s;
  while (*p != '\0') ++p;
  return static_cast<std::size_t>(p - s);
}

}  // extern "C"
