// Test helpers for the panel driver and the panel sink:
//   RecordingBus  a PanelBus that logs every call (commands with their parameters, pixel
//                 transfer sizes, waits with their timeout and outcome, reset, backlight, delays),
//                 completes pixel transfers asynchronously (at wait()), and can make chosen
//                 commands, transfers or waits fail or time out. It flags what a real bus would
//                 not forgive: a command or a second transfer while pixels are in flight, pixels
//                 not right after RAMWR, a buffer changed while it was on the wire, and (with
//                 require_clean) a transfer not preceded by clean_dcache() of its bytes.
//   RamModel      the controller's 240 x 320 graphics RAM as the datasheets describe it: CASET,
//                 RASET, RAMWR and MADCTL (MV exchanges host x and y, then MX / MY count RAM
//                 columns / rows from the other side); completed transfers land in it.
//   view()        what a viewer sees on the module: the visible window of RAM (mirrored on
//                 ILI9341 glass), turned by the config's rotation, as an image_width x
//                 image_height image, to be compared with the frame that was sent.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/hal/panel_bus.hpp"
#include "lineraster/hal/panel_config.hpp"

namespace lr::test {

struct BusEvent {
  enum class Kind : uint8_t { kCommand, kPixels, kWait, kReset, kBacklight, kDelay };
  Kind kind = Kind::kCommand;
  uint8_t cmd = 0;
  std::vector<uint8_t> params;  // command parameters
  size_t bytes = 0;             // pixel transfer size
  uint32_t value = 0;           // delay / timeout in ms, reset asserted, backlight on
  Status result = Status::kOk;  // what the call returned
  friend bool operator==(const BusEvent&, const BusEvent&) = default;
};

inline BusEvent cmd(uint8_t c, std::vector<uint8_t> params = {}) {
  return {BusEvent::Kind::kCommand, c, std::move(params), 0, 0, Status::kOk};
}
inline BusEvent pixels(size_t bytes) {
  return {BusEvent::Kind::kPixels, 0, {}, bytes, 0, Status::kOk};
}
inline BusEvent wait_for(uint32_t timeout_ms, Status result = Status::kOk) {
  return {BusEvent::Kind::kWait, 0, {}, 0, timeout_ms, result};
}
inline BusEvent reset_line(bool asserted) {
  return {BusEvent::Kind::kReset, 0, {}, 0, asserted ? 1u : 0u, Status::kOk};
}
inline BusEvent backlight_line(bool on) {
  return {BusEvent::Kind::kBacklight, 0, {}, 0, on ? 1u : 0u, Status::kOk};
}
inline BusEvent delay(uint32_t ms) {
  return {BusEvent::Kind::kDelay, 0, {}, 0, ms, Status::kOk};
}
// CASET / RASET with 16-bit big-endian start and end.
inline BusEvent caset(uint16_t x0, uint16_t x1) {
  return cmd(0x2A, {uint8_t(x0 >> 8), uint8_t(x0 & 0xFF), uint8_t(x1 >> 8), uint8_t(x1 & 0xFF)});
}
inline BusEvent raset(uint16_t y0, uint16_t y1) {
  return cmd(0x2B, {uint8_t(y0 >> 8), uint8_t(y0 & 0xFF), uint8_t(y1 >> 8), uint8_t(y1 & 0xFF)});
}

inline void PrintTo(const BusEvent& e, std::ostream* os) {
  char buf[16];
  switch (e.kind) {
    case BusEvent::Kind::kCommand:
      std::snprintf(buf, sizeof buf, "cmd 0x%02X", e.cmd);
      *os << buf;
      for (uint8_t p : e.params) {
        std::snprintf(buf, sizeof buf, " %02X", p);
        *os << buf;
      }
      break;
    case BusEvent::Kind::kPixels:
      *os << "pixels " << e.bytes << " B";
      break;
    case BusEvent::Kind::kWait:
      *os << "wait " << e.value << " ms";
      break;
    case BusEvent::Kind::kReset:
      *os << "reset " << (e.value ? "asserted" : "released");
      break;
    case BusEvent::Kind::kBacklight:
      *os << "backlight " << (e.value ? "on" : "off");
      break;
    case BusEvent::Kind::kDelay:
      *os << "delay " << e.value << " ms";
      break;
  }
  if (e.result != Status::kOk) *os << " -> " << to_string(e.result);
}

class RamModel {
 public:
  static constexpr int kColumns = 240, kRows = 320;

  RamModel() : ram_(size_t{kColumns} * kRows, 0) {}

  void command(uint8_t c, std::span<const uint8_t> p) {
    writing_ = false;
    switch (c) {
      case 0x01:  // SWRESET: full window (MADCTL: "S/W reset: no change")
        xs_ = 0, xe_ = kColumns - 1, ys_ = 0, ye_ = kRows - 1;
        break;
      case 0x36:
        if (p.size() == 1) madctl_ = p[0];
        break;
      case 0x2A:
        if (p.size() == 4) xs_ = be16(p[0], p[1]), xe_ = be16(p[2], p[3]);
        break;
      case 0x2B:
        if (p.size() == 4) ys_ = be16(p[0], p[1]), ye_ = be16(p[2], p[3]);
        break;
      case 0x2C:
        x_ = xs_, y_ = ys_;
        writing_ = true;
        break;
      default:
        break;
    }
  }

  // Pixel data after RAMWR: RGB565, high byte first, host x fastest within the window.
  void data(std::span<const uint8_t> bytes) {
    if (!writing_) {
      ++errors_;
      return;
    }
    for (size_t i = 0; i + 1 < bytes.size(); i += 2) {
      store(x_, y_, be16(bytes[i], bytes[i + 1]));
      if (++x_ > xe_) {
        x_ = xs_;
        if (++y_ > ye_) y_ = ys_;
      }
    }
    if (bytes.size() % 2) ++errors_;
  }

  uint16_t at(int column, int row) const { return ram_[size_t(row) * kColumns + size_t(column)]; }
  void fill(uint16_t v) { std::fill(ram_.begin(), ram_.end(), v); }
  uint8_t madctl() const { return madctl_; }
  // Pixels addressed outside the RAM, data without RAMWR, odd byte counts.
  int errors() const { return errors_; }

 private:
  static uint16_t be16(uint8_t hi, uint8_t lo) { return uint16_t((hi << 8) | lo); }
  void store(int x, int y, uint16_t v) {
    int c = (madctl_ & 0x20) ? y : x;
    int r = (madctl_ & 0x20) ? x : y;
    if (madctl_ & 0x40) c = kColumns - 1 - c;
    if (madctl_ & 0x80) r = kRows - 1 - r;
    if (c < 0 || c >= kColumns || r < 0 || r >= kRows) {
      ++errors_;
      return;
    }
    ram_[size_t(r) * kColumns + size_t(c)] = v;
  }

  std::vector<uint16_t> ram_;
  uint8_t madctl_ = 0;
  int xs_ = 0, xe_ = kColumns - 1, ys_ = 0, ye_ = kRows - 1;
  int x_ = 0, y_ = 0;
  bool writing_ = false;
  int errors_ = 0;
};

// What the viewer sees: image_width x image_height RGB565 values, row 0 at the top of the module
// as mounted. ILI9341 glass shows RAM column c at 239 - c (the modules' wiring).
inline std::vector<uint16_t> view(const RamModel& ram, const PanelConfig& c) {
  const bool mirrored = c.controller == Controller::kIli9341;
  const int w = c.width, h = c.height;  // the visible window, native orientation
  const int iw = c.image_width(), ih = c.image_height();
  std::vector<uint16_t> out(size_t(iw) * size_t(ih));
  for (int y = 0; y < ih; ++y) {
    for (int x = 0; x < iw; ++x) {
      int gx = x, gy = y;  // glass position, rotation 0
      switch (c.rotation) {
        case Rotation::k0:
          break;
        case Rotation::k90:  // image turned clockwise: its top-left at the glass's top-right
          gx = w - 1 - y, gy = x;
          break;
        case Rotation::k180:
          gx = w - 1 - x, gy = h - 1 - y;
          break;
        case Rotation::k270:
          gx = y, gy = h - 1 - x;
          break;
      }
      const int column = c.col_offset + (mirrored ? w - 1 - gx : gx);
      out[size_t(y) * size_t(iw) + size_t(x)] = ram.at(column, c.row_offset + gy);
    }
  }
  return out;
}

class RecordingBus final : public PanelBus {
 public:
  std::vector<BusEvent> events;
  RamModel ram;
  std::vector<std::string> violations;
  // The byte ranges of clean_dcache() and of start_pixels() calls, in call order. With
  // require_clean, a transfer whose bytes were not the last ones cleaned is a violation.
  std::vector<std::span<const uint8_t>> cleaned, started;
  bool require_clean = false;
  // Outcomes by call index (0-based, counted per kind over the bus's life); kOk otherwise.
  std::map<size_t, Status> command_results;
  std::map<size_t, Status> start_results;
  std::map<size_t, Status> wait_results;  // indexed by the transfer waited for

  Status command(uint8_t c, std::span<const uint8_t> params) override {
    if (pending_) violations.push_back("command while pixels are in flight");
    const Status r = outcome(command_results, commands_++);
    BusEvent e = cmd(c, {params.begin(), params.end()});
    e.result = r;
    events.push_back(std::move(e));
    if (r == Status::kOk) ram.command(c, params);
    last_was_ramwr_ = r == Status::kOk && c == 0x2C;
    return r;
  }

  void clean_dcache(std::span<const uint8_t> bytes) override { cleaned.push_back(bytes); }

  Status start_pixels(std::span<const uint8_t> px) override {
    started.push_back(px);
    if (require_clean && (cleaned.empty() || cleaned.back().data() != px.data() ||
                          cleaned.back().size() != px.size()))
      violations.push_back("pixels started without clean_dcache() of exactly their bytes");
    if (pending_) violations.push_back("start_pixels while a transfer is in flight");
    if (!last_was_ramwr_) violations.push_back("pixels not right after RAMWR");
    last_was_ramwr_ = false;
    const Status r = outcome(start_results, starts_++);
    BusEvent e = pixels(px.size());
    e.result = r;
    events.push_back(std::move(e));
    if (r != Status::kOk) return r;
    pending_ = true;
    pending_data_ = px.data();
    pending_copy_.assign(px.begin(), px.end());
    return r;
  }

  Status wait(uint32_t timeout_ms) override {
    Status r = Status::kOk;
    if (pending_) {
      r = outcome(wait_results, transfers_++);
      if (std::memcmp(pending_data_, pending_copy_.data(), pending_copy_.size()) != 0)
        violations.push_back("buffer changed while on the wire");
      if (r == Status::kOk) ram.data(pending_copy_);
      pending_ = false;
      pending_data_ = nullptr;
    }
    events.push_back(wait_for(timeout_ms, r));
    return r;
  }

  Status set_reset(bool asserted) override {
    events.push_back(reset_line(asserted));
    return Status::kOk;
  }
  Status set_backlight(bool on) override {
    events.push_back(backlight_line(on));
    return Status::kOk;
  }
  void delay_ms(uint32_t ms) override { events.push_back(delay(ms)); }

  // The buffer on the wire (nullptr when none).
  const void* in_flight() const { return pending_ ? pending_data_ : nullptr; }
  void clear_events() { events.clear(); }
  std::vector<BusEvent> commands() const {
    std::vector<BusEvent> out;
    for (const BusEvent& e : events)
      if (e.kind == BusEvent::Kind::kCommand) out.push_back(e);
    return out;
  }
  size_t pixel_bytes() const {
    size_t n = 0;
    for (const BusEvent& e : events)
      if (e.kind == BusEvent::Kind::kPixels && e.result == Status::kOk) n += e.bytes;
    return n;
  }

 private:
  static Status outcome(const std::map<size_t, Status>& m, size_t i) {
    auto it = m.find(i);
    return it == m.end() ? Status::kOk : it->second;
  }

  bool pending_ = false;
  const uint8_t* pending_data_ = nullptr;
  std::vector<uint8_t> pending_copy_;
  bool last_was_ramwr_ = false;
  size_t commands_ = 0, starts_ = 0, transfers_ = 0;
};

}  // namespace lr::test
