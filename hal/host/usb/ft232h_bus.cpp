#include "lineraster/hal/host/usb/ft232h_bus.hpp"

#include "lineraster/hal/host/parse_number.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <thread>

namespace lr {
namespace {

// FTDI vendor requests (the chip's "SIO" requests, as in the Linux ftdi_sio driver), sent to
// the device with wIndex = 1 (interface A, the FT232H's only one).
constexpr uint8_t kVendorOut = 0x40;  // host to device, vendor, device recipient
constexpr uint8_t kSioReset = 0x00;   // wValue 0: reset, 1: purge RX, 2: purge TX
constexpr uint8_t kSioSetLatencyTimer = 0x09;
constexpr uint8_t kSioSetBitmode = 0x0B;  // wValue: mode << 8 | pin mask
constexpr uint16_t kBitmodeReset = 0x0000;
constexpr uint16_t kBitmodeMpsse = 0x0200;
constexpr uint16_t kInterfaceA = 1;

constexpr uint8_t kRamwr = 0x2C;
constexpr uint8_t kRamwrc = 0x3C;

constexpr const char* kSpecForm =
    "expected ft232h[:SERIAL][,hz=N][,cs=PIN][,dc=PIN][,rst=PIN|none][,bl=PIN|none], PIN being "
    "D3-D7 or C0-C7";

using backend::parse_u32;

}  // namespace

bool parse_ft232h_spec(std::string_view spec, Ft232hConfig& out, std::string& error) {
  if (spec.empty()) {
    error = std::string("empty FT232H spec (") + kSpecForm + ")";
    return false;
  }
  const size_t comma = std::min(spec.find(','), spec.size());
  const std::string_view head = spec.substr(0, comma);
  if (head.substr(0, 6) != "ft232h" || (head.size() > 6 && head[6] != ':')) {
    error = std::string(spec) + ": not an FT232H spec (" + kSpecForm + ")";
    return false;
  }
  Ft232hConfig c = out;
  c.serial.clear();
  c.hz = Ft232hConfig{}.hz;
  c.pins = mpsse::PinMap{};
  if (head.size() > 6) {
    c.serial = std::string(head.substr(7));
    if (c.serial.empty()) {
      error = std::string("empty serial number after ft232h: (") + kSpecForm + ")";
      return false;
    }
  }
  bool seen_hz = false, seen_cs = false, seen_dc = false, seen_rst = false, seen_bl = false;
  size_t pos = comma + 1;
  while (pos <= spec.size()) {
    size_t next = spec.find(',', pos);
    if (next == std::string_view::npos) next = spec.size();
    const std::string_view field = spec.substr(pos, next - pos);
    pos = next + 1;
    const std::string f(field);
    const size_t eq = field.find('=');
    if (eq == std::string_view::npos) {
      error = f + ": not key=value (" + kSpecForm + ")";
      return false;
    }
    const std::string_view key = field.substr(0, eq);
    const std::string_view value = field.substr(eq + 1);
    bool* seen = key == "hz"    ? &seen_hz
                 : key == "cs"  ? &seen_cs
                 : key == "dc"  ? &seen_dc
                 : key == "rst" ? &seen_rst
                 : key == "bl"  ? &seen_bl
                                : nullptr;
    if (!seen) {
      error = f + ": unknown option (hz=, cs=, dc=, rst=, bl=)";
      return false;
    }
    if (*seen) {
      error = std::string(key) + "= given twice";
      return false;
    }
    *seen = true;
    if (key == "hz") {
      if (!parse_u32(value, c.hz) || c.hz == 0) {
        error = f + ": the SPI clock in hertz, a whole number above 0 (e.g. hz=30000000)";
        return false;
      }
      continue;
    }
    const bool optional = key == "rst" || key == "bl";
    if (optional && value == "none") {
      (key == "rst" ? c.pins.reset : c.pins.backlight).reset();
      continue;
    }
    mpsse::Pin pin;
    std::string why;
    if (!mpsse::parse_pin(value, pin, why)) {
      error = std::string(key) + "=" + why;
      return false;
    }
    if (key == "cs") c.pins.cs = pin;
    if (key == "dc") c.pins.dc = pin;
    if (key == "rst") c.pins.reset = pin;
    if (key == "bl") c.pins.backlight = pin;
  }
  if (!mpsse::check_pins(c.pins, error)) return false;
  out = std::move(c);
  return true;
}

std::unique_ptr<Ft232hBus> Ft232hBus::open(const Ft232hConfig& config, std::string& error) {
  try {
    if (!mpsse::check_pins(config.pins, error)) return nullptr;
    if (config.hz == 0) {
      error = "ft232h: SPI clock of 0 Hz";
      return nullptr;
    }
    std::unique_ptr<Ft232hBus> bus(new Ft232hBus(config));
    UsbBulkConfig usb;
    usb.vid = config.vid;
    usb.pid = config.pid;
    usb.serial = config.serial;
    usb.interface = 0;
    usb.out_endpoint = 0x02;
    usb.in_endpoint = 0x81;
    usb.what = "the FT232H";
    bus->usb_ = UsbBulk::open(usb, error);
    if (!bus->usb_) return nullptr;
    if (bus->setup(error) != Status::kOk) return nullptr;
    bus->worker_ = backend::TransferWorker::create(*bus, error);
    if (!bus->worker_) {
      error = bus->usb_->id() + ": " + error;
      return nullptr;
    }
    return bus;
  } catch (const std::exception& e) {
    error = usb_id(config.vid, config.pid) + ": " + e.what();
    return nullptr;
  }
}

Ft232hBus::~Ft232hBus() {
  worker_.reset();
}  // joins: the packet in flight and CS release first

uint32_t Ft232hBus::timeout_for(size_t bytes) const {
  const uint64_t wire_ms = uint64_t{bytes} * 8 * 1000 / hz() + 1;
  return static_cast<uint32_t>(std::min<uint64_t>(config_.usb_timeout_ms + wire_ms, 0xFFFFFFFFu));
}

Status Ft232hBus::send(std::span<const uint8_t> bytes, std::string& error) {
  if (bytes.empty()) return Status::kOk;
  const Status s = usb_->write(bytes, timeout_for(bytes.size()));
  if (s != Status::kOk) {
    error = usb_->last_error();
    broken_ = true;
  }
  return s;
}

Status Ft232hBus::setup(std::string& error) {
  const std::string& id = usb_->id();
  struct Request {
    uint8_t request;
    uint16_t value;
    const char* what;
  };
  const Request requests[] = {
      {kSioReset, 0, "reset"},
      {kSioSetLatencyTimer, config_.latency_ms, "latency timer"},
      {kSioSetBitmode, kBitmodeReset, "bit mode reset"},
      {kSioSetBitmode, kBitmodeMpsse, "MPSSE mode"},
      {kSioReset, 1, "purge"},
      {kSioReset, 2, "purge"},
  };
  for (const Request& r : requests) {
    if (usb_->control_out(kVendorOut, r.request, r.value, kInterfaceA, config_.usb_timeout_ms) !=
        Status::kOk) {
      error = id + ": FTDI " + r.what + " request failed (" + usb_->last_error() + ")";
      return Status::kDisplayError;
    }
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(20));

  // In step? The chip answers an unknown opcode with 0xFA and the opcode.
  std::vector<uint8_t> probe;
  mpsse::sync_probe(probe);
  if (usb_->write(probe, config_.usb_timeout_ms) != Status::kOk) {
    error = id + ": cannot write to the chip (" + usb_->last_error() + ")";
    return Status::kDisplayError;
  }
  std::vector<uint8_t> payload;
  std::vector<uint8_t> buf(usb_->in_max_packet() * 4);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
  bool answered = false;
  while (!answered && std::chrono::steady_clock::now() < deadline) {
    size_t got = 0;
    const Status s = usb_->read(buf, 50, got);
    if (s != Status::kOk && s != Status::kTimeout) break;
    mpsse::strip_modem_status(std::span<const uint8_t>(buf.data(), got), usb_->in_max_packet(),
                              payload);
    answered = mpsse::has_bad_command_reply(payload, mpsse::kBogusOpcode);
  }
  if (!answered) {
    error = id + ": the MPSSE did not answer (not an FT232H, or unplug and replug it)";
    return Status::kDisplayError;
  }

  tx_.clear();
  enc_.init(config_.hz, tx_);
  if (usb_->write(tx_, config_.usb_timeout_ms) != Status::kOk) {
    error = id + ": cannot write to the chip (" + usb_->last_error() + ")";
    return Status::kDisplayError;
  }
  broken_ = false;
  return Status::kOk;
}

Status Ft232hBus::ready() {
  const Status s = worker_->idle(config_.busy_timeout_ms);
  if (s == Status::kTimeout)
    error_ = usb_->id() + ": the abandoned pixel transfer is still running";
  if (s != Status::kOk) return s;
  if (broken_ && setup(error_) != Status::kOk) return Status::kDisplayError;
  return Status::kOk;
}

Status Ft232hBus::command(uint8_t cmd, std::span<const uint8_t> params) {
  if (const Status s = ready(); s != Status::kOk) return s;
  tx_.clear();
  const bool keep_cs = (cmd == kRamwr || cmd == kRamwrc) && params.empty();
  try {
    enc_.command(cmd, params, keep_cs, tx_);
  } catch (const std::bad_alloc&) {
    error_ = usb_->id() + ": out of memory";
    broken_ = true;  // the encoder's pin state may be ahead of the chip's
    return Status::kCapacity;
  }
  return send(tx_, error_);
}

Status Ft232hBus::start_pixels(std::span<const uint8_t> pixels) {
  if (const Status s = ready(); s != Status::kOk) return s;
  if (pixels.empty()) return Status::kOk;
  stream_.clear();
  piece_end_.clear();
  tail_.clear();
  try {
    enc_.select_data(stream_);
    for (size_t at = 0; at < pixels.size(); at += mpsse::kMaxPacket) {
      enc_.write_bytes(pixels.subspan(at, std::min(mpsse::kMaxPacket, pixels.size() - at)),
                       stream_);
      piece_end_.push_back(stream_.size());
    }
    enc_.deselect(tail_);
  } catch (const std::bad_alloc&) {
    error_ = usb_->id() + ": out of memory for " + std::to_string(pixels.size()) + " pixel bytes";
    broken_ = true;
    return Status::kCapacity;
  }
  job_failed_ = false;
  worker_error_.clear();
  return worker_->start(piece_end_.size());
}

bool Ft232hBus::piece(size_t index) {
  const size_t begin = index ? piece_end_[index - 1] : 0;
  const std::span<const uint8_t> bytes(stream_.data() + begin, piece_end_[index] - begin);
  if (send(bytes, worker_error_) == Status::kOk) return true;
  job_failed_ = true;
  return false;
}

bool Ft232hBus::finish() {
  if (job_failed_) return false;  // the chip is set up again before the next call
  return send(tail_, worker_error_) == Status::kOk;
}

Status Ft232hBus::wait(uint32_t timeout_ms) {
  const Status s = worker_->wait(timeout_ms);
  if (s == Status::kDisplayError) error_ = worker_error_;
  if (s == Status::kTimeout) {
    error_ = usb_->id() + ": pixel transfer not done after " + std::to_string(timeout_ms) + " ms";
  }
  return s;
}

Status Ft232hBus::set_reset(bool asserted) {
  if (!config_.pins.reset) return Status::kOk;
  if (const Status s = ready(); s != Status::kOk) return s;
  tx_.clear();
  enc_.set_reset(asserted, tx_);
  return send(tx_, error_);
}

Status Ft232hBus::set_backlight(bool on) {
  if (!config_.pins.backlight) return Status::kOk;
  if (const Status s = ready(); s != Status::kOk) return s;
  tx_.clear();
  enc_.set_backlight(on, tx_);
  return send(tx_, error_);
}

void Ft232hBus::delay_ms(uint32_t ms) {
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
}

}  // namespace lr
