#include "lineraster/host_sim/programs/frame_pattern.hpp"

namespace lr::host {

std::string FramePattern::name(int frame) const {
  std::string digits = std::to_string(frame);
  if (static_cast<int>(digits.size()) < width)
    digits.insert(0, static_cast<size_t>(width) - digits.size(), zero_pad ? '0' : ' ');
  return before + digits + after;
}

bool parse_frame_pattern(std::string_view text, FramePattern& out, std::string& why) {
  why = "exactly one %d (or %0Nd, %Nd) for the frame number, %% for a '%'";
  FramePattern p;
  bool seen = false;
  for (size_t i = 0; i < text.size(); ++i) {
    std::string& part = seen ? p.after : p.before;
    if (text[i] != '%') {
      part += text[i];
      continue;
    }
    if (i + 1 < text.size() && text[i + 1] == '%') {
      part += '%';
      ++i;
      continue;
    }
    if (seen) return false;  // a second conversion
    size_t k = i + 1;
    if (k < text.size() && text[k] == '0') {
      p.zero_pad = true;
      ++k;
    }
    int width = 0;
    for (; k < text.size() && text[k] >= '0' && text[k] <= '9'; ++k) {
      width = width * 10 + (text[k] - '0');
      if (width > kMaxFrameWidth) {
        why = "a width of at most " + std::to_string(kMaxFrameWidth) + " digits";
        return false;
      }
    }
    if (k >= text.size() || (text[k] != 'd' && text[k] != 'i' && text[k] != 'u')) return false;
    p.width = width;
    seen = true;
    i = k;
  }
  if (!seen) return false;
  p.given = true;
  out = p;
  return true;
}

}  // namespace lr::host
