#include "lineraster/hal/panel_sink.hpp"

#include <cstring>

namespace lr {

namespace {
// Moves the columns [cols.begin, cols.end) of each row of a rect.width-wide strip together at the
// front of the buffer. Row r's columns go to r * n, which is never after where they are
// (r * width + cols.begin), so working front to back never overwrites a row not yet moved.
void gather_columns(std::span<Rgb565Be::Storage> px, const StripRect& rect, ColumnRange cols) {
  const size_t w = rect.width, n = cols.width();
  for (size_t r = 0; r < rect.height; ++r) {
    Rgb565Be::Storage* dst = px.data() + r * n;
    const Rgb565Be::Storage* src = px.data() + r * w + cols.begin;
    if (dst != src) std::memmove(dst, src, n * sizeof(Rgb565Be::Storage));
  }
}
}  // namespace

void PanelSink::invalidate() {
  for (StripSignature& s : signatures_) s = StripSignature{};
  retained_ = false;
}

Status PanelSink::begin(uint16_t width, uint16_t height) {
  // What a frame given up without end_frame() left on the wire: its strips are good pixels, so
  // let them finish; if that fails the panel's RAM is unknown (drain() forgets it).
  if (in_frame_) retained_ = false;  // given up part way: the panel shows a mix
  (void)drain();
  for (Buffer& b : buffers_)
    if (b.state == State::kLent) b.state = State::kFree;  // leases of the old frame are void
  stats_ = PanelSinkStats{};
  abort_ = Status::kOk;
  in_frame_ = false;
  next_signature_ = 0;
  next_lend_ = 0;
  if (width == 0 || height == 0 || width > panel_.image_width() || height > panel_.image_height() ||
      buffers_[0].pixels.empty())
    return Status::kInvalidArgument;
  if (width != known_width_ || height != known_height_ || panel_.epoch() != known_epoch_) {
    invalidate();
    known_width_ = width;
    known_height_ = height;
    known_epoch_ = panel_.epoch();
  }
  frame_width_ = width;
  frame_height_ = height;
  in_frame_ = true;
  return Status::kOk;
}

Status PanelSink::lend_buffer(StripLease<Rgb565Be>& out) {
  if (!in_frame_) return Status::kBusy;
  if (abort_ != Status::kOk) return abort_;
  for (;;) {
    for (uint8_t i = 0; i < 2; ++i) {
      const auto slot = static_cast<uint8_t>((next_lend_ + i) & 1u);
      Buffer& b = buffers_[slot];
      if (b.state == State::kFree && !b.pixels.empty()) {
        b.state = State::kLent;
        next_lend_ = static_cast<uint8_t>(slot ^ 1u);
        out = lend(b.pixels.data(), b.pixels.size(), slot);
        return Status::kOk;
      }
    }
    // No buffer is free: wait for the older transfer. Nothing on the wire means every buffer is
    // lent out, which no wait can change.
    if (on_wire_ == kNone) return Status::kBusy;
    const Status st = finish_transfer();
    if (st != Status::kOk) return abort(st);
  }
}

Status PanelSink::take(const StripRect& rect, StripLease<Rgb565Be>& strip) {
  std::span<Pixel> px;
  const uint8_t slot = take_back(strip, px);
  if (slot >= buffers_.size() || buffers_[slot].state != State::kLent ||
      px.data() != buffers_[slot].pixels.data())
    return Status::kInvalidArgument;
  Buffer& b = buffers_[slot];
  b.state = State::kFree;
  if (!in_frame_) return Status::kBusy;
  if (abort_ != Status::kOk) return abort_;
  const size_t count = size_t{rect.width} * rect.height;
  if (count == 0 || uint32_t{rect.x} + rect.width > frame_width_ ||
      uint32_t{rect.y} + rect.height > frame_height_ || count > px.size())
    return Status::kInvalidArgument;

  StripRect window = rect;
  if (!signatures_.empty()) {
    if (next_signature_ < signatures_.size()) {
      StripSignature& known = signatures_[next_signature_];
      const StripSignature now = sign_strip(rect, px.first(count));
      const ColumnRange cols = changed_columns(known, now);
      known = now;  // what the panel holds once this goes out (an abort forgets it again)
      ++next_signature_;
      if (cols.empty()) {
        ++stats_.strips_skipped;
        return Status::kOk;
      }
      if (cols.width() < rect.width) {
        gather_columns(px, rect, cols);
        window.x = static_cast<uint16_t>(rect.x + cols.begin);
        window.width = cols.width();
        ++stats_.strips_narrowed;
      }
    } else {
      ++stats_.strips_unchecked;
    }
  }
  ++stats_.strips_sent;
  b.window = window;
  b.state = State::kQueued;
  // With two buffers nothing is queued here (the queued one and the one on the wire would leave
  // none to lend); with more, the older must go first.
  while (queued_ != kNone) {
    const Status st = finish_transfer();
    if (st != Status::kOk) {
      b.state = State::kFree;
      return abort(st);
    }
  }
  if (on_wire_ != kNone) {
    queued_ = slot;
    return Status::kOk;
  }
  const Status st = start(slot);
  return st == Status::kOk ? st : abort(st);
}

Status PanelSink::end() {
  if (!in_frame_) return Status::kBusy;
  in_frame_ = false;
  if (abort_ != Status::kOk) return abort_;
  const Status st = drain();
  if (st != Status::kOk) {
    abort_ = st;
    stats_.status = st;
  }
  retained_ = st == Status::kOk;
  return st;
}

Status PanelSink::keep_strip(const StripRect& rect) {
  if (!in_frame_) return Status::kBusy;
  if (abort_ != Status::kOk) return abort_;
  if (!retained_ || rect.width == 0 || rect.height == 0 || rect.x + rect.width > frame_width_ ||
      rect.y + rect.height > frame_height_)
    return Status::kInvalidArgument;
  if (!signatures_.empty() && next_signature_ < signatures_.size()) {
    // The n-th signature must describe this strip as the panel holds it.
    if (signatures_[next_signature_].rect != rect) return Status::kInvalidArgument;
    ++next_signature_;
  }
  ++stats_.strips_kept;
  return Status::kOk;
}

// CASET/RASET/RAMWR for the buffer's window, then its pixels.
Status PanelSink::start(uint8_t slot) {
  Buffer& b = buffers_[slot];
  Status st = panel_.begin_write(b.window);
  if (st != Status::kOk) {
    b.state = State::kFree;
    return st;
  }
  stats_.transactions += kWindowCommands;
  stats_.command_bytes += kWindowCommandBytes;
  const size_t bytes = size_t{b.window.width} * b.window.height * sizeof(Pixel);
  const std::span<const uint8_t> wire{reinterpret_cast<const uint8_t*>(b.pixels.data()), bytes};
  panel_.bus().clean_dcache(wire);  // the gather of a narrowed strip is the last write
  st = panel_.bus().start_pixels(wire);
  if (st != Status::kOk) {
    b.state = State::kFree;
    return st;
  }
  ++stats_.transactions;
  stats_.pixel_bytes += static_cast<uint32_t>(bytes);
  b.state = State::kOnWire;
  on_wire_ = slot;
  return Status::kOk;
}

// Waits (bounded) for the transfer on the wire; its buffer is free again whatever the outcome
// (after a failed wait the bus has abandoned it). Then starts the queued strip, if any.
Status PanelSink::finish_transfer() {
  if (on_wire_ == kNone) return Status::kOk;
  ++stats_.waits;
  const Status st = panel_.bus().wait(timeout_ms_);
  buffers_[on_wire_].state = State::kFree;
  on_wire_ = kNone;
  if (st != Status::kOk) return st;
  if (queued_ == kNone) return Status::kOk;
  const uint8_t next = queued_;
  queued_ = kNone;
  return start(next);
}

// Everything on the wire and queued sent; on failure nothing is left in flight and what the
// panel holds is forgotten.
Status PanelSink::drain() {
  while (on_wire_ != kNone) {
    const Status st = finish_transfer();
    if (st != Status::kOk) {
      release_all();
      return st;
    }
  }
  return Status::kOk;
}

Status PanelSink::abort(Status st) {
  release_all();
  retained_ = false;
  abort_ = st;
  stats_.status = st;
  return st;
}

// Drops what is queued and in flight (after a failure: the bus is idle, or is made so by a last
// bounded wait) and forgets what the panel holds: the strips that did not arrive are unknown.
void PanelSink::release_all() {
  if (on_wire_ != kNone) {
    (void)panel_.bus().wait(timeout_ms_);
    ++stats_.waits;
    buffers_[on_wire_].state = State::kFree;
    on_wire_ = kNone;
  }
  if (queued_ != kNone) {
    buffers_[queued_].state = State::kFree;
    queued_ = kNone;
  }
  invalidate();
}

}  // namespace lr
