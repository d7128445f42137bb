// PanelSink: the renderer's strips to an SPI panel (a StripSink<Rgb565Be> over a Panel and its
// PanelBus), double-buffered, optionally sending only what changed since the last frame.
//
// Memory: none of its own. The caller gives two strip buffers (each at least frame width x K
// pixels; Rgb565Be is stored in wire order, so a buffer goes to the bus as it is) and, to skip
// unchanged strips, one StripSignature per strip (hal/strip_signature.hpp: 44 bytes each).
//
// Buffers. Each is free, lent (the renderer holds its lease), queued (submitted, waiting for the
// bus) or on the wire (the bus owns it until wait() returns). The bus carries one transfer at a
// time, and commands may not interleave with pixels, so:
//   submit()   signs the strip, skips or narrows it, then, if the bus is idle, sends CASET,
//              RASET, RAMWR and starts the pixels (start_pixels, asynchronous); if a transfer is
//              on the wire the strip is queued behind it;
//   acquire()  lends a free buffer; when there is none (one on the wire, the other queued) it
//              waits for the older transfer (bus.wait with the timeout), starts the queued one
//              and lends the buffer that came back. A buffer is lent only when it is free: one on
//              the wire or queued is never lent, and the lease (move-only, emptied by submit)
//              leaves the renderer no pointer to it. Two buffers alternate strip by strip.
//   end_frame() waits for the transfer on the wire and the queued one.
// Every wait is bus.wait(timeout_ms): bounded. A failed or timed-out transfer, or a command the
// bus refuses, aborts the frame: the sink returns that status from the call that found it and
// from every later call of the frame (acquire, submit, end_frame), forgets what the panel holds
// (its RAM is no longer known) and is ready for the next begin_frame(). A frame given up without
// end_frame() is finished by the next begin_frame(), and leases still out are void from then on.
//
// Skipping (with signature storage). The n-th strip submitted in a frame is compared with the
// n-th signature, which describes what the panel got for that rectangle last time: equal: nothing
// is sent; different: only the columns from the first to the last changed band
// (kSignatureBands = 8 bands per strip) are sent. Narrowing is a gather in the strip buffer
// itself: the changed columns of each row are moved together (memmove, front to back, in place),
// so a narrowed strip still goes out as one window and one transfer (3 commands + 1 transfer per
// strip, as for a whole one), never as one transfer per row. The first frame, a frame whose size
// differs from the last, a frame after Panel::init() or set_rotation() (Panel::epoch), after an
// abort or after invalidate() sends everything. Strips beyond the signature storage are sent
// whole (counted as unchecked).
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/output/status.hpp"
#include "lineraster/core/output/strip_sink.hpp"
#include "lineraster/hal/panel.hpp"
#include "lineraster/hal/strip_signature.hpp"

namespace lr {

// What one frame sent (reset by begin_frame).
struct PanelSinkStats {
  uint32_t pixel_bytes = 0;       // pixel data
  uint32_t command_bytes = 0;     // command and parameter bytes (CASET, RASET, RAMWR)
  uint32_t transactions = 0;      // commands + pixel transfers
  uint32_t strips_sent = 0;       // strips with a transfer, whole or narrowed
  uint32_t strips_narrowed = 0;   // of those, sent with their changed columns only
  uint32_t strips_skipped = 0;    // unchanged: nothing sent
  uint32_t strips_unchecked = 0;  // sent whole: no signature left for them
  uint32_t strips_kept = 0;       // not rendered (inputs unchanged): nothing sent
  uint32_t waits = 0;             // bounded waits for a transfer
  Status status = Status::kOk;    // what aborted the frame, kOk if nothing did

  constexpr uint32_t bytes() const { return pixel_bytes + command_bytes; }
};

class PanelSink final : public StripSink<Rgb565Be> {
 public:
  static constexpr uint32_t kDefaultTimeoutMs = 250;

  // buffer1 may be empty (single buffering: acquire() then waits for every transfer).
  PanelSink(Panel& panel, std::span<Pixel> buffer0, std::span<Pixel> buffer1,
            std::span<StripSignature> signatures = {}, uint32_t timeout_ms = kDefaultTimeoutMs)
      : panel_(panel), signatures_(signatures), timeout_ms_(timeout_ms) {
    buffers_[0].pixels = buffer0;
    buffers_[1].pixels = buffer1;
    invalidate();  // the caller's storage may hold anything
  }
  PanelSink(const PanelSink&) = delete;
  PanelSink& operator=(const PanelSink&) = delete;

  // The frame is placed at the image's top-left corner: width and height may not exceed the
  // panel's image_width() x image_height() (kInvalidArgument).
  Status begin_frame(uint16_t width, uint16_t height) override { return begin(width, height); }
  Status acquire(StripLease<Rgb565Be>& out) override { return lend_buffer(out); }
  // kInvalidArgument for a lease this sink did not lend (or lent before the frame began) and for
  // a rectangle outside the frame or larger than the buffer.
  Status submit(const StripRect& rect, StripLease<Rgb565Be>&& strip) override {
    return take(rect, strip);
  }
  Status end_frame() override { return end(); }
  // The panel's RAM holds the previous frame when that frame ended without error, at this size,
  // since the last Panel::init()/set_rotation() and invalidate().
  bool retains_frame() const override { return in_frame_ && retained_; }
  // Sends nothing; the strip's signature (if any) stays what the panel holds.
  Status keep(const StripRect& rect) override { return keep_strip(rect); }

  // Forget what the panel holds (e.g. after drawing on it directly): the next frame sends all.
  void invalidate();
  void set_timeout(uint32_t timeout_ms) { timeout_ms_ = timeout_ms; }
  uint32_t timeout() const { return timeout_ms_; }
  // The current frame's statistics, or the last frame's after end_frame().
  const PanelSinkStats& stats() const { return stats_; }

 private:
  enum class State : uint8_t { kFree, kLent, kQueued, kOnWire };
  static constexpr uint8_t kNone = 0xFF;
  struct Buffer {
    std::span<Pixel> pixels;
    State state = State::kFree;
    StripRect window{};  // what goes out: the strip, or its changed columns gathered
  };

  // The constructor and the overrides are inline, so the class has no key function and this
  // library (compiled without RTTI) never emits its vtable: the vtable (and, in builds with RTTI
  // such as the tests, whose UBSan vptr checks need it, its type_info) comes from the code that
  // constructs the sink, consistently.
  Status begin(uint16_t width, uint16_t height);
  Status lend_buffer(StripLease<Rgb565Be>& out);
  Status take(const StripRect& rect, StripLease<Rgb565Be>& strip);
  Status end();
  Status keep_strip(const StripRect& rect);
  Status start(uint8_t slot);
  Status finish_transfer();
  Status drain();
  Status abort(Status st);
  void release_all();

  Panel& panel_;
  std::array<Buffer, 2> buffers_;
  std::span<StripSignature> signatures_;
  uint32_t timeout_ms_;
  uint8_t on_wire_ = kNone;
  uint8_t queued_ = kNone;
  uint8_t next_lend_ = 0;
  bool in_frame_ = false;
  bool retained_ = false;  // the panel shows the last frame, whole (see retains_frame)
  Status abort_ = Status::kOk;
  uint16_t frame_width_ = 0, frame_height_ = 0;
  uint16_t known_width_ = 0, known_height_ = 0;  // the frame size the signatures describe
  uint32_t known_epoch_ = 0;
  size_t next_signature_ = 0;
  PanelSinkStats stats_;
};

}  // namespace lr
