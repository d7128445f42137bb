// The pixel formats (core/output/pixel_format.hpp): the memory bytes of known colours in each,
// rounding to RGB565 as docs/numerics.md states, encode15 against encode, decode; and the same
// frame (lit, textured and Phong draws) rendered in every format: Rgb565 is Rgb565Be with its
// bytes swapped on a little-endian CPU, Xrgb8888 is Rgb888 with 0xFF in the fourth byte.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/span/tex_exact_span.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"
#include "tests/support/format_scene.hpp"

namespace lr {
namespace {

constexpr bool kLittle = std::endian::native == std::endian::little;

template <class T>
std::array<uint8_t, sizeof(T)> bytes_of(const T& v) {
  std::array<uint8_t, sizeof(T)> b{};
  std::memcpy(b.data(), &v, sizeof(T));
  return b;
}

// A colour, its RGB565 value (rounded to nearest: (31 v + 127) / 255, (63 v + 127) / 255).
struct Known {
  Rgb8 c;
  uint16_t v565;
};
constexpr Known kKnown[] = {
    {{255, 0, 0}, 0xF800},     {{0, 255, 0}, 0x07E0}, {{0, 0, 255}, 0x001F},
    {{255, 255, 255}, 0xFFFF}, {{0, 0, 0}, 0x0000},   {{16, 24, 48}, 0x10C6},
    {{128, 128, 128}, 0x8410}, {{5, 2, 5}, 0x0801},  // rounded up where truncating gives 0
    {{4, 1, 4}, 0x0000},
};

TEST(PixelFormat, Rgb565IsTheValueInTheCpusByteOrder) {
  for (const Known& k : kKnown) {
    const uint16_t s = Rgb565::encode(k.c);
    EXPECT_EQ(s, k.v565);  // the uint16_t a canvas holds
    EXPECT_EQ(Rgb565::to_value(s), k.v565);
    const auto lo = static_cast<uint8_t>(k.v565 & 0xFF), hi = static_cast<uint8_t>(k.v565 >> 8);
    const std::array<uint8_t, 2> expect = kLittle ? std::array{lo, hi} : std::array{hi, lo};
    EXPECT_EQ(bytes_of(s), expect) << k.v565;
  }
}

TEST(PixelFormat, Rgb565BeIsTheValueHighByteFirst) {
  for (const Known& k : kKnown) {
    const uint16_t s = Rgb565Be::encode(k.c);
    EXPECT_EQ(Rgb565Be::to_value(s), k.v565);
    const auto lo = static_cast<uint8_t>(k.v565 & 0xFF), hi = static_cast<uint8_t>(k.v565 >> 8);
    EXPECT_EQ(bytes_of(s), (std::array{hi, lo})) << k.v565;
  }
}

TEST(PixelFormat, Xrgb8888IsOpaqueBgrxInMemory) {
  EXPECT_EQ(Xrgb8888::encode({0x12, 0x34, 0x56}), 0xFF123456u);
  const std::array<uint8_t, 4> bgrx{0x56, 0x34, 0x12, 0xFF}, xrgb{0xFF, 0x12, 0x34, 0x56};
  EXPECT_EQ(bytes_of(Xrgb8888::encode({0x12, 0x34, 0x56})), kLittle ? bgrx : xrgb);
  EXPECT_EQ(Xrgb8888::encode({0, 0, 0}), 0xFF000000u);
  EXPECT_EQ(Xrgb8888::encode({255, 255, 255}), 0xFFFFFFFFu);
  // decode ignores the fourth byte, whatever a reader wrote there.
  EXPECT_EQ(Xrgb8888::decode(0x00123456u), (Rgb8{0x12, 0x34, 0x56}));
  EXPECT_EQ(Xrgb8888::decode(0x80ABCDEFu), (Rgb8{0xAB, 0xCD, 0xEF}));
  for (uint32_t v = 0; v < 256; ++v) {
    const Rgb8 c{static_cast<uint8_t>(v), static_cast<uint8_t>(255 - v),
                 static_cast<uint8_t>(v ^ 0x5A)};
    EXPECT_EQ(Xrgb8888::decode(Xrgb8888::encode(c)), c);
  }
}

// Every byte of every channel rounds as docs/numerics.md says, and both RGB565 formats agree.
TEST(PixelFormat, Rgb565RoundsToNearestInBothByteOrders) {
  int mismatches = 0;
  for (uint32_t v = 0; v <= 255; ++v) {
    const auto b = static_cast<uint8_t>(v);
    const uint32_t r5 = (31 * v + 127) / 255, g6 = (63 * v + 127) / 255;
    for (const Rgb8 c : {Rgb8{b, 0, 0}, Rgb8{0, b, 0}, Rgb8{0, 0, b}, Rgb8{b, b, b}}) {
      const uint32_t expect = (c.r ? r5 << 11 : 0) | (c.g ? g6 << 5 : 0) | (c.b ? r5 : 0);
      mismatches += Rgb565::to_value(Rgb565::encode(c)) != expect;
      mismatches += Rgb565Be::to_value(Rgb565Be::encode(c)) != expect;
    }
  }
  EXPECT_EQ(mismatches, 0);
}

// decode expands by bit replication; the two byte orders decode every value alike.
TEST(PixelFormat, Rgb565DecodesEveryValueAsRgb565Be) {
  EXPECT_EQ(Rgb565::decode(0x10C6), (Rgb8{16, 24, 49}));
  EXPECT_EQ(Rgb565::decode(0xF800), (Rgb8{255, 0, 0}));
  EXPECT_EQ(Rgb565::decode(0x0801), (Rgb8{8, 0, 8}));
  int mismatches = 0;
  for (uint32_t v = 0; v <= 0xFFFF; ++v) {
    const uint16_t native = Rgb565::from_value(v), wire = Rgb565Be::from_value(v);
    mismatches += Rgb565::to_value(native) != v;
    mismatches += !(Rgb565::decode(native) == Rgb565Be::decode(wire));
    const auto a = bytes_of(native), b = bytes_of(wire);
    mismatches += kLittle ? (a[0] != b[1] || a[1] != b[0]) : a != b;
  }
  EXPECT_EQ(mismatches, 0);
}

// encode15 stores what encode of the rounded bytes stores, in the new formats as in the others
// (tests/core/math_test.cpp: Color.Encode15IsEncodeOfTheBytes).
TEST(PixelFormat, Encode15IsEncodeOfTheBytes) {
  int mismatches = 0;
  for (uint32_t v = 0; v <= Color15::kOne; ++v) {
    const uint8_t b = to_byte(v);
    for (uint32_t o : {0u, uint32_t{Color15::kOne}, uint32_t{Color15::kOne / 3}}) {
      const uint8_t ob = to_byte(o);
      mismatches += Rgb565::encode15(v, o, o) != Rgb565::encode({b, ob, ob});
      mismatches += Rgb565::encode15(o, v, o) != Rgb565::encode({ob, b, ob});
      mismatches += Rgb565::encode15(o, o, v) != Rgb565::encode({ob, ob, b});
      mismatches += Xrgb8888::encode15(v, o, o) != Xrgb8888::encode({b, ob, ob});
      mismatches += Xrgb8888::encode15(o, v, o) != Xrgb8888::encode({ob, b, ob});
      mismatches += Xrgb8888::encode15(o, o, v) != Xrgb8888::encode({ob, ob, b});
    }
  }
  EXPECT_EQ(mismatches, 0);
}

// A replaced RGB565 texel is stored as it is in both RGB565 formats (no decode and encode).
TEST(PixelFormat, RawTexelStoresInBothRgb565Formats) {
  EXPECT_TRUE(detail::stores_565<Rgb565>());
  EXPECT_TRUE(detail::stores_565<Rgb565Be>());
  EXPECT_FALSE(detail::stores_565<Xrgb8888>());
  EXPECT_FALSE(detail::stores_565<Rgb888>());
}

constexpr int kW = 160, kH = 120, kK = 8;

template <class PF>
struct Frame {
  std::vector<typename PF::Storage> pixels;
  FrameStats stats;
};

template <class PF>
Frame<PF> render_scene(const test::FormatScene& scene) {
  BasicFrameStorage<std::vector> store(test::format_scene_capacities(kW, kH, kK, false));
  host::CaptureDisplay<PF> display(size_t{kW} * kK);
  auto renderer = std::make_unique<Renderer<PF, kK>>();
  EXPECT_EQ(renderer->configure(store.storage(), kW, kH), Status::kOk);
  scene.build(*renderer);
  EXPECT_EQ(renderer->render(display), Status::kOk) << display.error();
  return {display.raw_frame(), renderer->stats()};
}

TEST(PixelFormat, TheSameFrameInEveryFormat) {
  const test::FormatScene scene(kW, kH);
  const Frame<Rgb565Be> be = render_scene<Rgb565Be>(scene);
  const Frame<Rgb565> native = render_scene<Rgb565>(scene);
  const Frame<Rgb888> rgb = render_scene<Rgb888>(scene);
  const Frame<Xrgb8888> xrgb = render_scene<Xrgb8888>(scene);
  const size_t n = size_t{kW} * kH;
  ASSERT_EQ(be.pixels.size(), n);
  ASSERT_EQ(native.pixels.size(), n);
  ASSERT_EQ(rgb.pixels.size(), n);
  ASSERT_EQ(xrgb.pixels.size(), n);
  // A real picture: most of the span families wrote pixels, in many colours.
  EXPECT_GT(rgb.stats.pixels_written, n / 5);
  std::vector<bool> seen(0x10000);
  size_t colours = 0;
  for (uint16_t p : native.pixels)
    if (!seen[p]) {
      seen[p] = true;
      ++colours;
    }
  EXPECT_GT(colours, 500u);

  size_t rgb565_diff = 0, rgb888_diff = 0, encoded_diff = 0;
  for (size_t i = 0; i < n; ++i) {
    const auto a = bytes_of(native.pixels[i]), b = bytes_of(be.pixels[i]);
    rgb565_diff += kLittle ? (a[0] != b[1] || a[1] != b[0]) : a != b;
    const Rgb8 c = rgb.pixels[i];
    rgb888_diff += xrgb.pixels[i] != (0xFF000000u | uint32_t{c.r} << 16 | uint32_t{c.g} << 8 | c.b);
    // Every span routine computes a colour and encodes it (a replaced RGB565 texel stored raw is
    // what encoding its expansion stores): what both RGB565 formats share is checked here.
    encoded_diff += native.pixels[i] != Rgb565::encode(c);
  }
  EXPECT_EQ(rgb565_diff, 0u) << "Rgb565 pixels that are not Rgb565Be's bytes swapped";
  EXPECT_EQ(rgb888_diff, 0u) << "Xrgb8888 pixels that are not Rgb888's";
  EXPECT_EQ(encoded_diff, 0u) << "Rgb565 pixels that are not Rgb888's encoded";
  // The format changes the pixels' bytes only: the same work.
  EXPECT_EQ(native.stats.pixels_written, be.stats.pixels_written);
  EXPECT_EQ(xrgb.stats.pixels_written, rgb.stats.pixels_written);
  EXPECT_EQ(native.stats.pixels_written, rgb.stats.pixels_written);
}

}  // namespace
}  // namespace lr
