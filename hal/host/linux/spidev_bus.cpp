#include "lineraster/hal/host/linux/spidev_bus.hpp"

#include "lineraster/hal/host/parse_number.hpp"

#include <fcntl.h>
#include <linux/spi/spidev.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <system_error>
#include <thread>

namespace lr {
namespace {

constexpr const char* kSpecForm =
    "expected /dev/spidevB.C,dc=LINE[,rst=LINE][,bl=LINE][,hz=N][,mode=0-3], LINE being "
    "CHIP:OFFSET such as gpiochip0:24 or a line name";

std::string errno_text(int e) {
  return std::generic_category().message(e);
}

using backend::parse_u32;

// spidev's buffer size: the most bytes one SPI_IOC_MESSAGE may carry.
size_t spidev_bufsiz() {
  std::ifstream f("/sys/module/spidev/parameters/bufsiz");
  unsigned long v = 0;
  if (f >> v && v > 0) return static_cast<size_t>(v);
  return 4096;
}

}  // namespace

bool parse_spidev_spec(std::string_view spec, SpidevConfig& out, std::string& error) {
  if (spec.empty()) {
    error = std::string("empty SPI device spec (") + kSpecForm + ")";
    return false;
  }
  SpidevConfig c = out;
  c.reset.clear();
  c.backlight.clear();
  c.dc.clear();
  c.hz = SpidevConfig{}.hz;
  c.mode = SpidevConfig{}.mode;
  bool seen_dc = false, seen_rst = false, seen_bl = false, seen_hz = false, seen_mode = false;
  size_t pos = 0;
  bool first = true;
  while (pos <= spec.size()) {
    size_t comma = spec.find(',', pos);
    if (comma == std::string_view::npos) comma = spec.size();
    const std::string_view field = spec.substr(pos, comma - pos);
    pos = comma + 1;
    if (first) {
      first = false;
      if (field.empty() || field.find('=') != std::string_view::npos) {
        error = std::string(spec) + ": the SPI device comes first (" + kSpecForm + ")";
        return false;
      }
      c.device = std::string(field);
      continue;
    }
    const size_t eq = field.find('=');
    if (eq == std::string_view::npos) {
      error = std::string(field) + ": not key=value (" + kSpecForm + ")";
      return false;
    }
    const std::string_view key = field.substr(0, eq);
    const std::string_view value = field.substr(eq + 1);
    const std::string f(field);
    auto twice = [&](bool& seen) {
      if (seen) error = std::string(key) + "= given twice";
      const bool again = seen;
      seen = true;
      return again;
    };
    if (key == "dc" || key == "rst" || key == "bl") {
      bool& seen = key == "dc" ? seen_dc : key == "rst" ? seen_rst : seen_bl;
      if (twice(seen)) return false;
      GpioLineSpec line;
      std::string why;
      if (!parse_gpio_line_spec(value, line, why)) {
        error = std::string(key) + "=" + std::string(value) + ": " + why;
        return false;
      }
      (key == "dc" ? c.dc : key == "rst" ? c.reset : c.backlight) = std::string(value);
    } else if (key == "hz") {
      if (twice(seen_hz)) return false;
      if (!parse_u32(value, c.hz) || c.hz == 0) {
        error = f + ": the SPI clock in hertz, a whole number above 0 (e.g. hz=32000000)";
        return false;
      }
    } else if (key == "mode") {
      if (twice(seen_mode)) return false;
      uint32_t m = 0;
      if (!parse_u32(value, m) || m > 3) {
        error = f + ": the SPI mode is 0, 1, 2 or 3";
        return false;
      }
      c.mode = static_cast<uint8_t>(m);
    } else {
      error = f + ": unknown option (dc=, rst=, bl=, hz=, mode=)";
      return false;
    }
  }
  if (!seen_dc) {
    error = c.device + ": dc= missing (the panel's D/C line, e.g. dc=gpiochip0:24)";
    return false;
  }
  const std::pair<const char*, const std::string*> lines[] = {
      {"dc", &c.dc}, {"rst", &c.reset}, {"bl", &c.backlight}};
  for (size_t i = 0; i < 3; ++i) {
    for (size_t j = i + 1; j < 3; ++j) {
      if (!lines[i].second->empty() && *lines[i].second == *lines[j].second) {
        error = std::string(lines[i].first) + " and " + lines[j].first + " name the same line " +
                *lines[i].second;
        return false;
      }
    }
  }
  out = std::move(c);
  return true;
}

std::unique_ptr<SpidevBus> SpidevBus::open(const SpidevConfig& config, std::string& error) {
  try {
    const std::string& dev = config.device;
    if (dev.empty()) {
      error = "no SPI device given (e.g. /dev/spidev0.0)";
      return nullptr;
    }
    if (config.mode > 3) {
      error = dev + ": SPI mode " + std::to_string(config.mode) + " (the mode is 0, 1, 2 or 3)";
      return nullptr;
    }
    if (config.hz == 0) {
      error = dev + ": SPI clock of 0 Hz";
      return nullptr;
    }
    if (config.dc.empty()) {
      error = dev + ": no D/C line given (the panel's D/C pin, e.g. dc=gpiochip0:24)";
      return nullptr;
    }
    std::unique_ptr<SpidevBus> bus(new SpidevBus());
    bus->device_ = dev;
    bus->busy_timeout_ms_ = config.busy_timeout_ms;
    bus->fd_ = ::open(dev.c_str(), O_RDWR | O_CLOEXEC);
    if (bus->fd_ < 0) {
      const int e = errno;
      if (e == ENOENT || e == ENODEV || e == ENXIO) {
        error = dev +
                ": no such device (enable SPI: dtparam=spi=on on a Raspberry Pi, or load "
                "spidev)";
      } else if (e == EACCES || e == EPERM) {
        error = dev + ": permission denied (add the user to the spi group or run as root)";
      } else {
        error = dev + ": cannot open (" + errno_text(e) + ")";
      }
      return nullptr;
    }
    const int fd = bus->fd_;
    uint8_t mode = config.mode;
    if (ioctl(fd, SPI_IOC_WR_MODE, &mode) < 0) {
      const int e = errno;
      error = e == ENOTTY ? dev + ": not an SPI device (spidev refused SPI_IOC_WR_MODE)"
                          : dev + ": cannot set SPI mode " + std::to_string(config.mode) + " (" +
                                errno_text(e) + ")";
      return nullptr;
    }
    uint8_t bits = 8;
    if (ioctl(fd, SPI_IOC_WR_BITS_PER_WORD, &bits) < 0) {
      error = dev + ": cannot set 8 bits per word (" + errno_text(errno) + ")";
      return nullptr;
    }
    uint32_t hz = config.hz;
    if (ioctl(fd, SPI_IOC_WR_MAX_SPEED_HZ, &hz) < 0) {
      error = dev + ": cannot set the clock to " + std::to_string(config.hz) + " Hz (" +
              errno_text(errno) + ")";
      return nullptr;
    }
    uint32_t actual = 0;
    bus->hz_ = ioctl(fd, SPI_IOC_RD_MAX_SPEED_HZ, &actual) == 0 && actual ? actual : config.hz;
    bus->chunk_ = config.chunk_bytes ? config.chunk_bytes : spidev_bufsiz();

    bus->dc_ = GpioLine::open(config.dc, "lineraster-dc", true, error);
    if (!bus->dc_) return nullptr;
    if (!config.reset.empty()) {
      bus->reset_ = GpioLine::open(config.reset, "lineraster-reset", true, error);
      if (!bus->reset_) return nullptr;
    }
    if (!config.backlight.empty()) {
      bus->backlight_ = GpioLine::open(config.backlight, "lineraster-backlight", false, error);
      if (!bus->backlight_) return nullptr;
    }
    bus->worker_ = backend::TransferWorker::create(*bus, error);
    if (!bus->worker_) {
      error = dev + ": " + error;
      return nullptr;
    }
    return bus;
  } catch (const std::exception& e) {
    error = config.device + ": " + e.what();
    return nullptr;
  }
}

SpidevBus::~SpidevBus() {
  worker_.reset();  // joins: the transfer in flight completes first
  if (fd_ >= 0) ::close(fd_);
}

bool SpidevBus::transfer(const uint8_t* data, size_t size, std::string* error) {
  while (size > 0) {
    const size_t n = std::min(size, chunk_);
    spi_ioc_transfer tr;
    std::memset(&tr, 0, sizeof tr);
    tr.tx_buf = reinterpret_cast<uintptr_t>(data);
    tr.len = static_cast<uint32_t>(n);
    tr.speed_hz = hz_;
    tr.bits_per_word = 8;
    if (ioctl(fd_, SPI_IOC_MESSAGE(1), &tr) < 0) {
      if (error) {
        *error = device_ + ": SPI transfer of " + std::to_string(n) + " bytes failed (" +
                 errno_text(errno) + ")";
      }
      return false;
    }
    data += n;
    size -= n;
  }
  return true;
}

Status SpidevBus::ready() {
  const Status s = worker_->idle(busy_timeout_ms_);
  if (s == Status::kTimeout) error_ = device_ + ": the abandoned pixel transfer is still running";
  return s;
}

Status SpidevBus::set_dc(bool high) {
  if (dc_->value() == high) return Status::kOk;
  if (!dc_->set(high)) {
    error_ = dc_->description() + " (D/C): cannot set (" + errno_text(errno) + ")";
    return Status::kDisplayError;
  }
  return Status::kOk;
}

Status SpidevBus::command(uint8_t cmd, std::span<const uint8_t> params) {
  if (const Status s = ready(); s != Status::kOk) return s;
  if (const Status s = set_dc(false); s != Status::kOk) return s;
  if (!transfer(&cmd, 1, &error_)) return Status::kDisplayError;
  if (params.empty()) return Status::kOk;
  if (const Status s = set_dc(true); s != Status::kOk) return s;
  return transfer(params.data(), params.size(), &error_) ? Status::kOk : Status::kDisplayError;
}

Status SpidevBus::start_pixels(std::span<const uint8_t> pixels) {
  if (const Status s = ready(); s != Status::kOk) return s;
  if (pixels.empty()) return Status::kOk;
  if (const Status s = set_dc(true); s != Status::kOk) return s;
  try {
    pixels_.assign(pixels.begin(), pixels.end());
  } catch (const std::bad_alloc&) {
    error_ = device_ + ": out of memory for " + std::to_string(pixels.size()) + " pixel bytes";
    return Status::kCapacity;
  }
  worker_error_.clear();
  return worker_->start((pixels_.size() + chunk_ - 1) / chunk_);
}

bool SpidevBus::piece(size_t index) {
  const size_t begin = index * chunk_;
  const size_t n = std::min(chunk_, pixels_.size() - begin);
  return transfer(pixels_.data() + begin, n, &worker_error_);
}

Status SpidevBus::wait(uint32_t timeout_ms) {
  const Status s = worker_->wait(timeout_ms);
  if (s == Status::kDisplayError) error_ = worker_error_;
  if (s == Status::kTimeout) {
    error_ = device_ + ": pixel transfer not done after " + std::to_string(timeout_ms) + " ms";
  }
  return s;
}

Status SpidevBus::set_reset(bool asserted) {
  if (!reset_) return Status::kOk;
  if (const Status s = ready(); s != Status::kOk) return s;
  if (!reset_->set(!asserted)) {  // the panel's RESX is active low
    error_ = reset_->description() + " (reset): cannot set (" + errno_text(errno) + ")";
    return Status::kDisplayError;
  }
  return Status::kOk;
}

Status SpidevBus::set_backlight(bool on) {
  if (!backlight_) return Status::kOk;
  if (const Status s = ready(); s != Status::kOk) return s;
  if (!backlight_->set(on)) {
    error_ = backlight_->description() + " (backlight): cannot set (" + errno_text(errno) + ")";
    return Status::kDisplayError;
  }
  return Status::kOk;
}

void SpidevBus::delay_ms(uint32_t ms) {
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
}

std::string SpidevBus::last_error() const {
  return error_;
}

}  // namespace lr
