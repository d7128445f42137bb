// Runs inside the emulated ARM Linux guest of scripts/ci_guest.sh (tests/guest/init.sh starts
// it): checks that the kernel interfaces the Linux display backends are built on work there --
// the PL061 GPIO chip through libgpiod, the spi-gpio spidev with its 1024-byte buffer, the USB
// gadget through libusb. One line per check ("PASS name: details" / "FAIL name: details") and a
// summary line ("guest: N passed, M failed"), which the host script reads from the console.
//
// The guest's wiring (tests/guest/virt_spi_gpio.dtsi, tests/guest/init.sh):
//   PL061 "9030000.pl061": lines 0-3 SCK, MOSI, MISO, CS of the spi-gpio bus; 4 D/C, 5 reset,
//   6 backlight, 7 free. spidev: the only /dev/spidev*, bufsiz 1024.
//   USB: 1209:0001, serial "lr-guest-0001", interface 0: SourceSink with pattern 1 (every packet
//   is i % 63 for its byte i; the sink stalls its endpoint on any other byte).
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
#include <string>
#include <vector>

namespace {

constexpr const char* kChipLabel = "9030000.pl061";
constexpr unsigned kChipLines = 8;
constexpr unsigned kDcLine = 4;
constexpr unsigned kSpidevBufsiz = 1024;
constexpr uint16_t kUsbVid = 0x1209;
constexpr uint16_t kUsbPid = 0x0001;
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

std::string errno_text(int e) {
  return std::string(std::strerror(e));
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The spidev node whose device tree node is the test's "rohm,dh2228fv" child; empty when none.
std::string find_spidev() {
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/sys/class/spidev", ec)) {
    if (read_text(e.path() / "device/of_node/compatible") == "rohm,dh2228fv") {
      return "/dev/" + e.path().filename().string();
    }
  }
  return {};
}

// --- GPIO

void check_gpio() {
  gpiod_chip* chip = gpiod_chip_open_by_label(kChipLabel);
  if (!chip) {
    check(false, "gpio_chip", std::string(kChipLabel) + ": " + errno_text(errno));
    check(false, "gpio_readback", "no chip");
    return;
  }
  unsigned lines = gpiod_chip_num_lines(chip);
  std::string spi_consumers;
  for (unsigned i = 0; i < 4 && i < lines; ++i) {
    gpiod_line* l = gpiod_chip_get_line(chip, i);
    const char* c = l ? gpiod_line_consumer(l) : nullptr;
    spi_consumers += std::string(i ? "," : "") + (c ? c : "-");
  }
  check(lines == kChipLines && spi_consumers == "sck,mosi,miso,spi0 CS0", "gpio_chip",
        std::string(gpiod_chip_name(chip)) + " (" + gpiod_chip_label(chip) + "), " +
            std::to_string(lines) + " lines, lines 0-3 used by " + spi_consumers);

  // Drive the D/C line high, let it go, read it back: the PL061 keeps driving a released output.
  gpiod_line* line = gpiod_chip_get_line(chip, kDcLine);
  bool ok = line && gpiod_line_request_output(line, "lr-guest", 1) == 0;
  std::string details = ok ? "" : "request: " + errno_text(errno);
  if (ok) {
    ok = gpiod_line_set_value(line, 0) == 0 && gpiod_line_set_value(line, 1) == 0;
    gpiod_line_release(line);
    gpiod_line_request_config cfg{"lr-guest-read", GPIOD_LINE_REQUEST_DIRECTION_AS_IS, 0};
    int v = gpiod_line_request(line, &cfg, 0) == 0 ? gpiod_line_get_value(line) : -1;
    ok = ok && v == 1 && gpiod_line_direction(line) == GPIOD_LINE_DIRECTION_OUTPUT;
    details =
        "line " + std::to_string(kDcLine) + " driven 0 then 1, read back " + std::to_string(v);
    gpiod_line_release(line);
  }
  check(ok, "gpio_readback", details);
  gpiod_chip_close(chip);
}

// --- spidev

void check_spidev() {
  std::string path = find_spidev();
  std::string bufsiz = read_text("/sys/module/spidev/parameters/bufsiz");
  int fd = path.empty() ? -1 : open(path.c_str(), O_RDWR);
  check(fd >= 0 && bufsiz == std::to_string(kSpidevBufsiz), "spidev_device",
        path.empty() ? "no spidev with compatible rohm,dh2228fv"
        : fd < 0     ? path + ": " + errno_text(errno)
                     : path + ", bufsiz " + bufsiz);
  if (fd < 0) {
    check(false, "spidev_chunks", "no spidev");
    return;
  }
  // One message larger than bufsiz is refused (so a backend must split), pieces of bufsiz go.
  std::vector<uint8_t> data(16 * kSpidevBufsiz);
  for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<uint8_t>(i);
  spi_ioc_transfer t{};
  t.tx_buf = reinterpret_cast<uintptr_t>(data.data());
  t.len = kSpidevBufsiz + 1;
  t.speed_hz = 10000000;
  t.bits_per_word = 8;
  int r = ioctl(fd, SPI_IOC_MESSAGE(1), &t);
  int e = errno;
  bool ok = r < 0 && e == EMSGSIZE;
  std::string details =
      std::to_string(kSpidevBufsiz + 1) + " bytes at once: " + (r < 0 ? errno_text(e) : "accepted");
  auto t0 = std::chrono::steady_clock::now();
  size_t sent = 0;
  for (size_t off = 0; ok && off < data.size(); off += kSpidevBufsiz) {
    t.tx_buf = reinterpret_cast<uintptr_t>(data.data() + off);
    t.len = kSpidevBufsiz;
    r = ioctl(fd, SPI_IOC_MESSAGE(1), &t);
    ok = r == static_cast<int>(kSpidevBufsiz);
    if (ok) sent += kSpidevBufsiz;
  }
  double s = seconds_since(t0);
  details += "; " + std::to_string(sent) + " bytes in " + std::to_string(sent / kSpidevBufsiz) +
             " pieces of " + std::to_string(kSpidevBufsiz) + " in " + std::to_string(s) + " s";
  check(ok, "spidev_chunks", details);
  close(fd);
}

// --- USB

void check_usb() {
  libusb_context* ctx = nullptr;
  int r = libusb_init(&ctx);
  if (r != 0) {
    check(false, "usb_enumerate", std::string("libusb_init: ") + libusb_error_name(r));
    check(false, "usb_bulk_out", "no libusb");
    check(false, "usb_bulk_in", "no libusb");
    return;
  }
  libusb_device** list = nullptr;
  ssize_t n = libusb_get_device_list(ctx, &list);
  libusb_device* dev = nullptr;
  for (ssize_t i = 0; i < n; ++i) {
    libusb_device_descriptor d{};
    if (libusb_get_device_descriptor(list[i], &d) == 0 && d.idVendor == kUsbVid &&
        d.idProduct == kUsbPid) {
      dev = libusb_ref_device(list[i]);
    }
  }
  libusb_free_device_list(list, 1);
  libusb_device_handle* h = nullptr;
  unsigned char serial[64] = {};
  uint8_t ep_in = 0, ep_out = 0;
  uint16_t mps = 0;
  if (dev && libusb_open(dev, &h) == 0) {
    libusb_device_descriptor d{};
    libusb_get_device_descriptor(dev, &d);
    libusb_get_string_descriptor_ascii(h, d.iSerialNumber, serial, sizeof serial);
    libusb_config_descriptor* cd = nullptr;
    if (libusb_get_active_config_descriptor(dev, &cd) == 0) {
      const libusb_interface_descriptor& alt = cd->interface[0].altsetting[0];
      for (int i = 0; i < alt.bNumEndpoints; ++i) {
        const libusb_endpoint_descriptor& ep = alt.endpoint[i];
        if ((ep.bmAttributes & 3) != LIBUSB_TRANSFER_TYPE_BULK) continue;
        (ep.bEndpointAddress & 0x80 ? ep_in : ep_out) = ep.bEndpointAddress;
        mps = ep.wMaxPacketSize;
      }
      libusb_free_config_descriptor(cd);
    }
  }
  char ids[64];
  std::snprintf(ids, sizeof ids, "%04x:%04x on bus %d device %d", kUsbVid, kUsbPid,
                dev ? libusb_get_bus_number(dev) : 0, dev ? libusb_get_device_address(dev) : 0);
  bool ok = h && std::string(reinterpret_cast<char*>(serial)) == kUsbSerial && ep_in && ep_out &&
            mps > 0 && libusb_claim_interface(h, 0) == 0;
  char eps[64];
  std::snprintf(eps, sizeof eps, "bulk IN 0x%02x, OUT 0x%02x, %u-byte packets", ep_in, ep_out, mps);
  check(ok, "usb_enumerate",
        !dev ? std::string(ids) + ": not found"
        : !h ? std::string(ids) + ": cannot open"
             : std::string(ids) + ", serial " + reinterpret_cast<char*>(serial) + ", " + eps);
  if (!ok) {
    check(false, "usb_bulk_out", "no device");
    check(false, "usb_bulk_in", "no device");
    if (h) libusb_close(h);
    if (dev) libusb_unref_device(dev);
    libusb_exit(ctx);
    return;
  }

  // OUT: the sink checks every byte and halts the endpoint on a wrong one, so a second transfer
  // after the first one also proves the data arrived as sent.
  const size_t kBytes = 64 * 1024;
  std::vector<uint8_t> out(kBytes), in(kBytes);
  for (size_t i = 0; i < kBytes; ++i) out[i] = static_cast<uint8_t>((i % mps) % 63);
  int done = 0, done2 = 0;
  auto t0 = std::chrono::steady_clock::now();
  r = libusb_bulk_transfer(h, ep_out, out.data(), static_cast<int>(kBytes), &done, 2000);
  double s = seconds_since(t0);
  int r2 = libusb_bulk_transfer(h, ep_out, out.data(), mps, &done2, 2000);
  check(r == 0 && done == static_cast<int>(kBytes) && r2 == 0 && done2 == mps, "usb_bulk_out",
        std::to_string(done) + " of " + std::to_string(kBytes) + " bytes in " + std::to_string(s) +
            " s (" + libusb_error_name(r) + "), then " + std::to_string(done2) + " (" +
            libusb_error_name(r2) + ")");

  r = libusb_bulk_transfer(h, ep_in, in.data(), static_cast<int>(kBytes), &done, 2000);
  size_t bad = 0;
  for (int i = 0; i < done; ++i) {
    bad +=
        in[static_cast<size_t>(i)] != static_cast<uint8_t>((static_cast<unsigned>(i) % mps) % 63);
  }
  check(r == 0 && done == static_cast<int>(kBytes) && bad == 0, "usb_bulk_in",
        std::to_string(done) + " bytes (" + libusb_error_name(r) + "), " + std::to_string(bad) +
            " differ from the source's pattern");
  libusb_release_interface(h, 0);
  libusb_close(h);
  libusb_unref_device(dev);
  libusb_exit(ctx);
}

}  // namespace

int main() {
  check_gpio();
  check_spidev();
  check_usb();
  std::printf("guest: %d passed, %d failed\n", g_passed, g_failed);
  return g_failed == 0 ? 0 : 1;
}
