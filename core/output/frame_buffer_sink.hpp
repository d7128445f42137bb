// FrameBufferSink<PF>: the renderer's strips written into a frame buffer the caller owns: a GUI
// canvas (LVGL's, Adafruit_GFX's GFXcanvas16), a display controller's layer (the STM32 LTDC), any
// memory of rows a stride apart (docs/framebuffer.md).
//
// Memory: none of its own. The caller gives the frame buffer (FrameBuffer: its bytes, the stride
// from row to row in bytes, its size in pixels) and places the renderer's viewport in it with its
// top-left corner at (x, y). Where the buffer's rows are packed for the viewport (stride = viewport
// width x bytes per pixel, which means x = 0 and a viewport as wide as the buffer) the renderer
// draws each strip straight into the frame buffer's rows: no strip buffer and no copy. Otherwise
// each strip is drawn in the caller's strip buffer (at least viewport width x K pixels) and
// copied row by row into place (in_place() says which).
//
// Retaining: the frame buffer keeps what was drawn, so after a complete frame of the same size,
// at the same place in the same buffer, retains_frame() is true: with FrameStorage::strip_inputs
// the renderer leaves out the strips whose inputs did not change (keep()) and their pixels stay.
// Call invalidate() when something else drew over the viewport (the GUI, another renderer);
// set_frame() (another buffer, e.g. double buffering, or another place) does it too.
//
// Checks (kInvalidArgument, nothing written): begin_frame() refuses a buffer whose bytes are
// fewer than its rows need, a stride shorter than a row, a pointer or stride not aligned for
// PF::Storage, a viewport that does not fit the buffer at (x, y), and, when strips are copied, a
// strip buffer shorter than one row; submit() and keep() refuse a strip that is not the frame's
// next full-width rows, and a lease this sink did not lend. Calls outside a frame: kBusy.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "lineraster/core/output/status.hpp"
#include "lineraster/core/output/strip_sink.hpp"

namespace lr {

// A caller's frame buffer: `height` rows of `width` pixels, each row starting `stride` bytes after
// the one above (stride >= width x bytes per pixel; what lies between the end of a row and the
// next is never written). `bytes` must hold (height - 1) x stride + width x bytes per pixel.
struct FrameBuffer {
  std::span<std::byte> bytes;
  size_t stride = 0;               // bytes from the first pixel of a row to that of the next
  uint16_t width = 0, height = 0;  // pixels
};

// What the current frame (or, after end_frame(), the last one) wrote.
struct FrameBufferSinkStats {
  uint32_t strips_drawn = 0;  // submitted (drawn in place or copied)
  uint32_t strips_kept = 0;   // left as they were (keep)
  uint32_t bytes_copied = 0;  // from the strip buffer into the frame buffer (0 in place)
};

template <class PF>
class FrameBufferSink final : public StripSink<PF> {
 public:
  using Pixel = typename PF::Storage;
  static_assert(sizeof(Pixel) == PF::kBytesPerPixel);

  // The viewport goes at (x, y) of `frame_buffer`. `strip_buffer` is used only when the frame
  // buffer's rows are not packed for the viewport; it may be empty otherwise.
  explicit FrameBufferSink(const FrameBuffer& frame_buffer, std::span<Pixel> strip_buffer = {},
                           uint16_t x = 0, uint16_t y = 0)
      : frame_(frame_buffer), strip_(strip_buffer), x_(x), y_(y) {}
  FrameBufferSink(const FrameBufferSink&) = delete;
  FrameBufferSink& operator=(const FrameBufferSink&) = delete;

  Status begin_frame(uint16_t width, uint16_t height) override {
    const bool same = complete_ && !changed_ && width == width_ && height == height_;
    in_frame_ = complete_ = lent_ = false;
    changed_ = true;  // until this frame is complete, the buffer holds no known frame
    stats_ = {};
    width_ = width;
    height_ = height;
    next_row_ = 0;
    if (!fits(width, height)) return Status::kInvalidArgument;
    in_place_ = frame_.stride == size_t{width} * sizeof(Pixel);
    if (!in_place_ && strip_.size() < width) return Status::kInvalidArgument;
    retained_ = same;
    changed_ = false;
    in_frame_ = true;
    return Status::kOk;
  }

  // In place: the frame buffer's rows from the next strip's first row to the viewport's last.
  Status acquire(StripLease<PF>& out) override {
    if (!in_frame_ || lent_) return Status::kBusy;
    if (next_row_ >= height_) return Status::kInvalidArgument;
    lent_ = true;
    if (in_place_) {
      lent_data_ = pixel_row(next_row_);
      out = this->lend(lent_data_, size_t{width_} * (height_ - next_row_), 0);
    } else {
      lent_data_ = strip_.data();
      out = this->lend(lent_data_, strip_.size(), 0);
    }
    return Status::kOk;
  }

  Status submit(const StripRect& rect, StripLease<PF>&& lease) override {
    std::span<Pixel> px;
    this->take_back(lease, px);
    if (!in_frame_ || !lent_) return Status::kBusy;
    lent_ = false;
    if (px.data() != lent_data_ || !next_strip(rect) ||
        px.size() < size_t{rect.width} * rect.height)
      return Status::kInvalidArgument;
    if (!in_place_) {
      const size_t row_bytes = size_t{rect.width} * sizeof(Pixel);
      for (size_t r = 0; r < rect.height; ++r)
        std::memcpy(row_bytes_at(rect.y + r), px.data() + r * rect.width, row_bytes);
      stats_.bytes_copied += static_cast<uint32_t>(row_bytes * rect.height);
    }
    next_row_ = rect.y + rect.height;
    ++stats_.strips_drawn;
    return Status::kOk;
  }

  // kInvalidArgument unless every row of the frame was submitted or kept.
  Status end_frame() override {
    if (!in_frame_) return Status::kBusy;
    in_frame_ = false;
    complete_ = !lent_ && next_row_ == height_;
    lent_ = false;
    return complete_ ? Status::kOk : Status::kInvalidArgument;
  }

  // The buffer holds the previous frame: it was complete, of this size, at this place of this
  // buffer, and nothing called invalidate() or set_frame() since.
  bool retains_frame() const override { return in_frame_ && retained_; }
  Status keep(const StripRect& rect) override {
    if (!in_frame_ || lent_) return Status::kBusy;
    if (!retained_ || !next_strip(rect)) return Status::kInvalidArgument;
    next_row_ = rect.y + rect.height;
    ++stats_.strips_kept;
    return Status::kOk;
  }

  // Another frame buffer, or another place in it, from the next frame on (every strip drawn).
  void set_frame(const FrameBuffer& frame_buffer, std::span<Pixel> strip_buffer = {},
                 uint16_t x = 0, uint16_t y = 0) {
    frame_ = frame_buffer;
    strip_ = strip_buffer;
    x_ = x;
    y_ = y;
    invalidate();
  }
  // Something else drew over the viewport: the next frame draws every strip.
  void invalidate() { changed_ = true; }

  // Whether this frame's strips are drawn in the frame buffer itself (valid after begin_frame).
  bool in_place() const { return in_place_; }
  const FrameBufferSinkStats& stats() const { return stats_; }

 private:
  // The buffer holds its own rows, aligned for Pixel, with the viewport inside it; every product
  // is checked against the span's size first, so nothing overflows.
  bool fits(uint16_t width, uint16_t height) const {
    const size_t row = size_t{frame_.width} * sizeof(Pixel);
    const auto address = reinterpret_cast<uintptr_t>(frame_.bytes.data());
    if (width == 0 || height == 0 || frame_.width == 0 || frame_.height == 0) return false;
    if (address % alignof(Pixel) != 0 || frame_.stride % alignof(Pixel) != 0) return false;
    if (frame_.stride < row || frame_.bytes.size() < row) return false;
    if (frame_.height > 1 && (frame_.bytes.size() - row) / frame_.stride < frame_.height - 1u)
      return false;
    return size_t{x_} + width <= frame_.width && size_t{y_} + height <= frame_.height;
  }
  // The frame's next rows, full width.
  bool next_strip(const StripRect& rect) const {
    return rect.x == 0 && rect.width == width_ && rect.y == next_row_ && rect.height > 0 &&
           rect.height <= height_ - next_row_;
  }
  std::byte* row_bytes_at(size_t row) const {
    return frame_.bytes.data() + (y_ + row) * frame_.stride + size_t{x_} * sizeof(Pixel);
  }
  // Pixels live in the caller's buffer as Pixel objects (a canvas of uint16_t, ...): its bytes
  // are viewed as what they hold.
  Pixel* pixel_row(size_t row) const { return reinterpret_cast<Pixel*>(row_bytes_at(row)); }

  FrameBuffer frame_;
  std::span<Pixel> strip_;
  uint16_t x_ = 0, y_ = 0;
  uint16_t width_ = 0, height_ = 0;  // the viewport of the current (or last) frame
  uint32_t next_row_ = 0;            // the first row not yet submitted or kept
  Pixel* lent_data_ = nullptr;
  bool in_frame_ = false, lent_ = false, in_place_ = false;
  bool complete_ = false;  // the last frame ended with every row drawn or kept
  bool changed_ = true;    // the buffer may hold something else than the last frame
  bool retained_ = false;  // this frame may keep strips
  FrameBufferSinkStats stats_{};
};

}  // namespace lr
