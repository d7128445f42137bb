// Pixel formats of strip buffers: a template parameter of the renderer and the display path.
//
// Each format says how one pixel is stored (Storage), how many bytes it puts on the wire and
// how an 8-bit colour becomes a stored pixel. Conversion to RGB565 rounds to nearest
// (r5 = (31 r8 + 127) / 255: docs/numerics.md#colour-conversions) through tables built at
// compile time.
#pragma once

#include <array>
#include <bit>
#include <cstdint>

#include "core/output/color.hpp"

namespace lr {

namespace detail {
template <unsigned kMax>
consteval std::array<uint8_t, 256> make_reduce_table() {
  std::array<uint8_t, 256> t{};
  for (unsigned v = 0; v < 256; ++v) t[v] = static_cast<uint8_t>((kMax * v + 127u) / 255u);
  return t;
}
inline constexpr std::array<uint8_t, 256> kTo5 = make_reduce_table<31>();
inline constexpr std::array<uint8_t, 256> kTo6 = make_reduce_table<63>();
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
    return from_value((unsigned{detail::kTo5[c.r]} << 11) | (unsigned{detail::kTo6[c.g]} << 5) |
                      detail::kTo5[c.b]);
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
  static constexpr Rgb8 decode(Storage s) { return s; }
};

}  // namespace lr
