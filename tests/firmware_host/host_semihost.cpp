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
// Handles are indices into a small table of open files (the firmware opens one at a time).
namespace {
std::FILE* g_files[4] = {};
}
int open_write(const char* path) {
  for (int i = 0; i < 4; ++i) {
    if (g_files[i] == nullptr) {
      g_files[i] = std::fopen(path, "wb");
      return g_files[i] == nullptr ? -1 : i;
    }
  }
  return -1;
}
bool write_file(int handle, const void* data, uint32_t size) {
  if (handle < 0 || handle >= 4 || g_files[handle] == nullptr) return false;
  return std::fwrite(data, 1, size, g_files[handle]) == size;
}
bool close_file(int handle) {
  if (handle < 0 || handle >= 4 || g_files[handle] == nullptr) return false;
  const bool ok = std::fclose(g_files[handle]) == 0;
  g_files[handle] = nullptr;
  return ok;
}
void exit(bool success) {
  std::exit(success ? 0 : 1);
}

}  // namespace lr::fw::semihost
