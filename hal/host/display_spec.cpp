#include "lineraster/hal/host/display_spec.hpp"

namespace lr::host {
namespace {

constexpr const char* kPanelSyntax =
    "expected st7789:240x240|240x320|135x240|320x240[:0|90|180|270] or "
    "ili9341:240x320|320x240[:ROT]";

Rotation add_rotation(Rotation a, int degrees) {
  const int total = (static_cast<int>(a) * 90 + degrees) % 360;
  return static_cast<Rotation>(total / 90);
}

}  // namespace

bool parse_panel_spec(std::string_view spec, PanelConfig& out, std::string& error) {
  const size_t c1 = spec.find(':');
  if (c1 == std::string_view::npos) {
    error = kPanelSyntax;
    return false;
  }
  const std::string_view controller = spec.substr(0, c1);
  std::string_view size = spec.substr(c1 + 1), rot;
  if (const size_t c2 = size.find(':'); c2 != std::string_view::npos) {
    rot = size.substr(c2 + 1);
    size = size.substr(0, c2);
    if (rot.empty()) {
      error = kPanelSyntax;
      return false;
    }
  }
  int degrees = 0;
  if (!rot.empty()) {
    if (rot == "0")
      degrees = 0;
    else if (rot == "90")
      degrees = 90;
    else if (rot == "180")
      degrees = 180;
    else if (rot == "270")
      degrees = 270;
    else {
      error = "rotation '" + std::string(rot) + "': 0, 90, 180 or 270";
      return false;
    }
  }
  PanelConfig p;
  if (controller == "st7789") {
    if (size == "240x240")
      p = st7789_240x240();
    else if (size == "240x320")
      p = st7789_240x320();
    else if (size == "135x240")
      p = st7789_135x240();
    else if (size == "320x240")
      p = st7789_240x320(Rotation::k90);
    else {
      error = "st7789: size '" + std::string(size) + "': 240x240, 240x320, 135x240 or 320x240";
      return false;
    }
  } else if (controller == "ili9341") {
    if (size == "240x320")
      p = ili9341_240x320();
    else if (size == "320x240")
      p = ili9341_320x240();
    else {
      error = "ili9341: size '" + std::string(size) + "': 240x320 or 320x240 (the ILI9341 modules)";
      return false;
    }
  } else {
    error = "controller '" + std::string(controller) + "': st7789 or ili9341";
    return false;
  }
  p.rotation = add_rotation(p.rotation, degrees);
  out = p;
  return true;
}

std::string describe_panel(const PanelConfig& p) {
  return std::string(p.controller == Controller::kSt7789 ? "st7789" : "ili9341") + " " +
         std::to_string(p.width) + "x" + std::to_string(p.height) + " rotation " +
         std::to_string(static_cast<int>(p.rotation) * 90) + " (image " +
         std::to_string(p.image_width()) + "x" + std::to_string(p.image_height()) + ")";
}

bool parse_display_spec(std::string_view spec, DisplaySpec& out, std::string& error) {
  DisplaySpec d;
  d.text = spec;
  if (spec.substr(0, 9) == "emulator:") {
    d.kind = DisplayKind::kEmulator;
    if (!parse_panel_spec(spec.substr(9), d.panel, error)) {
      error = "emulator: " + error;
      return false;
    }
  } else if (spec.substr(0, 7) == "spidev:") {
    d.kind = DisplayKind::kSpidev;
    if (spec.size() == 7) {
      error = "expected spidev:DEVICE,dc=CHIP:LINE,rst=CHIP:LINE[,bl=CHIP:LINE][,hz=N]";
      return false;
    }
    d.device = spec.substr(7);
  } else if (spec == "ft232h" || spec.substr(0, 7) == "ft232h:" || spec.substr(0, 7) == "ft232h,") {
    d.kind = DisplayKind::kFt232h;
    d.device = spec;
  } else {
    error =
        "expected emulator:CONTROLLER:WxH[:ROT], spidev:DEVICE,dc=CHIP:LINE,rst=CHIP:LINE[,...] "
        "or ft232h[:SERIAL]";
    return false;
  }
  out = d;
  return true;
}

}  // namespace lr::host
