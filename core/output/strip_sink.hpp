// The display interface: where finished strips go.
//
// A sink lends strip buffers to the renderer (acquire) and takes them back with the strip's
// rectangle (submit). The lease is move-only and submit() consumes it, so once a strip is
// handed over the renderer holds no pointer to its pixels: a buffer still on the wire (DMA)
// cannot be written by the next strip. A sink with two buffers lets strip n be sent while strip
// n+1 renders; acquire() blocks, with a bounded wait, until a buffer is free again.
// (The model: Zephyr's display_write with a buffer descriptor per write, and LVGL's flush
// callback with explicit flush-ready.)
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>

#include "lineraster/core/output/status.hpp"

namespace lr {

// A rectangle of the display in pixels: x, y of the top-left corner, width, height.
struct StripRect {
  uint16_t x = 0, y = 0, width = 0, height = 0;
  friend constexpr bool operator==(const StripRect&, const StripRect&) = default;
};

template <class PF>
class StripSink;

// A strip buffer on loan from a sink: width x height pixels, rows packed, row 0 first.
template <class PF>
class StripLease {
 public:
  using Pixel = typename PF::Storage;
  StripLease() = default;
  StripLease(const StripLease&) = delete;
  StripLease& operator=(const StripLease&) = delete;
  StripLease(StripLease&& o) noexcept { *this = std::move(o); }
  StripLease& operator=(StripLease&& o) noexcept {
    data_ = std::exchange(o.data_, nullptr);
    size_ = std::exchange(o.size_, 0);
    slot_ = o.slot_;
    return *this;
  }
  ~StripLease() = default;

  std::span<Pixel> pixels() const { return {data_, size_}; }
  bool valid() const { return data_ != nullptr; }

 private:
  friend class StripSink<PF>;
  StripLease(Pixel* data, size_t size, uint8_t slot) : data_(data), size_(size), slot_(slot) {}
  Pixel* data_ = nullptr;
  size_t size_ = 0;
  uint8_t slot_ = 0;
};

// What a display backend implements.
template <class PF>
class StripSink {
 public:
  using Pixel = typename PF::Storage;

  // A frame of width x height pixels begins; strips follow top to bottom.
  virtual Status begin_frame(uint16_t width, uint16_t height) = 0;
  // Lends a free buffer of at least width x (strip height) pixels; waits (bounded) for one.
  virtual Status acquire(StripLease<PF>& out) = 0;
  // Takes the strip back: `rect` says where its pixels go. The lease is emptied.
  virtual Status submit(const StripRect& rect, StripLease<PF>&& strip) = 0;
  // All strips submitted: waits (bounded) until every transfer has completed.
  virtual Status end_frame() = 0;

  // Asked after begin_frame(): true when the display holds the previous frame's pixels and
  // this frame has its size, so that a strip left out with keep() still shows them. Only then
  // does the renderer skip strips whose inputs did not change (FrameStorage::strip_inputs).
  virtual bool retains_frame() const { return false; }
  // In place of acquire + submit: the strip `rect` is the previous frame's, unchanged.
  // Only called when retains_frame() said true.
  virtual Status keep(const StripRect& rect) {
    (void)rect;
    return Status::kInvalidArgument;
  }

 protected:
  StripSink() = default;
  ~StripSink() = default;
  static StripLease<PF> lend(Pixel* data, size_t size, uint8_t slot) { return {data, size, slot}; }
  // Empties the lease and says which buffer it was.
  static uint8_t take_back(StripLease<PF>& lease, std::span<Pixel>& pixels) {
    pixels = lease.pixels();
    lease.data_ = nullptr;
    lease.size_ = 0;
    return lease.slot_;
  }
};

}  // namespace lr
