// lr_panel_app's command line, parsed without opening anything (the unit test runs it on any
// machine). The --display and --panel values have lineraster-sim's syntax: --panel is parsed by
// hal/host/display_spec (lr_display_spec: it needs no libpng), the spidev details by the
// backend's own parse_spidev_spec.
#pragma once

#include <cstdint>
#include <string>

#include "lineraster/hal/host/linux/spidev_bus.hpp"
#include "lineraster/hal/panel_config.hpp"

namespace lr::app {

extern const char* const kUsage;

struct AppOptions {
  SpidevConfig bus;     // device, hz, D/C, reset and backlight lines (syntax checked)
  PanelConfig panel{};  // controller, module size, rotation
  uint32_t frames = 0;  // 0: until SIGINT or SIGTERM
  std::string display;  // the --display value as given, for messages
};

enum class ParseResult : uint8_t { kRun, kHelp, kError };

// argv[1..argc-1]. kError with a one-line `error` (without the program name) for an unknown
// option, a missing or bad value, a display other than spidev, or a missing --display / --panel.
ParseResult parse_options(int argc, const char* const* argv, AppOptions& out, std::string& error);

}  // namespace lr::app
