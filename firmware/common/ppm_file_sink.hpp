// A display backend that writes the frame to a file on the host: a binary PPM (P6, 8 bits per
// channel), written strip by strip through semihosting as the strips arrive. The file is the
// same bytes lineraster-sim writes with --out NAME.ppm for the same frame, so the two can be
// compared with cmp. Every pixel is also folded into an FNV-1a checksum (over the PPM's pixel
// bytes), printed by the firmware so a run without the file can still be compared.
//
// The sink owns no storage: two strip buffers of at least width x strip-height pixels each are
// given to it. Writes complete inside submit(), so a submitted buffer is free again at once
// (a DMA backend would instead wait, bounded, in acquire()).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/pixel_format.hpp"
#include "firmware/common/semihost.hpp"
#include "hal/display.hpp"

namespace lr::fw {

template <class PF>
class PpmFileSink final : public StripSink<PF> {
 public:
  using Pixel = typename PF::Storage;

  // `path` must outlive the sink; the buffers must not overlap.
  PpmFileSink(const char* path, std::span<Pixel> buffer0, std::span<Pixel> buffer1)
      : path_(path), buffers_{buffer0, buffer1} {}

  Status begin_frame(uint16_t width, uint16_t height) override {
    if (width == 0 || height == 0 || in_frame_) return Status::kInvalidArgument;
    width_ = width;
    height_ = height;
    next_row_ = 0;
    next_slot_ = 0;
    lent_ = {false, false};
    hash_ = kFnvOffset;
    bytes_ = 0;
    handle_ = semihost::open_write(path_);
    if (handle_ < 0) return Status::kDisplayError;
    char header[32];
    const uint32_t n = ppm_header(header, width, height);
    if (!semihost::write_file(handle_, header, n)) return fail();
    in_frame_ = true;
    return Status::kOk;
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
    // The file is written in order: strips must come top to bottom, full width.
    if (!in_frame_ || rect.x != 0 || rect.width != width_ || rect.y != next_row_ ||
        rect.height == 0 || rect.y + rect.height > height_)
      return Status::kInvalidArgument;
    const size_t count = size_t{rect.width} * rect.height;
    if (count > px.size()) return Status::kInvalidArgument;
    // Through a small chunk: the pixel format's storage need not be 3 packed bytes.
    std::array<uint8_t, 3 * kChunkPixels> bytes;
    for (size_t done = 0; done < count;) {
      const size_t n = count - done < kChunkPixels ? count - done : kChunkPixels;
      uint32_t h = hash_;
      for (size_t i = 0; i < n; ++i) {
        const Rgb8 c = PF::decode(px[done + i]);
        bytes[3 * i] = c.r;
        bytes[3 * i + 1] = c.g;
        bytes[3 * i + 2] = c.b;
        h = (h ^ c.r) * kFnvPrime;
        h = (h ^ c.g) * kFnvPrime;
        h = (h ^ c.b) * kFnvPrime;
      }
      hash_ = h;
      if (!semihost::write_file(handle_, bytes.data(), static_cast<uint32_t>(3 * n))) return fail();
      bytes_ += 3 * n;
      done += n;
    }
    next_row_ = static_cast<uint16_t>(next_row_ + rect.height);
    ++strips_;
    return Status::kOk;
  }

  Status end_frame() override {
    const bool complete = in_frame_ && next_row_ == height_ && !lent_[0] && !lent_[1];
    in_frame_ = false;
    const bool closed = semihost::close_file(handle_);
    handle_ = -1;
    return complete && closed ? Status::kOk : Status::kDisplayError;
  }

  // FNV-1a (32 bit) of the frame's RGB888 bytes, rows top to bottom.
  uint32_t checksum() const { return hash_; }
  uint32_t strips() const { return strips_; }
  uint32_t pixel_bytes() const { return bytes_; }

 private:
  static constexpr uint32_t kFnvOffset = 2166136261u;
  static constexpr uint32_t kFnvPrime = 16777619u;
  static constexpr size_t kChunkPixels = 128;  // 384 bytes of stack per write

  Status fail() {
    semihost::close_file(handle_);
    handle_ = -1;
    in_frame_ = false;
    return Status::kDisplayError;
  }

  // "P6\n<w> <h>\n255\n", as lineraster-sim writes it.
  static uint32_t ppm_header(char* out, unsigned w, unsigned h) {
    uint32_t n = 0;
    auto put = [&](char c) { out[n++] = c; };
    auto put_dec = [&](unsigned v) {
      char digits[5];
      int k = 0;
      do {
        digits[k++] = static_cast<char>('0' + v % 10u);
        v /= 10u;
      } while (v != 0);
      while (k > 0) put(digits[--k]);
    };
    put('P');
    put('6');
    put('\n');
    put_dec(w);
    put(' ');
    put_dec(h);
    put('\n');
    put('2');
    put('5');
    put('5');
    put('\n');
    return n;
  }

  const char* path_;
  std::array<std::span<Pixel>, 2> buffers_;
  std::array<bool, 2> lent_{};
  uint8_t next_slot_ = 0;
  bool in_frame_ = false;
  int handle_ = -1;
  uint16_t width_ = 0, height_ = 0, next_row_ = 0;
  uint32_t hash_ = kFnvOffset;
  uint32_t strips_ = 0;
  uint32_t bytes_ = 0;
};

}  // namespace lr::fw
