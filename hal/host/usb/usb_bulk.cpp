#include "lineraster/hal/host/usb/usb_bulk.hpp"

#include <libusb.h>

#include <algorithm>
#include <climits>
#include <cstdio>
#include <exception>
#include <vector>

namespace lr {
namespace {

std::string usb_error(int r) {
  return libusb_error_name(r);
}

std::string permission_error(const std::string& id, uint16_t vid, uint16_t pid) {
  char rule[160];
  std::snprintf(rule, sizeof rule,
                "SUBSYSTEM==\"usb\", ATTR{idVendor}==\"%04x\", ATTR{idProduct}==\"%04x\", "
                "MODE=\"0666\"",
                vid, pid);
  return id + ": permission denied (install a udev rule: " + rule +
         " in /etc/udev/rules.d/, or run as root)";
}

// The string descriptor iSerialNumber of an open device ("" when it has none).
std::string read_serial(libusb_device_handle* h, const libusb_device_descriptor& d) {
  if (d.iSerialNumber == 0) return {};
  unsigned char buf[256];
  const int n = libusb_get_string_descriptor_ascii(h, d.iSerialNumber, buf, sizeof buf);
  if (n <= 0) return {};
  return std::string(reinterpret_cast<const char*>(buf), static_cast<size_t>(n));
}

}  // namespace

std::string usb_id(uint16_t vid, uint16_t pid) {
  char s[16];
  std::snprintf(s, sizeof s, "%04x:%04x", vid, pid);
  return s;
}

std::unique_ptr<UsbBulk> UsbBulk::open(const UsbBulkConfig& config, std::string& error) {
  try {
    std::unique_ptr<UsbBulk> bus(new UsbBulk());
    const std::string id = usb_id(config.vid, config.pid);
    bus->id_ = id;
    bus->interface_ = config.interface;
    if (const int r = libusb_init(&bus->ctx_); r != 0) {
      bus->ctx_ = nullptr;
      error = "libusb: cannot initialise (" + usb_error(r) + ")";
      return nullptr;
    }
    libusb_device** list = nullptr;
    const ssize_t count = libusb_get_device_list(bus->ctx_, &list);
    if (count < 0) {
      error = "libusb: cannot list the USB devices (" + usb_error(static_cast<int>(count)) + ")";
      return nullptr;
    }
    libusb_device* chosen = nullptr;
    int matching = 0;
    bool denied = false;
    int open_error = 0;
    std::vector<std::string> other_serials;
    for (ssize_t i = 0; i < count && !chosen; ++i) {
      libusb_device_descriptor d;
      if (libusb_get_device_descriptor(list[i], &d) != 0) continue;
      if (d.idVendor != config.vid || d.idProduct != config.pid) continue;
      ++matching;
      libusb_device_handle* h = nullptr;
      if (const int r = libusb_open(list[i], &h); r != 0) {
        if (r == LIBUSB_ERROR_ACCESS) {
          denied = true;
        } else if (open_error == 0) {
          open_error = r;
        }
        continue;
      }
      const std::string serial = read_serial(h, d);
      if (config.serial.empty() || serial == config.serial) {
        chosen = list[i];
        bus->handle_ = h;
        bus->serial_ = serial;
      } else {
        other_serials.push_back(serial.empty() ? "(none)" : serial);
        libusb_close(h);
      }
    }
    if (chosen) libusb_ref_device(chosen);
    libusb_free_device_list(list, 1);
    if (!chosen) {
      if (denied) {
        error = permission_error(id, config.vid, config.pid);
      } else if (open_error != 0) {
        error = id + ": cannot open (" + usb_error(open_error) + ")";
      } else if (matching == 0) {
        error = "no USB device " + id + " (is " + config.what + " plugged in?)";
      } else {
        error = "no USB device " + id + " with serial " + config.serial + " (found:";
        for (size_t i = 0; i < other_serials.size(); ++i) {
          error += (i ? ", " : " ") + other_serials[i];
        }
        error += ")";
      }
      return nullptr;
    }

    // Endpoints of the interface's first alternate setting.
    libusb_config_descriptor* cfg = nullptr;
    const int cr = libusb_get_active_config_descriptor(chosen, &cfg);
    libusb_unref_device(chosen);
    if (cr != 0) {
      error = id + ": cannot read the configuration descriptor (" + usb_error(cr) + ")";
      return nullptr;
    }
    const libusb_interface_descriptor* alt = nullptr;
    for (int i = 0; i < cfg->bNumInterfaces; ++i) {
      const libusb_interface& itf = cfg->interface[i];
      if (itf.num_altsetting > 0 && itf.altsetting[0].bInterfaceNumber == config.interface) {
        alt = &itf.altsetting[0];
      }
    }
    struct Endpoint {
      uint8_t address;
      size_t max_packet;
    };
    std::vector<Endpoint> outs, ins;  // bulk endpoints, in descriptor order
    if (alt) {
      for (int e = 0; e < alt->bNumEndpoints; ++e) {
        const libusb_endpoint_descriptor& ep = alt->endpoint[e];
        if ((ep.bmAttributes & 0x03) != LIBUSB_TRANSFER_TYPE_BULK) continue;
        ((ep.bEndpointAddress & LIBUSB_ENDPOINT_IN) ? ins : outs)
            .push_back({ep.bEndpointAddress, ep.wMaxPacketSize});
      }
    }
    libusb_free_config_descriptor(cfg);
    const std::string itf_name = "interface " + std::to_string(config.interface);
    if (!alt) {
      error = id + ": no " + itf_name;
      return nullptr;
    }
    // The requested endpoint, or the first one when none was requested.
    auto pick = [](const std::vector<Endpoint>& eps, uint8_t wanted) -> const Endpoint* {
      for (const Endpoint& e : eps) {
        if (!wanted || e.address == wanted) return &e;
      }
      return nullptr;
    };
    char ep_text[8] = "";
    const Endpoint* out = pick(outs, config.out_endpoint);
    if (!out) {
      if (config.out_endpoint)
        std::snprintf(ep_text, sizeof ep_text, " 0x%02x", config.out_endpoint);
      error = id + ": " + itf_name + " has no bulk OUT endpoint" + ep_text;
      return nullptr;
    }
    const Endpoint* in = pick(ins, config.in_endpoint);
    if (!in && config.in_endpoint) {
      std::snprintf(ep_text, sizeof ep_text, " 0x%02x", config.in_endpoint);
      error = id + ": " + itf_name + " has no bulk IN endpoint" + ep_text;
      return nullptr;
    }
    bus->out_ep_ = out->address;
    if (in) {
      bus->in_ep_ = in->address;
      if (in->max_packet) bus->in_max_packet_ = in->max_packet;
    }

    libusb_set_auto_detach_kernel_driver(bus->handle_, 1);  // LIBUSB_ERROR_NOT_SUPPORTED: none
    if (const int r = libusb_claim_interface(bus->handle_, config.interface); r != 0) {
      if (r == LIBUSB_ERROR_BUSY) {
        error = id + ": " + itf_name + " busy (another program has claimed it)";
      } else if (r == LIBUSB_ERROR_ACCESS) {
        error = permission_error(id, config.vid, config.pid);
      } else {
        error = id + ": cannot claim " + itf_name + " (" + usb_error(r) + ")";
      }
      return nullptr;
    }
    bus->claimed_ = true;
    return bus;
  } catch (const std::exception& e) {
    error = usb_id(config.vid, config.pid) + ": " + e.what();
    return nullptr;
  }
}

UsbBulk::~UsbBulk() {
  if (claimed_) libusb_release_interface(handle_, interface_);
  if (handle_) libusb_close(handle_);
  if (ctx_) libusb_exit(ctx_);
}

Status UsbBulk::write(std::span<const uint8_t> data, uint32_t timeout_ms, size_t* sent) {
  size_t done = 0;
  Status status = Status::kOk;
  while (done < data.size()) {
    const size_t n = std::min<size_t>(data.size() - done, size_t{1} << 30);
    int transferred = 0;
    const int r = libusb_bulk_transfer(handle_, out_ep_, const_cast<uint8_t*>(data.data() + done),
                                       static_cast<int>(n), &transferred, timeout_ms);
    done += static_cast<size_t>(std::max(transferred, 0));
    if (r != 0 || static_cast<size_t>(transferred) != n) {
      error_ = id_ + ": bulk OUT of " + std::to_string(data.size()) +
               " bytes: " + (r ? usb_error(r) : "short transfer") + " after " +
               std::to_string(done) + " bytes";
      status = r == LIBUSB_ERROR_TIMEOUT ? Status::kTimeout : Status::kDisplayError;
      break;
    }
  }
  if (sent) *sent = done;
  return status;
}

Status UsbBulk::read(std::span<uint8_t> buffer, uint32_t timeout_ms, size_t& received) {
  received = 0;
  if (!in_ep_) {
    error_ = id_ + ": no bulk IN endpoint";
    return Status::kInvalidArgument;
  }
  int transferred = 0;
  const int r = libusb_bulk_transfer(handle_, in_ep_, buffer.data(),
                                     static_cast<int>(std::min<size_t>(buffer.size(), INT_MAX)),
                                     &transferred, timeout_ms);
  received = static_cast<size_t>(std::max(transferred, 0));
  if (r == 0) return Status::kOk;
  error_ = id_ + ": bulk IN: " + usb_error(r);
  return r == LIBUSB_ERROR_TIMEOUT ? Status::kTimeout : Status::kDisplayError;
}

Status UsbBulk::control_out(uint8_t request_type, uint8_t request, uint16_t value, uint16_t index,
                            uint32_t timeout_ms) {
  const int r =
      libusb_control_transfer(handle_, request_type, request, value, index, nullptr, 0, timeout_ms);
  if (r >= 0) return Status::kOk;
  char what[48];
  std::snprintf(what, sizeof what, "control request 0x%02x value 0x%04x", request, value);
  error_ = id_ + ": " + what + ": " + usb_error(r);
  return r == LIBUSB_ERROR_TIMEOUT ? Status::kTimeout : Status::kDisplayError;
}

}  // namespace lr
