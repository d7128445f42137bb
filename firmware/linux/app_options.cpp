#include "firmware/linux/app_options.hpp"

#include <string_view>

#include "lineraster/hal/host/display_spec.hpp"
#include "lineraster/hal/host/parse_number.hpp"

namespace lr::app {

const char* const kUsage =
    "usage: lr_panel_app --display spidev:DEVICE,dc=CHIP:LINE,rst=CHIP:LINE[,bl=CHIP:LINE][,hz=N]\n"
    "                    --panel CONTROLLER:WxH[:ROT] [--frames N]\n"
    "Renders the demo scene (the torus knot in gold, turning about y) strip by strip to an SPI\n"
    "panel on Linux spidev, with D/C, reset and backlight on GPIO lines (libgpiod).\n"
    "PANEL: st7789:240x240|240x320|135x240|320x240[:ROT] or ili9341:240x320|320x240[:ROT], ROT\n"
    "  0|90|180|270 (default 0). LINE: CHIP:OFFSET (gpiochip0:24, or the chip's label) or a line\n"
    "  name. hz: the SPI clock (default 32000000).\n"
    "--frames N: stop after N frames (default 0: run until interrupted).\n"
    "Prints one line per frame (bytes sent, strips sent / narrowed / skipped, ms) and the fps.\n"
    "Exit status: 0 done, 1 device error (no spidev, no GPIO chip or line, a failed transfer),\n"
    "2 bad options.\n";

ParseResult parse_options(int argc, const char* const* argv, AppOptions& out, std::string& error) {
  AppOptions o;
  bool have_display = false, have_panel = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "--help" || a == "-h") return ParseResult::kHelp;
    if (a != "--display" && a != "--panel" && a != "--frames") {
      error = "unknown option '" + std::string(a) + "' (see --help)";
      return ParseResult::kError;
    }
    // A value never starts with "--": "--panel --frames 2" is a missing value.
    if (i + 1 >= argc || std::string_view(argv[i + 1]).substr(0, 2) == "--") {
      error = std::string(a) + ": missing value";
      return ParseResult::kError;
    }
    const std::string_view v = argv[++i];
    const std::string bad = std::string(a) + ": bad value '" + std::string(v) + "'";
    std::string why;
    if (a == "--display") {
      host::DisplaySpec d;
      if (!host::parse_display_spec(v, d, why)) {
        error = bad + " (" + why + ")";
        return ParseResult::kError;
      }
      if (d.kind != host::DisplayKind::kSpidev) {
        error = bad + " (lr_panel_app drives spidev panels: spidev:DEVICE,dc=CHIP:LINE,...)";
        return ParseResult::kError;
      }
      if (!parse_spidev_spec(d.device, o.bus, why)) {
        error = bad + " (" + why + ")";
        return ParseResult::kError;
      }
      o.display = v;
      have_display = true;
    } else if (a == "--panel") {
      if (!host::parse_panel_spec(v, o.panel, why)) {
        error = bad + " (" + why + ")";
        return ParseResult::kError;
      }
      have_panel = true;
    } else if (!backend::parse_u32(v, o.frames)) {
      error = bad + " (a whole number, 0 = until interrupted)";
      return ParseResult::kError;
    }
  }
  if (!have_display) {
    error = "--display spidev:DEVICE,dc=CHIP:LINE,rst=CHIP:LINE[,...] is required (see --help)";
    return ParseResult::kError;
  }
  if (!have_panel) {
    error = "--panel CONTROLLER:WxH[:ROT] is required (see --help)";
    return ParseResult::kError;
  }
  out = std::move(o);
  return ParseResult::kRun;
}

}  // namespace lr::app
