// The panel driver: one class for the ST7789 and the ILI9341, parameterised by a PanelConfig
// (hal/panel_config.hpp). It speaks to the controller through a PanelBus: start-up, sleep,
// display on/off, backlight, rotation, and the address window of a rectangle of the image.
//
// Coordinates. The image is what the renderer draws: config.image_width() x image_height()
// pixels, row 0 at the top as the module is mounted (rotated clockwise by config.rotation from
// the controller's native portrait). MADCTL makes the controller do the rotation, so an image
// rectangle maps to one address window: its x, y plus the offset of the visible window in the
// rotated address space, which address_offset() computes from the config (any module, no table
// of module offsets).
//
// Start-up (init): hardware reset (line asserted 1 ms, released, 120 ms), SWRESET and 120 ms,
// the controller's setup table, SLPOUT and 120 ms, COLMOD 0x55 (RGB565), MADCTL, INVON when
// config.invert, NORON, DISPON and a short wait. The backlight is left alone: switch it on with
// backlight(true) once the first frame is sent, so the RAM's power-on noise is never seen.
//
// Every call goes straight to the bus and returns its status; none may be made while a pixel
// transfer is in flight (a PanelSink's frame: call them between frames).
#pragma once

#include <cstdint>

#include "lineraster/core/output/status.hpp"
#include "lineraster/core/output/strip_sink.hpp"
#include "lineraster/hal/ili9341.hpp"
#include "lineraster/hal/mipi_dbi.hpp"
#include "lineraster/hal/panel_bus.hpp"
#include "lineraster/hal/panel_config.hpp"
#include "lineraster/hal/st7789.hpp"

namespace lr {

constexpr bool known_controller(Controller c) {
  return c == Controller::kSt7789 || c == Controller::kIli9341;
}
// The controller's data (the ST7789's for a value known_controller() refuses).
constexpr const ControllerInfo& controller_info(Controller c) {
  return c == Controller::kIli9341 ? ili9341::kInfo : st7789::kInfo;
}

// A config the driver can use: a known controller and rotation, a visible window of at least one
// pixel inside the controller's RAM.
constexpr bool valid_config(const PanelConfig& c) {
  if (!known_controller(c.controller) ||
      static_cast<uint8_t>(c.rotation) > static_cast<uint8_t>(Rotation::k270))
    return false;
  const ControllerInfo& info = controller_info(c.controller);
  return c.width > 0 && c.height > 0 && uint32_t{c.col_offset} + c.width <= info.ram_columns &&
         uint32_t{c.row_offset} + c.height <= info.ram_rows;
}

// MADCTL for the config: the rotation's MY/MX/MV (0: none, 90: MX|MV, 180: MX|MY, 270: MY|MV),
// the controller's glass mirror flipped in, BGR when the panel is wired BGR.
constexpr uint8_t madctl_for(const PanelConfig& c) {
  uint8_t bits = 0;
  switch (c.rotation) {
    case Rotation::k0:
      bits = 0;
      break;
    case Rotation::k90:
      bits = dcs::kMX | dcs::kMV;
      break;
    case Rotation::k180:
      bits = dcs::kMX | dcs::kMY;
      break;
    case Rotation::k270:
      bits = dcs::kMY | dcs::kMV;
      break;
  }
  bits = static_cast<uint8_t>(bits ^ controller_info(c.controller).madctl_mirror);
  if (c.bgr) bits = static_cast<uint8_t>(bits | dcs::kBGR);
  return bits;
}

// Where image pixel (0, 0) lies in the controller's address space (CASET x, RASET y) under
// madctl_for(c). The visible window covers RAM columns [col_offset, col_offset + width) and rows
// [row_offset, row_offset + height). Along RAM columns the host address counts from column 0, or
// with MX from the last column, so the window starts at col_offset or at
// ram_columns - col_offset - width; rows likewise with MY. MV makes the host's x run along RAM
// rows, so the two swap. (240x240 at 180: rows 320 - 0 - 240 = 80; 135x240 at 90: x 40, y 53.)
struct AddressOffset {
  uint16_t x = 0, y = 0;
  friend constexpr bool operator==(const AddressOffset&, const AddressOffset&) = default;
};
constexpr AddressOffset address_offset(const PanelConfig& c) {
  if (!valid_config(c)) return {};
  const ControllerInfo& info = controller_info(c.controller);
  const uint8_t m = madctl_for(c);
  const uint16_t along_columns =
      (m & dcs::kMX) ? static_cast<uint16_t>(info.ram_columns - c.col_offset - c.width)
                     : c.col_offset;
  const uint16_t along_rows = (m & dcs::kMY)
                                  ? static_cast<uint16_t>(info.ram_rows - c.row_offset - c.height)
                                  : c.row_offset;
  if (m & dcs::kMV) return {along_rows, along_columns};
  return {along_columns, along_rows};
}

// The address window (inclusive ends) of an image rectangle.
struct AddressWindow {
  uint16_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  friend constexpr bool operator==(const AddressWindow&, const AddressWindow&) = default;
};
// False when the rectangle is empty or not inside the image.
constexpr bool address_window(const PanelConfig& c, const StripRect& r, AddressWindow& out) {
  if (!valid_config(c) || r.width == 0 || r.height == 0 ||
      uint32_t{r.x} + r.width > c.image_width() || uint32_t{r.y} + r.height > c.image_height())
    return false;
  const AddressOffset o = address_offset(c);
  out.x0 = static_cast<uint16_t>(o.x + r.x);
  out.y0 = static_cast<uint16_t>(o.y + r.y);
  out.x1 = static_cast<uint16_t>(out.x0 + r.width - 1);
  out.y1 = static_cast<uint16_t>(out.y0 + r.height - 1);
  return true;
}

class Panel {
 public:
  Panel(PanelBus& bus, const PanelConfig& config) : bus_(bus), config_(config) {}
  Panel(const Panel&) = delete;
  Panel& operator=(const Panel&) = delete;

  // Resets the controller (with the reset line too when hardware_reset) and starts it: sleep out,
  // RGB565, the config's rotation and inversion, normal mode, display on. kInvalidArgument (and
  // nothing sent) for a config valid_config() refuses.
  Status init(bool hardware_reset = true);
  // SLPIN (true) or SLPOUT (false), each followed by its 120 ms. RAM is kept while asleep.
  Status sleep(bool enter);
  // DISPON (followed by a short wait) or DISPOFF.
  Status display_on(bool on);
  Status backlight(bool on) { return bus_.set_backlight(on); }
  // Rotates the image: sends MADCTL; image_width()/image_height() swap for 90 and 270.
  Status set_rotation(Rotation r);
  // CASET/RASET for an image rectangle, then RAMWR: the bus takes its pixels next, rows of
  // r.width pixels, top to bottom. kInvalidArgument for a rectangle outside the image.
  Status begin_write(const StripRect& r);

  const PanelConfig& config() const { return config_; }
  uint16_t image_width() const { return config_.image_width(); }
  uint16_t image_height() const { return config_.image_height(); }
  PanelBus& bus() { return bus_; }
  // Changes whenever the RAM's contents or the address mapping may have changed (init,
  // set_rotation): a sink that remembers what the panel shows starts over.
  uint32_t epoch() const { return epoch_; }

 private:
  Status send(uint8_t cmd, uint8_t param) { return bus_.command(cmd, {&param, 1}); }

  PanelBus& bus_;
  PanelConfig config_;
  uint32_t epoch_ = 0;
};

}  // namespace lr
