// A file name with the frame number in it, as printf would write it: lineraster-sim's
// --out-pattern frame_%03d.png. The pattern is read here, never handed to printf.
#pragma once

#include <string>
#include <string_view>

namespace lr::host {

// The name of frame f is before + f (at least `width` digits, padded with zeros or spaces) +
// after. Empty (`before` and `after` both "", width 0) when no pattern was given.
struct FramePattern {
  std::string before, after;  // the text around the number, "%%" already turned into '%'
  int width = 0;              // 0: as many digits as the number has; else 1..kMaxFrameWidth
  bool zero_pad = false;      // padded with '0' (%03d), else with ' ' (%3d)
  bool given = false;

  std::string name(int frame) const;
};

inline constexpr int kMaxFrameWidth = 16;

// Exactly one integer conversion, %d, %i or %u, with an optional '0' flag and a width of
// 1..kMaxFrameWidth; "%%" for a '%'; nothing else printf-like (no other flag, precision, length
// or conversion). False with `why` the hint of the option's error message.
bool parse_frame_pattern(std::string_view text, FramePattern& out, std::string& why);

}  // namespace lr::host
