// A PanelBus for a board with no panel attached (QEMU's): it takes the MIPI DBI stream a
// PanelSink sends (the controller's commands, CASET/RASET windows, RAMWR and the pixels) and
// writes the frame the panel would show to a PPM file on the host (ppm_file.hpp), so that the
// whole panel path of a firmware (Panel, PanelSink, DMA strip buffers) is checked byte for byte
// against lineraster-sim's emulated panel.
//
// It behaves as a DMA bus does: start_pixels() only takes the buffer, the transfer "completes" at
// wait(), when the bytes are read; before each transfer the buffer's lines are cleaned
// (clean_dcache, with CleanFn: a Cortex-M7's m7::clean_dcache, or nothing without a cache). It
// refuses what a real bus would not forgive and says so in `error`: pixels not right after RAMWR,
// a transfer while one is in flight, bytes that were not the ones last cleaned, a window the file
// cannot take (the file is written front to back: full-width windows, top to bottom).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "firmware/common/ppm_file.hpp"
#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/output/status.hpp"
#include "lineraster/hal/mipi_dbi.hpp"
#include "lineraster/hal/panel.hpp"
#include "lineraster/hal/panel_bus.hpp"

namespace lr::fw {

// CleanFn: uint32_t(std::span<const uint8_t>) returning the cache lines it cleaned.
template <auto CleanFn>
class PpmPanelBus final : public PanelBus {
 public:
  // What went through the bus in a frame.
  struct Counts {
    uint32_t commands = 0, transfers = 0, cleans = 0, lines_cleaned = 0;
  };

  // `file` receives the frame; `config` is the panel's (its address offset maps windows back to
  // image rows and columns).
  PpmPanelBus(PpmFile<Rgb565Be>& file, const PanelConfig& config)
      : file_(file),
        offset_(address_offset(config)),
        width_(config.image_width()),
        height_(config.image_height()) {}

  // Opens the file for one frame (its header) and closes it.
  Status begin_frame() {
    next_row_ = 0;
    counts_ = {};
    return file_.begin(width_, height_);
  }
  Status end_frame() {
    if (!pending_.empty()) return refuse("the frame ended with a transfer in flight");
    const Status s = file_.end();
    if (s != Status::kOk) return s;
    return next_row_ == height_ ? Status::kOk : refuse("the frame's rows did not all arrive");
  }

  Status command(uint8_t cmd, std::span<const uint8_t> params) override {
    if (!pending_.empty()) return refuse("a command while pixels are in flight");
    ++counts_.commands;
    ramwr_ = cmd == dcs::kMemoryWrite;
    if ((cmd == dcs::kColumnSet || cmd == dcs::kRowSet) && params.size() == 4) {
      const auto start = static_cast<uint16_t>(params[0] << 8 | params[1]);
      const auto end = static_cast<uint16_t>(params[2] << 8 | params[3]);
      (cmd == dcs::kColumnSet ? columns_ : rows_) = {start, end};
    }
    return Status::kOk;
  }

  void clean_dcache(std::span<const uint8_t> bytes) override {
    cleaned_ = bytes;
    ++counts_.cleans;
    counts_.lines_cleaned += CleanFn(bytes);
  }

  Status start_pixels(std::span<const uint8_t> pixels) override {
    if (!pending_.empty()) return refuse("a transfer while one is in flight");
    if (!ramwr_) return refuse("pixels not right after RAMWR");
    ramwr_ = false;
    if (pixels.data() != cleaned_.data() || pixels.size() != cleaned_.size())
      return refuse("pixels not cleaned first (clean_dcache of exactly these bytes)");
    const uint32_t w = columns_.end - columns_.start + 1u, h = rows_.end - rows_.start + 1u;
    if (columns_.start != offset_.x || w != width_ || rows_.start != offset_.y + next_row_ ||
        next_row_ + h > height_ || pixels.size() != size_t{w} * h * sizeof(Rgb565Be::Storage))
      return refuse("a window out of order (this bus writes whole rows, top to bottom)");
    pending_ = pixels;
    ++counts_.transfers;
    return Status::kOk;
  }

  // The transfer completes: the bytes are read now, as a DMA engine reads them while it sends.
  Status wait(uint32_t) override {
    if (pending_.empty()) return Status::kOk;
    const auto rows = static_cast<uint16_t>(rows_.end - rows_.start + 1u);
    const std::span<const Rgb565Be::Storage> px{
        reinterpret_cast<const Rgb565Be::Storage*>(pending_.data()),
        pending_.size() / sizeof(Rgb565Be::Storage)};
    pending_ = {};
    const Status s = file_.strip({0, next_row_, width_, rows}, px);
    next_row_ = static_cast<uint16_t>(next_row_ + rows);
    return s;
  }

  Status set_reset(bool) override { return Status::kOk; }
  Status set_backlight(bool) override { return Status::kOk; }
  void delay_ms(uint32_t) override {}  // no controller to wait for

  const Counts& counts() const { return counts_; }
  // The first misuse seen, or nullptr.
  const char* error() const { return error_; }

 private:
  struct Range {
    uint16_t start = 0, end = 0;
  };
  Status refuse(const char* why) {
    if (error_ == nullptr) error_ = why;
    return Status::kDisplayError;
  }

  PpmFile<Rgb565Be>& file_;
  AddressOffset offset_;
  uint16_t width_, height_;
  Range columns_, rows_;
  uint16_t next_row_ = 0;
  bool ramwr_ = false;
  std::span<const uint8_t> cleaned_, pending_;
  Counts counts_;
  const char* error_ = nullptr;
};

}  // namespace lr::fw
