// Pixel formats of strip buffers: a template parameter of the renderer and the display path.
//
// Each format says how one pixel is stored (Storage), how many bytes it puts on the wire and
// how an 8-bit colour becomes a stored pixel. Conversion to RGB565 rounds to nearest
// (r5 = (31 r8 + 127) / 255: docs/numerics.md#colour-conversions) through tables built at
// compile time.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>

#include "lineraster/core/output/color.hpp"

namespace lr {

namespace detail {
template <unsigned kMax>
consteval std::array<uint8_t, 256> make_reduce_table() {
  std::array<uint8_t, 256> t{};
  for (unsigned v = 0; v < 256; ++v) t[v] = static_cast<uint8_t>((kMax * v + 127u) / 255u);
  return t;
}
// The 5-bit table, then the 6-bit one: one base address for both (encode15).
consteval std::array<uint8_t, 512> make_565_table() {
  std::array<uint8_t, 512> t{};
  const auto to5 = make_reduce_table<31>(), to6 = make_reduce_table<63>();
  for (size_t v = 0; v < 256; ++v) {
    t[v] = to5[v];
    t[256 + v] = to6[v];
  }
  return t;
}
inline constexpr std::array<uint8_t, 512> kTo565 = make_565_table();
inline constexpr size_t kTo6Offset = 256;
}  // namespace detail

// RGB565 stored big-endian (the byte order on the SPI wire): the first byte in memory is the
// high byte on any CPU, so a strip can go out by DMA as it is.
struct Rgb565Be {
  using Storage = uint16_t;
  static constexpr int kBytesPerPixel = 2;
  // The stored value whose memory bytes are (v >> 8, v & 0xFF).
  static constexpr Storage from_value(unsigned v) {
    if constexpr (std::endian::native == std::endian::little) {
      return static_cast<Storage>(((v & 0xFFu) << 8) | ((v >> 8) & 0xFFu));
    } else {
      return static_cast<Storage>(v);
    }
  }
  static constexpr unsigned to_value(Storage s) { return from_value(s); }  // a swap is its inverse
  static constexpr Storage encode(Rgb8 c) {
    using detail::kTo565, detail::kTo6Offset;
    return from_value((unsigned{kTo565[c.r]} << 11) | (unsigned{kTo565[kTo6Offset + c.g]} << 5) |
                      kTo565[c.b]);
  }
  // encode(Rgb8{to_byte(r15), to_byte(g15), to_byte(b15)}) for Q1.15 channels in [0, 1]: the
  // 6-bit table's offset folded into to_byte's rounding constant, one table address.
  static constexpr Storage encode15(uint32_t r15, uint32_t g15, uint32_t b15) {
    constexpr uint32_t kRound = Color15::kOne / 2;
    constexpr uint32_t kGreen = kRound + (detail::kTo6Offset << Color15::kFracBits);
    const uint8_t* t = detail::kTo565.data();
    const unsigned r5 = t[(r15 * 255u + kRound) >> Color15::kFracBits];
    const unsigned g6 = t[(g15 * 255u + kGreen) >> Color15::kFracBits];
    const unsigned b5 = t[(b15 * 255u + kRound) >> Color15::kFracBits];
    return from_value((r5 << 11) | (g6 << 5) | b5);
  }
  // The 8-bit colour a stored pixel stands for (bit replication, as controllers expand 565).
  static constexpr Rgb8 decode(Storage s) {
    unsigned v = to_value(s);
    unsigned r5 = v >> 11, g6 = (v >> 5) & 63u, b5 = v & 31u;
    return {static_cast<uint8_t>((r5 << 3) | (r5 >> 2)),
            static_cast<uint8_t>((g6 << 2) | (g6 >> 4)),
            static_cast<uint8_t>((b5 << 3) | (b5 >> 2))};
  }
};

// 24-bit RGB, one byte per channel in R, G, B order: host frames and 18/24-bit panels.
struct Rgb888 {
  using Storage = Rgb8;
  static constexpr int kBytesPerPixel = 3;
  static constexpr Storage encode(Rgb8 c) { return c; }
  static constexpr Storage encode15(uint32_t r15, uint32_t g15, uint32_t b15) {
    return {to_byte(r15), to_byte(g15), to_byte(b15)};
  }
  static constexpr Rgb8 decode(Storage s) { return s; }
};

}  // namespace lr
