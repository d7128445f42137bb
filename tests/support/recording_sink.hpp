// A strip sink for tests of the renderer's call order: it counts every call it gets (a refused
// render() must not reach the sink at all), keeps the frame's pixels, checks that each row
// arrives exactly once per frame, and can fail on purpose at its n-th call of a frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lineraster/core/output/strip_sink.hpp"

namespace lr::test {

template <class PF>
class RecordingSink final : public StripSink<PF> {
 public:
  using Pixel = typename PF::Storage;

  // strip_pixels: the size of the one strip buffer it lends (width x K at least).
  explicit RecordingSink(size_t strip_pixels) : buffer_(strip_pixels) {}

  // Counts over the sink's life.
  struct Calls {
    uint32_t begin_frame = 0, acquire = 0, submit = 0, keep = 0, end_frame = 0;
    uint32_t total() const { return begin_frame + acquire + submit + keep + end_frame; }
  };
  const Calls& calls() const { return calls_; }
  // This frame's strips: sent, and left as they were (keep).
  uint32_t submitted() const { return submitted_; }
  uint32_t kept() const { return kept_; }
  const std::vector<Pixel>& frame() const { return frame_; }
  // Rows seen other than once, or strips outside the frame (0: the frame arrived whole).
  uint32_t faults() const { return faults_; }
  // The frame's n-th call (1-based, from its begin_frame) returns kDisplayError; 0: none fails.
  void fail_at(uint32_t n) { fail_at_ = n; }
  bool failed() const { return failed_; }
  // Whether to tell the renderer that the last frame is still shown (strip skipping).
  void set_retain(bool on) { retain_ = on; }

  Status begin_frame(uint16_t width, uint16_t height) override {
    ++calls_.begin_frame;
    frame_calls_ = 0;
    failed_ = false;
    retained_ = complete_ && width == width_ && height == height_;
    complete_ = false;
    width_ = width;
    height_ = height;
    if (!retained_) frame_.assign(size_t{width} * height, Pixel{});
    rows_.assign(height, 0);
    submitted_ = kept_ = faults_ = 0;
    lent_ = false;
    return fail_now() ? Status::kDisplayError : Status::kOk;
  }
  Status acquire(StripLease<PF>& out) override {
    ++calls_.acquire;
    if (fail_now()) return Status::kDisplayError;
    if (lent_) {
      ++faults_;
      return Status::kBusy;
    }
    lent_ = true;
    out = this->lend(buffer_.data(), buffer_.size(), 0);
    return Status::kOk;
  }
  Status submit(const StripRect& rect, StripLease<PF>&& strip) override {
    ++calls_.submit;
    std::span<Pixel> px;
    this->take_back(strip, px);
    lent_ = false;
    if (fail_now()) return Status::kDisplayError;
    if (!inside(rect) || px.size() < size_t{rect.width} * rect.height) {
      ++faults_;
      return Status::kInvalidArgument;
    }
    for (int r = 0; r < rect.height; ++r) {
      ++rows_[size_t{rect.y} + static_cast<size_t>(r)];
      for (int c = 0; c < rect.width; ++c)
        frame_[(size_t{rect.y} + static_cast<size_t>(r)) * width_ + rect.x +
               static_cast<size_t>(c)] =
            px[static_cast<size_t>(r) * rect.width + static_cast<size_t>(c)];
    }
    ++submitted_;
    return Status::kOk;
  }
  Status end_frame() override {
    ++calls_.end_frame;
    if (fail_now()) return Status::kDisplayError;
    for (uint8_t seen : rows_) faults_ += seen != 1 ? 1u : 0u;
    complete_ = faults_ == 0;
    return Status::kOk;
  }
  bool retains_frame() const override { return retain_ && retained_; }
  Status keep(const StripRect& rect) override {
    ++calls_.keep;
    if (fail_now()) return Status::kDisplayError;
    if (!retained_ || !inside(rect)) {
      ++faults_;
      return Status::kInvalidArgument;
    }
    for (int r = 0; r < rect.height; ++r) ++rows_[size_t{rect.y} + static_cast<size_t>(r)];
    ++kept_;
    return Status::kOk;
  }

 private:
  bool fail_now() {
    if (fail_at_ == 0 || ++frame_calls_ != fail_at_) return false;
    failed_ = true;
    complete_ = false;
    return true;
  }
  bool inside(const StripRect& r) const {
    return r.x + r.width <= width_ && r.y + r.height <= height_;
  }

  std::vector<Pixel> buffer_;
  std::vector<Pixel> frame_;
  std::vector<uint8_t> rows_;
  Calls calls_{};
  uint32_t submitted_ = 0, kept_ = 0, faults_ = 0;
  uint32_t fail_at_ = 0, frame_calls_ = 0;
  uint16_t width_ = 0, height_ = 0;
  bool lent_ = false, failed_ = false, retain_ = false, retained_ = false, complete_ = false;
};

}  // namespace lr::test
