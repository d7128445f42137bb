// The C library functions that compiled code calls without asking: memcpy, memmove, memset,
// memcmp (GCC emits them for struct copies, zeroing, std::fill of a byte pattern,
// std::string_view comparison) and strlen (std::string_view from a C string, when not folded at
// compile time, e.g. at -O0), and on Armv6-M the run-time ABI's 64-bit multiply. The firmware
// links no C library (-nostdlib): this is all of it, so that nothing can pull in malloc, stdio or
// the C library's startup.
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

#if defined(__ARM_ARCH_6M__)
// The 64-bit product (low 64 bits, the same for signed and unsigned operands) that Armv6-M code
// calls for every 64-bit multiply, 32 x 32 -> 64 included: libgcc's takes 45 instructions, this
// one 21 (24 when the middle sum carries): four 16 x 16 products for the low words, two for the
// cross terms. a in r1:r0, b in r3:r2, the product in r1:r0 (the run-time ABI's __aeabi_lmul).
asm(R"(
  .pushsection .text.__aeabi_lmul, "ax", %progbits
  .thumb
  .syntax unified
  .global __aeabi_lmul
  .type __aeabi_lmul, %function
  .thumb_func
__aeabi_lmul:
  push {r4, r5, r6, lr}
  muls r1, r2          @ a_hi b_lo
  muls r3, r0          @ a_lo b_hi
  adds r6, r1, r3      @ the cross terms, modulo 2^32
  lsrs r4, r0, #16     @ a_lo = ah 2^16 + al, b_lo = bh 2^16 + bl
  uxth r0, r0
  lsrs r5, r2, #16
  uxth r2, r2
  movs r1, r0
  muls r1, r5          @ al bh
  muls r5, r4          @ ah bh
  muls r4, r2          @ ah bl
  muls r0, r2          @ al bl
  adds r1, r1, r4      @ mid = al bh + ah bl; a carry is 2^48 of the product
  bcc 1f
  movs r4, #1
  lsls r4, r4, #16
  adds r5, r5, r4
1:
  lsls r4, r1, #16
  lsrs r1, r1, #16
  adds r0, r0, r4      @ al bl + mid 2^16, its carry into the high word
  adcs r1, r5
  adds r1, r1, r6
  pop {r4, r5, r6, pc}
  .size __aeabi_lmul, . - __aeabi_lmul
  .popsection
)");
#endif
