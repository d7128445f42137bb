// The frame-storage helpers: every store sized from FrameCapacities, the stores apart from one
// another, accepted by the renderer they are sized for and refused (or reported full) where
// they are too small; the static form all zero bytes, as firmware needs it to stay in .bss.
#include "lineraster/core/raster/frame_storage.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"

namespace lr {
namespace {

constexpr FrameCapacities kCaps{.width = 64,
                                .height = 40,
                                .strip_height = 8,
                                .vertices = 48,
                                .triangles = 40,
                                .draws = 3,
                                .active = 16,
                                .surfaces = 48,
                                .lighting_table_words = 2 * lighting_table_words(8, true),
                                .pixel_lights = 2,
                                .tex_vertices = 48,
                                .active_extra = 16,
                                .triangle_colors = 40,
                                .strip_skipping = true};

// The spans of a FrameStorage as byte ranges.
struct Range {
  const char* begin;
  size_t bytes;
};
template <class T>
Range range(std::span<T> s) {
  return {reinterpret_cast<const char*>(s.data()), s.size_bytes()};
}
std::vector<Range> ranges(const FrameStorage& s) {
  return {range(s.vertices),     range(s.triangles),      range(s.draws),
          range(s.buckets),      range(s.active),         range(s.active_index),
          range(s.depth),        range(s.surfaces),       range(s.lighting_tables),
          range(s.pixel_lights), range(s.strip_inputs),   range(s.tex_vertices),
          range(s.active_extra), range(s.triangle_colors)};
}

void expect_sized(const FrameStorage& s, const FrameCapacities& c) {
  EXPECT_EQ(s.vertices.size(), c.vertices);
  EXPECT_EQ(s.triangles.size(), c.triangles);
  EXPECT_EQ(s.draws.size(), c.draws);
  EXPECT_EQ(s.buckets.size(), c.strips());
  EXPECT_EQ(s.active.size(), c.active);
  EXPECT_EQ(s.active_index.size(), 2 * c.active);
  EXPECT_EQ(s.depth.size(), static_cast<size_t>(c.width) * static_cast<size_t>(c.strip_height));
  EXPECT_EQ(s.surfaces.size(), c.surfaces);
  EXPECT_EQ(s.lighting_tables.size(), c.lighting_table_words);
  EXPECT_EQ(s.pixel_lights.size(), c.pixel_lights);
  EXPECT_EQ(s.strip_inputs.size(), c.strip_skipping ? 2 * c.strips() : 0u);
  EXPECT_EQ(s.tex_vertices.size(), c.tex_vertices);
  EXPECT_EQ(s.active_extra.size(), c.active_extra);
  EXPECT_EQ(s.triangle_colors.size(), c.triangle_colors);
}

void expect_disjoint(const FrameStorage& s) {
  const std::vector<Range> r = ranges(s);
  for (size_t i = 0; i < r.size(); ++i)
    for (size_t j = i + 1; j < r.size(); ++j) {
      if (r[i].bytes == 0 || r[j].bytes == 0) continue;
      const bool apart =
          r[i].begin + r[i].bytes <= r[j].begin || r[j].begin + r[j].bytes <= r[i].begin;
      EXPECT_TRUE(apart) << "stores " << i << " and " << j << " overlap";
    }
}

// A few triangles over the whole viewport, rendered: the renderer takes the stores and uses them.
Status draw_and_render(Renderer<Rgb888, 8>& r, int width, int height, size_t triangles,
                       host::CaptureDisplay<Rgb888>& display) {
  if (const Status st = r.begin_frame(Camera{}, LightSet{}, Rgb8{0, 0, 0}); st != Status::kOk)
    return st;
  const int32_t w = width * kSubpixel, h = height * kSubpixel;
  std::vector<ScreenVertex> v(3 * triangles);
  std::vector<std::array<uint16_t, 3>> t(triangles);
  for (size_t i = 0; i < triangles; ++i) {
    const auto k = static_cast<int32_t>(i);
    v[3 * i].x = 0;
    v[3 * i].y = 0;
    v[3 * i + 1].x = w;
    v[3 * i + 1].y = h - k;
    v[3 * i + 2].x = 0;
    v[3 * i + 2].y = h;
    for (size_t j = 0; j < 3; ++j) v[3 * i + j].color = {20000, 10000, 5000};
    t[i] = {static_cast<uint16_t>(3 * i), static_cast<uint16_t>(3 * i + 1),
            static_cast<uint16_t>(3 * i + 2)};
  }
  DrawState state;
  state.shading = Shading::kFlat;
  state.lighting = false;
  const Status st = r.draw_screen(v, t, state);
  if (st != Status::kOk) return st;
  return r.render(display);
}

TEST(FrameStorage, StaticStoresAreSizedFromTheCapacities) {
  static StaticFrameStorage<kCaps> store;
  const FrameStorage s = store.storage();
  expect_sized(s, kCaps);
  expect_disjoint(s);
  static_assert(StaticFrameStorage<kCaps>::kCapacities == kCaps);
}

TEST(FrameStorage, DynamicStoresAreSizedFromTheCapacities) {
  BasicFrameStorage<std::vector> store(kCaps);
  const FrameStorage s = store.storage();
  expect_sized(s, kCaps);
  expect_disjoint(s);
  EXPECT_EQ(store.capacities, kCaps);
}

TEST(FrameStorage, StaticStoresAreConstantInitialisedToZeroBytes) {
  // Zero bytes in every record's default: what puts a firmware's stores into .bss (a record
  // default such as `bool depth = true` would move the whole object into .data, and flash).
  constinit static StaticFrameStorage<kCaps> store;
  const auto* bytes = reinterpret_cast<const unsigned char*>(&store);
  size_t nonzero = 0;
  for (size_t i = 0; i < sizeof(store); ++i) nonzero += bytes[i] != 0 ? 1 : 0;
  EXPECT_EQ(nonzero, 0u);
}

TEST(FrameStorage, StaticRenderersAreConstantInitialisedToZeroBytes) {
  // Likewise the renderer object (its front end's working memory is 2 KB): all zero bytes, it
  // goes to .bss and costs no flash.
  constinit static Renderer<Rgb565Be, 8, kUntexturedSpans> renderer;
  const auto* bytes = reinterpret_cast<const unsigned char*>(&renderer);
  size_t nonzero = 0;
  for (size_t i = 0; i < sizeof(renderer); ++i) nonzero += bytes[i] != 0 ? 1 : 0;
  EXPECT_EQ(nonzero, 0u);
}

TEST(FrameStorage, TheRendererItIsSizedForAcceptsIt) {
  BasicFrameStorage<std::vector> store(kCaps);
  Renderer<Rgb888, 8> r;
  ASSERT_EQ(r.configure(store.storage(), kCaps.width, kCaps.height), Status::kOk);
  host::CaptureDisplay<Rgb888> display(static_cast<size_t>(kCaps.width) * 8);
  EXPECT_EQ(draw_and_render(r, kCaps.width, kCaps.height, 10, display), Status::kOk);
  EXPECT_EQ(r.stats().triangles_binned, 10u);
  EXPECT_GT(r.stats().pixels_written, 0u);
  EXPECT_EQ(r.stats().strips, kCaps.strips());
}

TEST(FrameStorage, TooSmallCapacitiesAreReported) {
  // Sized for a smaller viewport, or another strip height: configure() refuses it.
  BasicFrameStorage<std::vector> store(kCaps);
  Renderer<Rgb888, 8> r;
  EXPECT_EQ(r.configure(store.storage(), kCaps.width + 1, kCaps.height), Status::kStoreTooSmall);
  EXPECT_EQ(r.configure(store.storage(), kCaps.width, kCaps.height + 8), Status::kStoreTooSmall);
  FrameCapacities short_strips = kCaps;
  short_strips.strip_height = 4;  // a depth strip of 4 rows for a renderer of 8
  BasicFrameStorage<std::vector> four(short_strips);
  EXPECT_EQ(r.configure(four.storage(), kCaps.width, kCaps.height), Status::kStoreTooSmall);
  FrameCapacities no_draws = kCaps;
  no_draws.draws = 0;
  BasicFrameStorage<std::vector> none(no_draws);
  EXPECT_EQ(r.configure(none.storage(), kCaps.width, kCaps.height), Status::kStoreTooSmall);

  // Too few vertices for a draw: accepted, and the draw is dropped and counted.
  FrameCapacities few = kCaps;
  few.vertices = 20;
  BasicFrameStorage<std::vector> small(few);
  ASSERT_EQ(r.configure(small.storage(), kCaps.width, kCaps.height), Status::kOk);
  host::CaptureDisplay<Rgb888> display(static_cast<size_t>(kCaps.width) * 8);
  EXPECT_EQ(draw_and_render(r, kCaps.width, kCaps.height, 10, display), Status::kCapacity);
  EXPECT_EQ(r.stats().dropped_vertex_capacity, 10u);
  EXPECT_EQ(r.stats().triangles_binned, 0u);
}

}  // namespace
}  // namespace lr
