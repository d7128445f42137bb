// A display backend for the host: assembles the strips of a frame into an image and counts
// what a real link would carry (strips, bytes). It checks what a panel would not forgive:
// strips outside the frame, rows sent twice or never, buffers reused while lent out.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/output/strip_sink.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/host_sim/formats/image_io.hpp"

namespace lr::host {

template <class PF>
class CaptureDisplay final : public StripSink<PF> {
 public:
  using Pixel = typename PF::Storage;

  // strip_pixels: size of each of the two strip buffers (width x K).
  explicit CaptureDisplay(size_t strip_pixels) {
    for (auto& b : buffers_) b.assign(strip_pixels, Pixel{});
  }

  Status begin_frame(uint16_t width, uint16_t height) override {
    // The previous frame stays in place (a panel's RAM does the same): strips the renderer
    // keeps show it.
    retained_ = complete_ && width == width_ && height == height_;
    complete_ = false;
    width_ = width;
    height_ = height;
    if (!retained_) frame_.assign(size_t{width} * height, Pixel{});
    rows_seen_.assign(height, 0);
    strips_ = 0;
    kept_ = 0;
    bytes_ = 0;
    lent_[0] = lent_[1] = false;
    error_.clear();
    return Status::kOk;
  }

  Status acquire(StripLease<PF>& out) override {
    for (uint8_t i = 0; i < 2; ++i) {
      uint8_t slot = static_cast<uint8_t>((next_ + i) % 2);
      if (!lent_[slot]) {
        lent_[slot] = true;
        next_ = static_cast<uint8_t>(slot + 1);
        out = this->lend(buffers_[slot].data(), buffers_[slot].size(), slot);
        return Status::kOk;
      }
    }
    error_ = "acquire: both strip buffers are lent out";
    return Status::kBusy;
  }

  Status submit(const StripRect& rect, StripLease<PF>&& strip) override {
    std::span<Pixel> px;
    uint8_t slot = this->take_back(strip, px);
    lent_[slot] = false;
    if (rect.x + rect.width > width_ || rect.y + rect.height > height_ ||
        px.size() < size_t{rect.width} * rect.height) {
      error_ = "submit: strip outside the frame";
      return Status::kInvalidArgument;
    }
    for (int r = 0; r < rect.height; ++r) {
      ++rows_seen_[static_cast<size_t>(rect.y + r)];
      for (int c = 0; c < rect.width; ++c)
        frame_[size_t(rect.y + r) * width_ + rect.x + static_cast<size_t>(c)] =
            px[size_t(r) * rect.width + static_cast<size_t>(c)];
    }
    ++strips_;
    bytes_ += uint64_t{rect.width} * rect.height * PF::kBytesPerPixel;
    return Status::kOk;
  }

  Status end_frame() override {
    for (uint8_t seen : rows_seen_) {
      if (seen != 1) {
        error_ = "end_frame: a row was sent " + std::to_string(seen) + " times";
        return Status::kDisplayError;
      }
    }
    complete_ = true;
    return Status::kOk;
  }

  bool retains_frame() const override { return retained_ && retain_enabled_; }
  Status keep(const StripRect& rect) override {
    if (!retained_ || rect.x + rect.width > width_ || rect.y + rect.height > height_) {
      error_ = "keep: no previous frame of this size, or a strip outside the frame";
      return Status::kInvalidArgument;
    }
    for (int r = 0; r < rect.height; ++r) ++rows_seen_[static_cast<size_t>(rect.y + r)];
    ++kept_;
    return Status::kOk;
  }
  // Whether to offer the renderer to keep strips (on by default; off: every strip is sent).
  void set_retain(bool on) { retain_enabled_ = on; }
  uint32_t kept() const { return kept_; }

  ImageRgb8 image() const {
    ImageRgb8 img;
    img.width = width_;
    img.height = height_;
    img.rgb.resize(frame_.size() * 3);
    for (size_t i = 0; i < frame_.size(); ++i) {
      Rgb8 c = PF::decode(frame_[i]);
      img.rgb[3 * i] = c.r;
      img.rgb[3 * i + 1] = c.g;
      img.rgb[3 * i + 2] = c.b;
    }
    return img;
  }
  const std::vector<Pixel>& raw_frame() const { return frame_; }
  uint32_t strips() const { return strips_; }
  uint64_t bytes() const { return bytes_; }
  const std::string& error() const { return error_; }

 private:
  std::vector<Pixel> buffers_[2];
  bool lent_[2] = {false, false};
  uint8_t next_ = 0;
  std::vector<Pixel> frame_;
  std::vector<uint8_t> rows_seen_;
  uint16_t width_ = 0, height_ = 0;
  uint32_t strips_ = 0, kept_ = 0;
  bool retained_ = false, complete_ = false, retain_enabled_ = true;
  uint64_t bytes_ = 0;
  std::string error_;
};

// Collects each strip's depth buffer into a frame-sized 16-bit depth image.
class DepthCapture final : public DepthSink {
 public:
  void resize(int width, int height) {
    width_ = width;
    depth_.assign(size_t(width) * size_t(height), 0xFFFF);
  }
  void on_depth(const StripRect& rect, std::span<const uint16_t> depth) override {
    for (int r = 0; r < rect.height; ++r)
      for (int c = 0; c < rect.width; ++c)
        depth_[size_t(rect.y + r) * size_t(width_) + rect.x + size_t(c)] =
            depth[size_t(r) * rect.width + size_t(c)];
  }
  const std::vector<uint16_t>& depth() const { return depth_; }

 private:
  int width_ = 0;
  std::vector<uint16_t> depth_;
};

}  // namespace lr::host
