// ARM semihosting: text output and exit through the debugger or emulator (QEMU -semihosting).
//
// A semihosting call is `bkpt 0xAB` with the operation in r0 and its argument in r1. Without a
// debugger (or QEMU's -semihosting) attached, that breakpoint is a HardFault on a Cortex-M, so
// the calls are compiled in only when LR_SEMIHOSTING is 1 (CMake option LR_SEMIHOSTING); when it
// is 0, output is dropped and exit() parks the core (the result stays in the volatile globals
// for a debugger to read).
#pragma once

#include <cstdint>

namespace lr::fw::semihost {

// True when the semihosting calls are compiled in.
bool enabled();

// SYS_WRITE0: writes a NUL-terminated string to the host's console.
void write(const char* text);
// Writes v in decimal, or in hexadecimal as 0x%08x.
void write_dec(uint32_t v);
void write_hex(uint32_t v);

// SYS_EXIT: ends the session; the host (QEMU) exits with status 0 on success, 1 otherwise.
// Without semihosting: disables interrupts and waits forever.
[[noreturn]] void exit(bool success);

}  // namespace lr::fw::semihost
