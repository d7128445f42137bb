// Sitronix ST7789 (ST7789V, ST7789VW): 240 x 320 RGB graphics RAM, MIPI DCS over 4-line SPI.
//
// From the ST7789V datasheet: after SWRESET wait 5 ms before the next command and 120 ms before
// SLPOUT; after SLPOUT wait 5 ms before the next command and 120 ms before SLPIN; after SLPIN
// 120 ms before SLPOUT. The driver waits 120 ms after each, which satisfies both limits whatever
// follows. A hardware reset needs a low pulse of at least 10 us and 120 ms before commands.
//
// The controller needs nothing besides the generic sequence: its reset values of the porch, gate,
// VCOM, power and gamma registers are the ones module vendors ship (Adafruit's ST7789 driver
// sends none of them either), so the setup table is empty. Modules whose vendor asks for other
// VCOM or gamma values can send them with lr::send_commands() after Panel::init().
//
// Rotation (MADCTL), with the glass showing RAM as it is (no mirror): 0: 0, 90: MX|MV,
// 180: MX|MY, 270: MY|MV. The same values as TFT_eSPI's ST7789 rotations 0..3 and, with the
// device tree's counter-clockwise angles, the kernel's st7789v driver.
#pragma once

#include <array>

#include "lineraster/hal/mipi_dbi.hpp"

namespace lr::st7789 {

inline constexpr std::array<PanelCommand, 0> kSetup{};

inline constexpr ControllerInfo kInfo{
    .name = "ST7789",
    .ram_columns = 240,
    .ram_rows = 320,
    .setup = kSetup,
    .madctl_mirror = 0,
    .reset_delay_ms = 120,
    .sleep_out_delay_ms = 120,
    .sleep_in_delay_ms = 120,
    .display_on_delay_ms = 20,
};

}  // namespace lr::st7789
