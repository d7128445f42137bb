// The pieces of lineraster-sim's frame files: --out-pattern's names (printf's, without printf),
// the median cut palette (exact up to 256 colours, bounded beyond), the GIF writer (an
// unfinished GIF leaves nothing behind).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "lineraster/host_sim/programs/frame_pattern.hpp"
#include "lineraster/host_sim/programs/gif_writer.hpp"
#include "lineraster/host_sim/programs/palette_quantize.hpp"
#include "tests/support/tmp_dir.hpp"

namespace lr::host {
namespace {

TEST(FramePattern, NamesAreWhatPrintfWrites) {
  struct Case {
    const char* pattern;
    int frame;
    const char* name;
  };
  const Case cases[] = {
      {"frame_%03d.png", 7, "frame_007.png"},
      {"frame_%03d.png", 1234, "frame_1234.png"},
      {"f%d.png", 0, "f0.png"},
      {"f%i.ppm", 12, "f12.ppm"},
      {"f%u.png", 3, "f3.png"},
      {"f%4d.png", 25, "f  25.png"},
      {"%%_%d_%%.png", 5, "%_5_%.png"},
      {"dir/%02d/x.png", 3, "dir/03/x.png"},
      {"f%0d.png", 9, "f9.png"},
      {"f%016d.png", 1, "f0000000000000001.png"},
  };
  for (const Case& c : cases) {
    FramePattern p;
    std::string why;
    ASSERT_TRUE(parse_frame_pattern(c.pattern, p, why)) << c.pattern << ": " << why;
    EXPECT_TRUE(p.given);
    EXPECT_EQ(p.name(c.frame), c.name) << c.pattern;
    // printf agrees (the pattern is safe to hand it here: one int conversion).
    char buf[64];
    std::snprintf(buf, sizeof buf, c.pattern, c.frame);
    EXPECT_EQ(p.name(c.frame), buf) << c.pattern;
  }
}

TEST(FramePattern, AnythingElsePrintfLikeIsRefused) {
  for (const char* bad : {"f.png", "f%d%d.png", "f%s.png", "f%x.png", "f%ld.png", "f%lld.png",
                          "f%-3d.png", "f%+d.png", "f% d.png", "f%.3d.png", "f%*d.png", "f%n.png",
                          "f%", "f%3", "f%017d.png", "%d%%%d", "%p"}) {
    FramePattern p;
    std::string why;
    EXPECT_FALSE(parse_frame_pattern(bad, p, why)) << bad;
    EXPECT_FALSE(p.given) << bad;
    EXPECT_FALSE(why.empty());
  }
}

ImageRgb8 image_of(int w, int h, uint32_t (*colour)(int x, int y)) {
  ImageRgb8 img;
  img.width = w;
  img.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint32_t c = colour(x, y);
      img.rgb.insert(img.rgb.end(), {static_cast<uint8_t>(c >> 16), static_cast<uint8_t>(c >> 8),
                                     static_cast<uint8_t>(c)});
    }
  return img;
}

ImageRgb8 expand(const PalettedImage& q) {
  ImageRgb8 img;
  img.width = q.width;
  img.height = q.height;
  for (uint8_t i : q.indices) {
    EXPECT_LT(i, q.palette.size());
    img.rgb.insert(img.rgb.end(), q.palette[i].begin(), q.palette[i].end());
  }
  return img;
}

// 256 colours (16 x 16 blocks of distinct colours): kept exactly, 256 entries.
TEST(MedianCut, UpTo256ColoursAreKeptExactly) {
  const ImageRgb8 img = image_of(64, 64, [](int x, int y) {
    return static_cast<uint32_t>(((x / 4) * 16 + 3) << 16 | ((y / 4) * 16 + 1) << 8 | 77);
  });
  const PalettedImage q = quantize_median_cut(img);
  EXPECT_EQ(q.palette.size(), 256u);
  EXPECT_TRUE(expand(q).rgb == img.rgb);
  const ImageRgb8 two = image_of(5, 3, [](int x, int) { return x < 2 ? 0xff0000u : 0x00ff80u; });
  const PalettedImage q2 = quantize_median_cut(two);
  EXPECT_EQ(q2.palette.size(), 2u);
  EXPECT_TRUE(expand(q2).rgb == two.rgb);
}

// A smooth ramp of 4,096 colours (what a lit surface is made of) in 256 entries: every pixel
// within 8 levels per channel, 4.0 on average (measured: 6 and 3.5; 16 colours a box is the
// floor for 4,096 on a sheet). A fixed 6x7x6 cube on the same ramp: 25 and 12.1.
TEST(MedianCut, ASmoothRampIsCloseEverywhere) {
  const ImageRgb8 img = image_of(64, 64, [](int x, int y) {
    return static_cast<uint32_t>((x * 4) << 16 | (y * 4) << 8 | ((x + y) * 2));
  });
  const PalettedImage q = quantize_median_cut(img);
  ASSERT_EQ(q.palette.size(), kMaxPaletteColors);
  const ImageRgb8 back = expand(q);
  int worst = 0;
  long long sum = 0;
  for (size_t i = 0; i < img.rgb.size(); ++i) {
    const int e = std::abs(int{img.rgb[i]} - int{back.rgb[i]});
    worst = std::max(worst, e);
    sum += e;
  }
  EXPECT_LE(worst, 8);
  EXPECT_LE(static_cast<double>(sum) / static_cast<double>(img.rgb.size()), 4.0);
  // Deterministic: the same image, the same result.
  const PalettedImage again = quantize_median_cut(img);
  EXPECT_EQ(again.indices, q.indices);
  EXPECT_EQ(again.palette, q.palette);
}

#ifdef LR_HAVE_GIF

// A GIF that is not finished (an error, or the program giving up) leaves no file, and a frame
// of the wrong size is refused with one line.
TEST(GifWriter, AnUnfinishedGifLeavesNothing) {
  const test::TmpDir dir("lr_gif_writer");
  const ImageRgb8 frame =
      image_of(8, 4, [](int x, int) { return static_cast<uint32_t>(x) * 0x102030u; });
  std::string error;
  {
    GifWriter gif;
    ASSERT_TRUE(gif.open(dir.file("a.gif"), 8, 4, 10, error)) << error;
    ASSERT_TRUE(gif.add(frame, error)) << error;
    const ImageRgb8 wrong = image_of(4, 4, [](int, int) { return 0u; });
    EXPECT_FALSE(gif.add(wrong, error));
    EXPECT_EQ(error, dir.file("a.gif") + ": a frame of 4x4 in a GIF of 8x4");
    EXPECT_EQ(dir.entries().size(), 1u);  // the temporary file only
  }
  EXPECT_TRUE(dir.entries().empty());
  GifWriter gif;
  ASSERT_TRUE(gif.open(dir.file("b.gif"), 8, 4, 10, error)) << error;
  ASSERT_TRUE(gif.add(frame, error)) << error;
  ASSERT_TRUE(gif.finish(error)) << error;
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"b.gif"});
  // Into a missing directory: the output's usual line.
  GifWriter missing;
  EXPECT_FALSE(missing.open(dir.file("no/c.gif"), 8, 4, 10, error));
  EXPECT_EQ(error, dir.file("no/c.gif") + ": cannot open for writing: No such file or directory");
}

#endif

}  // namespace
}  // namespace lr::host
