// The per-strip depth buffer: 16 bits, test LESS, cleared to 65535 (far) for every strip.
#include <gtest/gtest.h>

#include "tests/support/core_harness.hpp"

namespace lr {
namespace {

using test::CoreHarness;
constexpr int32_t S = kSubpixel;

// A screen-space quad at constant depth (window depth d in [0, 1]).
void quad(std::vector<ScreenVertex>& v, std::vector<std::array<uint16_t, 3>>& t, int x0, int y0,
          int x1, int y1, double d, Rgb8 c) {
  auto base = static_cast<uint16_t>(v.size());
  int xs[4] = {x0, x0, x1, x1}, ys[4] = {y0, y1, y1, y0};
  for (int k = 0; k < 4; ++k) {
    ScreenVertex sv;
    sv.x = xs[k] * S;
    sv.y = ys[k] * S;
    sv.z = static_cast<uint32_t>(d * kDepthMax);
    sv.color = from_rgb8(c);
    v.push_back(sv);
  }
  t.push_back({base, static_cast<uint16_t>(base + 1), static_cast<uint16_t>(base + 2)});
  t.push_back({base, static_cast<uint16_t>(base + 2), static_cast<uint16_t>(base + 3)});
}

DrawState flat_depth() {
  DrawState s;
  s.shading = Shading::kFlat;
  s.lighting = false;
  s.depth_test = true;
  return s;
}

Rgb8 at(const host::ImageRgb8& img, int x, int y) {
  size_t p = 3 * (size_t(y) * size_t(img.width) + size_t(x));
  return {img.rgb[p], img.rgb[p + 1], img.rgb[p + 2]};
}

TEST(Depth, NearerWinsWhateverTheOrder) {
  for (int order = 0; order < 2; ++order) {
    std::vector<ScreenVertex> v;
    std::vector<std::array<uint16_t, 3>> t;
    if (order == 0) {
      quad(v, t, 0, 0, 20, 20, 0.25, {255, 0, 0});
      quad(v, t, 10, 10, 30, 30, 0.75, {0, 255, 0});
    } else {
      quad(v, t, 10, 10, 30, 30, 0.75, {0, 255, 0});
      quad(v, t, 0, 0, 20, 20, 0.25, {255, 0, 0});
    }
    CoreHarness<4> core(32, 32);
    core.begin();
    core.renderer().draw_screen(v, t, flat_depth());
    host::ImageRgb8 img = core.render();
    EXPECT_EQ(at(img, 15, 15), (Rgb8{255, 0, 0}));  // overlap: the nearer (red)
    EXPECT_EQ(at(img, 25, 25), (Rgb8{0, 255, 0}));
    EXPECT_EQ(core.depth()[15 * 32 + 15], std::lround(0.25 * 65535));
    EXPECT_EQ(core.depth()[25 * 32 + 25], std::lround(0.75 * 65535));
    EXPECT_EQ(core.depth()[31 * 32 + 0], 65535);  // cleared
  }
}

TEST(Depth, EqualDepthKeepsTheFirstDrawnAsLessDoes) {
  std::vector<ScreenVertex> v;
  std::vector<std::array<uint16_t, 3>> t;
  quad(v, t, 0, 0, 20, 20, 0.5, {255, 0, 0});
  quad(v, t, 0, 0, 20, 20, 0.5, {0, 0, 255});
  CoreHarness<8> core(32, 32);
  core.begin();
  core.renderer().draw_screen(v, t, flat_depth());
  EXPECT_EQ(at(core.render(), 5, 5), (Rgb8{255, 0, 0}));
}

TEST(Depth, SixteenBitPrecision) {
  // Depths one 16-bit step apart resolve; closer than half a step they tie (first wins).
  std::vector<ScreenVertex> v;
  std::vector<std::array<uint16_t, 3>> t;
  const double step = 1.0 / 65535, level = 32767 * step;  // exactly on a 16-bit level
  quad(v, t, 0, 0, 8, 8, level + step, {255, 0, 0});
  quad(v, t, 0, 0, 8, 8, level, {0, 255, 0});  // one step nearer: wins
  quad(v, t, 16, 0, 24, 8, level, {255, 0, 0});
  quad(v, t, 16, 0, 24, 8, level - 0.3 * step, {0, 255, 0});  // under half a step: same value
  CoreHarness<8> core(32, 16);
  core.begin();
  core.renderer().draw_screen(v, t, flat_depth());
  host::ImageRgb8 img = core.render();
  EXPECT_EQ(at(img, 4, 4), (Rgb8{0, 255, 0}));
  EXPECT_EQ(at(img, 20, 4), (Rgb8{255, 0, 0}));
}

TEST(Depth, NoDepthDrawsInSubmissionOrder) {
  std::vector<ScreenVertex> v;
  std::vector<std::array<uint16_t, 3>> t;
  quad(v, t, 0, 0, 20, 20, 0.25, {255, 0, 0});
  quad(v, t, 10, 10, 30, 30, 0.75, {0, 255, 0});  // farther but later: painted over
  DrawState s = flat_depth();
  s.depth_test = false;
  CoreHarness<8> core(32, 32);
  core.begin();
  core.renderer().draw_screen(v, t, s);
  EXPECT_EQ(at(core.render(), 15, 15), (Rgb8{0, 255, 0}));
}

}  // namespace
}  // namespace lr
