// Known instruction sequences between instruction-count markers: proves the QEMU counting plugin
// (tools/qemu_icount) exact. scripts/icount_check.sh runs this image under the plugin and checks
// that every measured count equals the count this program prints for it.
//
// Markers. lr_icount_begin and lr_icount_end are functions of exactly one instruction (`bx lr`;
// naked, so no prologue, and they change no register and no flag). The plugin prints the number of
// instructions executed before a marker's first instruction, so the difference between a begin
// line and the next end line counts
//   lr_icount_begin's own instructions (1: its bx lr)
//   + the measured sequence
//   + the instructions that call lr_icount_end (1: the bl)
// which is the sequence's length + 2 (kOverhead) for the cases below, whose assembly calls the
// markers itself. The case "begin_body" checks this rule with a 4-instruction begin marker.
//
// The measured region contains plain instructions only: no semihosting call (a BKPT the host
// services), no SVC, no access that can fault, and interrupts are masked around it (PRIMASK, set
// and cleared outside the region), because the plugin counts a whole translation block when it
// starts and would count a cut-short block's remaining instructions, or an exception handler's.
// Each case returns its expected count; main() prints it (semihosting) only after the region.
//
// Only ARMv6-M instructions are used (16-bit Thumb plus BL), so the same source checks Cortex-M0+
// and Cortex-M4F images. Registers: r0-r3 only (the low registers, caller-saved).
#include <cstdint>

#include "firmware/common/semihost.hpp"

// GCC assembles inline asm for Thumb-1 targets (ARMv6-M) in the old divided syntax unless told
// otherwise (-masm-syntax-unified); every block below starts with this, and GCC switches back
// after the block itself.
#define LR_UNIFIED ".syntax unified\n\t"

extern "C" {
// The markers, resolved by name (arm-none-eabi-nm) by scripts/icount.sh. `used`: referenced
// from assembly only.
__attribute__((naked, noinline, used)) void lr_icount_begin() {
  __asm__ volatile(LR_UNIFIED "bx lr");
}
__attribute__((naked, noinline, used)) void lr_icount_end() {
  __asm__ volatile(LR_UNIFIED "bx lr");
}
// A begin marker with a body of 4 instructions (3 nops and the return).
__attribute__((naked, noinline, used)) void lr_icount_begin4() {
  __asm__ volatile(LR_UNIFIED
                   "nop\n\t"
                   "nop\n\t"
                   "nop\n\t"
                   "bx lr");
}
// A leaf function of 4 instructions (3 adds and the return) for the call case.
__attribute__((naked, noinline, used)) void lr_icount_leaf4() {
  __asm__ volatile(LR_UNIFIED
                   "adds r0, r0, #1\n\t"
                   "adds r0, r0, #1\n\t"
                   "adds r0, r0, #1\n\t"
                   "bx lr");
}
}

namespace {

namespace sh = lr::fw::semihost;

// The begin marker's bx lr and the bl to the end marker (see the top of the file).
constexpr uint32_t kOverhead = 2;

// Wraps a measured sequence: interrupts masked outside the region, the markers around it.
#define LR_MEASURED_FROM(begin_marker, body) \
  LR_UNIFIED                                 \
  "cpsid i\n\t"                              \
  "bl " begin_marker "\n\t" body             \
  "bl lr_icount_end\n\t"                     \
  "cpsie i\n\t"
#define LR_MEASURED(body) LR_MEASURED_FROM("lr_icount_begin", body)

// Every case's assembly calls functions (bl clobbers lr) and may change r0-r3 and the flags.
#define LR_CLOBBERS "r0", "r1", "r2", "r3", "lr", "cc", "memory"

// Nothing between the markers.
__attribute__((noinline)) uint32_t case_empty() {
  __asm__ volatile(LR_MEASURED("") : : : LR_CLOBBERS);
  return kOverhead;
}

// 16 straight-line data-processing instructions.
__attribute__((noinline)) uint32_t case_straight16() {
  __asm__ volatile(LR_MEASURED("movs r0, #1\n\t"
                               "movs r1, #2\n\t"
                               "adds r2, r0, r1\n\t"
                               "lsls r2, r2, #3\n\t"
                               "eors r0, r2\n\t"
                               "subs r1, r2, r0\n\t"
                               "orrs r1, r0\n\t"
                               "ands r2, r1\n\t"
                               "mvns r3, r2\n\t"
                               "lsrs r3, r3, #4\n\t"
                               "adds r3, r3, #7\n\t"
                               "muls r3, r0\n\t"
                               "rev r0, r3\n\t"
                               "uxtb r1, r0\n\t"
                               "cmp r1, r2\n\t"
                               "mov r2, r3\n\t")
                   :
                   :
                   : LR_CLOBBERS);
  return kOverhead + 16;
}

// A loop of kIterations x 4 instructions (the count is loaded before the region).
__attribute__((noinline)) uint32_t case_loop() {
  constexpr uint32_t kIterations = 1000;
  register uint32_t n __asm__("r1") = kIterations;
  __asm__ volatile(LR_MEASURED("1:\n\t"
                               "adds r0, r0, #3\n\t"
                               "eors r2, r0\n\t"
                               "subs r1, r1, #1\n\t"
                               "bne 1b\n\t")
                   : "+r"(n)
                   :
                   : "r0", "r2", "r3", "lr", "cc", "memory");
  return kOverhead + 4 * kIterations;
}

// A long loop: 250,000 iterations of 3 instructions, 750,000 in all.
__attribute__((noinline)) uint32_t case_long_loop() {
  constexpr uint32_t kIterations = 250000;
  register uint32_t n __asm__("r1") = kIterations;
  __asm__ volatile(LR_MEASURED("1:\n\t"
                               "adds r0, r0, r1\n\t"
                               "subs r1, r1, #1\n\t"
                               "bne 1b\n\t")
                   : "+r"(n)
                   :
                   : "r0", "r2", "r3", "lr", "cc", "memory");
  return kOverhead + 3 * kIterations;
}

// Nested loops: 12 outer iterations, each 1 (movs) + 25 x 2 (inner subs, bne) + 2 (subs, bne).
__attribute__((noinline)) uint32_t case_nested() {
  constexpr uint32_t kOuter = 12;
  constexpr uint32_t kInner = 25;
  register uint32_t n __asm__("r1") = kOuter;
  __asm__ volatile(LR_MEASURED("1:\n\t"
                               "movs r2, %[inner]\n\t"
                               "2:\n\t"
                               "subs r2, r2, #1\n\t"
                               "bne 2b\n\t"
                               "subs r1, r1, #1\n\t"
                               "bne 1b\n\t")
                   : "+r"(n)
                   : [inner] "I"(kInner)
                   : "r0", "r2", "r3", "lr", "cc", "memory");
  return kOverhead + kOuter * (1 + 2 * kInner + 2);
}

// Three calls of a 4-instruction leaf: 3 x (bl + 4).
__attribute__((noinline)) uint32_t case_call() {
  __asm__ volatile(LR_MEASURED("movs r0, #0\n\t"
                               "bl lr_icount_leaf4\n\t"
                               "bl lr_icount_leaf4\n\t"
                               "bl lr_icount_leaf4\n\t")
                   :
                   :
                   : LR_CLOBBERS);
  return kOverhead + 1 + 3 * (1 + 4);
}

// Branches: instructions that are jumped over are not counted; a branch not taken is.
//   cmp, beq (taken: skips 2 nops), b (skips 1 nop), nop, cmp, bne (not taken), nop  = 7
__attribute__((noinline)) uint32_t case_branches() {
  __asm__ volatile(LR_MEASURED("cmp r0, r0\n\t"
                               "beq 1f\n\t"
                               "nop\n\t"
                               "nop\n\t"
                               "1:\n\t"
                               "b 2f\n\t"
                               "nop\n\t"
                               "2:\n\t"
                               "nop\n\t"
                               "cmp r0, r0\n\t"
                               "bne 3f\n\t"
                               "nop\n\t"
                               "3:\n\t")
                   :
                   :
                   : LR_CLOBBERS);
  return kOverhead + 7;
}

uint32_t g_words[4];

// Loads, stores, load/store multiple and the stack: 10 instructions.
__attribute__((noinline)) uint32_t case_memory() {
  register uint32_t* p __asm__("r3") = g_words;
  __asm__ volatile(LR_MEASURED("ldr r0, [r3]\n\t"
                               "adds r0, r0, #1\n\t"
                               "str r0, [r3]\n\t"
                               "ldr r1, [r3, #4]\n\t"
                               "str r1, [r3, #8]\n\t"
                               "push {r0, r1}\n\t"
                               "pop {r1, r2}\n\t"
                               "stm r3!, {r1, r2}\n\t"
                               "subs r3, r3, #8\n\t"
                               "ldm r3!, {r0, r1}\n\t")
                   : "+r"(p)
                   :
                   : "r0", "r1", "r2", "lr", "cc", "memory");
  return kOverhead + 10;
}

// The marker rule: a begin marker's own instructions are inside the difference (4 here: 3 nops and
// bx lr), the end marker's are not; with the bl to the end marker, 4 + 1.
__attribute__((noinline)) uint32_t case_begin_body() {
  __asm__ volatile(LR_MEASURED_FROM("lr_icount_begin4", "") : : : LR_CLOBBERS);
  return 4 + 1;
}

struct Case {
  const char* name;
  // Runs the measured region (between a begin marker and lr_icount_end) and returns its expected
  // count. The begin marker is lr_icount_begin, except for "begin_body" (lr_icount_begin4).
  uint32_t (*run)();
};

constexpr Case kCases[] = {
    {"empty", case_empty},         {"straight16", case_straight16}, {"loop", case_loop},
    {"long_loop", case_long_loop}, {"nested", case_nested},         {"call", case_call},
    {"branches", case_branches},   {"memory", case_memory},         {"begin_body", case_begin_body},
};

}  // namespace

int main() {
  // Output format, read by scripts/icount_check.sh:
  //   icount_check: case NAME expected N      (one per case, in the order the regions ran)
  //   icount_check: done CASES
  for (const Case& c : kCases) {
    const uint32_t expected = c.run();  // the measured region; nothing is printed inside it
    sh::write("icount_check: case ");
    sh::write(c.name);
    sh::write(" expected ");
    sh::write_dec(expected);
    sh::write("\n");
  }
  sh::write("icount_check: done ");
  sh::write_dec(static_cast<uint32_t>(sizeof kCases / sizeof kCases[0]));
  sh::write("\n");
  return 0;
}
