// Runs inside the emulated ARM Linux guest of scripts/ci_guest.sh (tests/guest/init.sh starts
// it) and drives the Linux display backends on a real kernel: SpidevBus (hal/host/linux: spidev +
// libgpiod) on a spi-gpio bus over the virt board's PL061 GPIO chip, and UsbBulk (hal/host/usb:
// libusb) on a USB gadget. One line per check ("PASS name: details" / "FAIL name: details") and
// a summary ("guest: N passed, M failed"), which the host script reads from the serial console.
//
// The guest's wiring (tests/guest/virt_spi_gpio.dtsi, tests/guest/init.sh):
//   PL061 "9030000.pl061", 8 lines: 0-3 SCK, MOSI, MISO, CS of the spi-gpio bus (taken by the
//   kernel); 4 D/C, 5 reset, 6 backlight; 7 free. spidev: the /dev/spidevB.0 whose device tree
//   node is compatible "rohm,dh2228fv", bufsiz 1024 (kernel command line spidev.bufsiz=1024).
//   USB: 1209:0001 (pid.codes' test IDs), serial "lr-guest-0001", interface 0 = SourceSink with
//   pattern 1: byte i of every packet is i % 63, both ways (the sink halts its endpoint on any
//   other byte).
// Line values are read back through the kernel's GPIO debugfs file, which reads the PL061's data
// register (/sys/kernel/debug/gpio: "gpio-N (name|consumer) out hi"), and through libgpiod.
#include <fcntl.h>
#include <gpiod.h>
#include <libusb.h>
#include <linux/spi/spidev.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "lineraster/hal/host/linux/spidev_bus.hpp"
#include "lineraster/hal/host/usb/usb_bulk.hpp"

namespace {

constexpr const char* kChip = "9030000.pl061";  // the PL061's label (its device name)
constexpr unsigned kChipLines = 8;
constexpr unsigned kDcLine = 4, kResetLine = 5, kBacklightLine = 6;
constexpr size_t kSpidevBufsiz = 1024;
constexpr uint16_t kUsbVid = 0x1209, kUsbPid = 0x0001;
constexpr const char* kUsbSerial = "lr-guest-0001";

int g_passed = 0;
int g_failed = 0;

void check(bool ok, const char* name, const std::string& details) {
  std::printf("%s %s: %s\n", ok ? "PASS" : "FAIL", name, details.c_str());
  std::fflush(stdout);
  ++(ok ? g_passed : g_failed);
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream f(path);
  std::string s;
  std::getline(f, s, '\0');
  while (!s.empty() && (s.back() == '\n' || s.back() == '\0')) s.pop_back();
  return s;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string line_spec(unsigned offset) {
  return std::string(kChip) + ":" + std::to_string(offset);
}

// A line of the PL061 as the kernel reports it: "out hi lineraster-dc", "in lo -", or "free".
std::string line_state(unsigned offset) {
  std::string result = "free";
  // debugfs numbers lines globally ("gpio-2044"); find the chip's base from its header line.
  std::istringstream in(read_text("/sys/kernel/debug/gpio"));
  std::string text;
  int base = -1;
  while (std::getline(in, text)) {
    if (text.rfind("gpiochip", 0) == 0) {
      base = -1;
      size_t at = text.find("GPIOs ");
      if (text.find(std::string(kChip) + ":") != std::string::npos && at != std::string::npos) {
        base = std::stoi(text.substr(at + 6));
      }
      continue;
    }
    if (base < 0) continue;
    const std::string tag = "gpio-" + std::to_string(base + static_cast<int>(offset)) + " ";
    const size_t p = text.find(tag);
    if (p == std::string::npos) continue;
    const size_t bar = text.find('|'), close = text.find(')');
    std::string consumer = bar != std::string::npos && close != std::string::npos
                               ? text.substr(bar + 1, close - bar - 1)
                               : "?";
    while (!consumer.empty() && consumer.back() == ' ') consumer.pop_back();
    std::istringstream rest(text.substr(close + 1));
    std::string dir, value;
    rest >> dir >> value;
    result = dir + " " + value + " " + consumer;
  }
  return result;
}

bool starts_with(const std::string& s, const std::string& prefix) {
  return s.rfind(prefix, 0) == 0;
}

// An error the backends return: one line, naming what `must_contain` says.
bool one_line_error(const std::string& error, const std::string& must_contain) {
  return !error.empty() && error.find('\n') == std::string::npos &&
         error.find(must_contain) != std::string::npos;
}

const char* str(lr::Status s) {
  return lr::to_string(s);
}

// ---- kernel interfaces, directly

void check_gpio_chip() {
  gpiod_chip* chip = gpiod_chip_open_by_label(kChip);
  if (!chip) {
    check(false, "gpio_chip", std::string(kChip) + ": " + std::strerror(errno));
    return;
  }
  const unsigned lines = gpiod_chip_num_lines(chip);
  std::string spi;
  for (unsigned i = 0; i < 4 && i < lines; ++i) {
    gpiod_line* l = gpiod_chip_get_line(chip, i);
    const char* c = l ? gpiod_line_consumer(l) : nullptr;
    spi += std::string(i ? "," : "") + (c ? c : "-");
  }
  check(lines == kChipLines && spi == "sck,mosi,miso,spi0 CS0", "gpio_chip",
        std::string("libgpiod: ") + gpiod_chip_name(chip) + " (" + gpiod_chip_label(chip) + "), " +
            std::to_string(lines) + " lines, lines 0-3 used by " + spi);
  gpiod_chip_close(chip);
}

// The spidev of the test's device tree node; empty when none.
std::string find_spidev() {
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/sys/class/spidev", ec)) {
    if (read_text(e.path() / "device/of_node/compatible") == "rohm,dh2228fv") {
      return "/dev/" + e.path().filename().string();
    }
  }
  return {};
}

void check_spidev_device(const std::string& path) {
  const std::string bufsiz = read_text("/sys/module/spidev/parameters/bufsiz");
  const int fd = path.empty() ? -1 : open(path.c_str(), O_RDWR);
  if (fd < 0) {
    check(false, "spidev_device",
          path.empty() ? "no spidev with compatible rohm,dh2228fv"
                       : path + ": " + std::strerror(errno));
    return;
  }
  // One message larger than bufsiz is refused: the bus has to split pixel data.
  std::vector<uint8_t> data(kSpidevBufsiz + 1, 0x5a);
  spi_ioc_transfer t{};
  t.tx_buf = reinterpret_cast<uintptr_t>(data.data());
  t.len = static_cast<uint32_t>(data.size());
  t.bits_per_word = 8;
  const int r = ioctl(fd, SPI_IOC_MESSAGE(1), &t);
  const int e = errno;
  close(fd);
  check(bufsiz == std::to_string(kSpidevBufsiz) && r < 0 && e == EMSGSIZE, "spidev_device",
        path + ", bufsiz " + bufsiz + "; one message of " + std::to_string(data.size()) +
            " bytes: " + (r < 0 ? std::strerror(e) : "accepted"));
}

// ---- SpidevBus

lr::SpidevConfig bus_config(const std::string& device) {
  lr::SpidevConfig c;
  c.device = device;
  c.hz = 10'000'000;
  c.dc = line_spec(kDcLine);
  c.reset = line_spec(kResetLine);
  c.backlight = line_spec(kBacklightLine);
  return c;
}

void check_spidev_bus(const std::string& device) {
  std::string error;
  std::unique_ptr<lr::SpidevBus> bus = lr::SpidevBus::open(bus_config(device), error);
  const std::string dc0 = line_state(kDcLine), rst0 = line_state(kResetLine),
                    bl0 = line_state(kBacklightLine);
  check(bus && bus->chunk_bytes() == kSpidevBufsiz && dc0 == "out hi lineraster-dc" &&
            rst0 == "out hi lineraster-reset" && bl0 == "out lo lineraster-backlight",
        "spidev_bus_open",
        bus ? device + ", " + std::to_string(bus->hz()) + " Hz, " +
                  std::to_string(bus->chunk_bytes()) + "-byte transfers; D/C " + dc0 + ", reset " +
                  rst0 + ", backlight " + bl0
            : error);
  if (!bus) {
    for (const char* name : {"spidev_bus_reset_backlight", "spidev_bus_command",
                             "spidev_bus_pixels", "spidev_bus_busy_line", "gpio_dc_readback"}) {
      check(false, name, "no bus");
    }
    return;
  }

  // Reset (active low on the panel) and backlight (active high), read back from the PL061.
  {
    const lr::Status a = bus->set_reset(true);
    const std::string held = line_state(kResetLine);
    const lr::Status b = bus->set_reset(false);
    const std::string released = line_state(kResetLine);
    const lr::Status c = bus->set_backlight(true);
    const std::string on = line_state(kBacklightLine);
    const lr::Status d = bus->set_backlight(false);
    const std::string off = line_state(kBacklightLine);
    const bool ok = a == lr::Status::kOk && b == lr::Status::kOk && c == lr::Status::kOk &&
                    d == lr::Status::kOk && starts_with(held, "out lo") &&
                    starts_with(released, "out hi") && starts_with(on, "out hi") &&
                    starts_with(off, "out lo");
    check(ok, "spidev_bus_reset_backlight",
          std::string("reset asserted: ") + str(a) + ", line " + held + "; released: " + str(b) +
              ", " + released + "; backlight on: " + str(c) + ", " + on + "; off: " + str(d) +
              ", " + off);
  }

  // A command without parameters leaves D/C low, one with parameters leaves it high.
  {
    const lr::Status a = bus->command(0x29, {});  // DISPON
    const std::string after_cmd = line_state(kDcLine);
    const uint8_t caset[] = {0x00, 0x00, 0x01, 0x3f};
    const lr::Status b = bus->command(0x2a, caset);  // CASET 0..319
    const std::string after_params = line_state(kDcLine);
    check(a == lr::Status::kOk && b == lr::Status::kOk && starts_with(after_cmd, "out lo") &&
              starts_with(after_params, "out hi"),
          "spidev_bus_command",
          std::string("DISPON: ") + str(a) + ", D/C " + after_cmd +
              "; CASET with 4 bytes: " + str(b) + ", D/C " + after_params +
              (a == lr::Status::kOk && b == lr::Status::kOk ? "" : "; " + bus->last_error()));
  }

  // A 320x240 RGB565 frame after RAMWR: 150 transfers of 1024 bytes (spidev's bufsiz).
  {
    std::vector<uint8_t> frame(320 * 240 * 2);
    for (size_t i = 0; i < frame.size(); ++i) frame[i] = static_cast<uint8_t>(i * 7);
    const lr::Status ramwr = bus->command(0x2c, {});
    const auto t0 = std::chrono::steady_clock::now();
    const lr::Status start = bus->start_pixels(frame);
    const lr::Status busy = bus->command(0x00, {});  // not allowed before wait()
    const lr::Status done = bus->wait(60'000);
    const double s = seconds_since(t0);
    const std::string dc = line_state(kDcLine);
    check(ramwr == lr::Status::kOk && start == lr::Status::kOk && busy == lr::Status::kBusy &&
              done == lr::Status::kOk && starts_with(dc, "out hi"),
          "spidev_bus_pixels",
          std::to_string(frame.size()) + " bytes in " +
              std::to_string((frame.size() + kSpidevBufsiz - 1) / kSpidevBufsiz) +
              " transfers: RAMWR " + str(ramwr) + ", start " + str(start) +
              ", command before wait " + str(busy) + ", wait " + str(done) + " after " +
              std::to_string(s) + " s (" +
              std::to_string(static_cast<double>(frame.size()) / s / 1024.0) + " KB/s), D/C " + dc +
              (done == lr::Status::kOk ? "" : "; " + bus->last_error()));
  }

  // A second bus on the same D/C line while the first holds it.
  {
    std::string busy_error;
    lr::SpidevConfig c = bus_config(device);
    c.reset.clear();
    c.backlight.clear();
    auto second = lr::SpidevBus::open(c, busy_error);
    check(!second && one_line_error(busy_error, "busy (used by lineraster-dc)"),
          "spidev_bus_busy_line", second ? "second bus opened" : busy_error);
  }

  // The last value SpidevBus drove on D/C (low after a command without parameters), read back
  // with libgpiod after the bus has let the line go: the PL061 keeps driving it.
  {
    const lr::Status nop = bus->command(0x00, {});
    bus.reset();
    gpiod_chip* chip = gpiod_chip_open_by_label(kChip);
    gpiod_line* line = chip ? gpiod_chip_get_line(chip, kDcLine) : nullptr;
    gpiod_line_request_config cfg{"lr-guest-read", GPIOD_LINE_REQUEST_DIRECTION_AS_IS, 0};
    const bool requested = line && gpiod_line_request(line, &cfg, 0) == 0;
    const int value = requested ? gpiod_line_get_value(line) : -1;
    const bool output = requested && gpiod_line_direction(line) == GPIOD_LINE_DIRECTION_OUTPUT;
    if (requested) gpiod_line_release(line);
    if (chip) gpiod_chip_close(chip);
    check(nop == lr::Status::kOk && value == 0 && output, "gpio_dc_readback",
          std::string("NOP: ") + str(nop) + "; after closing the bus libgpiod reads line " +
              std::to_string(kDcLine) + " = " + std::to_string(value) +
              (output ? " (output)" : " (not an output)"));
  }
}

// The bounded waits and a failed transfer: wait() gives up on time and the bus is usable again;
// transfers larger than spidev's buffer fail and wait() says so in one line.
void check_spidev_bus_failures(const std::string& device) {
  std::vector<uint8_t> frame(320 * 240 * 2, 0xa5);
  {
    std::string error;
    auto bus = lr::SpidevBus::open(bus_config(device), error);
    const lr::Status start = bus ? bus->start_pixels(frame) : lr::Status::kDisplayError;
    const lr::Status waited = bus ? bus->wait(1) : lr::Status::kDisplayError;
    const std::string why = bus ? bus->last_error() : error;
    const lr::Status after = bus ? bus->command(0x00, {}) : lr::Status::kDisplayError;
    check(start == lr::Status::kOk && waited == lr::Status::kTimeout && after == lr::Status::kOk &&
              one_line_error(why, "not done after 1 ms"),
          "spidev_bus_timeout",
          std::string("start ") + str(start) + ", wait(1 ms) " + str(waited) + " (\"" + why +
              "\"), then a command: " + str(after));
  }
  {
    std::string error;
    lr::SpidevConfig c = bus_config(device);
    c.chunk_bytes = 2 * kSpidevBufsiz;
    auto bus = lr::SpidevBus::open(c, error);
    const lr::Status start = bus ? bus->start_pixels(frame) : lr::Status::kDisplayError;
    const lr::Status waited = bus ? bus->wait(10'000) : lr::Status::kOk;
    const std::string why = bus ? bus->last_error() : error;
    const lr::Status again = bus ? bus->command(0x00, {}) : lr::Status::kDisplayError;
    check(bus && start == lr::Status::kOk && waited == lr::Status::kDisplayError &&
              one_line_error(why, "Message too long") && again == lr::Status::kOk,
          "spidev_bus_transfer_error",
          std::to_string(c.chunk_bytes) + "-byte transfers: start " + str(start) + ", wait " +
              str(waited) + " (\"" + why + "\"), then a command: " + str(again));
  }
}

void check_spidev_errors(const std::string& device) {
  struct Case {
    const char* name;
    lr::SpidevConfig config;
    std::string expect;
  };
  lr::SpidevConfig wrong_device = bus_config("/dev/spidev9.9");
  lr::SpidevConfig kernel_line = bus_config(device);
  kernel_line.dc = line_spec(0);  // SCK, held by spi-gpio
  lr::SpidevConfig no_chip = bus_config(device);
  no_chip.dc = "gpiochip7:4";
  lr::SpidevConfig no_line = bus_config(device);
  no_line.reset = line_spec(kChipLines);
  const Case cases[] = {
      {"spidev_error_device", wrong_device, "/dev/spidev9.9: no such device"},
      {"spidev_error_line_busy", kernel_line, "line 0: busy (used by sck)"},
      {"spidev_error_no_chip", no_chip, "gpiochip7: "},
      {"spidev_error_no_line", no_line, "line 8: no such line"},
  };
  for (const Case& c : cases) {
    std::string error;
    auto bus = lr::SpidevBus::open(c.config, error);
    check(!bus && one_line_error(error, c.expect), c.name, bus ? "opened" : "\"" + error + "\"");
  }
}

// ---- USB: the gadget through libusb, then UsbBulk

void check_usb_enumerate() {
  libusb_context* ctx = nullptr;
  if (const int r = libusb_init(&ctx); r != 0) {
    check(false, "usb_enumerate", std::string("libusb_init: ") + libusb_error_name(r));
    return;
  }
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &list);
  std::string found;
  int speed = 0;
  for (ssize_t i = 0; i < n; ++i) {
    libusb_device_descriptor d{};
    if (libusb_get_device_descriptor(list[i], &d) != 0) continue;
    char s[80];
    std::snprintf(s, sizeof s, "%s%04x:%04x (bus %d device %d)", found.empty() ? "" : ", ",
                  d.idVendor, d.idProduct, libusb_get_bus_number(list[i]),
                  libusb_get_device_address(list[i]));
    found += s;
    if (d.idVendor == kUsbVid && d.idProduct == kUsbPid) speed = libusb_get_device_speed(list[i]);
  }
  if (n >= 0) libusb_free_device_list(list, 1);
  libusb_exit(ctx);
  const char* speeds[] = {"unknown", "low", "full", "high", "super", "super+"};
  check(speed != 0, "usb_enumerate",
        "libusb lists " + found +
            (speed ? std::string("; the gadget at ") + (speed < 6 ? speeds[speed] : "another") +
                         " speed"
                   : std::string("; no 1209:0001")));
}

void check_usb_bulk() {
  lr::UsbBulkConfig config;
  config.vid = kUsbVid;
  config.pid = kUsbPid;
  config.serial = kUsbSerial;
  config.what = "the guest's USB gadget";
  std::string error;
  std::unique_ptr<lr::UsbBulk> usb = lr::UsbBulk::open(config, error);
  char eps[64] = "";
  if (usb) {
    std::snprintf(eps, sizeof eps, "bulk OUT 0x%02x, bulk IN 0x%02x (%zu-byte packets)",
                  usb->out_endpoint(), usb->in_endpoint(), usb->in_max_packet());
  }
  check(usb && usb->serial() == kUsbSerial && usb->out_endpoint() != 0 && usb->in_endpoint() != 0,
        "usb_bulk_open", usb ? usb->id() + " serial " + usb->serial() + ", " + eps : error);
  if (!usb) {
    check(false, "usb_bulk_write", "not open");
    check(false, "usb_bulk_read", "not open");
    check(false, "usb_bulk_busy", "not open");
    return;
  }
  const size_t packet = usb->in_max_packet();

  // 64 KiB in the sink's pattern; a second write after it proves the sink took every byte
  // (a wrong byte halts its endpoint and the next transfer fails).
  {
    const size_t kBytes = 64 * 1024;
    std::vector<uint8_t> data(kBytes);
    for (size_t i = 0; i < kBytes; ++i) data[i] = static_cast<uint8_t>((i % packet) % 63);
    size_t sent = 0, sent2 = 0;
    const auto t0 = std::chrono::steady_clock::now();
    const lr::Status a = usb->write(data, 2000, &sent);
    const double s = seconds_since(t0);
    const std::string error_a = usb->last_error();
    const lr::Status b = usb->write(std::span<const uint8_t>(data.data(), packet), 2000, &sent2);
    check(a == lr::Status::kOk && sent == kBytes && b == lr::Status::kOk && sent2 == packet,
          "usb_bulk_write",
          std::to_string(sent) + " of " + std::to_string(kBytes) + " bytes: " + str(a) + " in " +
              std::to_string(s) + " s; then " + std::to_string(sent2) + " more: " + str(b) +
              (a == lr::Status::kOk && b == lr::Status::kOk
                   ? ""
                   : "; " + error_a + " / " + usb->last_error()));
  }

  // The source's pattern back from bulk IN.
  {
    std::vector<uint8_t> data(16 * packet);
    size_t received = 0;
    const lr::Status r = usb->read(data, 2000, received);
    size_t wrong = 0;
    for (size_t i = 0; i < received; ++i) {
      wrong += data[i] != static_cast<uint8_t>((i % packet) % 63);
    }
    check(r == lr::Status::kOk && received == data.size() && wrong == 0, "usb_bulk_read",
          std::to_string(received) + " of " + std::to_string(data.size()) + " bytes: " + str(r) +
              ", " + std::to_string(wrong) + " differ from the source's pattern" +
              (r == lr::Status::kOk ? "" : "; " + usb->last_error()));
  }

  // The interface is claimed: a second UsbBulk on it is refused.
  {
    std::string busy_error;
    auto second = lr::UsbBulk::open(config, busy_error);
    check(!second && one_line_error(busy_error, "busy"), "usb_bulk_busy",
          second ? "second open succeeded" : "\"" + busy_error + "\"");
  }
}

void check_usb_errors() {
  struct Case {
    const char* name;
    uint16_t pid;
    const char* serial;
    std::string expect;
  };
  const Case cases[] = {
      {"usb_error_no_device", 0x0002, "",
       "no USB device 1209:0002 (is the guest's USB gadget plugged in?)"},
      {"usb_error_serial", kUsbPid, "lr-guest-9999",
       "no USB device 1209:0001 with serial lr-guest-9999 (found: lr-guest-0001)"},
  };
  for (const Case& c : cases) {
    lr::UsbBulkConfig config;
    config.vid = kUsbVid;
    config.pid = c.pid;
    config.serial = c.serial;
    config.what = "the guest's USB gadget";
    std::string error;
    auto usb = lr::UsbBulk::open(config, error);
    check(!usb && one_line_error(error, c.expect), c.name, usb ? "opened" : "\"" + error + "\"");
  }
}

}  // namespace

int main() {
  check_gpio_chip();
  const std::string spidev = find_spidev();
  check_spidev_device(spidev);
  check_spidev_bus(spidev);
  check_spidev_bus_failures(spidev);
  check_spidev_errors(spidev);
  check_usb_enumerate();
  check_usb_bulk();
  check_usb_errors();
  std::printf("guest: %d passed, %d failed\n", g_passed, g_failed);
  return g_failed == 0 ? 0 : 1;
}
