// Pixel formats of strip buffers: a template parameter of the renderer and the display path.
//
// Each format says how one pixel is stored (Storage), how many bytes it puts on the wire and
// how an 8-bit colour becomes a stored pixel. Rgb565Be is the SPI panels' (hal/); Rgb565 and
// Xrgb8888 are those of frame buffers and GUI canvases (core/output/frame_buffer_sink.hpp,
// docs/framebuffer.md); Rgb888 is the host tools'. Conversion to RGB565 rounds to nearest
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

// Whether RGB565 conversion reads kTo565 (a load a channel) or computes its entry (a multiply
// and four additions and shifts a channel, no division: div255): the arithmetic where the code
// is built for size, which leaves the 512-byte table out of the image. The same values (checked
// below).
#if defined(__OPTIMIZE_SIZE__)
inline constexpr bool kReduceByTable = false;
#else
inline constexpr bool kReduceByTable = true;
#endif
// x / 255 for x below 2^16 - 1 (checked below), without a division (a library call on
// Armv6-M).
constexpr unsigned div255(unsigned x) {
  return (x + (x >> 8) + 1u) >> 8;
}
// An 8-bit channel v (0..255) to kMax (31 or 63) levels, rounded to nearest: kTo565's entry.
template <unsigned kMax>
constexpr unsigned reduce8(unsigned v) {
  if constexpr (kReduceByTable)
    return kTo565[(kMax == 63 ? kTo6Offset : 0) + v];
  else
    return div255(kMax * v + 127u);  // kMax v + 127 below 2^14
}
consteval bool reduce_matches_table() {
  for (unsigned x = 0; x < (1u << 16) - 1; ++x)
    if (div255(x) != x / 255u) return false;
  for (unsigned v = 0; v < 256; ++v)
    if (reduce8<31>(v) != kTo565[v] || reduce8<63>(v) != kTo565[kTo6Offset + v]) return false;
  return true;
}
static_assert(reduce_matches_table());

// The RGB565 formats: the 16-bit value r5 << 11 | g6 << 5 | b5, stored in the CPU's byte order
// (kWireOrder false) or with its high byte first in memory on any CPU (kWireOrder true).
template <bool kWireOrder>
struct Rgb565Format {
  using Storage = uint16_t;
  static constexpr int kBytesPerPixel = 2;
  // The stored pixel of an RGB565 value v (0..65535).
  static constexpr Storage from_value(unsigned v) {
    if constexpr (kWireOrder && std::endian::native == std::endian::little) {
      return static_cast<Storage>(((v & 0xFFu) << 8) | ((v >> 8) & 0xFFu));
    } else {
      return static_cast<Storage>(v);
    }
  }
  static constexpr unsigned to_value(Storage s) { return from_value(s); }  // a swap is its inverse
  static constexpr Storage encode(Rgb8 c) {
    return from_value((reduce8<31>(c.r) << 11) | (reduce8<63>(c.g) << 5) | reduce8<31>(c.b));
  }
  // encode(Rgb8{to_byte(r15), to_byte(g15), to_byte(b15)}) for Q1.15 channels in [0, 1].
  static constexpr Storage encode15(uint32_t r15, uint32_t g15, uint32_t b15) {
    return from_value((level15<31>(r15) << 11) | (level15<63>(g15) << 5) | level15<31>(b15));
  }
  // A Q1.15 channel c (0..1) to kMax levels: reduce8<kMax>(to_byte(c)). From the table, the
  // 6-bit part's offset is folded into to_byte's rounding constant: one table address for all
  // three channels, no addition.
  template <unsigned kMax>
  static constexpr unsigned level15(uint32_t c) {
    constexpr uint32_t kRound = Color15::kOne / 2;
    if constexpr (kReduceByTable) {
      constexpr uint32_t kOffset = (kMax == 63 ? kTo6Offset : 0) << Color15::kFracBits;
      return kTo565[(c * 255u + kRound + kOffset) >> Color15::kFracBits];
    } else {
      return reduce8<kMax>((c * 255u + kRound) >> Color15::kFracBits);
    }
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
}  // namespace detail

// RGB565 stored big-endian (the byte order on the SPI wire): the first byte in memory is the
// high byte on any CPU, so a strip can go out by DMA as it is. LVGL's RGB565_SWAPPED
// (LV_COLOR_16_SWAP 1 in LVGL 8).
struct Rgb565Be : detail::Rgb565Format<true> {};

// RGB565 in the CPU's byte order: a uint16_t holding r5 << 11 | g6 << 5 | b5, low byte first in
// memory on a little-endian CPU (Cortex-M, x86, RISC-V). What frame buffers and canvases hold:
// LVGL's LV_COLOR_FORMAT_RGB565 (LVGL 8: LV_COLOR_16_SWAP 0), Adafruit_GFX's GFXcanvas16,
// the STM32 LTDC's and DMA2D's RGB565 (docs/framebuffer.md). Rgb565Be byte-swapped on such a CPU.
struct Rgb565 : detail::Rgb565Format<false> {};

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

// 32-bit XRGB: a uint32_t holding 0xFFRRGGBB in the CPU's byte order, so that memory holds B, G,
// R, 0xFF on a little-endian CPU: there, what LVGL's LV_COLOR_FORMAT_XRGB8888 holds
// (lv_canvas_set_px writes 0xFF in its unused byte) and Linux's DRM_FORMAT_XRGB8888 (defined
// little-endian). The unused byte is 0xFF, not 0, so that a reader that takes it for alpha
// (LVGL's ARGB8888, the STM32 LTDC's ARGB8888, DRM_FORMAT_ARGB8888) sees an opaque pixel.
// Channels are Rgb888's bytes: no rounding beyond to_byte's.
struct Xrgb8888 {
  using Storage = uint32_t;
  static constexpr int kBytesPerPixel = 4;
  static constexpr Storage kOpaque = 0xFF000000u;  // the unused (alpha) byte: 0xFF
  static constexpr Storage encode(Rgb8 c) {
    return kOpaque | (Storage{c.r} << 16) | (Storage{c.g} << 8) | c.b;
  }
  static constexpr Storage encode15(uint32_t r15, uint32_t g15, uint32_t b15) {
    return encode({to_byte(r15), to_byte(g15), to_byte(b15)});
  }
  // The colour of a stored pixel; the unused byte is ignored.
  static constexpr Rgb8 decode(Storage s) {
    return {static_cast<uint8_t>(s >> 16), static_cast<uint8_t>(s >> 8), static_cast<uint8_t>(s)};
  }
};

}  // namespace lr
