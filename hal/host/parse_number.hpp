// Decimal numbers in the backends' spec strings ("hz=32000000", "mode=0").
#pragma once

#include <cstdint>
#include <string_view>

namespace lr::backend {

// A decimal uint32 (digits only, no sign, no spaces); false when empty, malformed or too large.
inline bool parse_u32(std::string_view s, uint32_t& out) {
  if (s.empty() || s.size() > 10) return false;
  uint64_t v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
    v = v * 10 + static_cast<uint64_t>(c - '0');
  }
  if (v > 0xFFFFFFFFu) return false;
  out = static_cast<uint32_t>(v);
  return true;
}

}  // namespace lr::backend
