// MIPI DBI type C panels (ST7789, ILI9341): the DCS commands both controllers share, the MADCTL
// bits, the format of the per-controller command tables, and the few helpers that put commands
// on a PanelBus.
//
// Command codes and timings are from the MIPI DCS command set as the ST7789V and ILI9341
// datasheets list them (the Linux kernel's include/video/mipi_display.h names them the same way).
//
// MADCTL (0x36) and the graphics RAM. Both controllers hold 240 columns x 320 rows. CASET (0x2A)
// sets the range of the host's x address, RASET (0x2B) that of its y address; RAMWR (0x2C) then
// fills the window x fastest. MADCTL decides where host address (x, y) lands in RAM:
//   MV (0x20) exchanges the axes first:  (c, r) = MV ? (y, x) : (x, y)
//   MX (0x40) then counts RAM columns from the other side:  column = MX ? 239 - c : c
//   MY (0x80) likewise counts RAM rows:                      row    = MY ? 319 - r : r
// (Checked against the offsets TFT_eSPI uses for the 135 x 240 ST7789 module: 52/40 at rotation 0,
// 40/53 with MX|MV; only this order of exchange and mirror gives 53.) BGR (0x08) swaps the
// colour filter order; it does not move pixels.
#pragma once

#include <array>
#include <cstdint>
#include <initializer_list>
#include <span>

#include "lineraster/core/output/status.hpp"
#include "lineraster/hal/panel_bus.hpp"

namespace lr {

namespace dcs {
inline constexpr uint8_t kNop = 0x00;
inline constexpr uint8_t kSoftReset = 0x01;    // SWRESET
inline constexpr uint8_t kSleepIn = 0x10;      // SLPIN
inline constexpr uint8_t kSleepOut = 0x11;     // SLPOUT
inline constexpr uint8_t kNormalMode = 0x13;   // NORON
inline constexpr uint8_t kInvertOff = 0x20;    // INVOFF
inline constexpr uint8_t kInvertOn = 0x21;     // INVON
inline constexpr uint8_t kGammaSet = 0x26;     // GAMSET
inline constexpr uint8_t kDisplayOff = 0x28;   // DISPOFF
inline constexpr uint8_t kDisplayOn = 0x29;    // DISPON
inline constexpr uint8_t kColumnSet = 0x2A;    // CASET: x start, x end (16-bit big-endian each)
inline constexpr uint8_t kRowSet = 0x2B;       // RASET (ILI9341: PASET): y start, y end
inline constexpr uint8_t kMemoryWrite = 0x2C;  // RAMWR: pixel data follows
inline constexpr uint8_t kAddressMode = 0x36;  // MADCTL
inline constexpr uint8_t kPixelFormat = 0x3A;  // COLMOD
// COLMOD parameter: 65K colours on the RGB interface (high nibble) and 16 bits per pixel on the
// MCU interface (low nibble), i.e. RGB565, two bytes per pixel, high byte first.
inline constexpr uint8_t kPixelFormat16 = 0x55;

// MADCTL bits.
inline constexpr uint8_t kMY = 0x80;   // row address order
inline constexpr uint8_t kMX = 0x40;   // column address order
inline constexpr uint8_t kMV = 0x20;   // row / column exchange
inline constexpr uint8_t kML = 0x10;   // vertical refresh order (no effect on addressing)
inline constexpr uint8_t kBGR = 0x08;  // BGR colour filter order
inline constexpr uint8_t kMH = 0x04;   // horizontal refresh order (no effect on addressing)
}  // namespace dcs

// One entry of a command table: a command, its parameter bytes and the wait after it.
struct PanelCommand {
  static constexpr size_t kMaxParams = 15;  // the longest: ILI9341's gamma curves
  uint8_t cmd = dcs::kNop;
  uint8_t count = 0;  // parameter bytes used
  std::array<uint8_t, kMaxParams> params{};
  uint16_t delay_ms = 0;

  constexpr std::span<const uint8_t> parameters() const { return {params.data(), count}; }
};

// A table entry from a list of parameters (more than kMaxParams does not compile).
consteval PanelCommand make_command(uint8_t cmd, std::initializer_list<uint8_t> params,
                                    uint16_t delay_ms = 0) {
  PanelCommand c;
  c.cmd = cmd;
  c.count = static_cast<uint8_t>(params.size());
  size_t i = 0;
  for (uint8_t p : params) c.params[i++] = p;
  c.delay_ms = delay_ms;
  return c;
}

// What the panel driver needs to know about one controller. The generic part of the start-up
// (reset, SLPOUT, COLMOD, MADCTL, INVON, NORON, DISPON) is the driver's; `setup` holds what a
// controller needs besides (power, VCOM, gamma), sent after the software reset and before SLPOUT.
struct ControllerInfo {
  const char* name = "";
  uint16_t ram_columns = 240;  // graphics RAM in the controller's native orientation
  uint16_t ram_rows = 320;
  std::span<const PanelCommand> setup{};
  // MADCTL bits the modules' glass needs on top of the rotation's (xor): ILI9341 modules show
  // RAM column c at glass column 239 - c, so every driver for them sets MX at rotation 0.
  uint8_t madctl_mirror = 0;
  uint16_t reset_delay_ms = 120;      // after SWRESET or the release of the reset line
  uint16_t sleep_out_delay_ms = 120;  // after SLPOUT
  uint16_t sleep_in_delay_ms = 120;   // after SLPIN
  uint16_t display_on_delay_ms = 20;  // after DISPON
};

// Sends one table entry (command and parameters), then waits its delay.
Status send_command(PanelBus& bus, const PanelCommand& command);
// Sends the entries in order; stops at the first error and returns it.
Status send_commands(PanelBus& bus, std::span<const PanelCommand> table);
// CASET x0..x1 and RASET y0..y1 (inclusive, 16-bit big-endian), then RAMWR: the bus is ready for
// the pixels of the window. Three commands, 11 bytes on the wire.
Status write_window(PanelBus& bus, uint16_t x0, uint16_t y0, uint16_t x1, uint16_t y1);
inline constexpr uint32_t kWindowCommands = 3;
inline constexpr uint32_t kWindowCommandBytes = 11;

}  // namespace lr
