// Console lines the firmware applications print through semihosting.
#pragma once

#include <cstdint>

#include "firmware/common/semihost.hpp"
#include "lineraster/core/output/status.hpp"

namespace lr::fw {

// True for kOk; otherwise prints "<app>: <what> failed: <status>".
inline bool check(const char* app, Status st, const char* what) {
  if (st == Status::kOk) return true;
  semihost::write(app);
  semihost::write(": ");
  semihost::write(what);
  semihost::write(" failed: ");
  semihost::write(to_string(st));
  semihost::write("\n");
  return false;
}

// "  <label> <value>" in decimal, or 0x%08x.
inline void report(const char* label, uint32_t value, bool hex = false) {
  semihost::write("  ");
  semihost::write(label);
  semihost::write(" ");
  if (hex) {
    semihost::write_hex(value);
  } else {
    semihost::write_dec(value);
  }
  semihost::write("\n");
}

}  // namespace lr::fw
