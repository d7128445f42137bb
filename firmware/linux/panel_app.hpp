// What lr_panel_app does once its bus is open, for any PanelBus (main.cpp gives it a SpidevBus;
// the unit test a recording bus): the panel driver, a double-buffered PanelSink that skips
// unchanged strips and narrows changed ones, and the demo scene rendered into it strip by strip.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "firmware/linux/demo_scene.hpp"
#include "lineraster/core/output/frame_stats.hpp"
#include "lineraster/hal/panel.hpp"
#include "lineraster/hal/panel_sink.hpp"

namespace lr::app {

struct FrameReport {
  uint32_t index = 0;
  int degrees = 0;      // the model's rotation about y
  PanelSinkStats sink;  // what went to the panel (bytes, strips sent / skipped ...)
  FrameStats render;    // what the renderer did
};

class PanelApp {
 public:
  // A strip's pixel transfer may take this long before the frame is given up. Generous: a
  // strip of a 320-wide panel is 5,120 bytes, 41 ms at 1 MHz (bit-banged SPI is that slow).
  static constexpr uint32_t kTransferTimeoutMs = 1000;

  PanelApp(PanelBus& bus, const PanelConfig& config);

  // Resets and initialises the panel and sizes the renderer's stores. Not kOk: `error` says
  // what failed in one line (without the bus's own detail, which the caller adds).
  Status start(std::string& error);
  // Renders frame `index` and sends it; the backlight goes on after the first frame, so the
  // panel's power-on RAM noise is never shown. Not kOk: `error` says which step failed.
  Status frame(uint32_t index, FrameReport& out, std::string& error);

 private:
  Panel panel_;
  DemoScene scene_;
  std::vector<uint16_t> buffers_[2];
  std::vector<StripSignature> signatures_;
  std::unique_ptr<PanelSink> sink_;
  bool backlight_ = false;
};

}  // namespace lr::app
