// The panel sink: the bytes a frame puts on the bus, the lease protocol (a buffer on the wire or
// queued is never lent; two buffers alternate), aborts on failed and timed-out transfers with a
// working next frame, and skipping unchanged strips / sending only the changed columns.
// Frames go out the way the renderer sends them (full-width strips of K rows, top to bottom);
// the recording bus completes transfers at wait() into a model of the controller's RAM, and
// what the viewer would see is compared with the frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "lineraster/core/math/hash.hpp"
#include "lineraster/hal/dma_buffer.hpp"
#include "lineraster/hal/panel_sink.hpp"
#include "tests/hal/recording_bus.hpp"

namespace lr {
namespace {

using test::BusEvent;
using test::caset;
using test::cmd;
using test::pixels;
using test::raset;
using test::RecordingBus;
using test::wait_for;
using Pixel = Rgb565Be::Storage;

constexpr uint32_t kTimeout = 50;

// A frame of RGB565 values (as the wire carries them).
struct Frame {
  uint16_t width = 0, height = 0;
  std::vector<uint16_t> values;
  Frame(uint16_t w, uint16_t h, uint16_t background)
      : width(w), height(h), values(size_t(w) * h, background) {}
  void rect(int x, int y, int w, int h, uint16_t v) {
    for (int j = y; j < y + h; ++j)
      for (int i = x; i < x + w; ++i) values[size_t(j) * width + size_t(i)] = v;
  }
  void set(int x, int y, uint16_t v) { values[size_t(y) * width + size_t(x)] = v; }
  void noise(int seed) {
    uint32_t s = uint32_t(seed) * 2654435761u + 1;
    for (uint16_t& v : values) {
      s = s * 1664525u + 1013904223u;
      v = uint16_t(s >> 16);
    }
  }
};

struct SendLog {
  std::vector<const void*> leases;  // each lease's buffer, in order
  int lent_while_on_wire = 0;       // leases of the buffer the bus was sending
};

// What Renderer::render does with a sink: begin, then per strip acquire, fill, submit; end.
Status send_frame(StripSink<Rgb565Be>& sink, const RecordingBus& bus, const Frame& f, int k,
                  SendLog* log = nullptr) {
  Status st = sink.begin_frame(f.width, f.height);
  if (st != Status::kOk) return st;
  for (int y0 = 0; y0 < f.height; y0 += k) {
    const int rows = std::min(k, f.height - y0);
    StripLease<Rgb565Be> lease;
    st = sink.acquire(lease);
    if (st != Status::kOk) return st;
    std::span<Pixel> px = lease.pixels();
    if (log) {
      log->leases.push_back(px.data());
      if (px.data() == bus.in_flight()) ++log->lent_while_on_wire;
    }
    if (px.size() < size_t(f.width) * size_t(rows)) return Status::kInvalidArgument;
    for (size_t i = 0; i < size_t(f.width) * size_t(rows); ++i)
      px[i] = Rgb565Be::from_value(f.values[size_t(y0) * f.width + i]);
    st = sink.submit({0, uint16_t(y0), f.width, uint16_t(rows)}, std::move(lease));
    if (st != Status::kOk) return st;
  }
  return sink.end_frame();
}

// A 240x240 ST7789, two strip buffers of 240 x 8, 30 signatures.
struct Rig {
  explicit Rig(PanelConfig config = st7789_240x240(), size_t signatures = 30, int k = 8,
               bool single_buffer = false)
      : panel(bus, config),
        buffer0(size_t(config.image_width()) * size_t(k)),
        buffer1(single_buffer ? 0 : size_t(config.image_width()) * size_t(k)),
        signature_store(signatures),
        sink(panel, buffer0, buffer1, signature_store, kTimeout) {}

  // The viewer's image equals the frame.
  void expect_shows(const Frame& f) {
    const std::vector<uint16_t> v = test::view(bus.ram, panel.config());
    ASSERT_EQ(v.size(), f.values.size());
    size_t wrong = 0;
    for (size_t i = 0; i < v.size(); ++i) wrong += v[i] != f.values[i];
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(bus.ram.errors(), 0);
    EXPECT_TRUE(bus.violations.empty()) << bus.violations.front();
  }

  RecordingBus bus;
  Panel panel;
  std::vector<Pixel> buffer0, buffer1;
  std::vector<StripSignature> signature_store;
  PanelSink sink;
};

std::vector<BusEvent> strip_events(uint16_t x0, uint16_t x1, uint16_t y0, uint16_t y1) {
  return {caset(x0, x1), raset(y0, y1), cmd(0x2C),
          pixels(size_t(x1 - x0 + 1) * size_t(y1 - y0 + 1) * 2)};
}

TEST(PanelSinkFrame, WholeFrameBytesTransactionsAndOrder) {
  Rig rig(st7789_240x240(), 0);  // no signatures: everything is sent
  Frame f(240, 240, 0);
  f.noise(1);
  SendLog log;
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8, &log), Status::kOk);
  const PanelSinkStats& s = rig.sink.stats();
  EXPECT_EQ(s.pixel_bytes, 240u * 240u * 2u);
  EXPECT_EQ(s.command_bytes, 30u * 11u);  // CASET 1 + 4, RASET 1 + 4, RAMWR 1 per strip
  EXPECT_EQ(s.bytes(), 115200u + 330u);
  EXPECT_EQ(s.transactions, 30u * 4u);
  EXPECT_EQ(s.strips_sent, 30u);
  EXPECT_EQ(s.strips_skipped, 0u);
  EXPECT_EQ(s.waits, 30u);  // one per transfer
  EXPECT_EQ(s.status, Status::kOk);
  // Strip 0 starts at once; strip 1 queues behind it; acquiring for strip 2 waits for strip 0,
  // which starts strip 1; ...; end_frame waits for the last two.
  std::vector<BusEvent> want = strip_events(0, 239, 0, 7);
  for (uint16_t s8 = 1; s8 < 30; ++s8) {
    want.push_back(wait_for(kTimeout));
    const std::vector<BusEvent> e = strip_events(0, 239, uint16_t(8 * s8), uint16_t(8 * s8 + 7));
    want.insert(want.end(), e.begin(), e.end());
  }
  want.push_back(wait_for(kTimeout));
  EXPECT_EQ(rig.bus.events, want);
  rig.expect_shows(f);
  // Double buffering: the two buffers alternate, and no lease was of the buffer on the wire.
  ASSERT_EQ(log.leases.size(), 30u);
  for (size_t i = 0; i < log.leases.size(); ++i)
    EXPECT_EQ(log.leases[i], i % 2 ? rig.buffer1.data() : rig.buffer0.data()) << i;
  EXPECT_EQ(log.lent_while_on_wire, 0);
}

TEST(PanelSinkLease, ABufferOnTheWireOrQueuedIsNeverLent) {
  Rig rig;
  ASSERT_EQ(rig.sink.begin_frame(240, 240), Status::kOk);
  StripLease<Rgb565Be> a, b, c;
  ASSERT_EQ(rig.sink.acquire(a), Status::kOk);
  const Pixel* pa = a.pixels().data();
  EXPECT_EQ(pa, rig.buffer0.data());
  ASSERT_EQ(rig.sink.submit({0, 0, 240, 8}, std::move(a)), Status::kOk);
  EXPECT_FALSE(a.valid());
  EXPECT_EQ(rig.bus.in_flight(), static_cast<const void*>(pa));  // strip 0 on the wire

  rig.bus.clear_events();
  ASSERT_EQ(rig.sink.acquire(b), Status::kOk);  // the other buffer is free: no wait
  EXPECT_TRUE(rig.bus.events.empty());
  const Pixel* pb = b.pixels().data();
  EXPECT_EQ(pb, rig.buffer1.data());
  ASSERT_EQ(rig.sink.submit({0, 8, 240, 8}, std::move(b)), Status::kOk);
  EXPECT_TRUE(rig.bus.events.empty());  // queued behind strip 0: nothing may go out yet

  // Both buffers busy (one on the wire, one queued): acquire waits for the older, starts the
  // queued one and lends the buffer that came back.
  ASSERT_EQ(rig.sink.acquire(c), Status::kOk);
  std::vector<BusEvent> want = {wait_for(kTimeout)};
  const std::vector<BusEvent> e = strip_events(0, 239, 8, 15);
  want.insert(want.end(), e.begin(), e.end());
  EXPECT_EQ(rig.bus.events, want);
  EXPECT_EQ(c.pixels().data(), pa);
  EXPECT_EQ(rig.bus.in_flight(), static_cast<const void*>(pb));
  EXPECT_NE(static_cast<const void*>(c.pixels().data()), rig.bus.in_flight());
  EXPECT_TRUE(rig.bus.violations.empty());
}

TEST(PanelSinkLease, AllLentOutIsBusyNotAWait) {
  Rig rig;
  ASSERT_EQ(rig.sink.begin_frame(240, 240), Status::kOk);
  StripLease<Rgb565Be> a, b, c;
  ASSERT_EQ(rig.sink.acquire(a), Status::kOk);
  ASSERT_EQ(rig.sink.acquire(b), Status::kOk);
  EXPECT_NE(a.pixels().data(), b.pixels().data());
  EXPECT_EQ(rig.sink.acquire(c), Status::kBusy);
  EXPECT_FALSE(c.valid());
  EXPECT_TRUE(rig.bus.events.empty());
}

TEST(PanelSinkLease, LeasesNotLentNowAreRefused) {
  Rig rig, other;
  ASSERT_EQ(rig.sink.begin_frame(240, 240), Status::kOk);
  ASSERT_EQ(other.sink.begin_frame(240, 240), Status::kOk);
  StripLease<Rgb565Be> foreign, old, fresh;
  ASSERT_EQ(other.sink.acquire(foreign), Status::kOk);
  EXPECT_EQ(rig.sink.submit({0, 0, 240, 8}, std::move(foreign)), Status::kInvalidArgument);
  ASSERT_EQ(rig.sink.acquire(old), Status::kOk);           // buffer 0
  ASSERT_EQ(rig.sink.begin_frame(240, 240), Status::kOk);  // voids it
  EXPECT_EQ(rig.sink.submit({0, 0, 240, 8}, std::move(old)), Status::kInvalidArgument);
  EXPECT_TRUE(rig.bus.events.empty());
  // Outside the frame, or more than the buffer holds.
  ASSERT_EQ(rig.sink.acquire(fresh), Status::kOk);
  EXPECT_EQ(rig.sink.submit({0, 236, 240, 8}, std::move(fresh)), Status::kInvalidArgument);
  ASSERT_EQ(rig.sink.acquire(fresh), Status::kOk);
  EXPECT_EQ(rig.sink.submit({0, 0, 240, 9}, std::move(fresh)), Status::kInvalidArgument);
  EXPECT_TRUE(rig.bus.events.empty());
}

TEST(PanelSinkLease, CallsOutsideAFrameAndOversizedFrames) {
  Rig rig;
  StripLease<Rgb565Be> l;
  EXPECT_EQ(rig.sink.acquire(l), Status::kBusy);
  EXPECT_EQ(rig.sink.end_frame(), Status::kBusy);
  EXPECT_EQ(rig.sink.begin_frame(241, 240), Status::kInvalidArgument);
  EXPECT_EQ(rig.sink.begin_frame(240, 0), Status::kInvalidArgument);
  EXPECT_EQ(rig.sink.acquire(l), Status::kBusy);
  // A smaller frame goes to the image's top-left corner.
  Frame f(200, 100, 0x1234);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kOk);
  EXPECT_EQ(rig.bus.commands()[0], caset(0, 199));
  EXPECT_EQ(rig.sink.stats().pixel_bytes, 200u * 100u * 2u);
}

TEST(PanelSinkLease, SingleBufferWaitsForEveryTransfer) {
  Rig rig(st7789_240x240(), 30, 8, /*single_buffer=*/true);
  Frame f(240, 240, 0);
  f.noise(2);
  SendLog log;
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8, &log), Status::kOk);
  for (const void* p : log.leases) EXPECT_EQ(p, rig.buffer0.data());
  EXPECT_EQ(log.lent_while_on_wire, 0);
  EXPECT_EQ(rig.sink.stats().waits, 30u);
  rig.expect_shows(f);
}

TEST(PanelSinkAbort, TimeoutAbortsTheFrameAndTheNextFrameWorks) {
  Rig rig;
  Frame f1(240, 240, 0);
  f1.noise(3);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f1, 8), Status::kOk);
  rig.expect_shows(f1);

  // Frame 2: the 4th transfer of the frame times out. Strips 0..2 went out, 3 was on the wire,
  // 4 queued: acquiring for strip 5 waits for 3 and gets the timeout.
  Frame f2(240, 240, 0);
  f2.noise(4);
  rig.bus.wait_results[30 + 3] = Status::kTimeout;
  rig.bus.clear_events();
  EXPECT_EQ(send_frame(rig.sink, rig.bus, f2, 8), Status::kTimeout);
  EXPECT_EQ(rig.sink.stats().status, Status::kTimeout);
  EXPECT_EQ(rig.bus.events.back(), wait_for(kTimeout, Status::kTimeout));  // nothing after it
  EXPECT_EQ(rig.bus.in_flight(), nullptr);
  // The frame stays aborted until the next begin_frame.
  StripLease<Rgb565Be> l;
  EXPECT_EQ(rig.sink.acquire(l), Status::kTimeout);
  EXPECT_EQ(rig.sink.end_frame(), Status::kTimeout);

  // Frame 3 equals frame 2: the panel's RAM is unknown after the abort, so all of it is sent.
  rig.bus.clear_events();
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f2, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_sent, 30u);
  EXPECT_EQ(rig.sink.stats().strips_skipped, 0u);
  EXPECT_EQ(rig.sink.stats().status, Status::kOk);
  rig.expect_shows(f2);
}

TEST(PanelSinkAbort, FailedTransferAtTheEndOfTheFrame) {
  Rig rig(st7789_240x240(), 0);
  Frame f(240, 240, 0);
  f.noise(5);
  rig.bus.wait_results[29] = Status::kDisplayError;  // the last strip
  EXPECT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kDisplayError);
  EXPECT_EQ(rig.sink.stats().status, Status::kDisplayError);
  EXPECT_EQ(rig.bus.events.back(), wait_for(kTimeout, Status::kDisplayError));
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kOk);
  rig.expect_shows(f);
}

TEST(PanelSinkAbort, RefusedCommandOrTransferStartAborts) {
  Rig rig;
  Frame f(240, 240, 0);
  f.noise(6);
  rig.bus.command_results[4] = Status::kDisplayError;  // RASET of strip 1
  EXPECT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kDisplayError);
  EXPECT_EQ(rig.sink.stats().status, Status::kDisplayError);
  EXPECT_EQ(rig.bus.in_flight(), nullptr);

  rig.bus.start_results[5] = Status::kDisplayError;  // strip 4 of the next frame (5th start)
  EXPECT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kDisplayError);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_sent, 30u);
  rig.expect_shows(f);
}

TEST(PanelSinkAbort, TheTimeoutIsTheCallersAndAFrameGivenUpIsFinished) {
  Rig rig;
  rig.sink.set_timeout(7);
  Frame f(240, 240, 0x0F0F);
  ASSERT_EQ(rig.sink.begin_frame(240, 240), Status::kOk);
  for (uint16_t y = 0; y < 24; y = uint16_t(y + 8)) {  // three strips, then given up
    StripLease<Rgb565Be> l;
    ASSERT_EQ(rig.sink.acquire(l), Status::kOk);
    std::fill(l.pixels().begin(), l.pixels().end(), Rgb565Be::from_value(0x0F0F));
    ASSERT_EQ(rig.sink.submit({0, y, 240, 8}, std::move(l)), Status::kOk);
  }
  ASSERT_NE(rig.bus.in_flight(), nullptr);
  rig.bus.clear_events();
  ASSERT_EQ(rig.sink.begin_frame(240, 240), Status::kOk);  // finishes strips 1 and 2
  std::vector<BusEvent> want = {wait_for(7)};
  const std::vector<BusEvent> e = strip_events(0, 239, 16, 23);
  want.insert(want.end(), e.begin(), e.end());
  want.push_back(wait_for(7));
  EXPECT_EQ(rig.bus.events, want);
  EXPECT_EQ(rig.bus.in_flight(), nullptr);
  ASSERT_EQ(rig.sink.end_frame(), Status::kOk);
  // The strips that arrived are known: a full frame of that colour sends only the rest.
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_skipped, 3u);
  EXPECT_EQ(rig.sink.stats().strips_sent, 27u);
  rig.expect_shows(f);
}

TEST(PanelSinkSkip, AStaticFrameSentTwiceSendsNothingTheSecondTime) {
  Rig rig;
  Frame f(240, 240, 0);
  f.noise(7);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_sent, 30u);
  rig.bus.clear_events();
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kOk);
  const PanelSinkStats& s = rig.sink.stats();
  EXPECT_EQ(s.bytes(), 0u);
  EXPECT_EQ(s.transactions, 0u);
  EXPECT_EQ(s.strips_sent, 0u);
  EXPECT_EQ(s.strips_skipped, 30u);
  EXPECT_EQ(s.waits, 0u);
  EXPECT_TRUE(rig.bus.events.empty());
  rig.expect_shows(f);
}

TEST(PanelSinkSkip, ASmallMovingObjectSendsOnlyItsStripsAndColumns) {
  Rig rig;
  Frame a(240, 240, 0x001F);
  a.rect(50, 20, 10, 10, 0xF800);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, a, 8), Status::kOk);
  Frame b(240, 240, 0x001F);
  b.rect(53, 20, 10, 10, 0xF800);  // moved 3 pixels right: columns 50..62 of rows 20..29 change
  rig.bus.clear_events();
  ASSERT_EQ(send_frame(rig.sink, rig.bus, b, 8), Status::kOk);
  // Rows 20..29: strips 2 (16..23) and 3 (24..31). Columns 50..62: bands 1 (30..59) and
  // 2 (60..89) of 30 columns each, so columns 30..89 of both strips: 60 x 8 x 2 bytes each.
  const PanelSinkStats& s = rig.sink.stats();
  EXPECT_EQ(s.pixel_bytes, 2u * 60u * 8u * 2u);
  EXPECT_EQ(s.transactions, 2u * 4u);
  EXPECT_EQ(s.strips_sent, 2u);
  EXPECT_EQ(s.strips_narrowed, 2u);
  EXPECT_EQ(s.strips_skipped, 28u);
  std::vector<BusEvent> want = strip_events(30, 89, 16, 23);
  want.push_back(wait_for(kTimeout));
  const std::vector<BusEvent> e = strip_events(30, 89, 24, 31);
  want.insert(want.end(), e.begin(), e.end());
  want.push_back(wait_for(kTimeout));
  EXPECT_EQ(rig.bus.events, want);
  rig.expect_shows(b);
}

TEST(PanelSinkSkip, ChangesAtBothEdgesSendTheWholeStrip) {
  Rig rig;
  Frame a(240, 240, 0);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, a, 8), Status::kOk);
  a.set(0, 100, 1);
  a.set(239, 101, 1);  // strip 12, first and last band
  a.set(120, 239, 7);  // strip 29, band 4 only: columns 120..149
  rig.bus.clear_events();
  ASSERT_EQ(send_frame(rig.sink, rig.bus, a, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_sent, 2u);
  EXPECT_EQ(rig.sink.stats().strips_narrowed, 1u);
  EXPECT_EQ(rig.sink.stats().pixel_bytes, 240u * 8u * 2u + 30u * 8u * 2u);
  EXPECT_EQ(rig.bus.commands()[0], caset(0, 239));
  EXPECT_EQ(rig.bus.commands()[3], caset(120, 149));
  rig.expect_shows(a);
}

TEST(PanelSinkSkip, NarrowedStripsOnARotatedOffsetModule) {
  // 135x240 at 90 degrees: image 240 x 135, the last strip 7 rows, window offsets 40 / 53.
  Rig rig(st7789_135x240(Rotation::k90), 17);
  ASSERT_EQ(rig.panel.init(false), Status::kOk);
  Frame f(240, 135, 0);
  f.noise(8);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kOk);
  rig.expect_shows(f);
  for (int step = 0; step < 6; ++step) {
    f.rect(17 + 31 * step, 3 + 21 * step, 25, 14, uint16_t(0x1111 * step));
    rig.bus.clear_events();
    ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kOk);
    EXPECT_GT(rig.sink.stats().strips_narrowed, 0u);
    EXPECT_LT(rig.sink.stats().pixel_bytes, 240u * 135u * 2u / 4u);
    rig.expect_shows(f);
  }
}

TEST(PanelSinkSkip, SizeChangeRotationInvalidateAndFullStoreSendEverything) {
  Rig rig(st7789_240x240(), 10);  // signatures for the first 10 strips only
  Frame f(240, 240, 0);
  f.noise(9);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_unchecked, 20u);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_skipped, 10u);
  EXPECT_EQ(rig.sink.stats().strips_sent, 20u);
  EXPECT_EQ(rig.sink.stats().strips_unchecked, 20u);

  // Another size: everything, then nothing.
  Frame g(240, 80, 0);
  g.noise(10);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, g, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_sent, 10u);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, g, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_skipped, 10u);

  rig.sink.invalidate();
  ASSERT_EQ(send_frame(rig.sink, rig.bus, g, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_sent, 10u);

  // Rotation 0 -> 180 keeps the size but moves everything.
  ASSERT_EQ(rig.panel.set_rotation(Rotation::k180), Status::kOk);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, g, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_sent, 10u);
  ASSERT_EQ(rig.panel.init(false), Status::kOk);  // a re-init may have lost the RAM
  ASSERT_EQ(send_frame(rig.sink, rig.bus, g, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_sent, 10u);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, g, 8), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_sent, 0u);
}

// keep(): the renderer leaves a strip out; the sink sends nothing and the panel keeps showing it.
TEST(PanelSinkKeep, KeptStripsSendNothingAndOnlyARetainedFrameMayBeKept) {
  Rig rig;
  Frame f(240, 240, 0);
  f.noise(11);
  // Nothing shown yet: nothing can be kept.
  ASSERT_EQ(rig.sink.begin_frame(240, 240), Status::kOk);
  EXPECT_FALSE(rig.sink.retains_frame());
  EXPECT_EQ(rig.sink.keep({0, 0, 240, 8}), Status::kInvalidArgument);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, f, 8), Status::kOk);
  EXPECT_FALSE(rig.sink.retains_frame());  // between frames

  // Keep the even strips, send the odd ones changed.
  Frame g = f;
  for (int y0 = 8; y0 < 240; y0 += 16) g.rect(100, y0, 10, 8, 0x1234);
  rig.bus.clear_events();
  ASSERT_EQ(rig.sink.begin_frame(240, 240), Status::kOk);
  ASSERT_TRUE(rig.sink.retains_frame());
  for (int y0 = 0; y0 < 240; y0 += 8) {
    const StripRect rect{0, uint16_t(y0), 240, 8};
    if ((y0 / 8) % 2 == 0) {
      ASSERT_EQ(rig.sink.keep(rect), Status::kOk);
      continue;
    }
    StripLease<Rgb565Be> lease;
    ASSERT_EQ(rig.sink.acquire(lease), Status::kOk);
    for (size_t i = 0; i < size_t{240} * 8; ++i)
      lease.pixels()[i] = Rgb565Be::from_value(g.values[size_t(y0) * 240 + i]);
    ASSERT_EQ(rig.sink.submit(rect, std::move(lease)), Status::kOk);
  }
  ASSERT_EQ(rig.sink.end_frame(), Status::kOk);
  EXPECT_EQ(rig.sink.stats().strips_kept, 15u);
  EXPECT_EQ(rig.sink.stats().strips_narrowed, 15u);
  EXPECT_EQ(rig.sink.stats().pixel_bytes, 15u * 30 * 8 * 2);  // band 3 of 8: 30 columns
  rig.expect_shows(g);

  // A rectangle that is not the one the strip's signature describes, or outside the frame.
  ASSERT_EQ(rig.sink.begin_frame(240, 240), Status::kOk);
  EXPECT_EQ(rig.sink.keep({0, 4, 240, 8}), Status::kInvalidArgument);
  EXPECT_EQ(rig.sink.keep({0, 236, 240, 8}), Status::kInvalidArgument);
  ASSERT_EQ(send_frame(rig.sink, rig.bus, g, 8), Status::kOk);

  // After init() (the module's RAM is unknown) or invalidate(), nothing is retained.
  ASSERT_EQ(rig.panel.init(), Status::kOk);
  ASSERT_EQ(rig.sink.begin_frame(240, 240), Status::kOk);
  EXPECT_FALSE(rig.sink.retains_frame());
  ASSERT_EQ(send_frame(rig.sink, rig.bus, g, 8), Status::kOk);
  ASSERT_EQ(rig.sink.begin_frame(240, 240), Status::kOk);
  EXPECT_TRUE(rig.sink.retains_frame());
  rig.sink.invalidate();
  EXPECT_FALSE(rig.sink.retains_frame());
  EXPECT_EQ(rig.sink.keep({0, 0, 240, 8}), Status::kInvalidArgument);
}

// The DMA contract: right before each transfer the bus is asked to clean exactly the bytes it is
// about to send, whole strips and narrowed ones alike.
TEST(PanelSinkDma, EveryTransferIsCleanedFirstWithExactlyItsBytes) {
  RecordingBus bus;
  bus.require_clean = true;
  Panel panel(bus, st7789_240x240());
  DmaStripBuffer<240 * 8> strip0, strip1;
  std::vector<StripSignature> signatures(30);
  PanelSink sink(panel, strip0.pixels(), strip1.pixels(), signatures, kTimeout);
  Frame a(240, 240, 0x001F);
  a.rect(50, 20, 10, 10, 0xF800);
  ASSERT_EQ(send_frame(sink, bus, a, 8), Status::kOk);
  Frame b(240, 240, 0x001F);
  b.rect(53, 20, 10, 10, 0xF800);  // strips 2 and 3 narrowed to columns 30..89
  ASSERT_EQ(send_frame(sink, bus, b, 8), Status::kOk);
  ASSERT_EQ(bus.started.size(), 32u);
  ASSERT_EQ(bus.cleaned.size(), bus.started.size());
  const auto* base0 = reinterpret_cast<const uint8_t*>(strip0.storage.data());
  const auto* base1 = reinterpret_cast<const uint8_t*>(strip1.storage.data());
  for (size_t i = 0; i < bus.started.size(); ++i) {
    EXPECT_EQ(bus.cleaned[i].data(), bus.started[i].data()) << i;
    EXPECT_EQ(bus.cleaned[i].size(), bus.started[i].size()) << i;
    EXPECT_EQ(bus.started[i].data(), i % 2 ? base1 : base0) << i;
    EXPECT_EQ(bus.started[i].size(), i < 30 ? 240u * 8u * 2u : 60u * 8u * 2u) << i;
  }
  EXPECT_TRUE(bus.violations.empty()) << bus.violations.front();
  EXPECT_EQ(sink.stats().strips_narrowed, 2u);
}

TEST(DmaStripBuffer, AlignedToTheLineAndPaddedToWholeLines) {
  static_assert(kDmaAlignment == 32);  // the default: the Cortex-M7 data-cache line
  static_assert(dma_padded(0) == 0 && dma_padded(1) == 32 && dma_padded(32) == 32 &&
                dma_padded(33) == 64);
  static_assert(alignof(DmaStripBuffer<7>) == 32 && sizeof(DmaStripBuffer<7>) == 32);
  static_assert(sizeof(DmaStripBuffer<17>) == 64 && DmaStripBuffer<17>::kBytes == 64);
  static_assert(sizeof(DmaStripBuffer<240 * 8>) == 240 * 8 * 2);
  DmaStripBuffer<17> one;
  std::array<DmaStripBuffer<17>, 2> two{};
  EXPECT_EQ(reinterpret_cast<uintptr_t>(one.storage.data()) % kDmaAlignment, 0u);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(two[1].storage.data()) % kDmaAlignment, 0u);
  EXPECT_EQ(one.pixels().size(), 17u);
  EXPECT_EQ(one.pixels().data(), one.storage.data());
}

TEST(StripSignature, BandsAndChangedColumns) {
  static_assert(band_begin(240, 1) == 30 && band_begin(240, 8) == 240);
  static_assert(band_begin(135, 1) == 16 && band_begin(135, 7) == 118);
  std::vector<Pixel> px(240 * 8, Rgb565Be::from_value(0x4208));
  const StripRect r{0, 16, 240, 8};
  const StripSignature s0 = sign_strip(r, px);
  EXPECT_TRUE(s0.known());
  EXPECT_EQ(changed_columns(s0, s0), ColumnRange{});
  EXPECT_EQ(changed_columns(StripSignature{}, s0), (ColumnRange{0, 240}));
  StripRect other = r;
  other.y = 24;
  EXPECT_EQ(changed_columns(sign_strip(other, px), s0), (ColumnRange{0, 240}));
  // Any single pixel changed is seen, in its band.
  for (size_t i : {size_t{0}, size_t{29}, size_t{30}, size_t{1000}, size_t{1919}}) {
    std::vector<Pixel> q = px;
    q[i] = Rgb565Be::from_value(0x4209);
    const StripSignature s1 = sign_strip(r, q);
    EXPECT_NE(s1.hash, s0.hash);
    const uint16_t band = uint16_t((i % 240) / 30);
    EXPECT_EQ(changed_columns(s0, s1),
              (ColumnRange{uint16_t(band * 30), uint16_t(band * 30 + 30)}));
  }
  // Swapping two pixels of a band is a change too (the hash depends on the order).
  std::vector<Pixel> q = px;
  q[31] = Rgb565Be::from_value(1);
  q[32] = Rgb565Be::from_value(2);
  std::vector<Pixel> t = px;
  t[31] = Rgb565Be::from_value(2);
  t[32] = Rgb565Be::from_value(1);
  EXPECT_EQ(changed_columns(sign_strip(r, q), sign_strip(r, t)), (ColumnRange{30, 60}));
}

TEST(StripSignature, HashesAreTheWireBytesOnEveryCpu) {
  // FNV-1a over the 16-bit wire values: fixed numbers, the same on big- and little-endian hosts.
  std::vector<Pixel> px(16);
  for (size_t i = 0; i < px.size(); ++i) px[i] = Rgb565Be::from_value(unsigned(i * 4099u));
  const StripSignature s = sign_strip({0, 0, 8, 2}, px);
  uint32_t band0 = kFnv1a32Offset;
  for (unsigned v : {0u * 4099u, 8u * 4099u}) band0 = fnv1a32(band0, v & 0xFFFFu);
  EXPECT_EQ(s.bands[0], band0);
  uint32_t h = kFnv1a32Offset;
  for (uint32_t b : s.bands) h = fnv1a32(h, b);
  EXPECT_EQ(s.hash, h);
  EXPECT_EQ(s.hash, 0xE1688A3Du);  // pinned: the same on every platform
}

}  // namespace
}  // namespace lr
