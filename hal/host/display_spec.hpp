// lineraster-sim's --display and --panel values.
//
//   --panel CONTROLLER:WxH[:ROT]     st7789: 240x240, 240x320, 135x240, 320x240;
//                                    ili9341: 240x320, 320x240; ROT 0, 90, 180, 270 (default 0)
//   --display emulator:CONTROLLER:WxH[:ROT]
//   --display spidev:DEVICE,dc=CHIP:LINE,rst=CHIP:LINE[,bl=CHIP:LINE][,hz=N]
//   --display ft232h[:SERIAL][,hz=N][,...]
//
// WxH is the image size at ROT 0: the module presets of hal/panel_config.hpp (st7789_240x240,
// st7789_240x320, st7789_135x240, ili9341_240x320), and 320x240, the 240x320 panel held
// landscape (PanelConfig rotation 90 + ROT). The spidev and ft232h details are the backends'
// (hal/host/linux/spidev_bus: parse_spidev_spec, hal/host/usb/ft232h_bus: parse_ft232h_spec):
// kept as text here and parsed by them.
#pragma once

#include <string>
#include <string_view>

#include "lineraster/hal/panel_config.hpp"

namespace lr::host {

// CONTROLLER:WxH[:ROT]. On failure: false and a one-line reason.
bool parse_panel_spec(std::string_view spec, PanelConfig& out, std::string& error);

// "st7789 240x240 rotation 90" (the image size at the configured rotation follows).
std::string describe_panel(const PanelConfig& panel);

enum class DisplayKind : uint8_t { kNone, kEmulator, kSpidev, kFt232h };

struct DisplaySpec {
  DisplayKind kind = DisplayKind::kNone;
  PanelConfig panel{};  // kEmulator: from the spec
  std::string device;   // kSpidev: the whole spec ("spidev:..."); kFt232h: the serial or ""
  std::string text;     // the value as given
};

bool parse_display_spec(std::string_view spec, DisplaySpec& out, std::string& error);

}  // namespace lr::host
