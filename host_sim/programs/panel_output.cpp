#include "lineraster/host_sim/programs/panel_output.hpp"

#include <algorithm>
#include <span>
#include <utility>

#ifdef LR_HAVE_SPIDEV
#include "lineraster/hal/host/linux/spidev_bus.hpp"
#endif
#ifdef LR_HAVE_FT232H
#include "lineraster/hal/host/usb/ft232h_bus.hpp"
#endif

namespace lr::host {

// Owns a backend's bus; the backends' buses are not deletable through PanelBus.
class DeviceBus {
 public:
  virtual ~DeviceBus() = default;
  virtual PanelBus& bus() = 0;
  virtual std::string last_error() const = 0;
};

namespace {

template <class Bus>
class OwnedDevice final : public DeviceBus {
 public:
  explicit OwnedDevice(std::unique_ptr<Bus> bus) : bus_(std::move(bus)) {}
  PanelBus& bus() override { return *bus_; }
  std::string last_error() const override { return bus_->last_error(); }

 private:
  std::unique_ptr<Bus> bus_;
};

// Parses the backend's part of the spec and opens it; null with a one-line error.
template <class Bus, class Config, class Parse>
std::unique_ptr<DeviceBus> open_device(const std::string& spec, Parse parse, std::string& error) {
  Config c;
  if (!parse(spec, c, error)) return nullptr;
  std::unique_ptr<Bus> bus = Bus::open(c, error);
  if (!bus) return nullptr;
  return std::make_unique<OwnedDevice<Bus>>(std::move(bus));
}

}  // namespace

Status send_frame(StripSink<Rgb565Be>& sink, std::span<const uint16_t> rgb565, int width,
                  int height, int k) {
  if (width < 1 || height < 1 || width > 0xFFFF || height > 0xFFFF || k < 1 ||
      rgb565.size() != static_cast<size_t>(width) * static_cast<size_t>(height))
    return Status::kInvalidArgument;
  const auto w = static_cast<uint16_t>(width), h = static_cast<uint16_t>(height);
  Status st = sink.begin_frame(w, h);
  if (st != Status::kOk) return st;
  for (int y0 = 0; y0 < h; y0 += k) {
    const int rows = std::min(k, h - y0);
    StripLease<Rgb565Be> lease;
    st = sink.acquire(lease);
    if (st != Status::kOk) return st;
    std::span<uint16_t> px = lease.pixels();
    const size_t n = size_t{w} * static_cast<size_t>(rows);
    if (px.size() < n) return Status::kInvalidArgument;
    const size_t first = static_cast<size_t>(y0) * w;
    for (size_t i = 0; i < n; ++i) px[i] = Rgb565Be::from_value(rgb565[first + i]);
    const StripRect rect{0, static_cast<uint16_t>(y0), w, static_cast<uint16_t>(rows)};
    st = sink.submit(rect, std::move(lease));
    if (st != Status::kOk) return st;
  }
  return sink.end_frame();
}

PanelOutput::PanelOutput() = default;
PanelOutput::~PanelOutput() = default;

bool PanelOutput::open_bus(const DisplaySpec& spec, const PanelConfig& config, PanelBus*& bus,
                           std::string& error) {
  switch (spec.kind) {
    case DisplayKind::kEmulator: {
      emulator_ = std::make_unique<PanelEmulator>(config);
      EmulatorBus::Options options;
      options.deferred = true;  // transfers complete in wait(), as on a real bus
      options.log = false;
      emulator_bus_ = std::make_unique<EmulatorBus>(*emulator_, options);
      bus = emulator_bus_.get();
      return true;
    }
    case DisplayKind::kSpidev:
#ifdef LR_HAVE_SPIDEV
      device_ = open_device<SpidevBus, SpidevConfig>(spec.device, parse_spidev_spec, error);
      break;
#else
      error =
          "--display spidev: this lineraster-sim was built without the spidev backend "
          "(needs libgpiod 1.x: apt-get install libgpiod-dev, then rebuild)";
      return false;
#endif
    case DisplayKind::kFt232h:
#ifdef LR_HAVE_FT232H
      device_ = open_device<Ft232hBus, Ft232hConfig>(spec.device, parse_ft232h_spec, error);
      break;
#else
      error =
          "--display ft232h: this lineraster-sim was built without the FT232H backend "
          "(needs libusb-1.0: apt-get install libusb-1.0-0-dev, then rebuild)";
      return false;
#endif
    case DisplayKind::kNone:
      error = "no display";
      return false;
  }
  if (!device_) return false;
  bus = &device_->bus();
  return true;
}

bool PanelOutput::open(const DisplaySpec& spec, const PanelConfig& config, int strip_height,
                       std::string& error) {
  strip_height_ = strip_height;
  PanelBus* bus = nullptr;
  if (!open_bus(spec, config, bus, error)) return false;
  counting_ = std::make_unique<CountingBus>(*bus);
  panel_ = std::make_unique<Panel>(*counting_, config);
  if (const Status st = panel_->init(); st != Status::kOk) {
    error = std::string("panel: init: ") + to_string(st) + device_error();
    return false;
  }
  const size_t strip = size_t{config.image_width()} * static_cast<size_t>(strip_height);
  buffers_[0].assign(strip, 0);
  buffers_[1].assign(strip, 0);
  signatures_.assign((config.image_height() + static_cast<size_t>(strip_height) - 1) /
                         static_cast<size_t>(strip_height),
                     StripSignature{});
  sink_ = std::make_unique<PanelSink>(*panel_, buffers_[0], buffers_[1], signatures_);
  return true;
}

bool PanelOutput::send(std::span<const uint16_t> rgb565, int width, int height,
                       std::string& error) {
  const Status st = send_frame(*sink_, rgb565, width, height, strip_height_);
  if (st != Status::kOk) {
    error = std::string("panel: frame: ") + to_string(st) + device_error();
    return false;
  }
  if (!backlight_) {
    if (const Status b = panel_->backlight(true); b != Status::kOk) {
      error = std::string("panel: backlight: ") + to_string(b) + device_error();
      return false;
    }
    backlight_ = true;
  }
  return true;
}

std::string PanelOutput::device_error() const {
  const std::string e = device_ ? device_->last_error() : std::string();
  return e.empty() ? e : " (" + e + ")";
}

}  // namespace lr::host
