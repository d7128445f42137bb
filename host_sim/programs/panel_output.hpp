// lineraster-sim's --display: a rendered frame sent to a panel through the MCU's own path (the
// panel driver and a double-buffered PanelSink that skips unchanged strips), over the emulator's
// bus or a real backend's (hal/host), with the bus traffic counted.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/output/strip_sink.hpp"
#include "lineraster/hal/host/display_spec.hpp"
#include "lineraster/hal/panel.hpp"
#include "lineraster/hal/panel_sink.hpp"
#include "lineraster/host_sim/emulator/emulator_bus.hpp"
#include "lineraster/host_sim/emulator/panel_emulator.hpp"

namespace lr::host {

// Sends a frame of RGB565 values (width x height, row by row: render_scene's with
// SceneOptions::rgb565, what a Renderer<Rgb565Be, K> puts in its strips) to a strip sink as the
// renderer does: begin_frame, strips of k rows top to bottom (acquire, fill, submit), end_frame.
Status send_frame(StripSink<Rgb565Be>& sink, std::span<const uint16_t> rgb565, int width,
                  int height, int k);

// A real panel's bus (spidev or FT232H; defined where the backends are known).
class DeviceBus;

// A panel behind --display: its bus, counted, the driver and the sink. Nothing is opened until
// open(): a bad scene leaves the panel alone.
class PanelOutput {
 public:
  PanelOutput();
  ~PanelOutput();
  PanelOutput(const PanelOutput&) = delete;
  PanelOutput& operator=(const PanelOutput&) = delete;

  // Opens the bus and initialises the panel. False with a one-line error.
  bool open(const DisplaySpec& spec, const PanelConfig& config, int strip_height,
            std::string& error);
  // One frame of RGB565 values (send_frame) to the panel; the backlight goes on after the first
  // (never showing the RAM's power-on noise). False with a one-line error.
  bool send(std::span<const uint16_t> rgb565, int width, int height, std::string& error);

  const BusTotals& totals() const { return counting_->totals(); }
  const PanelSinkStats& sink_stats() const { return sink_->stats(); }
  // The emulated panel and its bus (--display emulator:...), else null.
  const PanelEmulator* emulator() const { return emulator_.get(); }
  const EmulatorBus* emulator_bus() const { return emulator_bus_.get(); }

 private:
  bool open_bus(const DisplaySpec& spec, const PanelConfig& config, PanelBus*& bus,
                std::string& error);
  std::string device_error() const;  // " (the backend's last error)", or ""

  int strip_height_ = 8;
  std::unique_ptr<PanelEmulator> emulator_;
  std::unique_ptr<EmulatorBus> emulator_bus_;
  std::unique_ptr<DeviceBus> device_;
  std::unique_ptr<CountingBus> counting_;
  std::unique_ptr<Panel> panel_;
  std::vector<uint16_t> buffers_[2];
  std::vector<StripSignature> signatures_;
  std::unique_ptr<PanelSink> sink_;
  bool backlight_ = false;
};

}  // namespace lr::host
