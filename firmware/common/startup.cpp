// Startup for Cortex-M: ARMv6-M (M0/M0+), ARMv7-M/ARMv7E-M (M3, M4F, M7) and ARMv8-M Mainline
// (M33, Secure state). Nothing in it is board specific: the memory layout comes from the linker
// script (firmware/common/cortex_m_sections.ld and the board's script).
//
// Reset_Handler: enables the FPU (when compiled for one), makes ARMv6-M code trap unaligned
// accesses on an ARMv7-M core too, paints the stack (for lr_stack_used_bytes), copies .data from
// flash, zeroes .bss, runs the C++ static constructors (.preinit_array, .init_array), calls
// main() and ends the session with main's result (semihosting), or parks the core.
// Every fault and unexpected exception reports over semihosting and ends the session with a
// failure status (QEMU exits with 1).
// No C library start files are linked (-nostartfiles -nostdlib): no heap, no atexit, no stdio.
#include <cstdint>

#include "firmware/common/semihost.hpp"

// Mainline (ARMv7-M, ARMv8-M Mainline) has the configurable fault status registers and Thumb-2;
// Baseline (ARMv6-M, ARMv8-M Baseline) has neither: its only fault is HardFault, with no status.
#if __ARM_ARCH_ISA_THUMB >= 2
#define LR_ARMV_MAINLINE 1
#else
#define LR_ARMV_MAINLINE 0
#endif

// Symbols of the linker script (firmware/common/cortex_m_sections.ld).
extern "C" {
extern uint32_t _sidata[];  // load address of .data in flash
extern uint32_t _sdata[], _edata[];
extern uint32_t _sbss[], _ebss[];
extern uint32_t _sstack[], _estack[];  // the main stack: [_sstack, _estack), _estack initial SP
extern void (*__preinit_array_start[])();
extern void (*__preinit_array_end[])();
extern void (*__init_array_start[])();
extern void (*__init_array_end[])();
}

int main();

namespace {

// System control block registers (the same addresses on every Cortex-M; some exist only on
// Mainline, as marked).
volatile uint32_t& reg(uint32_t address) {
  return *reinterpret_cast<volatile uint32_t*>(address);
}
[[maybe_unused]] constexpr uint32_t kCpuid = 0xE000ED00;  // CPU identification
[[maybe_unused]] constexpr uint32_t kCcr = 0xE000ED14;    // configuration and control
[[maybe_unused]] constexpr uint32_t kCpacr = 0xE000ED88;  // coprocessor access (with an FPU)
#if LR_ARMV_MAINLINE
constexpr uint32_t kCfsr = 0xE000ED28;   // configurable fault status
constexpr uint32_t kHfsr = 0xE000ED2C;   // hard fault status
constexpr uint32_t kMmfar = 0xE000ED34;  // memory management fault address
constexpr uint32_t kBfar = 0xE000ED38;   // bus fault address
#endif
#if defined(__ARM_FEATURE_CMSE)
constexpr uint32_t kSfsr = 0xE000EDE4;  // secure fault status (ARMv8-M Security Extension)
#endif

// Written over the whole stack before main; lr_stack_used_bytes() finds the deepest word that
// no longer holds it.
constexpr uint32_t kStackPaint = 0x5AC3A55Au;

}  // namespace

// What the last fault saw, for a debugger (and printed through semihosting). The status
// registers stay 0 on Baseline cores, which have none.
extern "C" {
struct FaultRecord {
  uint32_t r0, r1, r2, r3, r12, lr, pc, xpsr;  // the exception frame
  uint32_t exc_return;                         // the handler's LR: which stack, which state
  uint32_t cfsr, hfsr, mmfar, bfar, sfsr;
};
volatile FaultRecord g_fault_record;

[[noreturn]] void Reset_Handler();
void Default_Handler();
void HardFault_Handler();
void NMI_Handler() __attribute__((weak, alias("Default_Handler")));
void MemManage_Handler() __attribute__((weak, alias("Default_Handler")));
void BusFault_Handler() __attribute__((weak, alias("Default_Handler")));
void UsageFault_Handler() __attribute__((weak, alias("Default_Handler")));
void SecureFault_Handler() __attribute__((weak, alias("Default_Handler")));
void SVC_Handler() __attribute__((weak, alias("Default_Handler")));
void DebugMon_Handler() __attribute__((weak, alias("Default_Handler")));
void PendSV_Handler() __attribute__((weak, alias("Default_Handler")));
void SysTick_Handler() __attribute__((weak, alias("Default_Handler")));

// Bytes of the main stack used so far (deepest point since reset).
uint32_t lr_stack_used_bytes();
}

// The vector table: initial stack pointer, then the 15 system exceptions. The layout is the same
// on every profile; slots a core does not have (MemManage, BusFault, UsageFault, DebugMon on
// ARMv6-M; SecureFault before ARMv8-M) are never taken, and point at Default_Handler anyway.
// No external interrupt is enabled by the applications so far; add their entries when one is.
namespace {
using Handler = void (*)();
struct VectorTable {
  const void* initial_sp;
  Handler system[15];
};
}  // namespace

extern "C" __attribute__((section(".isr_vector"), used)) const VectorTable g_vector_table = {
    _estack,
    {
        Reset_Handler,
        NMI_Handler,
        HardFault_Handler,
        MemManage_Handler,
        BusFault_Handler,
        UsageFault_Handler,
        SecureFault_Handler,
        nullptr,
        nullptr,
        nullptr,
        SVC_Handler,
        DebugMon_Handler,
        nullptr,
        PendSV_Handler,
        SysTick_Handler,
    },
};

extern "C" void Reset_Handler() {
#if defined(__ARM_FP)
  // Full access to CP10 and CP11 (the FPU) before any floating-point instruction can run: code
  // built with -mfloat-abi=hard may use the FP registers anywhere, even in integer code.
  // (On the M33 this is the Secure CPACR, the one that counts for the Secure image.)
  reg(kCpacr) = reg(kCpacr) | (0xFu << 20);
  __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
#if defined(__ARM_ARCH_6M__)
  // ARMv6-M code on an ARMv7-M core (mps2-an385's M3 runs the M0+ images, firmware/boards.cmake):
  // ARMv6-M traps every unaligned word/halfword access, ARMv7-M only with CCR.UNALIGN_TRP. Set
  // it, so that such a bug faults on the M3 as on the M0+. CPUID[19:16] is 0xC on ARMv6-M, whose
  // CCR is read-only, and 0xF on ARMv7-M/ARMv8-M Mainline.
  if (((reg(kCpuid) >> 16) & 0xFu) == 0xFu) {
    reg(kCcr) = reg(kCcr) | (1u << 3);
    __asm__ volatile("dsb\n\tisb" ::: "memory");
  }
#endif
  // Paint the stack below this function's frame. Volatile stores: the compiler must not turn
  // the loop into a memset call, whose own frame would lie in the area being painted.
  uint32_t* sp;
  __asm__ volatile("mov %0, sp" : "=r"(sp));
  for (volatile uint32_t* p = _sstack; p < sp; ++p) *p = kStackPaint;

  for (uint32_t *src = _sidata, *dst = _sdata; dst < _edata;) *dst++ = *src++;
  for (uint32_t* dst = _sbss; dst < _ebss;) *dst++ = 0;
  for (void (**f)() = __preinit_array_start; f < __preinit_array_end; ++f) (*f)();
  for (void (**f)() = __init_array_start; f < __init_array_end; ++f) (*f)();
  const int rc = main();
  lr::fw::semihost::exit(rc == 0);
}

extern "C" uint32_t lr_stack_used_bytes() {
  const volatile uint32_t* p = _sstack;
  while (p < _estack && *p == kStackPaint) ++p;
  return static_cast<uint32_t>(reinterpret_cast<uintptr_t>(_estack) -
                               reinterpret_cast<uintptr_t>(p));
}

extern "C" void Default_Handler() {
  // IPSR: the number of the exception being handled.
  uint32_t ipsr;
  __asm__ volatile("mrs %0, ipsr" : "=r"(ipsr));
  lr::fw::semihost::write("unexpected exception ");
  lr::fw::semihost::write_dec(ipsr & 0x1FFu);
  lr::fw::semihost::write("\n");
  lr::fw::semihost::exit(false);
}

// Records the exception frame and the fault status registers, reports them, ends the session.
extern "C" __attribute__((used, noreturn)) void lr_fault_report(const uint32_t* frame,
                                                                uint32_t exc_return) {
  volatile FaultRecord& f = g_fault_record;
  f.r0 = frame[0];
  f.r1 = frame[1];
  f.r2 = frame[2];
  f.r3 = frame[3];
  f.r12 = frame[4];
  f.lr = frame[5];
  f.pc = frame[6];
  f.xpsr = frame[7];
  f.exc_return = exc_return;
#if LR_ARMV_MAINLINE
  f.cfsr = reg(kCfsr);
  f.hfsr = reg(kHfsr);
  f.mmfar = reg(kMmfar);
  f.bfar = reg(kBfar);
#endif
#if defined(__ARM_FEATURE_CMSE)
  f.sfsr = reg(kSfsr);
#endif
  namespace sh = lr::fw::semihost;
  sh::write("HardFault: pc=");
  sh::write_hex(f.pc);
  sh::write(" lr=");
  sh::write_hex(f.lr);
  sh::write(" xpsr=");
  sh::write_hex(f.xpsr);
  sh::write(" exc_return=");
  sh::write_hex(f.exc_return);
#if LR_ARMV_MAINLINE
  sh::write(" cfsr=");
  sh::write_hex(f.cfsr);
  sh::write(" hfsr=");
  sh::write_hex(f.hfsr);
#endif
#if defined(__ARM_FEATURE_CMSE)
  sh::write(" sfsr=");
  sh::write_hex(f.sfsr);
#endif
  sh::write("\n");
  sh::exit(false);
}

// The frame is on the stack that was in use: MSP or PSP, as bit 2 (SPSEL) of EXC_RETURN says.
// Written for ARMv6-M, whose Thumb-1 has no IT blocks, no TST with an immediate and a B range
// of 2 KB, so the same instructions serve every core: r0 = frame, r1 = EXC_RETURN, then a jump
// through a register to the reporter (which never returns).
extern "C" __attribute__((naked)) void HardFault_Handler() {
  __asm__ volatile(
      "movs r0, #4\n\t"
      "mov r1, lr\n\t"
      "tst r0, r1\n\t"
      "bne 1f\n\t"
      "mrs r0, msp\n\t"
      "b 2f\n"
      "1:\n\t"
      "mrs r0, psp\n"
      "2:\n\t"
      "ldr r2, =lr_fault_report\n\t"
      "bx r2\n\t"
      ".ltorg\n\t");
}

// Called through a pure virtual slot (a bug): without it libsupc++'s version would be linked,
// and with it std::terminate, the verbose terminate handler, the demangler and malloc.
extern "C" void __cxa_pure_virtual() {
  lr::fw::semihost::write("pure virtual call\n");
  lr::fw::semihost::exit(false);
}
