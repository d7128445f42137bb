// Colours.
//
// Color15: linear colour, Q1.15 per channel in uint16 (32768 = 1.0). The working format of
// lighting and interpolation: channels are clamped to [0, 1] wherever GL clamps, so 32768 is
// the largest value stored; 1/32768 resolution is 128 times finer than one 8-bit level.
// Rgb8: 8 bits per channel, what the reference and host frames hold.
#pragma once

#include <array>
#include <cstdint>

namespace lr {

struct Color15 {
  static constexpr int kFracBits = 15;
  static constexpr uint16_t kOne = 1u << kFracBits;
  uint16_t r = 0, g = 0, b = 0;
  friend constexpr bool operator==(const Color15&, const Color15&) = default;
};

// Channel i (0 = r, 1 = g, 2 = b) of a colour.
constexpr uint16_t channel(const Color15& c, int i) {
  return i == 0 ? c.r : i == 1 ? c.g : c.b;
}
constexpr Color15 make_color15(const uint16_t (&v)[3]) {
  return {v[0], v[1], v[2]};
}

struct Rgb8 {
  uint8_t r = 0, g = 0, b = 0;
  friend constexpr bool operator==(const Rgb8&, const Rgb8&) = default;
};

// round(255 * c) for c in [0, 1] in Q1.15: exact for every c (255 * 32768 + 16384 < 2^24).
constexpr uint8_t to_byte(uint32_t c15) {
  return static_cast<uint8_t>((c15 * 255u + (Color15::kOne / 2)) >> Color15::kFracBits);
}

constexpr Rgb8 to_rgb8(Color15 c) {
  return {to_byte(c.r), to_byte(c.g), to_byte(c.b)};
}

// A channel value clamped to [0, 1] in Q1.15 (interpolation and rounding can step outside).
constexpr uint32_t clamp_c15(int32_t v) {
  return v < 0 ? 0u : v > Color15::kOne ? Color15::kOne : static_cast<uint32_t>(v);
}

// An 8-bit level as Q1.15, exact to rounding: v * 32768 / 255.
constexpr uint16_t from_byte(uint8_t v) {
  return static_cast<uint16_t>((uint32_t{v} * Color15::kOne + 127u) / 255u);
}

constexpr Color15 from_rgb8(Rgb8 c) {
  return {from_byte(c.r), from_byte(c.g), from_byte(c.b)};
}

// A colour given in millionths (as published material tables are), converted at compile time.
consteval uint16_t c15_from_micro(uint32_t micro) {
  return static_cast<uint16_t>((uint64_t{micro} * Color15::kOne + 500000u) / 1000000u);
}

}  // namespace lr
