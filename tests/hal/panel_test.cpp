// The panel driver: exact start-up byte streams of both controllers, sleep / display / backlight,
// MADCTL and address windows for every module and rotation, and (through a model of the
// controller's RAM) that every rectangle of the image lands where the viewer expects it.
#include <gtest/gtest.h>

#include <vector>

#include "lineraster/hal/panel.hpp"
#include "tests/hal/recording_bus.hpp"

namespace lr {
namespace {

using test::BusEvent;
using test::caset;
using test::cmd;
using test::delay;
using test::raset;
using test::RecordingBus;

// The configs the panel_config.hpp presets describe, spelled out (so a change there shows).
static_assert(madctl_for(st7789_240x240(Rotation::k0)) == 0x00);
static_assert(madctl_for(st7789_240x240(Rotation::k90)) == 0x60);
static_assert(madctl_for(st7789_240x240(Rotation::k180)) == 0xC0);
static_assert(madctl_for(st7789_240x240(Rotation::k270)) == 0xA0);
static_assert(address_offset(st7789_240x240(Rotation::k180)) == AddressOffset{0, 80});
static_assert(address_offset(st7789_240x240(Rotation::k270)) == AddressOffset{80, 0});
static_assert(address_offset(st7789_135x240(Rotation::k0)) == AddressOffset{52, 40});
static_assert(address_offset(st7789_135x240(Rotation::k90)) == AddressOffset{40, 53});
static_assert(address_offset(st7789_135x240(Rotation::k180)) == AddressOffset{53, 40});
static_assert(address_offset(st7789_135x240(Rotation::k270)) == AddressOffset{40, 52});
static_assert(madctl_for(ili9341_240x320(Rotation::k0)) == 0x48);  // MX | BGR
static_assert(madctl_for(ili9341_320x240()) == 0x28);              // MV | BGR (rotation 90)
static_assert(valid_config(st7789_135x240()));
static_assert(!valid_config({Controller::kSt7789, 240, 240, 0, 81, Rotation::k0, false, false, 0}));
static_assert(!valid_config({Controller::kSt7789, 0, 240, 0, 0, Rotation::k0, false, false, 0}));

std::vector<BusEvent> reset_pulse() {
  return {test::reset_line(true), delay(1), test::reset_line(false), delay(120)};
}

TEST(PanelInit, St7789StreamIsExact) {
  RecordingBus bus;
  Panel panel(bus, st7789_240x240());  // IPS module: inverted
  ASSERT_EQ(panel.init(), Status::kOk);
  std::vector<BusEvent> want = reset_pulse();
  const std::vector<BusEvent> rest = {
      cmd(0x01),         delay(120),  // SWRESET, 120 ms before SLPOUT
      cmd(0x11),         delay(120),  // SLPOUT
      cmd(0x3A, {0x55}),              // COLMOD: RGB565
      cmd(0x36, {0x00}),              // MADCTL: rotation 0, RGB
      cmd(0x21),                      // INVON
      cmd(0x13),                      // NORON
      cmd(0x29),         delay(20),   // DISPON
  };
  want.insert(want.end(), rest.begin(), rest.end());
  EXPECT_EQ(bus.events, want);
  EXPECT_TRUE(bus.violations.empty());
}

TEST(PanelInit, St7789WithoutResetLineOrInversionBgrRotated) {
  RecordingBus bus;
  PanelConfig c = st7789_240x320(Rotation::k270);
  c.invert = false;
  c.bgr = true;
  Panel panel(bus, c);
  ASSERT_EQ(panel.init(false), Status::kOk);
  const std::vector<BusEvent> want = {
      cmd(0x01),  delay(120),        cmd(0x11),
      delay(120), cmd(0x3A, {0x55}), cmd(0x36, {0xA8}),  // MY | MV | BGR
      cmd(0x13),  cmd(0x29),         delay(20),
  };
  EXPECT_EQ(bus.events, want);
}

TEST(PanelInit, Ili9341StreamIsExact) {
  RecordingBus bus;
  Panel panel(bus, ili9341_240x320());
  ASSERT_EQ(panel.init(), Status::kOk);
  std::vector<BusEvent> want = reset_pulse();
  const std::vector<BusEvent> rest = {
      cmd(0x01),
      delay(120),
      cmd(0xCF, {0x00, 0xC1, 0x30}),              // power control B
      cmd(0xED, {0x64, 0x03, 0x12, 0x81}),        // power-on sequence
      cmd(0xE8, {0x85, 0x00, 0x78}),              // driver timing A
      cmd(0xCB, {0x39, 0x2C, 0x00, 0x34, 0x02}),  // power control A
      cmd(0xF7, {0x20}),                          // pump ratio
      cmd(0xEA, {0x00, 0x00}),                    // driver timing B
      cmd(0xC0, {0x23}),                          // power control 1: GVDD 4.6 V
      cmd(0xC1, {0x10}),                          // power control 2
      cmd(0xC5, {0x3E, 0x28}),                    // VCOM 1
      cmd(0xC7, {0x86}),                          // VCOM 2
      cmd(0xB1, {0x00, 0x1B}),                    // frame rate 70 Hz
      cmd(0xB6, {0x08, 0x82, 0x27, 0x00}),        // display function: 320 lines
      cmd(0xB7, {0x07}),                          // entry mode
      cmd(0xF2, {0x00}),                          // 3-gamma off
      cmd(0x26, {0x01}),                          // gamma curve 1
      cmd(0xE0, {0x0F, 0x31, 0x2B, 0x0C, 0x0E, 0x08, 0x4E, 0xF1, 0x37, 0x07, 0x10, 0x03, 0x0E, 0x09,
                 0x00}),
      cmd(0xE1, {0x00, 0x0E, 0x14, 0x03, 0x11, 0x07, 0x31, 0xC1, 0x48, 0x08, 0x0F, 0x0C, 0x31, 0x36,
                 0x0F}),
      cmd(0x11),
      delay(120),
      cmd(0x3A, {0x55}),
      cmd(0x36, {0x48}),  // MX (the glass's mirror) | BGR
      cmd(0x13),
      cmd(0x29),
      delay(20),
  };
  want.insert(want.end(), rest.begin(), rest.end());
  EXPECT_EQ(bus.events, want);
}

TEST(PanelInit, InvalidConfigSendsNothing) {
  RecordingBus bus;
  Panel panel(bus, {Controller::kSt7789, 136, 240, 105, 0, Rotation::k0, false, false, 0});
  EXPECT_EQ(panel.init(), Status::kInvalidArgument);
  EXPECT_TRUE(bus.events.empty());
  EXPECT_EQ(panel.begin_write({0, 0, 1, 1}), Status::kInvalidArgument);
  EXPECT_TRUE(bus.events.empty());
}

TEST(PanelInit, StopsAtTheFirstRefusedCommand) {
  RecordingBus bus;
  bus.command_results[2] = Status::kDisplayError;  // the 3rd command: COLMOD on the ST7789
  Panel panel(bus, st7789_240x240());
  EXPECT_EQ(panel.init(false), Status::kDisplayError);
  ASSERT_EQ(bus.commands().size(), 3u);
  EXPECT_EQ(bus.events.back().cmd, 0x3A);
  EXPECT_EQ(bus.events.back().result, Status::kDisplayError);
}

TEST(PanelPower, SleepDisplayAndBacklight) {
  RecordingBus bus;
  Panel panel(bus, st7789_240x240());
  ASSERT_EQ(panel.sleep(true), Status::kOk);
  ASSERT_EQ(panel.sleep(false), Status::kOk);
  ASSERT_EQ(panel.display_on(false), Status::kOk);
  ASSERT_EQ(panel.display_on(true), Status::kOk);
  ASSERT_EQ(panel.backlight(true), Status::kOk);
  ASSERT_EQ(panel.backlight(false), Status::kOk);
  const std::vector<BusEvent> want = {
      cmd(0x10),
      delay(120),  // SLPIN, 120 ms before SLPOUT may follow
      cmd(0x11),
      delay(120),  // SLPOUT, 120 ms before SLPIN may follow
      cmd(0x28),   // DISPOFF
      cmd(0x29),
      delay(20),  // DISPON
      test::backlight_line(true),
      test::backlight_line(false),
  };
  EXPECT_EQ(bus.events, want);
}

TEST(PanelPower, SetRotationSendsMadctlAndChangesTheEpoch) {
  RecordingBus bus;
  Panel panel(bus, st7789_135x240());
  const uint32_t e0 = panel.epoch();
  ASSERT_EQ(panel.set_rotation(Rotation::k90), Status::kOk);
  EXPECT_NE(panel.epoch(), e0);
  EXPECT_EQ(panel.image_width(), 240);
  EXPECT_EQ(panel.image_height(), 135);
  EXPECT_EQ(bus.events, std::vector<BusEvent>{cmd(0x36, {0x60})});
  EXPECT_EQ(panel.set_rotation(static_cast<Rotation>(4)), Status::kInvalidArgument);
  EXPECT_EQ(panel.config().rotation, Rotation::k90);
}

struct WindowCase {
  const char* name;
  PanelConfig config;
  uint8_t madctl;
  uint16_t x0, x1, y0, y1;  // CASET / RASET of the whole image
};

// Every module of panel_config.hpp at every rotation: MADCTL and the whole image's window.
const WindowCase kWindowCases[] = {
    {"st7789 240x240 r0", st7789_240x240(Rotation::k0), 0x00, 0, 239, 0, 239},
    {"st7789 240x240 r90", st7789_240x240(Rotation::k90), 0x60, 0, 239, 0, 239},
    {"st7789 240x240 r180", st7789_240x240(Rotation::k180), 0xC0, 0, 239, 80, 319},
    {"st7789 240x240 r270", st7789_240x240(Rotation::k270), 0xA0, 80, 319, 0, 239},
    {"st7789 240x320 r0", st7789_240x320(Rotation::k0), 0x00, 0, 239, 0, 319},
    {"st7789 240x320 r90", st7789_240x320(Rotation::k90), 0x60, 0, 319, 0, 239},
    {"st7789 240x320 r180", st7789_240x320(Rotation::k180), 0xC0, 0, 239, 0, 319},
    {"st7789 240x320 r270", st7789_240x320(Rotation::k270), 0xA0, 0, 319, 0, 239},
    {"st7789 135x240 r0", st7789_135x240(Rotation::k0), 0x00, 52, 186, 40, 279},
    {"st7789 135x240 r90", st7789_135x240(Rotation::k90), 0x60, 40, 279, 53, 187},
    {"st7789 135x240 r180", st7789_135x240(Rotation::k180), 0xC0, 53, 187, 40, 279},
    {"st7789 135x240 r270", st7789_135x240(Rotation::k270), 0xA0, 40, 279, 52, 186},
    {"ili9341 240x320 r0", ili9341_240x320(Rotation::k0), 0x48, 0, 239, 0, 319},
    {"ili9341 240x320 r90", ili9341_240x320(Rotation::k90), 0x28, 0, 319, 0, 239},
    {"ili9341 240x320 r180", ili9341_240x320(Rotation::k180), 0x88, 0, 239, 0, 319},
    {"ili9341 240x320 r270", ili9341_240x320(Rotation::k270), 0xE8, 0, 319, 0, 239},
    {"ili9341 320x240 r90", ili9341_320x240(), 0x28, 0, 319, 0, 239},
    {"ili9341 320x240 r270", ili9341_320x240(Rotation::k270), 0xE8, 0, 319, 0, 239},
};

TEST(PanelWindow, MadctlCasetRasetForEveryModuleAndRotation) {
  for (const WindowCase& wc : kWindowCases) {
    SCOPED_TRACE(wc.name);
    RecordingBus bus;
    Panel panel(bus, wc.config);
    ASSERT_EQ(panel.init(false), Status::kOk);
    bool saw_madctl = false;
    for (const BusEvent& e : bus.events)
      if (e.kind == BusEvent::Kind::kCommand && e.cmd == 0x36) {
        EXPECT_EQ(e.params, std::vector<uint8_t>{wc.madctl});
        saw_madctl = true;
      }
    EXPECT_TRUE(saw_madctl);
    bus.clear_events();
    const StripRect all{0, 0, panel.image_width(), panel.image_height()};
    ASSERT_EQ(panel.begin_write(all), Status::kOk);
    EXPECT_EQ(bus.events,
              (std::vector<BusEvent>{caset(wc.x0, wc.x1), raset(wc.y0, wc.y1), cmd(0x2C)}));
    // A strip: the same offsets, its own rows and columns.
    bus.clear_events();
    ASSERT_EQ(panel.begin_write({3, 16, 10, 8}), Status::kOk);
    EXPECT_EQ(bus.events, (std::vector<BusEvent>{caset(uint16_t(wc.x0 + 3), uint16_t(wc.x0 + 12)),
                                                 raset(uint16_t(wc.y0 + 16), uint16_t(wc.y0 + 23)),
                                                 cmd(0x2C)}));
  }
}

TEST(PanelWindow, RectanglesOutsideTheImageAreRefused) {
  RecordingBus bus;
  Panel panel(bus, st7789_135x240(Rotation::k90));  // image 240 x 135
  EXPECT_EQ(panel.begin_write({0, 0, 241, 1}), Status::kInvalidArgument);
  EXPECT_EQ(panel.begin_write({0, 128, 240, 8}), Status::kInvalidArgument);
  EXPECT_EQ(panel.begin_write({10, 10, 0, 8}), Status::kInvalidArgument);
  EXPECT_TRUE(bus.events.empty());
  EXPECT_EQ(panel.begin_write({0, 127, 240, 8}), Status::kOk);
}

uint16_t pattern(int x, int y, int seed) {
  uint32_t h = uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u ^ uint32_t(seed) * 83492791u;
  h ^= h >> 13;
  return uint16_t(h * 2654435761u >> 16);
}

// The image's pixels in wire order (RGB565 high byte first), rows of rect.width.
std::vector<uint8_t> wire_bytes(const StripRect& r, int seed) {
  std::vector<uint8_t> out;
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) {
      const uint16_t v = pattern(x, y, seed);
      out.push_back(uint8_t(v >> 8));
      out.push_back(uint8_t(v & 0xFF));
    }
  return out;
}

void write_rect(Panel& panel, RecordingBus& bus, const StripRect& r, int seed) {
  ASSERT_EQ(panel.begin_write(r), Status::kOk);
  const std::vector<uint8_t> bytes = wire_bytes(r, seed);
  ASSERT_EQ(bus.start_pixels(bytes), Status::kOk);
  ASSERT_EQ(bus.wait(10), Status::kOk);
}

// Through the RAM model: the image sent whole, or strip by strip, or a rectangle inside it,
// appears on the glass turned by the rotation, and nothing lands outside the RAM.
TEST(PanelWindow, EveryModuleAndRotationShowsTheImageUpright) {
  for (const WindowCase& wc : kWindowCases) {
    SCOPED_TRACE(wc.name);
    RecordingBus bus;
    Panel panel(bus, wc.config);
    ASSERT_EQ(panel.init(false), Status::kOk);
    const uint16_t w = panel.image_width(), h = panel.image_height();
    auto expect_view = [&](auto value_at) {
      const std::vector<uint16_t> v = test::view(bus.ram, wc.config);
      int wrong = 0;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) wrong += v[size_t(y) * w + size_t(x)] != value_at(x, y);
      EXPECT_EQ(wrong, 0);
    };
    write_rect(panel, bus, {0, 0, w, h}, 1);
    expect_view([](int x, int y) { return pattern(x, y, 1); });
    for (uint16_t y = 0; y < h; y = uint16_t(y + 8))
      write_rect(panel, bus, {0, y, w, uint16_t(std::min(8, h - y))}, 2);
    expect_view([](int x, int y) { return pattern(x, y, 2); });
    const StripRect inner{7, 5, 33, 19};
    write_rect(panel, bus, inner, 3);
    expect_view([&](int x, int y) {
      const bool in =
          x >= inner.x && x < inner.x + inner.width && y >= inner.y && y < inner.y + inner.height;
      return pattern(x, y, in ? 3 : 2);
    });
    EXPECT_EQ(bus.ram.errors(), 0);
    EXPECT_TRUE(bus.violations.empty());
  }
}

}  // namespace
}  // namespace lr
