// PanelBus implementations for the host: EmulatorBus puts a driver's traffic on the wires of a
// PanelEmulator (command byte with D/C low, parameters with D/C high, chip select held around
// both; pixel data with D/C high right after RAMWR, chip select released at its end), keeps a
// log and totals, and turns delay_ms into emulated time. CountingBus forwards to any other bus
// (a real one) and keeps the same totals.
//
// Transactions are chip-select frames: a command with its parameters is one; RAMWR / RAMWRC keep
// chip select asserted for the pixel data that follows (one frame for command and pixels).
//
// EmulatorBus completes start_pixels() at once, or, with Options::deferred, only in wait() (an
// asynchronous transfer): then it also checks that the caller left the buffer alone while it was
// in flight. What a caller does against the PanelBus contract is recorded in misuse():
// start_pixels() while a transfer is pending (kBusy), start_pixels() not after RAMWR / RAMWRC,
// a command, reset or backlight change while a transfer is pending (the transfer is completed
// first), a buffer changed in flight.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "lineraster/hal/panel_bus.hpp"
#include "lineraster/host_sim/emulator/panel_emulator.hpp"

namespace lr::host {

struct BusTotals {
  uint64_t bytes = 0;  // everything on the wire: command, parameter and pixel bytes
  uint64_t command_bytes = 0, parameter_bytes = 0, pixel_bytes = 0;
  uint64_t transactions = 0;  // chip-select frames
  uint64_t commands = 0;
  uint64_t pixel_transfers = 0;  // start_pixels() calls that were accepted
  uint64_t delay_ms = 0;
  BusTotals operator-(const BusTotals& o) const {
    return {bytes - o.bytes,
            command_bytes - o.command_bytes,
            parameter_bytes - o.parameter_bytes,
            pixel_bytes - o.pixel_bytes,
            transactions - o.transactions,
            commands - o.commands,
            pixel_transfers - o.pixel_transfers,
            delay_ms - o.delay_ms};
  }
};

namespace detail {
inline bool is_memory_write(uint8_t cmd) {
  return cmd == 0x2C || cmd == 0x3C;
}
}  // namespace detail

class EmulatorBus final : public PanelBus {
 public:
  struct Options {
    bool deferred = false;  // start_pixels() queues; wait() sends (and checks the buffer)
    uint32_t spi_hz = 0;    // > 0: each byte takes 8 / spi_hz seconds of emulated time
    bool log = true;        // keep events()
  };
  struct Event {
    enum class Kind : uint8_t { kCommand, kPixels, kReset, kBacklight, kDelay };
    Kind kind = Kind::kCommand;
    uint8_t command = 0;          // kCommand
    std::vector<uint8_t> params;  // kCommand
    uint64_t bytes = 0;           // kPixels
    uint32_t value = 0;           // kReset: asserted, kBacklight: on, kDelay: ms
    uint64_t time_ns = 0;         // emulated time when issued
  };

  explicit EmulatorBus(PanelEmulator& panel) : EmulatorBus(panel, Options{}) {}
  EmulatorBus(PanelEmulator& panel, const Options& options) : panel_(panel), options_(options) {}

  Status command(uint8_t cmd, std::span<const uint8_t> params) override {
    if (pending_) {
      misuse("command " + panel_.command_name(cmd) + " while a pixel transfer is in flight");
      finish_pending();
    }
    open_frame();
    log({Event::Kind::kCommand, cmd, {params.begin(), params.end()}, 0, 0, panel_.now_ns()});
    panel_.command(cmd);
    panel_.data(params);
    pass_time(1 + params.size());
    ++totals_.commands;
    totals_.command_bytes += 1;
    totals_.parameter_bytes += params.size();
    totals_.bytes += 1 + params.size();
    last_command_ = cmd;
    if (!detail::is_memory_write(cmd)) close_frame();
    return Status::kOk;
  }

  Status start_pixels(std::span<const uint8_t> pixels) override {
    if (pending_) {
      misuse("start_pixels while a transfer is in flight (the bus holds one)");
      return Status::kBusy;
    }
    if (!detail::is_memory_write(last_command_))
      misuse("start_pixels after " + panel_.command_name(last_command_) +
             " instead of RAMWR / RAMWRC");
    open_frame();
    ++totals_.pixel_transfers;
    if (options_.deferred) {
      pending_ = true;
      in_flight_ = pixels;
      snapshot_.assign(pixels.begin(), pixels.end());
      return Status::kOk;
    }
    send(pixels);
    return Status::kOk;
  }

  Status wait(uint32_t /*timeout_ms*/) override {
    if (!pending_) return Status::kOk;
    if (fail_next_wait_ != Status::kOk) {
      const Status s = fail_next_wait_;
      fail_next_wait_ = Status::kOk;
      pending_ = false;  // abandoned: nothing reached the panel
      close_frame();
      return s;
    }
    finish_pending();
    return Status::kOk;
  }

  Status set_reset(bool asserted) override {
    if (pending_) {
      misuse("set_reset while a pixel transfer is in flight");
      finish_pending();
    }
    log({Event::Kind::kReset, 0, {}, 0, asserted ? 1u : 0u, panel_.now_ns()});
    panel_.set_reset(asserted);
    return Status::kOk;
  }

  Status set_backlight(bool on) override {
    if (pending_) {
      misuse("set_backlight while a pixel transfer is in flight");
      finish_pending();
    }
    log({Event::Kind::kBacklight, 0, {}, 0, on ? 1u : 0u, panel_.now_ns()});
    backlight_ = on;
    return Status::kOk;
  }

  void delay_ms(uint32_t ms) override {
    log({Event::Kind::kDelay, 0, {}, 0, ms, panel_.now_ns()});
    panel_.advance_ms(ms);
    totals_.delay_ms += ms;
  }

  // The next wait() on a pending transfer fails with `s` (kTimeout, kDisplayError) and abandons
  // it.
  void fail_next_wait(Status s) { fail_next_wait_ = s; }

  PanelEmulator& panel() { return panel_; }
  bool backlight() const { return backlight_; }  // on until set_backlight(false)
  bool pending() const { return pending_; }
  const BusTotals& totals() const { return totals_; }
  const std::vector<Event>& events() const { return events_; }
  void clear_events() { events_.clear(); }
  const std::vector<std::string>& misuse() const { return misuse_; }
  // The commands sent, in order (a convenience over events()).
  std::vector<uint8_t> commands() const {
    std::vector<uint8_t> out;
    for (const Event& e : events_)
      if (e.kind == Event::Kind::kCommand) out.push_back(e.command);
    return out;
  }

 private:
  void log(Event e) {
    if (options_.log) events_.push_back(std::move(e));
  }
  void misuse(std::string what) { misuse_.push_back(std::move(what)); }
  void open_frame() {
    if (!cs_open_) ++totals_.transactions;
    cs_open_ = true;
  }
  void close_frame() {
    if (cs_open_) panel_.cs_release();
    cs_open_ = false;
  }
  void pass_time(uint64_t bytes) {
    if (options_.spi_hz) panel_.advance_ns(bytes * 8u * 1000000000u / options_.spi_hz);
  }
  void send(std::span<const uint8_t> pixels) {
    log({Event::Kind::kPixels, 0, {}, pixels.size(), 0, panel_.now_ns()});
    panel_.data(pixels);
    pass_time(pixels.size());
    totals_.pixel_bytes += pixels.size();
    totals_.bytes += pixels.size();
    close_frame();
  }
  void finish_pending() {
    pending_ = false;
    if (!std::equal(in_flight_.begin(), in_flight_.end(), snapshot_.begin(), snapshot_.end()))
      misuse("a pixel buffer was changed while its transfer was in flight");
    send(in_flight_);
    in_flight_ = {};
  }

  PanelEmulator& panel_;
  Options options_;
  BusTotals totals_;
  std::vector<Event> events_;
  std::vector<std::string> misuse_;
  bool cs_open_ = false;
  bool pending_ = false;
  bool backlight_ = true;
  uint8_t last_command_ = 0;
  std::span<const uint8_t> in_flight_;
  std::vector<uint8_t> snapshot_;
  Status fail_next_wait_ = Status::kOk;
};

// Forwards to another bus (a real panel) and keeps the same totals as EmulatorBus.
class CountingBus final : public PanelBus {
 public:
  explicit CountingBus(PanelBus& inner) : inner_(inner) {}

  Status command(uint8_t cmd, std::span<const uint8_t> params) override {
    if (!cs_open_) ++totals_.transactions;
    cs_open_ = detail::is_memory_write(cmd);
    ++totals_.commands;
    totals_.command_bytes += 1;
    totals_.parameter_bytes += params.size();
    totals_.bytes += 1 + params.size();
    return inner_.command(cmd, params);
  }
  Status start_pixels(std::span<const uint8_t> pixels) override {
    const Status s = inner_.start_pixels(pixels);
    if (s != Status::kOk) return s;
    if (!cs_open_) ++totals_.transactions;
    cs_open_ = false;
    ++totals_.pixel_transfers;
    totals_.pixel_bytes += pixels.size();
    totals_.bytes += pixels.size();
    return s;
  }
  void clean_dcache(std::span<const uint8_t> bytes) override { inner_.clean_dcache(bytes); }
  Status wait(uint32_t timeout_ms) override { return inner_.wait(timeout_ms); }
  Status set_reset(bool asserted) override { return inner_.set_reset(asserted); }
  Status set_backlight(bool on) override { return inner_.set_backlight(on); }
  void delay_ms(uint32_t ms) override {
    totals_.delay_ms += ms;
    inner_.delay_ms(ms);
  }
  const BusTotals& totals() const { return totals_; }

 private:
  PanelBus& inner_;
  BusTotals totals_;
  bool cs_open_ = false;
};

}  // namespace lr::host
