// The footprint images' display: two static strip buffers whose strips are folded into FNV-1a
// (32 bit, over each pixel as RGB565 big-endian, rows top to bottom: the smoke test's checksum,
// so that frames compare across cores and with the host). A strip is "sent" inside submit(),
// so its buffer is free again at once; the lease protocol is still checked. Its virtual
// methods are what scripts/footprint.sh names to stack_usage.py as targets of the renderer's
// calls through StripSink (--indirect 'FootprintSink::').
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/pixel_format.hpp"
#include "hal/display.hpp"

namespace lr::fw::footprint {

template <class PF, size_t kPixels>
class FootprintSink final : public StripSink<PF> {
 public:
  using Pixel = typename PF::Storage;
  using Buffers = std::array<std::array<Pixel, kPixels>, 2>;

  explicit constexpr FootprintSink(Buffers& buffers) : buffers_(buffers) {}

  Status begin_frame(uint16_t width, uint16_t height) override {
    if (width == 0 || height == 0 || size_t{width} > kPixels) return Status::kInvalidArgument;
    width_ = width;
    height_ = height;
    next_row_ = 0;
    next_slot_ = 0;
    lent_ = {false, false};
    hash_ = kFnvOffset;
    strips_ = 0;
    in_frame_ = true;
    return Status::kOk;
  }

  Status acquire(StripLease<PF>& out) override {
    if (!in_frame_) return Status::kBusy;
    const uint8_t slot = next_slot_;
    if (lent_[slot]) return Status::kTimeout;  // a lease never came back
    lent_[slot] = true;
    next_slot_ = static_cast<uint8_t>(slot ^ 1u);
    out = this->lend(buffers_[slot].data(), kPixels, slot);
    return Status::kOk;
  }

  Status submit(const StripRect& rect, StripLease<PF>&& strip) override {
    std::span<Pixel> px;
    const uint8_t slot = this->take_back(strip, px);
    if (slot >= 2 || !lent_[slot] || px.data() != buffers_[slot].data())
      return Status::kInvalidArgument;
    lent_[slot] = false;
    if (!in_frame_ || rect.x != 0 || rect.width != width_ || rect.y != next_row_ ||
        rect.height == 0 || rect.y + rect.height > height_)
      return Status::kInvalidArgument;
    const size_t count = size_t{rect.width} * rect.height;
    if (count > px.size()) return Status::kInvalidArgument;
    uint32_t h = hash_;
    for (size_t i = 0; i < count; ++i) {
      const unsigned v = PF::to_value(px[i]);
      h = (h ^ (v >> 8)) * kFnvPrime;
      h = (h ^ (v & 0xFFu)) * kFnvPrime;
    }
    hash_ = h;
    next_row_ = static_cast<uint16_t>(next_row_ + rect.height);
    ++strips_;
    return Status::kOk;
  }

  Status end_frame() override {
    const bool complete = in_frame_ && next_row_ == height_ && !lent_[0] && !lent_[1];
    in_frame_ = false;
    return complete ? Status::kOk : Status::kDisplayError;
  }

  uint32_t checksum() const { return hash_; }
  uint32_t strips() const { return strips_; }

 private:
  static constexpr uint32_t kFnvOffset = 2166136261u;
  static constexpr uint32_t kFnvPrime = 16777619u;

  Buffers& buffers_;
  std::array<bool, 2> lent_{};
  uint8_t next_slot_ = 0;
  bool in_frame_ = false;
  uint16_t width_ = 0, height_ = 0, next_row_ = 0;
  uint32_t hash_ = kFnvOffset;
  uint32_t strips_ = 0;
};

}  // namespace lr::fw::footprint
