// PanelBus over an FTDI FT232H in MPSSE mode, through libusb-1.0 (hal/host/usb/usb_bulk.hpp): no
// kernel driver and no FTDI library. The byte stream comes from hal/host/usb/mpsse.hpp.
//
// Opening resets the chip (FTDI vendor request SIO_RESET), sets the latency timer, switches to
// MPSSE (SET_BITMODE 0x02), checks that the MPSSE answers the bogus opcode 0xAA with 0xFA 0xAA,
// then drives every line and sets the clock. Commands are written synchronously; pixels are
// encoded (one 0x11 packet per 64 KB) and written from a worker thread
// (hal/host/transfer_worker.hpp), one USB bulk transfer per packet, so an abandoned transfer
// stops between whole MPSSE commands and still releases chip select. Chip select is a GPIO
// here: it stays low from a RAMWR (0x2C) or RAMWRC (0x3C) command without parameters through
// the pixel data that follows.
//
// When a USB transfer fails the chip's command parser may be mid-command: the next call sets
// the chip up again (reset, MPSSE, pins) before it sends anything.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lineraster/hal/host/transfer_worker.hpp"
#include "lineraster/hal/host/usb/mpsse.hpp"
#include "lineraster/hal/host/usb/usb_bulk.hpp"
#include "lineraster/hal/panel_bus.hpp"

namespace lr {

struct Ft232hConfig {
  uint16_t vid = 0x0403, pid = 0x6014;
  std::string serial;               // iSerialNumber; empty: the first FT232H found
  uint32_t hz = 30'000'000;         // SCK; the fastest clock not above it (30 MHz at most)
  mpsse::PinMap pins;               // CS D3, D/C C0, reset C1, no backlight
  uint8_t latency_ms = 1;           // FTDI latency timer (only the open-time check reads)
  uint32_t usb_timeout_ms = 1000;   // per bulk transfer, on top of the time its bytes take on SCK
  uint32_t busy_timeout_ms = 1000;  // how long a call waits for an abandoned transfer's packet
};

// Parses "ft232h[:SERIAL][,hz=N][,cs=PIN][,dc=PIN][,rst=PIN|none][,bl=PIN|none]", PIN being
// D3-D7 or C0-C7. On success fills `out` (other fields keep their values); false and a one-line
// error otherwise, `out` untouched.
bool parse_ft232h_spec(std::string_view spec, Ft232hConfig& out, std::string& error);

class Ft232hBus final : public PanelBus, private backend::TransferSteps {
 public:
  // nullptr and one line naming the problem and its fix, e.g.
  //   "no USB device 0403:6014 (is the FT232H plugged in?)"
  //   "0403:6014: permission denied (install a udev rule: ... or run as root)"
  //   "libusb: cannot initialise (LIBUSB_ERROR_...)"
  //   "0403:6014: the MPSSE did not answer (not an FT232H, or unplug and replug it)"
  static std::unique_ptr<Ft232hBus> open(const Ft232hConfig& config, std::string& error);
  ~Ft232hBus();
  Ft232hBus(const Ft232hBus&) = delete;
  Ft232hBus& operator=(const Ft232hBus&) = delete;

  // PanelBus. Every call but wait() and delay_ms() returns kBusy while a pixel transfer has
  // not been waited for, and kTimeout when an abandoned one is still on the wire after
  // busy_timeout_ms. A failed USB transfer is kDisplayError (kTimeout when it timed out).
  Status command(uint8_t cmd, std::span<const uint8_t> params) override;
  Status start_pixels(std::span<const uint8_t> pixels) override;
  Status wait(uint32_t timeout_ms) override;
  Status set_reset(bool asserted) override;
  Status set_backlight(bool on) override;
  void delay_ms(uint32_t ms) override;

  uint32_t hz() const { return mpsse::clock_hz(mpsse::clock_divisor(config_.hz)); }
  const std::string& serial() const { return usb_->serial(); }
  // One line about the last failure.
  std::string last_error() const { return error_; }

 private:
  explicit Ft232hBus(const Ft232hConfig& config) : config_(config), enc_(config.pins) {}
  bool piece(size_t index) override;
  bool finish() override;
  Status ready();
  Status setup(std::string& error);
  Status send(std::span<const uint8_t> bytes, std::string& error);
  uint32_t timeout_for(size_t bytes) const;

  Ft232hConfig config_;
  mpsse::Encoder enc_;
  std::unique_ptr<UsbBulk> usb_;
  std::vector<uint8_t> tx_;        // caller's thread
  std::vector<uint8_t> stream_;    // the pixel job: select + packets...
  std::vector<size_t> piece_end_;  // ...split after each packet
  std::vector<uint8_t> tail_;      // ...and chip select released
  bool job_failed_ = false;        // worker thread during a job
  bool broken_ = false;            // set up the chip again before the next call
  std::string error_;              // caller's thread
  std::string worker_error_;       // worker thread; read after wait()
  std::unique_ptr<backend::TransferWorker> worker_;
};

}  // namespace lr
