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

// Files on the host (SYS_OPEN, SYS_WRITE, SYS_CLOSE; QEMU resolves a relative path against its
// working directory). open_write creates or truncates the file for binary writing ("wb") and
// returns a handle, or -1 (no semihosting, or the host refused). write_file writes all `size`
// bytes or returns false; close_file returns false if the host reports an error.
int open_write(const char* path);
bool write_file(int handle, const void* data, uint32_t size);
bool close_file(int handle);

// SYS_EXIT: ends the session; the host (QEMU) exits with status 0 on success, 1 otherwise.
// Without semihosting: disables interrupts and waits forever.
[[noreturn]] void exit(bool success);

}  // namespace lr::fw::semihost
