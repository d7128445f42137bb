// Where the demo's strips go, chosen at compile time (LR_DEMO_PANEL):
//
//   FileOutput   RGB888 strips straight into a PPM on the host (OrderedStripSink + PpmFile): the
//                frame lineraster-sim writes with --out.
//   PanelOutput  the path of a panel firmware on a Cortex-M7: RGB565 strips in two DMA strip
//                buffers (lr::DmaStripBuffer), a PanelSink driving an ST7789 (320 x 240) through
//                a bus that cleans the data cache of each transfer's bytes first (docs/dma.md)
//                and, having no panel under QEMU, writes what the panel would show to the PPM:
//                the frame lineraster-sim shows with --display emulator:st7789:320x240.
//
// Both give: start_core(), kSimOptions (lineraster-sim's options for the same frame), sink(),
// begin() / end() around the frame, strips(), checksum() (FNV-1a of the
// frame's RGB888 bytes), pixel_bytes(), and check(), which says whether the transfers kept to
// their contract (always true for the file).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/common/ordered_sink.hpp"
#include "firmware/common/ppm_file.hpp"
#include "firmware/common/semihost.hpp"
#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/output/status.hpp"

#ifndef LR_DEMO_PANEL
#define LR_DEMO_PANEL 0
#endif
#if LR_DEMO_PANEL
#include "firmware/common/cortex_m7_dcache.hpp"
#include "firmware/common/ppm_panel_bus.hpp"
#include "lineraster/hal/dma_buffer.hpp"
#include "lineraster/hal/panel.hpp"
#include "lineraster/hal/panel_config.hpp"
#include "lineraster/hal/panel_sink.hpp"
#endif

namespace lr::fw::demo {

template <size_t StripPixels>
class FileOutput {
 public:
  using PF = Rgb888;  // the format lineraster-sim writes
  explicit FileOutput(const char* path) : file_(path) {}
  static void start_core() {}
  static constexpr const char* kSimOptions = "";  // lineraster-sim's frame is this file's

  StripSink<PF>& sink() { return sink_; }
  Status begin() { return Status::kOk; }  // the sink opens the file at begin_frame
  Status end() { return Status::kOk; }
  uint32_t strips() const { return sink_.strips(); }
  uint32_t checksum() const { return file_.checksum(); }
  uint32_t pixel_bytes() const { return file_.pixel_bytes(); }
  bool check(uint32_t) const { return true; }

 private:
  // Word-aligned: the strip loop fills and clears strips with word stores (memset, memcpy).
  alignas(4) std::array<std::array<PF::Storage, StripPixels>, 2> strips_{};
  PpmFile<PF> file_;
  OrderedStripSink<PF, PpmFile<PF>> sink_{strips_[0], strips_[1], file_};
};

#if LR_DEMO_PANEL
// The panel lineraster-sim's --display emulator:st7789:320x240 names.
inline constexpr PanelConfig kDemoPanel = st7789_240x320(Rotation::k90);

template <size_t StripPixels>
class PanelOutput {
 public:
  using PF = Rgb565Be;
  explicit PanelOutput(const char* path) : file_(path) {}
  // What a Cortex-M7 firmware's startup does before anything is drawn.
  static void start_core() { m7::enable_dcache(); }
  // What lineraster-sim needs to show this frame: the emulated panel of kDemoPanel.
  static constexpr const char* kSimOptions = "--display emulator:st7789:320x240";

  StripSink<PF>& sink() { return sink_; }
  Status begin() {
    Status s = panel_.init();
    if (s == Status::kOk) s = bus_.begin_frame();
    return s;
  }
  Status end() {
    const Status s = bus_.end_frame();
    if (bus_.error() != nullptr) {
      semihost::write("lr_demo: bus: ");
      semihost::write(bus_.error());
      semihost::write("\n");
    }
    return s == Status::kOk ? panel_.backlight(true) : s;
  }
  uint32_t strips() const { return sink_.stats().strips_sent; }
  uint32_t checksum() const { return file_.checksum(); }
  uint32_t pixel_bytes() const { return file_.pixel_bytes(); }

  // Every transfer cleaned first, each a whole strip of `strip_bytes` in its own lines.
  bool check(uint32_t strip_bytes) const {
    const auto& c = bus_.counts();
    const uint32_t expected_lines =
        c.transfers * ((strip_bytes + m7::kDcacheLine - 1) / m7::kDcacheLine);
    semihost::write("lr_demo: DMA: ");
    semihost::write_dec(c.transfers);
    semihost::write(" transfers, ");
    semihost::write_dec(c.cleans);
    semihost::write(" data-cache cleans first, ");
    semihost::write_dec(c.lines_cleaned);
    semihost::write(" lines of 32 B\n");
    return c.transfers > 0 && c.cleans == c.transfers && c.lines_cleaned == expected_lines;
  }

 private:
  DmaStripBuffer<StripPixels> strip0_, strip1_;
  PpmFile<Rgb565Be> file_;
  PpmPanelBus<&m7::clean_dcache> bus_{file_, kDemoPanel};
  Panel panel_{bus_, kDemoPanel};
  PanelSink sink_{panel_, strip0_.pixels(), strip1_.pixels()};
};
#endif

}  // namespace lr::fw::demo
