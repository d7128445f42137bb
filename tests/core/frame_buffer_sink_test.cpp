// FrameBufferSink (core/output/frame_buffer_sink.hpp): every pixel of the viewport lands at its
// address in the caller's buffer (rows a stride apart, the viewport at an offset), in place when
// the rows are packed and copied from the strip buffer otherwise; no byte outside the viewport
// is written (guard bytes before, between and after the rows); unchanged strips are left as they
// were; buffers that cannot hold the frame are refused at begin_frame with nothing written.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <vector>

#include "lineraster/core/output/frame_buffer_sink.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"
#include "tests/support/format_scene.hpp"

namespace lr {
namespace {

constexpr int kW = 64, kH = 44, kK = 8;  // 6 strips, the last one 4 rows
constexpr int kStrips = (kH + kK - 1) / kK;
constexpr std::byte kGuard{0xA5};
constexpr size_t kGuardBytes = 64;  // before and after the frame buffer

// The caller's memory: guard bytes, the frame buffer's bytes, guard bytes. `offset` shifts the
// frame buffer off its natural alignment (for the refusal tests).
struct Memory {
  std::vector<std::byte> all;
  size_t size;
  Memory(size_t frame_bytes, size_t offset = 0)
      : all(frame_bytes + 2 * kGuardBytes, kGuard), size(frame_bytes) {
    start = kGuardBytes + offset;
  }
  size_t start;
  std::span<std::byte> frame() { return std::span(all).subspan(start, size); }
  bool untouched() const {
    for (const std::byte b : all)
      if (b != kGuard) return false;
    return true;
  }
};

// The buffer: fb_w x fb_h pixels, rows `stride` bytes apart (the last row without its padding).
template <class PF>
size_t frame_bytes(uint16_t fb_w, uint16_t fb_h, size_t stride) {
  return (fb_h - 1u) * stride + size_t{fb_w} * sizeof(typename PF::Storage);
}

template <class PF>
struct Rig {
  explicit Rig(bool skipping = false)
      : store(test::format_scene_capacities(kW, kH, kK, skipping)),
        renderer(std::make_unique<Renderer<PF, kK>>()) {
    EXPECT_EQ(renderer->configure(store.storage(), kW, kH), Status::kOk);
  }
  BasicFrameStorage<std::vector> store;
  std::unique_ptr<Renderer<PF, kK>> renderer;
};

// What a sink that assembles the frame receives: the reference.
template <class PF>
std::vector<typename PF::Storage> reference(const test::FormatScene& scene, double x = -0.8,
                                            double y = 0.6) {
  Rig<PF> rig;
  host::CaptureDisplay<PF> display(size_t{kW} * kK);
  scene.build(*rig.renderer, x, y);
  EXPECT_EQ(rig.renderer->render(display), Status::kOk);
  return display.raw_frame();
}

// Every byte of `mem`: the viewport's pixels equal the reference's at (x + i, y + j) of a buffer
// whose rows are `stride` bytes apart; every other byte is still the guard.
template <class PF>
void expect_frame_at(const Memory& mem, size_t stride, uint16_t x, uint16_t y,
                     const std::vector<typename PF::Storage>& ref) {
  using Pixel = typename PF::Storage;
  std::vector<bool> in_view(mem.all.size());
  size_t wrong = 0;
  for (size_t j = 0; j < kH; ++j)
    for (size_t i = 0; i < kW; ++i) {
      const size_t at = mem.start + (y + j) * stride + (x + i) * sizeof(Pixel);
      Pixel p;
      std::memcpy(&p, mem.all.data() + at, sizeof(Pixel));
      wrong += !(p == ref[j * kW + i]);
      for (size_t b = 0; b < sizeof(Pixel); ++b) in_view[at + b] = true;
    }
  EXPECT_EQ(wrong, 0u) << "viewport pixels unlike the reference";
  size_t outside = 0;
  for (size_t b = 0; b < mem.all.size(); ++b) outside += !in_view[b] && mem.all[b] != kGuard;
  EXPECT_EQ(outside, 0u) << "bytes written outside the viewport";
}

template <class PF>
class FrameBufferSinkTest : public ::testing::Test {};
using Formats = ::testing::Types<Rgb565, Rgb565Be, Xrgb8888, Rgb888>;
TYPED_TEST_SUITE(FrameBufferSinkTest, Formats);

// A canvas wider than the viewport, with padding at every row's end: strips are copied.
TYPED_TEST(FrameBufferSinkTest, StripsAreCopiedToTheirAddressesWithAStride) {
  using PF = TypeParam;
  using Pixel = typename PF::Storage;
  const test::FormatScene scene(kW, kH);
  constexpr uint16_t kFbW = 90, kFbH = 60, kX = 13, kY = 9;
  // A few bytes of padding per row, kept a multiple of the pixel's alignment.
  const size_t stride = kFbW * sizeof(Pixel) + 4 * alignof(Pixel) + (sizeof(Pixel) == 3 ? 1 : 0);
  Memory mem(frame_bytes<PF>(kFbW, kFbH, stride));
  std::vector<Pixel> strip(size_t{kW} * kK);
  FrameBufferSink<PF> sink(FrameBuffer{mem.frame(), stride, kFbW, kFbH}, strip, kX, kY);
  Rig<PF> rig;
  scene.build(*rig.renderer);
  ASSERT_EQ(rig.renderer->render(sink), Status::kOk);
  EXPECT_FALSE(sink.in_place());
  EXPECT_EQ(sink.stats().strips_drawn, uint32_t(kStrips));
  EXPECT_EQ(sink.stats().bytes_copied, uint32_t(kW * kH * sizeof(Pixel)));
  const auto ref = reference<PF>(scene);
  expect_frame_at<PF>(mem, stride, kX, kY, ref);
  // The viewport's first pixel, by address: the background's bytes.
  Pixel first;
  std::memcpy(&first, mem.all.data() + mem.start + kY * stride + kX * sizeof(Pixel), sizeof(Pixel));
  EXPECT_TRUE(first == PF::encode(scene.background));
}

// Rows packed for the viewport (stride = width x bytes per pixel), the viewport lower down in a
// taller buffer: the renderer draws in the frame buffer itself, no strip buffer given.
TYPED_TEST(FrameBufferSinkTest, PackedRowsAreDrawnInPlace) {
  using PF = TypeParam;
  using Pixel = typename PF::Storage;
  const test::FormatScene scene(kW, kH);
  constexpr uint16_t kFbH = kH + 7, kY = 5;
  const size_t stride = kW * sizeof(Pixel);
  Memory mem(frame_bytes<PF>(kW, kFbH, stride));
  FrameBufferSink<PF> sink(FrameBuffer{mem.frame(), stride, kW, kFbH}, {}, 0, kY);
  Rig<PF> rig;
  scene.build(*rig.renderer);
  ASSERT_EQ(rig.renderer->render(sink), Status::kOk);
  EXPECT_TRUE(sink.in_place());
  EXPECT_EQ(sink.stats().strips_drawn, uint32_t(kStrips));
  EXPECT_EQ(sink.stats().bytes_copied, 0u);
  expect_frame_at<PF>(mem, stride, 0, kY, reference<PF>(scene));
}

// The sink keeps strips whose inputs did not change: their bytes are not written again (a mark
// put in a kept strip survives), and the frame equals a full rendering whichever way it is drawn.
void kept_strips(bool in_place) {
  using PF = Rgb565;
  const test::FormatScene scene(kW, kH);
  const uint16_t fb_w = in_place ? kW : kW + 10;
  const size_t stride = fb_w * 2u;
  Memory mem(frame_bytes<PF>(fb_w, kH, stride));
  std::vector<uint16_t> strip(size_t{kW} * kK);
  FrameBufferSink<PF> sink(FrameBuffer{mem.frame(), stride, fb_w, kH}, strip);
  Rig<PF> rig(true);
  auto frame = [&](double x, double y) {
    scene.build(*rig.renderer, x, y);
    EXPECT_EQ(rig.renderer->render(sink), Status::kOk);
    EXPECT_EQ(sink.in_place(), in_place);
    expect_frame_at<PF>(mem, stride, 0, 0, reference<PF>(scene, x, y));
  };
  frame(-0.8, 0.6);
  EXPECT_EQ(sink.stats().strips_kept, 0u);
  EXPECT_FALSE(sink.retains_frame());  // after the frame: nothing to keep until one begins

  frame(-0.8, 0.6);  // nothing changed: every strip kept
  EXPECT_EQ(sink.stats().strips_kept, uint32_t(kStrips));
  EXPECT_EQ(sink.stats().strips_drawn, 0u);
  EXPECT_EQ(rig.renderer->stats().strips_skipped, uint32_t(kStrips));

  frame(-0.8, -0.6);  // the small cube moved down: its old and new strips drawn, others kept
  EXPECT_GT(sink.stats().strips_kept, 0u);
  EXPECT_GT(sink.stats().strips_drawn, 0u);
  EXPECT_EQ(sink.stats().strips_kept + sink.stats().strips_drawn, uint32_t(kStrips));

  // A mark in the first row (a strip the next frame keeps) stays: kept strips are not written.
  std::byte* mark = mem.all.data() + mem.start;
  *mark = std::byte{0x3C};
  scene.build(*rig.renderer, -0.8, -0.6);
  ASSERT_EQ(rig.renderer->render(sink), Status::kOk);
  EXPECT_EQ(sink.stats().strips_kept, uint32_t(kStrips));
  EXPECT_EQ(*mark, std::byte{0x3C});
  // After invalidate() every strip is drawn again: the mark is gone.
  sink.invalidate();
  frame(-0.8, -0.6);
  EXPECT_EQ(sink.stats().strips_kept, 0u);
  EXPECT_NE(*mark, std::byte{0x3C});

  // Another buffer (double buffering): it holds nothing yet, every strip is drawn into it.
  Memory other(mem.size);
  sink.set_frame(FrameBuffer{other.frame(), stride, fb_w, kH}, strip);
  scene.build(*rig.renderer, -0.8, -0.6);
  ASSERT_EQ(rig.renderer->render(sink), Status::kOk);
  EXPECT_EQ(sink.stats().strips_kept, 0u);
  expect_frame_at<PF>(other, stride, 0, 0, reference<PF>(scene, -0.8, -0.6));
}

TEST(FrameBufferSink, UnchangedStripsAreKeptInPlace) {
  kept_strips(true);
}
TEST(FrameBufferSink, UnchangedStripsAreKeptWhenCopied) {
  kept_strips(false);
}

// begin_frame refuses what cannot hold the viewport; render() returns its status, nothing is
// written, and the same sink renders once given a buffer that fits.
TEST(FrameBufferSink, BuffersThatDoNotFitAreRefused) {
  using PF = Rgb565;
  const test::FormatScene scene(kW, kH);
  std::vector<uint16_t> strip(size_t{kW} * kK);
  Rig<PF> rig;
  struct Case {
    const char* what;
    uint16_t fb_w, fb_h;
    size_t stride, bytes, offset;
    uint16_t x, y;
    size_t strip_pixels;
  };
  constexpr uint16_t kFbW = kW + 6;
  const size_t row = kFbW * 2u, stride = row + 8, fits = frame_bytes<PF>(kFbW, kH, stride);
  const Case cases[] = {
      {"one byte too few", kFbW, kH, stride, fits - 1, 0, 0, 0, strip.size()},
      {"no bytes", kFbW, kH, stride, 0, 0, 0, 0, strip.size()},
      {"stride shorter than a row", kFbW, kH, row - 2, fits, 0, 0, 0, strip.size()},
      {"odd stride for 16-bit pixels", kFbW, kH, stride + 1, fits + kH, 0, 0, 0, strip.size()},
      {"pointer not aligned for 16-bit pixels", kFbW, kH, stride, fits, 1, 0, 0, strip.size()},
      {"viewport past the right edge", kFbW, kH, stride, fits, 0, 7, 0, strip.size()},
      {"viewport past the bottom edge", kFbW, kH, stride, fits, 0, 0, 1, strip.size()},
      {"buffer narrower than the viewport", kW - 1, kH, stride, fits, 0, 0, 0, strip.size()},
      {"buffer lower than the viewport", kFbW, kH - 1, stride, fits, 0, 0, 0, strip.size()},
      {"no strip buffer for a padded row", kFbW, kH, stride, fits, 0, 0, 0, 0},
      {"strip buffer shorter than a row", kFbW, kH, stride, fits, 0, 0, 0, kW - 1},
      {"strip buffer shorter than a strip", kFbW, kH, stride, fits, 0, 0, 0, size_t{kW} * kK - 1},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    Memory mem(c.bytes, c.offset);
    FrameBufferSink<PF> sink(FrameBuffer{mem.frame(), c.stride, c.fb_w, c.fb_h},
                             std::span(strip).first(c.strip_pixels), c.x, c.y);
    scene.build(*rig.renderer);
    EXPECT_EQ(rig.renderer->render(sink), Status::kInvalidArgument);
    EXPECT_TRUE(mem.untouched());
    EXPECT_FALSE(sink.retains_frame());
  }
  Memory mem(fits);
  FrameBufferSink<PF> sink(FrameBuffer{mem.frame(), stride, kFbW, kH}, strip);
  scene.build(*rig.renderer);
  EXPECT_EQ(rig.renderer->render(sink), Status::kOk);
  expect_frame_at<PF>(mem, stride, 0, 0, reference<PF>(scene));
}

// The sink's own checks, called out of order as no renderer calls it.
TEST(FrameBufferSink, CallsOutOfOrderAreRefused) {
  using PF = Rgb565;
  constexpr uint16_t kFbW = 8, kFbH = 4;
  Memory mem(size_t{kFbW} * kFbH * 2);
  std::vector<uint16_t> strip(size_t{kFbW} * 2);
  FrameBufferSink<PF> sink(FrameBuffer{mem.frame(), kFbW * 2u, kFbW, kFbH}, strip);
  StripLease<PF> lease;
  EXPECT_EQ(sink.acquire(lease), Status::kBusy);  // no frame
  EXPECT_EQ(sink.end_frame(), Status::kBusy);
  EXPECT_EQ(sink.keep({0, 0, kFbW, 2}), Status::kBusy);

  ASSERT_EQ(sink.begin_frame(kFbW, kFbH), Status::kOk);
  EXPECT_TRUE(sink.in_place());
  EXPECT_FALSE(sink.retains_frame());
  EXPECT_EQ(sink.keep({0, 0, kFbW, 2}), Status::kInvalidArgument);  // no previous frame
  ASSERT_EQ(sink.acquire(lease), Status::kOk);
  EXPECT_EQ(lease.pixels().size(), size_t{kFbW} * kFbH);  // every row left, in place
  StripLease<PF> second;
  EXPECT_EQ(sink.acquire(second), Status::kBusy);  // one lease at a time
  EXPECT_EQ(sink.submit({0, 2, kFbW, 2}, std::move(lease)), Status::kInvalidArgument);  // not next
  ASSERT_EQ(sink.acquire(lease), Status::kOk);
  EXPECT_EQ(sink.submit({1, 0, kFbW - 1, 2}, std::move(lease)), Status::kInvalidArgument);
  ASSERT_EQ(sink.acquire(lease), Status::kOk);
  ASSERT_EQ(sink.submit({0, 0, kFbW, 2}, std::move(lease)), Status::kOk);
  ASSERT_EQ(sink.acquire(lease), Status::kOk);
  EXPECT_EQ(lease.pixels().size(), size_t{kFbW} * 2);  // the two rows left
  EXPECT_EQ(sink.submit({0, 2, kFbW, 3}, std::move(lease)), Status::kInvalidArgument);  // too tall
  EXPECT_EQ(sink.end_frame(), Status::kInvalidArgument);  // rows 2 and 3 missing
  EXPECT_EQ(sink.end_frame(), Status::kBusy);

  // The incomplete frame is not kept: the next one draws every strip.
  ASSERT_EQ(sink.begin_frame(kFbW, kFbH), Status::kOk);
  EXPECT_FALSE(sink.retains_frame());
  for (uint16_t y = 0; y < kFbH; y += 2) {
    ASSERT_EQ(sink.acquire(lease), Status::kOk);
    ASSERT_EQ(sink.submit({0, y, kFbW, 2}, std::move(lease)), Status::kOk);
  }
  ASSERT_EQ(sink.end_frame(), Status::kOk);
  ASSERT_EQ(sink.begin_frame(kFbW, kFbH), Status::kOk);
  EXPECT_TRUE(sink.retains_frame());
  EXPECT_EQ(sink.keep({0, 0, kFbW, 4}), Status::kOk);
  EXPECT_EQ(sink.end_frame(), Status::kOk);
  ASSERT_EQ(sink.begin_frame(kFbW, kFbH - 1), Status::kOk);  // another size: nothing to keep
  EXPECT_FALSE(sink.retains_frame());
}

}  // namespace
}  // namespace lr
