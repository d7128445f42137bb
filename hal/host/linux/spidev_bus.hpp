// PanelBus over Linux spidev (/dev/spidevB.C, SPI_IOC_MESSAGE) with the D/C, reset and
// backlight lines driven through libgpiod 1.6 (hal/host/linux/gpio_line.hpp).
//
// Commands go out synchronously from the caller's thread: D/C low, the command byte; D/C high,
// the parameter bytes. Pixels go out from a worker thread (hal/host/transfer_worker.hpp):
// start_pixels() copies the bytes (so the caller's buffer is free again as soon as wait()
// returns, whatever it returns), sets D/C high and returns; the worker sends the copy in
// transfers of at most the spidev buffer size (/sys/module/spidev/parameters/bufsiz, 4096 by
// default) while the caller renders.
//
// Chip select is the SPI controller's, driven by the kernel around every transfer: it rises
// between the command byte and its parameters and between chunks, as with the kernel's own
// MIPI DBI panel drivers (drm_mipi_dbi.c), which ST7789 and ILI9341 controllers accept.
//
// Usable from any program (no CLI dependency): open() with a SpidevConfig, or parse the
// command-line form with parse_spidev_spec() first.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lineraster/hal/host/linux/gpio_line.hpp"
#include "lineraster/hal/host/transfer_worker.hpp"
#include "lineraster/hal/panel_bus.hpp"

namespace lr {

struct SpidevConfig {
  std::string device;               // "/dev/spidev0.0"
  uint32_t hz = 32'000'000;         // SCLK; the controller may round it down
  uint8_t mode = 0;                 // SPI mode 0-3 (CPOL, CPHA)
  std::string dc;                   // D/C line, required: "gpiochip0:24" or a line name
  std::string reset;                // reset line, optional (empty: none)
  std::string backlight;            // backlight line (active high), optional (empty: none)
  size_t chunk_bytes = 0;           // bytes per transfer; 0: spidev's bufsiz (4096 when unreadable)
  uint32_t busy_timeout_ms = 1000;  // how long a call waits for an abandoned transfer's last chunk
};

// Parses "/dev/spidevB.C,dc=LINE[,rst=LINE][,bl=LINE][,hz=N][,mode=M]", LINE being CHIP:OFFSET
// (gpiochip0:24) or a line name. On success fills `out` (chunk_bytes and busy_timeout_ms keep
// their values); false and a one-line error otherwise, `out` untouched.
bool parse_spidev_spec(std::string_view spec, SpidevConfig& out, std::string& error);

class SpidevBus final : public PanelBus, private backend::TransferSteps {
 public:
  // Opens the device, sets mode, 8 bits per word and speed, requests the lines (D/C high,
  // reset released, backlight off) and starts the worker. nullptr and one line naming what is
  // missing and how to fix it, e.g.
  //   "/dev/spidev0.0: no such device (enable SPI: dtparam=spi=on on a Raspberry Pi, or load
  //   spidev)"
  //   "/dev/spidev0.0: permission denied (add the user to the spi group or run as root)"
  //   "gpiochip0: permission denied (add the user to the gpio group or run as root)"
  //   "gpiochip0 line 24: busy (used by spi0 CS0)"
  static std::unique_ptr<SpidevBus> open(const SpidevConfig& config, std::string& error);
  ~SpidevBus();
  SpidevBus(const SpidevBus&) = delete;
  SpidevBus& operator=(const SpidevBus&) = delete;

  // PanelBus. Every call but wait() and delay_ms() returns kBusy while a pixel transfer has
  // not been waited for, and kTimeout when an abandoned one is still on the wire after
  // busy_timeout_ms. A failed ioctl or GPIO write is kDisplayError (last_error() says which).
  Status command(uint8_t cmd, std::span<const uint8_t> params) override;
  Status start_pixels(std::span<const uint8_t> pixels) override;
  Status wait(uint32_t timeout_ms) override;
  Status set_reset(bool asserted) override;
  Status set_backlight(bool on) override;
  void delay_ms(uint32_t ms) override;

  // The speed the driver reports after setting it, and the bytes per transfer.
  uint32_t hz() const { return hz_; }
  size_t chunk_bytes() const { return chunk_; }
  // One line about the last kDisplayError (the failed call and errno).
  std::string last_error() const;

 private:
  SpidevBus() = default;
  bool piece(size_t index) override;
  bool finish() override { return true; }
  Status ready();
  Status set_dc(bool high);
  bool transfer(const uint8_t* data, size_t size, std::string* error);

  int fd_ = -1;
  std::string device_;
  uint32_t hz_ = 0;
  size_t chunk_ = 4096;
  uint32_t busy_timeout_ms_ = 1000;
  std::unique_ptr<GpioLine> dc_, reset_, backlight_;
  std::vector<uint8_t> pixels_;  // the transfer in flight (read by the worker only)
  std::string error_;            // caller's thread
  std::string worker_error_;     // worker thread; read after wait()
  std::unique_ptr<backend::TransferWorker> worker_;
};

}  // namespace lr
