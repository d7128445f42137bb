// A display sink for benchmarks: two strip buffers, lent in turn, and a running checksum of each
// strip's first and last pixel, as a DMA link would consume them; no frame in memory.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "lineraster/core/output/strip_sink.hpp"

namespace lr::bench {

template <class PF>
class NullSink final : public StripSink<PF> {
 public:
  explicit NullSink(size_t n) : a_(n), b_(n) {}
  Status begin_frame(uint16_t, uint16_t) override { return Status::kOk; }
  Status acquire(StripLease<PF>& out) override {
    flip_ = !flip_;
    auto& buf = flip_ ? a_ : b_;
    out = this->lend(buf.data(), buf.size(), flip_ ? 0 : 1);
    return Status::kOk;
  }
  Status submit(const StripRect& r, StripLease<PF>&& lease) override {
    std::span<typename PF::Storage> px;
    this->take_back(lease, px);
    Rgb8 a = PF::decode(px[0]), b = PF::decode(px[size_t(r.width) * r.height - 1]);
    sum_ += static_cast<uint64_t>(a.r + a.g + a.b + b.r + b.g + b.b);
    return Status::kOk;
  }
  Status end_frame() override { return Status::kOk; }
  // As a panel would: with `retain`, strips the renderer leaves unchanged are kept (not sent).
  bool retains_frame() const override { return retain_; }
  Status keep(const StripRect&) override { return Status::kOk; }
  void set_retain(bool on) { retain_ = on; }
  uint64_t sum() const { return sum_; }

 private:
  std::vector<typename PF::Storage> a_, b_;
  bool flip_ = false, retain_ = false;
  uint64_t sum_ = 0;
};

}  // namespace lr::bench
