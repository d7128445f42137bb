// The panel emulator on hand-written byte streams: the address window and its auto-increment,
// MADCTL (every MY/MX/MV combination, each rotation on the common modules with their known
// offsets), BGR, inversion, sleep and display off, pixel formats, chip-select pauses, malformed
// streams and timing; then EmulatorBus (transactions, deferred transfers, misuse).
#include "lineraster/host_sim/emulator/panel_emulator.hpp"

#include <gtest/gtest.h>

#include <initializer_list>
#include <vector>

#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/host_sim/emulator/emulator_bus.hpp"

namespace {

using lr::Controller;
using lr::PanelConfig;
using lr::Rotation;
using lr::host::EmulatorBus;
using lr::host::ImageRgb8;
using lr::host::PanelEmulator;
using lr::host::PanelIssue;

constexpr uint8_t kSwreset = 0x01, kSlpin = 0x10, kSlpout = 0x11, kPtlon = 0x12, kNoron = 0x13,
                  kInvon = 0x21, kDispoff = 0x28, kDispon = 0x29, kCaset = 0x2A, kRaset = 0x2B,
                  kRamwr = 0x2C, kPtlar = 0x30, kMadctl = 0x36, kIdmon = 0x39, kColmod = 0x3A,
                  kRamwrc = 0x3C;
constexpr uint8_t kMY = 0x80, kMX = 0x40, kMV = 0x20, kBGR = 0x08;

// A command with its parameters in one chip-select frame.
void cmd(PanelEmulator& p, uint8_t c, std::initializer_list<uint8_t> params = {}) {
  p.command(c);
  const std::vector<uint8_t> v(params);
  p.data(v);
  p.cs_release();
}

std::vector<uint8_t> be_bytes(const std::vector<uint16_t>& px) {
  std::vector<uint8_t> out;
  for (uint16_t v : px) {
    out.push_back(static_cast<uint8_t>(v >> 8));
    out.push_back(static_cast<uint8_t>(v & 0xFF));
  }
  return out;
}

void window(PanelEmulator& p, int x0, int x1, int y0, int y1) {
  cmd(p, kCaset, {uint8_t(x0 >> 8), uint8_t(x0 & 0xFF), uint8_t(x1 >> 8), uint8_t(x1 & 0xFF)});
  cmd(p, kRaset, {uint8_t(y0 >> 8), uint8_t(y0 & 0xFF), uint8_t(y1 >> 8), uint8_t(y1 & 0xFF)});
}

void write(PanelEmulator& p, const std::vector<uint16_t>& px, uint8_t c = kRamwr) {
  p.command(c);
  p.data(be_bytes(px));
  p.cs_release();
}

// The start-up every driver does, with the datasheets' delays: reset pulse, 120 ms, SLPOUT,
// 120 ms, RGB565, MADCTL, display on.
void start(PanelEmulator& p, uint8_t madctl = 0) {
  p.set_reset(true);
  p.advance_ms(1);
  p.set_reset(false);
  p.advance_ms(120);
  cmd(p, kSlpout);
  p.advance_ms(120);
  cmd(p, kColmod, {0x55});
  cmd(p, kMadctl, {madctl});
  cmd(p, kDispon);
}

lr::Rgb8 px_at(const ImageRgb8& img, int x, int y) {
  const size_t i = (size_t(y) * size_t(img.width) + size_t(x)) * 3;
  return {img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]};
}

lr::Rgb8 decode(uint16_t v) {
  return lr::Rgb565Be::decode(lr::Rgb565Be::from_value(v));
}

// A test pattern where every pixel differs from its neighbours.
uint16_t pattern(int x, int y) {
  return static_cast<uint16_t>((x * 131 + y * 7919 + 12345) & 0xFFFF);
}

bool all_black(const ImageRgb8& img) {
  for (uint8_t b : img.rgb)
    if (b) return false;
  return true;
}

TEST(PanelEmulator, PowerOnRamIsNoiseAndTheGlassIsDark) {
  PanelEmulator p(lr::st7789_240x320());
  EXPECT_TRUE(p.state().sleeping);
  EXPECT_FALSE(p.state().display_on);
  EXPECT_EQ(p.state().colmod, 0x66);
  const ImageRgb8 img = p.image();
  EXPECT_EQ(img.width, 240);
  EXPECT_EQ(img.height, 320);
  EXPECT_TRUE(all_black(img));
  int distinct = 0;
  for (int c = 1; c < 100; ++c) distinct += p.ram(c, 5) != p.ram(c - 1, 5);
  EXPECT_GT(distinct, 90);
}

TEST(PanelEmulator, WindowAutoIncrementsColumnsFirstAndWrapsToTheWindowStart) {
  PanelEmulator p(lr::st7789_240x320());
  start(p);
  window(p, 10, 12, 20, 21);
  write(p, {1, 2, 3, 4, 5, 6, 7, 8});  // 6 fit; 7 and 8 wrap to the start
  EXPECT_EQ(p.ram(10, 20), 7);
  EXPECT_EQ(p.ram(11, 20), 8);
  EXPECT_EQ(p.ram(12, 20), 3);
  EXPECT_EQ(p.ram(10, 21), 4);
  EXPECT_EQ(p.ram(11, 21), 5);
  EXPECT_EQ(p.ram(12, 21), 6);
  ASSERT_EQ(p.count(PanelIssue::kWindowOverflow), 1u);
  EXPECT_EQ(p.diagnostics().back().count, 2u);
  EXPECT_EQ(p.counters().pixels_stored, 8u);

  // RAMWR starts over at (XS, YS); RAMWRC continues after the last pixel written.
  write(p, {100, 101});
  write(p, {102, 103}, kRamwrc);
  EXPECT_EQ(p.ram(10, 20), 100);
  EXPECT_EQ(p.ram(11, 20), 101);
  EXPECT_EQ(p.ram(12, 20), 102);
  EXPECT_EQ(p.ram(10, 21), 103);
  EXPECT_EQ(p.count(PanelIssue::kWindowOverflow), 1u);

  // The DCS reading: pixels past the window are ignored.
  PanelEmulator::Options o;
  o.wrap_past_window_end = false;
  PanelEmulator q(lr::st7789_240x320(), o);
  start(q);
  window(q, 0, 1, 0, 0);
  write(q, {1, 2, 3});
  EXPECT_EQ(q.ram(0, 0), 1);
  EXPECT_EQ(q.ram(1, 0), 2);
  EXPECT_EQ(q.counters().pixels_dropped, 1u);
}

TEST(PanelEmulator, MadctlMapsTheCountersToRamAsTheDatasheetTableSays) {
  // Host address (x, y) = (1, 2), then (2, 2): column and row of each in RAM.
  struct Case {
    uint8_t madctl;
    int c0, r0, c1, r1;
  };
  const Case cases[] = {
      {0, 1, 2, 2, 2},
      {kMY, 1, 317, 2, 317},
      {kMX, 238, 2, 237, 2},
      {kMX | kMY, 238, 317, 237, 317},
      {kMV, 2, 1, 2, 2},
      {kMV | kMY, 2, 318, 2, 317},
      {kMV | kMX, 237, 1, 237, 2},
      {kMV | kMX | kMY, 237, 318, 237, 317},
  };
  for (const Case& c : cases) {
    PanelEmulator p(lr::st7789_240x320());
    start(p, c.madctl);
    window(p, 1, 2, 2, 2);
    write(p, {0xAAAA, 0x5555});
    EXPECT_EQ(p.ram(c.c0, c.r0), 0xAAAA) << int(c.madctl);
    EXPECT_EQ(p.ram(c.c1, c.r1), 0x5555) << int(c.madctl);
    EXPECT_EQ(p.errors(), 0u) << p.report();
  }
  // ML and MH change the refresh order only.
  PanelEmulator p(lr::st7789_240x320());
  start(p, 0x10 | 0x04);
  window(p, 1, 1, 2, 2);
  write(p, {0x1234});
  EXPECT_EQ(p.ram(1, 2), 0x1234);
}

// Writes `img` (image_width x image_height, row-major) the way every driver for these
// controllers does: MADCTL for the rotation (ST7789 glass: 0, MX|MV, MX|MY, MY|MV; ILI9341 glass
// with MX flipped), BGR when the glass is BGR, and the window at the module's offset.
void driver_write(PanelEmulator& p, const PanelConfig& cfg, int off_x, int off_y,
                  const std::vector<uint16_t>& img) {
  uint8_t m = 0;
  switch (cfg.rotation) {
    case Rotation::k0:
      m = 0;
      break;
    case Rotation::k90:
      m = kMX | kMV;
      break;
    case Rotation::k180:
      m = kMX | kMY;
      break;
    case Rotation::k270:
      m = kMY | kMV;
      break;
  }
  if (cfg.controller == Controller::kIli9341) m ^= kMX;
  if (cfg.bgr) m |= kBGR;
  start(p, m);
  if (cfg.invert) cmd(p, kInvon);
  window(p, off_x, off_x + cfg.image_width() - 1, off_y, off_y + cfg.image_height() - 1);
  write(p, img);
}

// The offsets the known drivers use for these modules (TFT_eSPI, Adafruit_ST7789): the 240x240
// module's visible rows are 0..239, so rotations that mirror rows start at row 80; the 135x240
// module sits at column 52, row 40 (53 from the other side).
TEST(PanelEmulator, EveryRotationOfTheCommonModulesShowsTheImageUpright) {
  struct Case {
    PanelConfig cfg;
    int off_x, off_y;
  };
  const Case cases[] = {
      {lr::st7789_240x320(Rotation::k0), 0, 0},     {lr::st7789_240x320(Rotation::k90), 0, 0},
      {lr::st7789_240x320(Rotation::k180), 0, 0},   {lr::st7789_240x320(Rotation::k270), 0, 0},
      {lr::st7789_240x240(Rotation::k0), 0, 0},     {lr::st7789_240x240(Rotation::k90), 0, 0},
      {lr::st7789_240x240(Rotation::k180), 0, 80},  {lr::st7789_240x240(Rotation::k270), 80, 0},
      {lr::st7789_135x240(Rotation::k0), 52, 40},   {lr::st7789_135x240(Rotation::k90), 40, 53},
      {lr::st7789_135x240(Rotation::k180), 53, 40}, {lr::st7789_135x240(Rotation::k270), 40, 52},
      {lr::ili9341_240x320(Rotation::k0), 0, 0},    {lr::ili9341_240x320(Rotation::k90), 0, 0},
      {lr::ili9341_240x320(Rotation::k180), 0, 0},  {lr::ili9341_240x320(Rotation::k270), 0, 0},
  };
  for (const Case& c : cases) {
    const int w = c.cfg.image_width(), h = c.cfg.image_height();
    std::vector<uint16_t> img(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) img[size_t(y) * size_t(w) + size_t(x)] = pattern(x, y);
    PanelEmulator p(c.cfg);
    driver_write(p, c.cfg, c.off_x, c.off_y, img);
    const ImageRgb8 shown = p.image();
    ASSERT_EQ(shown.width, w);
    ASSERT_EQ(shown.height, h);
    int wrong = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        wrong += !(px_at(shown, x, y) == decode(img[size_t(y) * size_t(w) + size_t(x)]));
    EXPECT_EQ(wrong, 0) << c.cfg.width << "x" << c.cfg.height << " rotation "
                        << int(c.cfg.rotation) * 90;
    EXPECT_EQ(p.errors(), 0u) << p.report();
  }
}

TEST(PanelEmulator, OneOffsetOffShowsNoiseAtTheEdge) {
  // 240x240 at 180 with the rotation-0 offset (row 0 instead of 80): the image lands in RAM rows
  // 80..319, a third of it below the glass, and the rows it never reached show noise.
  const PanelConfig cfg = lr::st7789_240x240(Rotation::k180);
  std::vector<uint16_t> img(240 * 240, 0xFFFF);
  PanelEmulator p(cfg);
  driver_write(p, cfg, 0, 0, img);
  const ImageRgb8 shown = p.image();
  EXPECT_EQ(px_at(shown, 10, 10), (lr::Rgb8{255, 255, 255}));        // RAM rows 80..239
  EXPECT_FALSE(px_at(shown, 10, 200) == (lr::Rgb8{255, 255, 255}));  // rows 0..79: noise
}

TEST(PanelEmulator, VisibleWindowOfThe240And135Modules) {
  for (const PanelConfig& cfg : {lr::st7789_240x240(), lr::st7789_135x240()}) {
    PanelEmulator p(cfg);
    start(p);
    cmd(p, kInvon);  // these IPS modules show true colours with INVON
    window(p, 0, 239, 0, 319);
    std::vector<uint16_t> ram(240 * 320);
    for (int r = 0; r < 320; ++r)
      for (int c = 0; c < 240; ++c) ram[size_t(r) * 240 + size_t(c)] = pattern(c, r);
    write(p, ram);
    const ImageRgb8 img = p.image();
    ASSERT_EQ(img.width, cfg.width);
    ASSERT_EQ(img.height, cfg.height);
    EXPECT_EQ(px_at(img, 0, 0), decode(pattern(cfg.col_offset, cfg.row_offset)));
    EXPECT_EQ(px_at(img, cfg.width - 1, cfg.height - 1),
              decode(pattern(cfg.col_offset + cfg.width - 1, cfg.row_offset + cfg.height - 1)));
    EXPECT_EQ(px_at(img, 7, 9), decode(pattern(cfg.col_offset + 7, cfg.row_offset + 9)));
  }
}

TEST(PanelEmulator, IliGlassIsMirroredAndDisctrlSsReversesIt) {
  const PanelConfig cfg = lr::ili9341_240x320();
  PanelEmulator p(cfg);
  start(p, kBGR);  // no MX: the image comes out mirrored on this glass
  window(p, 0, 0, 0, 0);
  write(p, {0xF800});  // red at host (0, 0)
  EXPECT_EQ(p.ram(0, 0), 0xF800);
  EXPECT_EQ(px_at(p.image(), 239, 0), (lr::Rgb8{255, 0, 0}));
  cmd(p, 0xB6, {0x0A, 0xA2, 0x27, 0x00});  // DISCTRL with SS = 1: the source scan reversed
  EXPECT_TRUE(p.state().source_reversed);
  EXPECT_EQ(px_at(p.image(), 0, 0), (lr::Rgb8{255, 0, 0}));
  // An ST7789 module's glass is not mirrored; the option overrides either.
  PanelEmulator::Options o;
  o.mirrored_glass = false;
  PanelEmulator q(cfg, o);
  start(q, kBGR);
  window(q, 0, 0, 0, 0);
  write(q, {0xF800});
  EXPECT_EQ(px_at(q.image(), 0, 0), (lr::Rgb8{255, 0, 0}));
}

TEST(PanelEmulator, BgrAndInversionAgainstTheGlass) {
  // ST7789 240x320: RGB glass, not inverted (PanelConfig says invert; use a plain config).
  PanelConfig rgb = lr::st7789_240x320();
  rgb.invert = false;
  PanelEmulator p(rgb);
  start(p);
  window(p, 0, 0, 0, 0);
  write(p, {0xF800});
  EXPECT_EQ(px_at(p.image(), 0, 0), (lr::Rgb8{255, 0, 0}));
  cmd(p, kMadctl, {kBGR});  // BGR on an RGB glass: red and blue swap
  EXPECT_EQ(px_at(p.image(), 0, 0), (lr::Rgb8{0, 0, 255}));
  cmd(p, kMadctl, {0});
  cmd(p, kInvon);
  EXPECT_EQ(px_at(p.image(), 0, 0), (lr::Rgb8{0, 255, 255}));
  cmd(p, 0x20);  // INVOFF
  EXPECT_EQ(px_at(p.image(), 0, 0), (lr::Rgb8{255, 0, 0}));

  // An IPS module (invert = true) shows inverted colours until INVON.
  PanelEmulator ips(lr::st7789_240x240());
  start(ips);
  window(ips, 0, 0, 0, 0);
  write(ips, {0x07E0});
  EXPECT_EQ(px_at(ips.image(), 0, 0), (lr::Rgb8{255, 0, 255}));
  cmd(ips, kInvon);
  EXPECT_EQ(px_at(ips.image(), 0, 0), (lr::Rgb8{0, 255, 0}));

  // ILI9341: BGR glass; true colours need MADCTL's BGR.
  PanelEmulator ili(lr::ili9341_240x320());
  start(ili, kMX);
  window(ili, 0, 0, 0, 0);
  write(ili, {0xF800});
  EXPECT_EQ(px_at(ili.image(), 0, 0), (lr::Rgb8{0, 0, 255}));
  cmd(ili, kMadctl, {kMX | kBGR});
  EXPECT_EQ(px_at(ili.image(), 0, 0), (lr::Rgb8{255, 0, 0}));
}

TEST(PanelEmulator, SleepAndDisplayOffShowBlackAndKeepTheRam) {
  PanelConfig cfg = lr::st7789_240x320();
  cfg.invert = false;
  PanelEmulator p(cfg);
  start(p);
  window(p, 0, 0, 0, 0);
  write(p, {0xFFFF});
  EXPECT_EQ(px_at(p.image(), 0, 0), (lr::Rgb8{255, 255, 255}));
  cmd(p, kDispoff);
  EXPECT_TRUE(all_black(p.image()));
  cmd(p, kDispon);
  EXPECT_EQ(px_at(p.image(), 0, 0), (lr::Rgb8{255, 255, 255}));
  cmd(p, kSlpin);
  EXPECT_TRUE(all_black(p.image()));
  p.advance_ms(120);
  // RAM writes in sleep mode work (only the interface and memory are powered): a note, no error.
  window(p, 0, 0, 0, 0);
  write(p, {0x001F});
  EXPECT_EQ(p.ram(0, 0), 0x001F);
  EXPECT_EQ(p.count(PanelIssue::kWriteWhileAsleep), 1u);
  EXPECT_EQ(p.errors(), 0u) << p.report();
  cmd(p, kSlpout);
  p.advance_ms(5);
  EXPECT_EQ(px_at(p.image(), 0, 0), (lr::Rgb8{0, 0, 255}));
  // SWRESET: asleep and off again, RAM and MADCTL / COLMOD kept; the reset line resets those.
  p.advance_ms(120);
  cmd(p, kMadctl, {kMX});
  cmd(p, kSwreset);
  EXPECT_TRUE(p.state().sleeping);
  EXPECT_FALSE(p.state().display_on);
  EXPECT_EQ(p.state().madctl, kMX);
  EXPECT_EQ(p.state().colmod, 0x55);
  EXPECT_EQ(p.ram(0, 0), 0x001F);
  p.set_reset(true);
  p.advance_ms(1);
  p.set_reset(false);
  EXPECT_EQ(p.state().madctl, 0);
  EXPECT_EQ(p.state().colmod, 0x66);
  EXPECT_EQ(p.ram(0, 0), 0x001F);
  EXPECT_EQ(p.errors(), 0u) << p.report();
}

TEST(PanelEmulator, IdleAndPartialModes) {
  PanelConfig cfg = lr::st7789_240x320();
  cfg.invert = false;
  PanelEmulator p(cfg);
  start(p);
  window(p, 0, 0, 0, 1);
  write(p, {lr::Rgb565Be::to_value(lr::Rgb565Be::encode({200, 100, 30})), 0xFFFF});
  cmd(p, kIdmon);  // 8 colours: each channel's top bit
  EXPECT_EQ(px_at(p.image(), 0, 0), (lr::Rgb8{255, 0, 0}));
  cmd(p, 0x38);
  cmd(p, kPtlar, {0, 1, 0, 10});  // rows 1..10
  cmd(p, kPtlon);
  EXPECT_EQ(px_at(p.image(), 0, 0), (lr::Rgb8{0, 0, 0}));
  EXPECT_EQ(px_at(p.image(), 0, 1), (lr::Rgb8{255, 255, 255}));
  cmd(p, kNoron);
  EXPECT_EQ(px_at(p.image(), 0, 0),
            decode(lr::Rgb565Be::to_value(lr::Rgb565Be::encode({200, 100, 30}))));
}

TEST(PanelEmulator, PixelFormatsAndByteOrder) {
  PanelEmulator p(lr::st7789_240x320());
  start(p);
  cmd(p, kColmod, {0x66});  // 18 bits: three bytes per pixel, 6 bits each at the top
  window(p, 0, 1, 0, 0);
  p.command(kRamwr);
  p.data(std::vector<uint8_t>{0xFC, 0x00, 0x00, 0x00, 0x00, 0xFC});
  EXPECT_EQ(p.ram(0, 0), 0xF800);
  EXPECT_EQ(p.ram(1, 0), 0x001F);
  EXPECT_EQ(p.count(PanelIssue::kPixelFormat), 1u);
  cmd(p, kColmod, {0x53});  // 12 bits: three bytes for two pixels
  p.command(kRamwr);
  p.data(std::vector<uint8_t>{0xF0, 0x00, 0x0F});
  EXPECT_EQ(p.ram(0, 0), 0xF800);
  EXPECT_EQ(p.ram(1, 0), 0x001F);
  // ST7789 RAMCTRL ENDIAN: little-endian 16-bit pixels.
  cmd(p, kColmod, {0x55});
  cmd(p, 0xB0, {0x00, 0xF8});
  EXPECT_TRUE(p.state().little_endian);
  p.command(kRamwr);
  p.data(std::vector<uint8_t>{0x34, 0x12});
  EXPECT_EQ(p.ram(0, 0), 0x1234);
  // The reset default, 18 bits, with 16-bit data: the pixels come out wrong (as on the glass).
  PanelEmulator q(lr::st7789_240x320());
  q.set_reset(true);
  q.advance_ms(1);
  q.set_reset(false);
  q.advance_ms(120);
  window(q, 0, 0, 0, 0);
  write(q, {0xF800});
  EXPECT_NE(q.ram(0, 0), 0xF800);
  EXPECT_EQ(q.count(PanelIssue::kPixelFormat), 1u);
  EXPECT_EQ(q.count(PanelIssue::kIncompletePixel), 0u);  // not yet: the write goes on
  cmd(q, 0x00);
  EXPECT_EQ(q.count(PanelIssue::kIncompletePixel), 1u);  // 2 bytes of a 3-byte pixel dropped
}

TEST(PanelEmulator, ChipSelectPausesAWriteInsideAPixel) {
  PanelEmulator p(lr::st7789_240x320());
  start(p);
  window(p, 5, 6, 0, 0);
  p.command(kRamwr);
  p.data(std::vector<uint8_t>{0x12});
  p.cs_release();
  p.data(std::vector<uint8_t>{0x34, 0x56});
  p.cs_release();
  p.data(std::vector<uint8_t>{0x78});
  p.cs_release();
  EXPECT_EQ(p.ram(5, 0), 0x1234);
  EXPECT_EQ(p.ram(6, 0), 0x5678);
  EXPECT_EQ(p.errors(), 0u) << p.report();
  EXPECT_EQ(p.counters().cs_releases, 4u + 2u + 3u);  // start(): 4 commands, window: 2
}

TEST(PanelEmulator, MalformedStreamsAreIgnoredAsTheControllerDoesAndReported) {
  PanelEmulator p(lr::st7789_240x320());
  // Data before any command (after the reset): ignored.
  p.set_reset(true);
  p.advance_ms(1);
  p.set_reset(false);
  p.data(std::vector<uint8_t>{1, 2, 3});
  ASSERT_EQ(p.count(PanelIssue::kDataBeforeCommand), 1u);
  EXPECT_EQ(p.diagnostics().back().count, 3u);
  p.advance_ms(120);
  cmd(p, kSlpout);
  p.advance_ms(120);
  cmd(p, kColmod, {0x55});
  cmd(p, kDispon);
  // Parameters beyond what a command takes: ignored.
  cmd(p, kMadctl, {kMX, kMY});
  EXPECT_EQ(p.state().madctl, kMX);
  ASSERT_EQ(p.count(PanelIssue::kExtraParameters), 1u);
  EXPECT_EQ(p.diagnostics().back().command, kMadctl);
  cmd(p, kMadctl, {0});
  // A command cut short: what arrived is taken, the rest keeps its value.
  cmd(p, kCaset, {0, 7});
  cmd(p, kRaset, {0, 0, 0, 0});
  EXPECT_EQ(p.state().xs, 7);
  EXPECT_EQ(p.state().xe, 239);
  EXPECT_EQ(p.count(PanelIssue::kMissingParameters), 1u);
  // Unknown command (0xEF is in many ILI9341 init tables but in neither datasheet): a NOP.
  cmd(p, 0xEF, {0x03, 0x80, 0x02});
  EXPECT_EQ(p.count(PanelIssue::kUnknownCommand), 1u);
  EXPECT_EQ(p.count(PanelIssue::kExtraParameters), 2u);
  // A window past the RAM: pixels outside ignored, the counter runs on.
  window(p, 238, 241, 0, 0);
  write(p, {1, 2, 3, 4});
  EXPECT_EQ(p.ram(238, 0), 1);
  EXPECT_EQ(p.ram(239, 0), 2);
  ASSERT_EQ(p.count(PanelIssue::kWindowOutsideRam), 1u);
  EXPECT_EQ(p.diagnostics().back().count, 2u);
  // The same window is fine with MV (320 columns).
  cmd(p, kMadctl, {kMV});
  window(p, 318, 319, 0, 0);
  write(p, {9, 10});
  EXPECT_EQ(p.ram(0, 318), 9);
  EXPECT_EQ(p.ram(0, 319), 10);
  EXPECT_EQ(p.count(PanelIssue::kWindowOutsideRam), 1u);
  cmd(p, kMadctl, {0});
  // Start after end: undefined; nothing written.
  const uint16_t before = p.ram(20, 0);
  window(p, 20, 10, 0, 0);
  write(p, {0xBEEF});
  EXPECT_EQ(p.ram(20, 0), before);
  EXPECT_EQ(p.count(PanelIssue::kWindowStartAfterEnd), 1u);
  // An odd byte at the end of a write.
  window(p, 0, 0, 0, 0);
  p.command(kRamwr);
  p.data(std::vector<uint8_t>{0xAB});
  cmd(p, 0x00);
  EXPECT_EQ(p.count(PanelIssue::kIncompletePixel), 1u);
  // A read command: the bus cannot read.
  cmd(p, 0x04);
  EXPECT_EQ(p.count(PanelIssue::kReadCommand), 1u);
  // Bytes while the reset line is held: ignored.
  p.set_reset(true);
  cmd(p, kDispon);
  EXPECT_EQ(p.count(PanelIssue::kWhileInReset), 1u);
  EXPECT_EQ(p.count(PanelIssue::kTiming), 0u) << p.report();
  EXPECT_EQ(p.errors(), 10u) << p.report();
  EXPECT_NE(p.report().find("unknown command 0xEF"), std::string::npos) << p.report();
}

TEST(PanelEmulator, CommandsBeforeTheDatasheetDelaysAreTimingViolations) {
  PanelEmulator p(lr::st7789_240x320());
  p.set_reset(true);
  p.set_reset(false);  // a 0 us pulse
  cmd(p, kSwreset);    // 0 ms after the reset
  p.advance_ms(5);
  cmd(p, kSlpout);          // 5 ms after SWRESET: needs 120
  cmd(p, kColmod, {0x55});  // 0 ms after SLPOUT: needs 5
  p.advance_ms(10);
  cmd(p, kSlpin);  // 10 ms after SLPOUT: needs 120
  ASSERT_EQ(p.count(PanelIssue::kTiming), 5u) << p.report();
  const std::string r = p.report();
  EXPECT_NE(r.find("reset pulse of 0 us (needs 10 us)"), std::string::npos) << r;
  EXPECT_NE(r.find("SLPOUT 5 ms after SWRESET (needs 120 ms)"), std::string::npos) << r;
  EXPECT_NE(r.find("COLMOD 0 ms after SLPOUT (needs 5 ms)"), std::string::npos) << r;
  EXPECT_NE(r.find("SLPIN 10 ms after SLPOUT (needs 120 ms)"), std::string::npos) << r;

  PanelEmulator q(lr::ili9341_240x320());
  start(q, kMX | kBGR);
  q.advance_ms(120);
  cmd(q, kSlpin);
  q.advance_ms(120);
  cmd(q, kSlpout);
  q.advance_ms(120);
  cmd(q, kSwreset);
  q.advance_ms(120);
  cmd(q, kSlpout);
  EXPECT_EQ(q.count(PanelIssue::kTiming), 0u) << q.report();
}

TEST(EmulatorBus, FramesCommandsAndPixelsAndCountsTransactions) {
  PanelConfig cfg = lr::st7789_240x320();
  cfg.invert = false;
  PanelEmulator p(cfg);
  EmulatorBus bus(p);
  ASSERT_EQ(bus.set_reset(true), lr::Status::kOk);
  bus.delay_ms(1);
  bus.set_reset(false);
  bus.delay_ms(120);
  bus.command(kSlpout, {});
  bus.delay_ms(120);
  const uint8_t colmod = 0x55;
  bus.command(kColmod, {&colmod, 1});
  bus.command(kDispon, {});
  const uint8_t cas[] = {0, 0, 0, 1}, ras[] = {0, 0, 0, 0};
  bus.command(kCaset, cas);
  bus.command(kRaset, ras);
  bus.command(kRamwr, {});
  const std::vector<uint8_t> px = be_bytes({0xF800, 0x07E0});
  ASSERT_EQ(bus.start_pixels(px), lr::Status::kOk);
  ASSERT_EQ(bus.wait(10), lr::Status::kOk);
  EXPECT_EQ(px_at(p.image(), 0, 0), (lr::Rgb8{255, 0, 0}));
  EXPECT_EQ(px_at(p.image(), 1, 0), (lr::Rgb8{0, 255, 0}));
  const lr::host::BusTotals& t = bus.totals();
  EXPECT_EQ(t.commands, 6u);
  EXPECT_EQ(t.transactions, 6u);  // RAMWR and its pixels share one frame
  EXPECT_EQ(t.bytes, 6u + 1u + 8u + 4u);
  EXPECT_EQ(t.pixel_bytes, 4u);
  EXPECT_EQ(t.delay_ms, 241u);
  EXPECT_EQ(p.now_ns(), 241u * 1000000u);
  EXPECT_TRUE(bus.misuse().empty());
  EXPECT_EQ(p.errors(), 0u) << p.report();
  EXPECT_EQ(bus.commands(),
            (std::vector<uint8_t>{kSlpout, kColmod, kDispon, kCaset, kRaset, kRamwr}));
}

TEST(EmulatorBus, DeferredTransfersCheckTheBufferAndTheProtocol) {
  PanelEmulator p(lr::st7789_240x320());
  EmulatorBus::Options o;
  o.deferred = true;
  EmulatorBus bus(p, o);
  bus.set_reset(true);
  bus.delay_ms(1);
  bus.set_reset(false);
  bus.delay_ms(120);
  const uint8_t colmod = 0x55;
  bus.command(kColmod, {&colmod, 1});
  bus.command(kRamwr, {});
  std::vector<uint8_t> px = be_bytes({0x1111, 0x2222});
  ASSERT_EQ(bus.start_pixels(px), lr::Status::kOk);
  EXPECT_TRUE(bus.pending());
  EXPECT_EQ(p.counters().pixel_bytes, 0u);  // nothing on the wire yet
  EXPECT_EQ(bus.start_pixels(px), lr::Status::kBusy);
  px[0] = 0x99;  // touched while in flight
  ASSERT_EQ(bus.wait(10), lr::Status::kOk);
  EXPECT_EQ(p.counters().pixel_bytes, 4u);
  ASSERT_EQ(bus.misuse().size(), 2u);
  EXPECT_NE(bus.misuse()[1].find("changed while its transfer was in flight"), std::string::npos);
  // Pixels after CASET instead of RAMWR; a failed wait abandons the transfer.
  const uint8_t cas[] = {0, 0, 0, 0};
  bus.command(kCaset, cas);
  bus.start_pixels(px);
  EXPECT_EQ(bus.misuse().size(), 3u);
  bus.fail_next_wait(lr::Status::kTimeout);
  EXPECT_EQ(bus.wait(10), lr::Status::kTimeout);
  EXPECT_FALSE(bus.pending());
  EXPECT_EQ(p.counters().pixel_bytes, 4u);
}

}  // namespace
