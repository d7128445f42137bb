// examples/host/framebuffer_canvas.cpp run as a user runs it: its exit status, what it prints
// and every pixel of the canvas it writes (a 200x150 RGB565 canvas, the 3D viewport a 160x120
// window at (20, 15) of it, the rest the GUI's grey).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "lineraster/host_sim/formats/image_io.hpp"
#include "tests/support/tmp_dir.hpp"

namespace {

using Rgb = std::array<uint8_t, 3>;

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

constexpr int kCanvasW = 200, kCanvasH = 150, kX = 20, kY = 15, kW = 160, kH = 120;
// The colours as RGB565 holds them (decoded by bit replication): the GUI's (200, 200, 200), the
// clear colour (16, 24, 48), the teal cube's three faces lit from (1, 3, 2).
constexpr Rgb kGui{198, 199, 198}, kClear{16, 24, 49};
constexpr Rgb kTop{90, 174, 198}, kLeft{74, 117, 132}, kRight{74, 113, 123};

TEST(ExamplesFramebufferCanvas, DrawsTheCubeInItsWindowOfTheCanvasThenKeepsEveryStrip) {
  const lr::test::TmpDir tmp("lr_framebuffer_canvas_test");
  const std::string ppm = tmp.file("canvas.ppm"), out = tmp.file("stdout");
  const int rc = std::system((std::string(LR_FRAMEBUFFER_CANVAS) + " " + ppm + " >" + out).c_str());
  ASSERT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0) << rc;
  // 15 strips of 160 x 8 pixels copied (the canvas is wider than the viewport), then, nothing
  // having changed, all 15 kept.
  EXPECT_EQ(slurp(out),
            "frame 0: 15 strips drawn, 0 kept, 38400 bytes copied\n"
            "frame 1: 0 strips drawn, 15 kept, 0 bytes copied\n");

  lr::host::ImageRgb8 img;
  std::string err;
  ASSERT_TRUE(lr::host::read_ppm(ppm, img, err)) << err;
  ASSERT_EQ(img.width, kCanvasW);
  ASSERT_EQ(img.height, kCanvasH);
  auto at = [&](int x, int y) {
    const auto i = 3 * (static_cast<size_t>(y) * kCanvasW + static_cast<size_t>(x));
    return Rgb{img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]};
  };
  std::map<Rgb, int> outside, inside;
  for (int y = 0; y < kCanvasH; ++y)
    for (int x = 0; x < kCanvasW; ++x) {
      const bool in_view = x >= kX && x < kX + kW && y >= kY && y < kY + kH;
      ++(in_view ? inside : outside)[at(x, y)];
    }
  // The GUI's pixels are untouched, all of them; the viewport holds the clear colour and the faces.
  EXPECT_EQ(outside, (std::map<Rgb, int>{{kGui, kCanvasW * kCanvasH - kW * kH}}));
  EXPECT_EQ(inside,
            (std::map<Rgb, int>{{kClear, 15095}, {kTop, 799}, {kLeft, 1391}, {kRight, 1915}}));
  for (const auto& [x, y] : {std::array{kX, kY}, std::array{kX + kW - 1, kY},
                             std::array{kX, kY + kH - 1}, std::array{kX + kW - 1, kY + kH - 1}})
    EXPECT_EQ(at(x, y), kClear) << x << ", " << y;
  EXPECT_EQ(at(kX - 1, kY), kGui);
  EXPECT_EQ(at(kX + kW, kY + kH - 1), kGui);
  EXPECT_EQ(at(102, 43), kTop);
  EXPECT_EQ(at(80, 90), kLeft);
  EXPECT_EQ(at(130, 80), kRight);
}

}  // namespace
