// The firmware's display sinks: two caller-supplied strip buffers, lent in turn, and a consumer
// that takes each finished strip inside submit() (a checksum, a file on the host, nothing). The
// transfer completes there, so a submitted buffer is free again at once; a DMA backend would
// instead wait (bounded) in acquire(). The lease protocol is checked on every strip: each buffer
// lent once, strips back in order, top to bottom, full width, the whole frame delivered.
//
// A consumer provides
//   Status begin(uint16_t width, uint16_t height);
//   Status strip(const StripRect& rect, std::span<const Pixel> pixels);  // rect's pixels, packed
//   Status end();
// and is called directly (no virtual call): scripts/stack_usage.py resolves the renderer's
// calls through StripSink to OrderedStripSink's methods.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "lineraster/core/math/hash.hpp"
#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/output/status.hpp"
#include "lineraster/core/output/strip_sink.hpp"

namespace lr::fw {

template <class PF, class Consumer>
class OrderedStripSink final : public StripSink<PF> {
 public:
  using Pixel = typename PF::Storage;

  // The buffers must not overlap; each holds at least width x strip-height pixels.
  OrderedStripSink(std::span<Pixel> buffer0, std::span<Pixel> buffer1, Consumer& consumer)
      : buffers_{buffer0, buffer1}, consumer_(consumer) {}

  Status begin_frame(uint16_t width, uint16_t height) override {
    if (width == 0 || height == 0 || in_frame_) return Status::kInvalidArgument;
    width_ = width;
    height_ = height;
    next_row_ = 0;
    next_slot_ = 0;
    lent_ = {false, false};
    strips_ = 0;
    const Status s = consumer_.begin(width, height);
    in_frame_ = s == Status::kOk;
    return s;
  }

  Status acquire(StripLease<PF>& out) override {
    if (!in_frame_) return Status::kBusy;
    const uint8_t slot = next_slot_;
    if (lent_[slot]) return Status::kTimeout;  // a lease never came back: nothing to wait for
    lent_[slot] = true;
    next_slot_ = static_cast<uint8_t>(slot ^ 1u);
    out = this->lend(buffers_[slot].data(), buffers_[slot].size(), slot);
    return Status::kOk;
  }

  Status submit(const StripRect& rect, StripLease<PF>&& strip) override {
    std::span<Pixel> px;
    const uint8_t slot = this->take_back(strip, px);
    if (slot > 1 || !lent_[slot] || px.data() != buffers_[slot].data())
      return Status::kInvalidArgument;
    lent_[slot] = false;
    if (!in_frame_ || rect.x != 0 || rect.width != width_ || rect.y != next_row_ ||
        rect.height == 0 || rect.y + rect.height > height_)
      return Status::kInvalidArgument;
    const size_t count = size_t{rect.width} * rect.height;
    if (count > px.size()) return Status::kInvalidArgument;
    const Status s = consumer_.strip(rect, std::span<const Pixel>(px.data(), count));
    if (s != Status::kOk) return s;
    next_row_ = static_cast<uint16_t>(next_row_ + rect.height);
    ++strips_;
    return Status::kOk;
  }

  Status end_frame() override {
    const bool complete = in_frame_ && next_row_ == height_ && !lent_[0] && !lent_[1];
    in_frame_ = false;
    const Status s = consumer_.end();
    if (s != Status::kOk) return s;
    return complete ? Status::kOk : Status::kDisplayError;
  }

  uint32_t strips() const { return strips_; }

 private:
  std::array<std::span<Pixel>, 2> buffers_;
  Consumer& consumer_;
  std::array<bool, 2> lent_{};
  uint8_t next_slot_ = 0;
  bool in_frame_ = false;
  uint16_t width_ = 0, height_ = 0, next_row_ = 0;
  uint32_t strips_ = 0;
};

// Folds every pixel into FNV-1a as its wire bytes: RGB565 big-endian (high byte first) for a
// 16-bit format, rows top to bottom. Integer arithmetic only, so the host build of the same
// firmware prints the same value. `enabled = false` makes strips free (benchmarks).
template <class PF>
struct ChecksumConsumer {
  Fnv1a32 hash;  // the firmware's frame checksum
  bool enabled = true;
  Status begin(uint16_t, uint16_t) {
    hash = {};
    return Status::kOk;
  }
  Status strip(const StripRect&, std::span<const typename PF::Storage> pixels) {
    if (!enabled) return Status::kOk;
    Fnv1a32 h = hash;
    for (const auto& p : pixels) {
      const unsigned v = PF::to_value(p);
      h.add(static_cast<uint8_t>(v >> 8));
      h.add(static_cast<uint8_t>(v & 0xFFu));
    }
    hash = h;
    return Status::kOk;
  }
  Status end() { return Status::kOk; }
};

}  // namespace lr::fw
