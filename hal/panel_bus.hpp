// The wires of an SPI panel as a panel driver sees them (the MIPI DBI type C model: the Linux
// kernel's drm_mipi_dbi.c): a command byte sent with D/C low, its parameter or pixel bytes
// with D/C high, chip select held for the whole command, a reset line and a backlight line.
//
// Pixel data goes out asynchronously: start_pixels() may return while the bytes are still on
// the wire (DMA, a driver thread, a USB transfer); the caller must not touch the buffer until
// wait() has returned kOk for it. A bus never holds more than one transfer in flight. Every
// wait is bounded: wait() returns kTimeout when the transfer did not finish in time, kDisplayError
// when it failed; after either the bus is idle again (the transfer is abandoned) and usable.
// Before each pixel transfer the sender calls clean_dcache() with exactly the bytes it is about
// to pass to start_pixels(), after its last write to them (the DMA contract: docs/dma.md).
// Implementations: hal/host/linux/spidev_bus (spidev + libgpiod), hal/host/usb/ft232h_bus (libusb,
// FT232H MPSSE), a board's own (bare metal: its SPI/DMA registers), and recording buses in the
// tests and the panel emulator.
#pragma once

#include <cstdint>
#include <span>

#include "lineraster/core/output/status.hpp"

namespace lr {

class PanelBus {
 public:
  // One command byte (D/C low) and its parameter bytes (D/C high, may be empty), CS asserted
  // around both. Returns when the bytes have been sent.
  virtual Status command(uint8_t cmd, std::span<const uint8_t> params) = 0;
  // Starts sending `pixels` as data (D/C high) right after a RAMWR command (CS still asserted
  // for the data, released at the end). The buffer belongs to the bus until wait() returns.
  virtual Status start_pixels(std::span<const uint8_t> pixels) = 0;
  // Cache maintenance for a DMA that reads memory behind a data cache (Cortex-M7): writes back
  // the lines holding `bytes` (SCB_CleanDCache_by_Addr, which works by whole lines). PanelSink
  // calls it right before start_pixels() with the same span. A bus that copies the bytes (spidev,
  // USB) or a core without a data cache has nothing to do, which is what the default does.
  virtual void clean_dcache(std::span<const uint8_t> bytes) { (void)bytes; }
  // Waits at most timeout_ms for the transfer started last (kOk at once when none is pending).
  virtual Status wait(uint32_t timeout_ms) = 0;
  // Hardware reset line, active low on the panel: asserted = held in reset. kOk without one.
  virtual Status set_reset(bool asserted) = 0;
  // Backlight on or off. kOk without a backlight line.
  virtual Status set_backlight(bool on) = 0;
  virtual void delay_ms(uint32_t ms) = 0;

 protected:
  PanelBus() = default;
  ~PanelBus() = default;
};

}  // namespace lr
