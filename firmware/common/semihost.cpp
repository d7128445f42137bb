#include "firmware/common/semihost.hpp"

#ifndef LR_SEMIHOSTING
#define LR_SEMIHOSTING 0
#endif

namespace lr::fw::semihost {
namespace {

// Operation numbers and exit reasons of the Arm semihosting specification.
constexpr uint32_t kSysOpen = 0x01;
constexpr uint32_t kSysClose = 0x02;
constexpr uint32_t kSysWrite0 = 0x04;
constexpr uint32_t kSysWrite = 0x05;
constexpr uint32_t kOpenModeWb = 5;  // the fopen() mode index of "wb" in the specification
constexpr uint32_t kSysExit = 0x18;
constexpr uint32_t kAdpStoppedApplicationExit = 0x20026;      // exit status 0
constexpr uint32_t kAdpStoppedRunTimeErrorUnknown = 0x20023;  // exit status 1

#if LR_SEMIHOSTING
uint32_t call(uint32_t op, const void* arg) {
  register uint32_t r0 __asm__("r0") = op;
  register const void* r1 __asm__("r1") = arg;
  __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}
uint32_t call_value(uint32_t op, uint32_t arg) {
  register uint32_t r0 __asm__("r0") = op;
  register uint32_t r1 __asm__("r1") = arg;
  __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}
#endif

[[noreturn]] void park() {
  __asm__ volatile("cpsid i" ::: "memory");
  for (;;) __asm__ volatile("wfi");
}

}  // namespace

bool enabled() {
  return LR_SEMIHOSTING != 0;
}

void write(const char* text) {
#if LR_SEMIHOSTING
  call(kSysWrite0, text);
#else
  (void)text;
  (void)kSysWrite0;
#endif
}

void write_dec(uint32_t v) {
  char buf[11];
  char* p = buf + sizeof buf;
  *--p = '\0';
  do {
    *--p = static_cast<char>('0' + v % 10u);
    v /= 10u;
  } while (v != 0);
  write(p);
}

void write_hex(uint32_t v) {
  char buf[11] = {'0', 'x'};
  for (int i = 0; i < 8; ++i) buf[2 + i] = "0123456789abcdef"[(v >> (28 - 4 * i)) & 0xFu];
  buf[10] = '\0';
  write(buf);
}

namespace {
[[maybe_unused]] uint32_t text_length(const char* s) {
  uint32_t n = 0;
  while (s[n] != '\0') ++n;
  return n;
}
}  // namespace

int open_write(const char* path) {
#if LR_SEMIHOSTING
  // Parameter block: pointer to the name, mode, length of the name without its NUL.
  const uint32_t block[3] = {reinterpret_cast<uintptr_t>(path), kOpenModeWb, text_length(path)};
  const uint32_t handle = call(kSysOpen, block);
  return handle == 0xFFFFFFFFu ? -1 : static_cast<int>(handle);
#else
  (void)path;
  (void)kSysOpen;
  (void)kOpenModeWb;
  return -1;
#endif
}

bool write_file(int handle, const void* data, uint32_t size) {
#if LR_SEMIHOSTING
  if (handle < 0) return false;
  // Returns the number of bytes NOT written: 0 on success.
  const uint32_t block[3] = {static_cast<uint32_t>(handle), reinterpret_cast<uintptr_t>(data),
                             size};
  return call(kSysWrite, block) == 0;
#else
  (void)handle;
  (void)data;
  (void)size;
  (void)kSysWrite;
  return false;
#endif
}

bool close_file(int handle) {
#if LR_SEMIHOSTING
  if (handle < 0) return false;
  const uint32_t block[1] = {static_cast<uint32_t>(handle)};
  return call(kSysClose, block) == 0;
#else
  (void)handle;
  (void)kSysClose;
  return false;
#endif
}

void exit(bool success) {
#if LR_SEMIHOSTING
  // On AArch32 the reason code itself is the argument (no parameter block).
  call_value(kSysExit, success ? kAdpStoppedApplicationExit : kAdpStoppedRunTimeErrorUnknown);
#else
  (void)success;
  (void)kSysExit;
  (void)kAdpStoppedApplicationExit;
  (void)kAdpStoppedRunTimeErrorUnknown;
#endif
  park();  // the host did not stop us (no debugger): stay here
}

}  // namespace lr::fw::semihost
