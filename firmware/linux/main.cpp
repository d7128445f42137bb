// lr_panel_app: the demo scene on an SPI panel (ST7789 / ILI9341) from a Linux board of the
// Raspberry Pi class: spidev carries the bytes, libgpiod drives D/C, reset and backlight
// (hal/host/linux). Options: app_options.cpp. Output, one line each, key=value so scripts can
// read it:
//   lr_panel_app: st7789 240x240 rotation 0 (image 240x240) on /dev/spidev0.0 ...
//   frame=0 degrees=0 bytes=... pixel_bytes=... command_bytes=... strips_sent=...
//     strips_narrowed=... strips_skipped=... pixels_written=... ms=...
//   frames=N bytes=... seconds=... fps=...
// Errors: one line on stderr; exit status 2 for bad options, 1 for a device error.
#include <pthread.h>
#include <signal.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

#include "firmware/linux/app_options.hpp"
#include "firmware/linux/panel_app.hpp"
#include "lineraster/hal/host/display_spec.hpp"
#include "lineraster/hal/host/linux/spidev_bus.hpp"

namespace {

int fail(const std::string& msg, int status) {
  std::fprintf(stderr, "lr_panel_app: %s\n", msg.c_str());
  return status;
}

// " (what the bus said)" after a failed step, or nothing.
std::string bus_detail(const lr::SpidevBus& bus) {
  const std::string e = bus.last_error();
  return e.empty() ? e : " (" + e + ")";
}

bool stop_requested() {
  sigset_t pending;
  if (sigpending(&pending) != 0) return false;
  return sigismember(&pending, SIGINT) == 1 || sigismember(&pending, SIGTERM) == 1;
}

}  // namespace

int main(int argc, char** argv) {
  lr::app::AppOptions o;
  std::string error;
  switch (lr::app::parse_options(argc, argv, o, error)) {
    case lr::app::ParseResult::kHelp:
      std::fputs(lr::app::kUsage, stdout);
      return 0;
    case lr::app::ParseResult::kError:
      return fail(error, 2);
    case lr::app::ParseResult::kRun:
      break;
  }

  // SIGINT and SIGTERM end the run between frames. They stay blocked in every thread (the bus's
  // transfer thread inherits this mask) and are polled after each frame: delivered to a thread,
  // they would interrupt an SPI ioctl in the middle of a strip.
  sigset_t stop;
  sigemptyset(&stop);
  sigaddset(&stop, SIGINT);
  sigaddset(&stop, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop, nullptr);

  std::unique_ptr<lr::SpidevBus> bus = lr::SpidevBus::open(o.bus, error);
  if (!bus) return fail(error, 1);
  lr::app::PanelApp app(*bus, o.panel);
  if (app.start(error) != lr::Status::kOk) return fail(error + bus_detail(*bus), 1);
  std::printf(
      "lr_panel_app: %s on %s at %u Hz (%zu-byte transfers), %zu triangles, strips of %d rows\n",
      lr::host::describe_panel(o.panel).c_str(), o.bus.device.c_str(), bus->hz(),
      bus->chunk_bytes(), lr::app::DemoScene::triangle_count(), lr::app::DemoScene::kStripRows);
  std::fflush(stdout);

  using Clock = std::chrono::steady_clock;
  const Clock::time_point t0 = Clock::now();
  uint64_t bytes = 0, pixel_bytes = 0;
  uint32_t done = 0;
  while ((o.frames == 0 || done < o.frames) && !stop_requested()) {
    const Clock::time_point f0 = Clock::now();
    lr::app::FrameReport r;
    if (app.frame(done, r, error) != lr::Status::kOk) return fail(error + bus_detail(*bus), 1);
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - f0).count();
    bytes += r.sink.bytes();
    pixel_bytes += r.sink.pixel_bytes;
    std::printf(
        "frame=%u degrees=%d bytes=%u pixel_bytes=%u command_bytes=%u strips_sent=%u "
        "strips_narrowed=%u strips_skipped=%u pixels_written=%u ms=%.2f\n",
        r.index, r.degrees, r.sink.bytes(), r.sink.pixel_bytes, r.sink.command_bytes,
        r.sink.strips_sent, r.sink.strips_narrowed, r.sink.strips_skipped, r.render.pixels_written,
        ms);
    std::fflush(stdout);
    ++done;
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("frames=%u bytes=%llu pixel_bytes=%llu seconds=%.3f fps=%.2f%s\n", done,
              static_cast<unsigned long long>(bytes), static_cast<unsigned long long>(pixel_bytes),
              seconds, seconds > 0 ? done / seconds : 0.0,
              o.frames != 0 && done < o.frames ? " (interrupted)" : "");
  return 0;
}
