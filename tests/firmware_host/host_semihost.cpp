// The firmware's semihosting interface on the host: stdout and exit(). With it the smoke
// firmware's own main.cpp runs on the PC, so its frame checksum can be compared with the one
// printed by the Cortex-M4F build under QEMU (bit-identical frames on both).
#include <cstdio>
#include <cstdlib>

#include "firmware/common/semihost.hpp"

namespace lr::fw::semihost {

bool enabled() {
  return true;
}
void write(const char* text) {
  std::fputs(text, stdout);
}
void write_dec(uint32_t v) {
  std::printf("%u", v);
}
void write_hex(uint32_t v) {
  std::printf("0x%08x", v);
}
void exit(bool success) {
  std::exit(success ? 0 : 1);
}

}  // namespace lr::fw::semihost
