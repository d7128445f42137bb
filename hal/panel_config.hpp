// Which panel and how it is mounted: chosen in the user's code (a value), never by editing the
// library. ST7789 and ILI9341 controllers both address 240 x 320 pixels of graphics RAM; a module
// shows a window of it (its visible width x height at a column/row offset, in the controller's
// native orientation, rotation 0).
#pragma once

#include <cstdint>

namespace lr {

enum class Controller : uint8_t { kSt7789, kIli9341 };

// Clockwise rotation of the image on the module (MADCTL's MV/MX/MY).
enum class Rotation : uint8_t { k0, k90, k180, k270 };

struct PanelConfig {
  Controller controller = Controller::kSt7789;
  uint16_t width = 240, height = 320;       // visible pixels at rotation 0
  uint16_t col_offset = 0, row_offset = 0;  // of the visible window in the 240 x 320 RAM
  Rotation rotation = Rotation::k0;
  bool bgr = false;     // panel wired BGR: MADCTL's BGR bit
  bool invert = false;  // INVON after init (most ST7789 IPS modules need it)
  uint32_t spi_hz = 0;  // informative for backends that set their own clock (0: backend default)

  // Size of the image at this rotation.
  constexpr uint16_t image_width() const {
    return rotation == Rotation::k90 || rotation == Rotation::k270 ? height : width;
  }
  constexpr uint16_t image_height() const {
    return rotation == Rotation::k90 || rotation == Rotation::k270 ? width : height;
  }
};

// Common modules.
constexpr PanelConfig st7789_240x240(Rotation r = Rotation::k0) {
  return {Controller::kSt7789, 240, 240, 0, 0, r, false, true, 0};
}
constexpr PanelConfig st7789_240x320(Rotation r = Rotation::k0) {
  return {Controller::kSt7789, 240, 320, 0, 0, r, false, true, 0};
}
constexpr PanelConfig st7789_135x240(Rotation r = Rotation::k0) {
  return {Controller::kSt7789, 135, 240, 52, 40, r, false, true, 0};
}
constexpr PanelConfig ili9341_240x320(Rotation r = Rotation::k0) {
  return {Controller::kIli9341, 240, 320, 0, 0, r, true, false, 0};
}
// The 320 x 240 landscape module is the 240 x 320 panel turned: rotation 90 by default.
constexpr PanelConfig ili9341_320x240(Rotation r = Rotation::k90) {
  return {Controller::kIli9341, 240, 320, 0, 0, r, true, false, 0};
}

}  // namespace lr
