// A USB device's interface opened for bulk transfers with libusb-1.0: find it by VID:PID (and
// optionally its serial number string), detach a kernel driver bound to the interface (ftdi_sio
// for an FT232H; re-attached on close), claim it, and move bytes with bounded waits.
//
// Ft232hBus is built on it; a test program can use it on its own, e.g. against a Linux USB
// gadget (configfs SourceSink function: bulk OUT and bulk IN on interface 0) by giving the
// gadget's VID:PID and leaving the endpoints to be found.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "lineraster/core/output/status.hpp"

struct libusb_context;
struct libusb_device_handle;

namespace lr {

struct UsbBulkConfig {
  uint16_t vid = 0, pid = 0;
  std::string serial;  // iSerialNumber to match; empty: the first VID:PID device
  uint8_t interface = 0;
  uint8_t out_endpoint = 0;  // bulk OUT address (0x02); 0: the interface's first bulk OUT
  uint8_t in_endpoint = 0;   // bulk IN address (0x81); 0: the interface's first bulk IN, if any
  std::string what = "the device";  // in "no USB device VID:PID (is <what> plugged in?)"
};

// "0403:6014".
std::string usb_id(uint16_t vid, uint16_t pid);

class UsbBulk {
 public:
  // nullptr and one line naming the problem and its fix:
  //   "libusb: cannot initialise (LIBUSB_ERROR_...)"
  //   "no USB device 0403:6014 (is the FT232H plugged in?)"
  //   "no USB device 0403:6014 with serial FT1 (found: FT2, FT3)"
  //   "0403:6014: permission denied (install a udev rule: SUBSYSTEM=="usb", ATTR{idVendor}=="0403",
  //    ATTR{idProduct}=="6014", MODE="0666", or run as root)"      (one line)
  //   "0403:6014: interface 0 busy (another program has claimed it)"
  //   "0403:6014: interface 0 has no bulk OUT endpoint"
  static std::unique_ptr<UsbBulk> open(const UsbBulkConfig& config, std::string& error);
  ~UsbBulk();
  UsbBulk(const UsbBulk&) = delete;
  UsbBulk& operator=(const UsbBulk&) = delete;

  // Sends all of `data` to the OUT endpoint within timeout_ms: kOk; kTimeout (part may have
  // gone: *sent says how much); kDisplayError for any other failure. last_error() says more.
  Status write(std::span<const uint8_t> data, uint32_t timeout_ms, size_t* sent = nullptr);
  // One bulk IN transfer into `buffer` within timeout_ms (kTimeout: nothing or part came).
  Status read(std::span<uint8_t> buffer, uint32_t timeout_ms, size_t& received);
  // A vendor/class control request without data stage (bmRequestType host-to-device).
  Status control_out(uint8_t request_type, uint8_t request, uint16_t value, uint16_t index,
                     uint32_t timeout_ms);

  uint8_t out_endpoint() const { return out_ep_; }
  uint8_t in_endpoint() const { return in_ep_; }  // 0: none
  size_t in_max_packet() const { return in_max_packet_; }
  const std::string& serial() const { return serial_; }
  const std::string& id() const { return id_; }  // "0403:6014"
  // One line about the last failed call. Not synchronised: read it on the thread that made
  // the call (or after joining it).
  const std::string& last_error() const { return error_; }
  libusb_device_handle* handle() const { return handle_; }

 private:
  UsbBulk() = default;
  libusb_context* ctx_ = nullptr;
  libusb_device_handle* handle_ = nullptr;
  bool claimed_ = false;
  uint8_t interface_ = 0;
  uint8_t out_ep_ = 0, in_ep_ = 0;
  size_t in_max_packet_ = 512;
  std::string serial_, id_, error_;
};

}  // namespace lr
