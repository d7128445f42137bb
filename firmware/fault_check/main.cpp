// Faults on purpose, to prove that the fault handler of firmware/common/startup.cpp reports and
// ends the session with a failure on every core: scripts/ci_cross.sh runs each image under QEMU
// and wants a non-zero exit status and the line "HardFault: pc=<address of lr_fault_trigger>"
// (the faulting instruction is the trigger's first), which also shows that the handler found
// the exception frame. On cores with an FPU it first runs an FPU instruction, which proves that
// startup.cpp enabled the FPU (the smoke firmware's Gouraud path runs none).
//
// LR_FAULT_KIND (set by CMakeLists.txt):
//   1  an undefined instruction (UDF): HardFault on ARMv6-M; UsageFault escalated to HardFault
//      on Mainline, where UsageFault is disabled after reset
//   2  a word load from an odd address: HardFault on ARMv6-M, which always traps unaligned
//      accesses; the M3 of mps2-an385 running the same ARMv6-M image traps only because
//      startup.cpp sets CCR.UNALIGN_TRP there (see firmware/boards.cmake)
#include <cstdint>

#include "firmware/common/semihost.hpp"

#ifndef LR_FAULT_KIND
#error "LR_FAULT_KIND must be defined (firmware/fault_check/CMakeLists.txt)"
#endif

// The faulting instruction first, at the symbol's address. Naked: no prologue before it. The
// argument (r0) is the address the load of kind 2 reads.
extern "C" __attribute__((naked, noinline)) void lr_fault_trigger(uintptr_t) {
#if LR_FAULT_KIND == 1
  __asm__ volatile("udf #0\n\tbx lr\n\t");
#elif LR_FAULT_KIND == 2
  __asm__ volatile("ldr r0, [r0]\n\tbx lr\n\t");
#else
#error "unknown LR_FAULT_KIND"
#endif
}

namespace {
alignas(4) volatile uint32_t g_words[2] = {0x01020304u, 0x05060708u};
#if defined(__ARM_FP)
volatile float g_value = 1.5f;
#endif
}  // namespace

int main() {
  namespace sh = lr::fw::semihost;
  sh::write(LR_FAULT_KIND == 1 ? "lr_fault_check: executing an undefined instruction\n"
                               : "lr_fault_check: loading a word from an odd address\n");
#if defined(__ARM_FP)
  // Hard-float images: one FPU instruction first. Had Reset_Handler not enabled the FPU (CPACR),
  // it would fault here (UsageFault NOCP) instead of at the trigger, and the pc check fails.
  g_value = g_value * 3.0f;
  if (g_value != 4.5f) sh::write("lr_fault_check: the FPU computed 1.5 * 3 wrong\n");
#endif
  lr_fault_trigger(reinterpret_cast<uintptr_t>(&g_words[0]) + 1u);
  // Only reached if nothing faulted: still a failure, but without the "HardFault" line.
  sh::write("lr_fault_check: FAIL: no fault was raised\n");
  return 1;
}
