// Startup for Cortex-M (written for the M4F of QEMU's mps2-an386; nothing in it is board
// specific beyond the memory layout in the linker script).
//
// Reset_Handler: enables the FPU (when compiled for one), copies .data from flash, zeroes .bss,
// runs the C++ static constructors (.preinit_array, .init_array), calls main() and ends the
// session with main's result (semihosting), or parks the core.
// No C library start files are linked (-nostartfiles -nostdlib): no heap, no atexit, no stdio.
#include <cstdint>

#include "firmware/common/semihost.hpp"

// Symbols of the linker script (firmware/common/mps2_an386.ld).
extern "C" {
extern uint32_t _sidata[];  // load address of .data in flash
extern uint32_t _sdata[], _edata[];
extern uint32_t _sbss[], _ebss[];
extern uint32_t _estack[];  // initial stack pointer (top of RAM)
extern void (*__preinit_array_start[])();
extern void (*__preinit_array_end[])();
extern void (*__init_array_start[])();
extern void (*__init_array_end[])();
}

int main();

namespace {

// System control block registers.
volatile uint32_t& reg(uint32_t address) {
  return *reinterpret_cast<volatile uint32_t*>(address);
}
constexpr uint32_t kCpacr = 0xE000ED88;  // coprocessor access control
constexpr uint32_t kCfsr = 0xE000ED28;   // configurable fault status
constexpr uint32_t kHfsr = 0xE000ED2C;   // hard fault status
constexpr uint32_t kMmfar = 0xE000ED34;  // memory management fault address
constexpr uint32_t kBfar = 0xE000ED38;   // bus fault address

}  // namespace

// What the last fault saw, for a debugger (and printed through semihosting).
extern "C" {
struct FaultRecord {
  uint32_t r0, r1, r2, r3, r12, lr, pc, xpsr;  // the exception frame
  uint32_t cfsr, hfsr, mmfar, bfar;
};
volatile FaultRecord g_fault_record;

[[noreturn]] void Reset_Handler();
void Default_Handler();
void HardFault_Handler();
void NMI_Handler() __attribute__((weak, alias("Default_Handler")));
void MemManage_Handler() __attribute__((weak, alias("Default_Handler")));
void BusFault_Handler() __attribute__((weak, alias("Default_Handler")));
void UsageFault_Handler() __attribute__((weak, alias("Default_Handler")));
void SVC_Handler() __attribute__((weak, alias("Default_Handler")));
void DebugMon_Handler() __attribute__((weak, alias("Default_Handler")));
void PendSV_Handler() __attribute__((weak, alias("Default_Handler")));
void SysTick_Handler() __attribute__((weak, alias("Default_Handler")));
}

// The vector table: initial stack pointer, then the system exceptions of ARMv7-M. No external
// interrupt is enabled by the applications so far; add their entries when one is.
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
        nullptr,
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
  reg(kCpacr) = reg(kCpacr) | (0xFu << 20);
  __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
  for (uint32_t *src = _sidata, *dst = _sdata; dst < _edata;) *dst++ = *src++;
  for (uint32_t* dst = _sbss; dst < _ebss;) *dst++ = 0;
  for (void (**f)() = __preinit_array_start; f < __preinit_array_end; ++f) (*f)();
  for (void (**f)() = __init_array_start; f < __init_array_end; ++f) (*f)();
  const int rc = main();
  lr::fw::semihost::exit(rc == 0);
}

extern "C" void Default_Handler() {
  lr::fw::semihost::write("unexpected exception\n");
  lr::fw::semihost::exit(false);
}

// Records the exception frame and the fault status registers, reports them, stops.
extern "C" __attribute__((used)) void lr_fault_report(const uint32_t* frame) {
  volatile FaultRecord& f = g_fault_record;
  f.r0 = frame[0];
  f.r1 = frame[1];
  f.r2 = frame[2];
  f.r3 = frame[3];
  f.r12 = frame[4];
  f.lr = frame[5];
  f.pc = frame[6];
  f.xpsr = frame[7];
  f.cfsr = reg(kCfsr);
  f.hfsr = reg(kHfsr);
  f.mmfar = reg(kMmfar);
  f.bfar = reg(kBfar);
  namespace sh = lr::fw::semihost;
  sh::write("HardFault: pc=");
  sh::write_hex(f.pc);
  sh::write(" lr=");
  sh::write_hex(f.lr);
  sh::write(" cfsr=");
  sh::write_hex(f.cfsr);
  sh::write(" hfsr=");
  sh::write_hex(f.hfsr);
  sh::write("\n");
  sh::exit(false);
}

// The frame is on the stack that was in use: MSP or PSP, as bit 2 of EXC_RETURN says.
extern "C" __attribute__((naked)) void HardFault_Handler() {
  __asm__ volatile(
      "tst lr, #4\n\t"
      "ite eq\n\t"
      "mrseq r0, msp\n\t"
      "mrsne r0, psp\n\t"
      "b lr_fault_report\n\t");
}

// Called through a pure virtual slot (a bug): without it libsupc++'s version would be linked,
// and with it std::terminate, the verbose terminate handler, the demangler and malloc.
extern "C" void __cxa_pure_virtual() {
  lr::fw::semihost::write("pure virtual call\n");
  lr::fw::semihost::exit(false);
}
