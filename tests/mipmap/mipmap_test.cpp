// Mip chains built by core/mipmap: exact texels of small hand-made cases in every format (even
// sizes, odd sizes whose last row/column folds into the last box, 1 x N), GL chain sizes, a
// brute-force cross-check on random NPOT textures, and the errors (capacity, invalid level 0).
#include "lineraster/core/texture/mipmap.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace lr {
namespace {

constexpr uint16_t pack565(unsigned r5, unsigned g6, unsigned b5) {
  return static_cast<uint16_t>((r5 << 11) | (g6 << 5) | b5);
}

Texture texture565(uint16_t w, uint16_t h, const std::vector<uint16_t>& texels) {
  Texture t;
  t.format = TexelFormat::kRgb565;
  t.levels[0].rgb565 = texels;
  t.levels[0].width = w;
  t.levels[0].height = h;
  t.level_count = 1;
  return t;
}

Texture texture_bytes(TexelFormat f, uint16_t w, uint16_t h, const std::vector<uint8_t>& bytes,
                      const std::vector<uint16_t>& palette = {}) {
  Texture t;
  t.format = f;
  t.levels[0].bytes = bytes;
  t.levels[0].width = w;
  t.levels[0].height = h;
  t.level_count = 1;
  t.palette = palette;
  return t;
}

std::vector<uint8_t> level_bytes(const Texture& t, int level) {
  const auto& b = t.levels[static_cast<size_t>(level)].bytes;
  return {b.begin(), b.end()};
}
std::vector<uint16_t> level_565(const Texture& t, int level) {
  const auto& b = t.levels[static_cast<size_t>(level)].rgb565;
  return {b.begin(), b.end()};
}

TEST(MipChain, Rgb565TwoByTwoAveragesEachFieldRoundingToNearest) {
  // r5: 0,1,1,1 -> 3/4 -> 1; g6: 63,62,0,0 -> 125/4 = 31.25 -> 31; b5: 0,0,1,1 -> 2/4 -> 1 (half
  // up).
  const std::vector<uint16_t> l0 = {pack565(0, 63, 0), pack565(1, 62, 0), pack565(1, 0, 1),
                                    pack565(1, 0, 1)};
  Texture t = texture565(2, 2, l0);
  std::vector<uint16_t> storage(mip_chain_size(t));
  ASSERT_EQ(storage.size(), 1u);
  ASSERT_EQ(build_mip_chain(t, storage, {}), Status::kOk);
  EXPECT_EQ(t.level_count, 2);
  EXPECT_EQ(t.levels[1].width, 1);
  EXPECT_EQ(t.levels[1].height, 1);
  EXPECT_EQ(level_565(t, 1), std::vector<uint16_t>{pack565(1, 31, 1)});
  EXPECT_EQ(t.levels[1].rgb565.data(), storage.data());
  EXPECT_EQ(validate(t), Status::kOk);
  // Extremes: all-white stays white, 0 and 1 in three of four stays 1 (3/4 rounds up).
  const std::vector<uint16_t> white(4, 0xFFFF);
  Texture tw = texture565(2, 2, white);
  ASSERT_EQ(build_mip_chain(tw, storage, {}), Status::kOk);
  EXPECT_EQ(storage[0], 0xFFFF);
}

TEST(MipChain, Rgb888FourByTwoGivesTwoByOneThenOneByOne) {
  // Storage rows bottom first: row 0 then row 1, 3 bytes per texel.
  const std::vector<uint8_t> l0 = {
      0, 0, 0, 10, 20, 30, 100, 100, 100, 255, 255, 255,  // row 0
      1, 2, 3, 4,  5,  6,  0,   0,   1,   255, 254, 253,  // row 1
  };
  Texture t = texture_bytes(TexelFormat::kRgb888, 4, 2, l0);
  ASSERT_EQ(mip_chain_size(t), 2u * 3u + 1u * 3u);
  std::vector<uint8_t> storage(mip_chain_size(t));
  ASSERT_EQ(build_mip_chain(t, {}, storage), Status::kOk);
  ASSERT_EQ(t.level_count, 3);
  EXPECT_EQ(t.levels[1].width, 2);
  EXPECT_EQ(t.levels[1].height, 1);
  // Box (0,0),(1,0),(0,1),(1,1): r (0+10+1+4+2)/4 = 17/4 -> 4; g (0+20+2+5+2)/4 = 29/4 -> 7;
  // b (0+30+3+6+2)/4 = 41/4 -> 10. Box 2..3: r (100+255+0+255+2)/4 = 612/4 = 153;
  // g (100+255+0+254+2)/4 = 611/4 -> 152; b (100+255+1+253+2)/4 = 611/4 -> 152.
  EXPECT_EQ(level_bytes(t, 1), (std::vector<uint8_t>{4, 7, 10, 153, 152, 152}));
  // 2x1 -> 1x1: (4+153+1)/2 = 79 (78.5 rounds up), (7+152+1)/2 = 80 (79.5 up), (10+152+1)/2 = 81.
  EXPECT_EQ(level_bytes(t, 2), (std::vector<uint8_t>{79, 80, 81}));
  EXPECT_EQ(t.levels[2].bytes.data(), storage.data() + 6);
  EXPECT_EQ(validate(t), Status::kOk);
}

TEST(MipChain, L8ThreeByThreeFoldsTheOddRowAndColumnIntoOneBox) {
  // 3x3 -> 1x1: the box covers all nine texels (not only the 2x2 corner).
  const std::vector<uint8_t> l0 = {10, 20, 30, 40, 50, 60, 70, 80, 100};
  Texture t = texture_bytes(TexelFormat::kL8, 3, 3, l0);
  std::vector<uint8_t> storage(mip_chain_size(t));
  ASSERT_EQ(storage.size(), 1u);
  ASSERT_EQ(build_mip_chain(t, {}, storage), Status::kOk);
  ASSERT_EQ(t.level_count, 2);
  EXPECT_EQ(level_bytes(t, 1), std::vector<uint8_t>{51});  // 460 / 9 = 51.1
  // The last column alone is bright: it must show in the mean (a 2x2 box would give 0).
  const std::vector<uint8_t> edge = {0, 0, 255, 0, 0, 255, 0, 0, 255};
  Texture te = texture_bytes(TexelFormat::kL8, 3, 3, edge);
  ASSERT_EQ(build_mip_chain(te, {}, storage), Status::kOk);
  EXPECT_EQ(storage[0], 85);  // 765 / 9
}

TEST(MipChain, L8FiveByThreeBoxesAreTwoByThreeAndThreeByThree) {
  // Rows bottom first; value = 10 * column + row.
  std::vector<uint8_t> l0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 5; ++c) l0.push_back(static_cast<uint8_t>(10 * c + r));
  Texture t = texture_bytes(TexelFormat::kL8, 5, 3, l0);
  ASSERT_EQ(mip_chain_size(t), 3u);  // 2x1 + 1x1
  std::vector<uint8_t> storage(3);
  ASSERT_EQ(build_mip_chain(t, {}, storage), Status::kOk);
  ASSERT_EQ(t.level_count, 3);
  EXPECT_EQ(t.levels[1].width, 2);
  EXPECT_EQ(t.levels[1].height, 1);
  EXPECT_EQ(t.levels[2].width, 1);
  EXPECT_EQ(t.levels[2].height, 1);
  // Texel 0: columns 0-1, rows 0-2: (0+1+2)*2 + 10*3 = 36, /6 = 6. Texel 1: columns 2-4,
  // rows 0-2: 3*(20+30+40) + 3*(0+1+2) = 279, /9 = 31. Then (6 + 31 + 1) / 2 = 19.
  EXPECT_EQ(level_bytes(t, 1), (std::vector<uint8_t>{6, 31}));
  EXPECT_EQ(level_bytes(t, 2), std::vector<uint8_t>{19});
}

TEST(MipChain, OneByNHalvesOnlyTheLongAxis) {
  // 1x4 RGB888 -> 1x2 -> 1x1.
  const std::vector<uint8_t> l0 = {0, 0, 0, 1, 2, 3, 200, 100, 50, 255, 255, 255};
  Texture t = texture_bytes(TexelFormat::kRgb888, 1, 4, l0);
  std::vector<uint8_t> storage(mip_chain_size(t));
  ASSERT_EQ(storage.size(), 9u);
  ASSERT_EQ(build_mip_chain(t, {}, storage), Status::kOk);
  ASSERT_EQ(t.level_count, 3);
  EXPECT_EQ(t.levels[1].width, 1);
  EXPECT_EQ(t.levels[1].height, 2);
  // (0+1+1)/2 = 1, (0+2+1)/2 = 1, (0+3+1)/2 = 2; (200+255+1)/2 = 228, (100+255+1)/2 = 178,
  // (50+255+1)/2 = 153; then (1+228+1)/2 = 115, (1+178+1)/2 = 90, (2+153+1)/2 = 78.
  EXPECT_EQ(level_bytes(t, 1), (std::vector<uint8_t>{1, 1, 2, 228, 178, 153}));
  EXPECT_EQ(level_bytes(t, 2), (std::vector<uint8_t>{115, 90, 78}));
  // 5x1 L8 -> 2x1 -> 1x1: boxes {0,1} and {2,3,4}.
  const std::vector<uint8_t> row = {10, 20, 30, 40, 51};
  Texture r = texture_bytes(TexelFormat::kL8, 5, 1, row);
  std::vector<uint8_t> rs(mip_chain_size(r));
  ASSERT_EQ(rs.size(), 3u);
  ASSERT_EQ(build_mip_chain(r, {}, rs), Status::kOk);
  EXPECT_EQ(rs, (std::vector<uint8_t>{15, 40, 28}));  // 121/3 = 40.3; (15+40+1)/2 = 28
}

TEST(MipChain, Palette8AveragesColoursThenPicksTheNearestEntry) {
  const std::vector<uint16_t> palette = {
      pack565(0, 0, 0),     // 0: black
      pack565(31, 63, 31),  // 1: white
      pack565(16, 32, 16),  // 2: grey (132, 130, 132)
      pack565(31, 0, 0),    // 3: red
      pack565(0, 0, 0),     // 4: black again (ties go to the lowest index)
  };
  // Black/white checker -> mean (128,128,128) -> grey. Four 4s -> black: entry 0, not 4.
  // Red, red, black, red -> mean (191, 0, 0) -> red (distance 64^2) rather than black (191^2).
  const std::vector<uint8_t> l0 = {0, 1, 4, 4, 3, 3,  //
                                   1, 0, 4, 4, 4, 3};
  Texture t = texture_bytes(TexelFormat::kPalette8, 6, 2, l0, palette);
  std::vector<uint8_t> storage(mip_chain_size(t));
  ASSERT_EQ(storage.size(), 3u + 1u);
  ASSERT_EQ(build_mip_chain(t, {}, storage), Status::kOk);
  ASSERT_EQ(t.level_count, 3);
  EXPECT_EQ(level_bytes(t, 1), (std::vector<uint8_t>{2, 0, 3}));
  // 3x1 -> 1x1 over grey, black, red: mean ((132+0+255+1)/3, (130+0+0+1)/3, (132+0+0+1)/3)
  // = (129, 43, 44): grey (3^2+87^2+88^2) beats black and red.
  EXPECT_EQ(level_bytes(t, 2), std::vector<uint8_t>{2});
  EXPECT_EQ(validate(t), Status::kOk);
}

TEST(MipChain, GlSizesDownToOneByOne) {
  EXPECT_EQ(mip_level_count(5, 3), 3);
  EXPECT_EQ(mip_level_count(1, 1), 1);
  EXPECT_EQ(mip_level_count(2048, 2048), 12);
  EXPECT_EQ(mip_level_count(2048, 1), 12);
  EXPECT_EQ(mip_level_count(640, 3), 10);  // 640 320 160 80 40 20 10 5 2 1
  EXPECT_EQ(mip_level_count(0, 4), 0);
  EXPECT_EQ(mip_level_count(2049, 4), 0);

  std::vector<uint8_t> bytes(size_t{640} * 3 * 3);
  Texture t = texture_bytes(TexelFormat::kRgb888, 640, 3, bytes);
  // 320x1 160x1 80x1 40x1 20x1 10x1 5x1 2x1 1x1: 638 texels.
  EXPECT_EQ(mip_chain_size(t), 638u * 3u);
  std::vector<uint8_t> storage(mip_chain_size(t));
  ASSERT_EQ(build_mip_chain(t, {}, storage), Status::kOk);
  ASSERT_EQ(t.level_count, 10);
  const uint16_t widths[10] = {640, 320, 160, 80, 40, 20, 10, 5, 2, 1};
  const uint16_t heights[10] = {3, 1, 1, 1, 1, 1, 1, 1, 1, 1};
  size_t offset = 0;
  for (int i = 0; i < 10; ++i) {
    const TextureLevel& l = t.levels[static_cast<size_t>(i)];
    EXPECT_EQ(l.width, widths[i]) << i;
    EXPECT_EQ(l.height, heights[i]) << i;
    if (i > 0) {
      EXPECT_EQ(l.bytes.data(), storage.data() + offset) << i;  // packed in order
      EXPECT_EQ(l.bytes.size(), size_t{l.width} * l.height * 3) << i;
      offset += l.bytes.size();
    }
  }
  EXPECT_EQ(offset, storage.size());
  EXPECT_EQ(validate(t), Status::kOk);

  std::vector<uint16_t> one = {0x1234};
  Texture single = texture565(1, 1, one);
  EXPECT_EQ(mip_chain_size(single), 0u);
  ASSERT_EQ(build_mip_chain(single, {}, {}), Status::kOk);
  EXPECT_EQ(single.level_count, 1);
  // RGB565 counts uint16 values: 5x3 -> 2 + 1.
  std::vector<uint16_t> t53(15);
  EXPECT_EQ(mip_chain_size(texture565(5, 3, t53)), 3u);
  EXPECT_EQ(mip_chain_size(texture_bytes(TexelFormat::kPalette8, 5, 3, {})), 3u);
}

TEST(MipChain, TooLittleStorageIsCapacityAndChangesNothing) {
  std::vector<uint8_t> l0(8 * 4 * 3, 7);
  Texture t = texture_bytes(TexelFormat::kRgb888, 8, 4, l0);
  const size_t need = mip_chain_size(t);
  ASSERT_EQ(need, (4u * 2 + 2 * 1 + 1) * 3);
  std::vector<uint8_t> storage(need - 1, 0xAB);
  EXPECT_EQ(build_mip_chain(t, {}, storage), Status::kCapacity);
  EXPECT_EQ(t.level_count, 1);
  EXPECT_EQ(t.levels[1].width, 0);
  for (uint8_t b : storage) EXPECT_EQ(b, 0xAB);
  // Storage of the wrong kind does not count.
  std::vector<uint16_t> wrong(need);
  EXPECT_EQ(build_mip_chain(t, wrong, {}), Status::kCapacity);
  // RGB565 needs uint16 storage.
  std::vector<uint16_t> l565(8 * 4, 0x1234);
  Texture t5 = texture565(8, 4, l565);
  std::vector<uint8_t> bytes(100);
  EXPECT_EQ(build_mip_chain(t5, {}, bytes), Status::kCapacity);
  std::vector<uint16_t> s565(mip_chain_size(t5));
  EXPECT_EQ(build_mip_chain(t5, s565, {}), Status::kOk);
  EXPECT_EQ(t5.level_count, 4);
  for (uint16_t v : s565) EXPECT_EQ(v, 0x1234);  // a flat texture stays flat
}

TEST(MipChain, InvalidLevelZeroIsRefused) {
  std::vector<uint8_t> storage(64);
  std::vector<uint8_t> l0(4, 0);
  // Span shorter than the size says.
  Texture t = texture_bytes(TexelFormat::kL8, 3, 2, l0);
  EXPECT_EQ(build_mip_chain(t, {}, storage), Status::kInvalidArgument);
  // Zero size.
  Texture z = texture_bytes(TexelFormat::kL8, 0, 2, l0);
  EXPECT_EQ(build_mip_chain(z, {}, storage), Status::kInvalidArgument);
  // Palette index beyond the palette.
  const std::vector<uint16_t> palette = {0, 0xFFFF};
  const std::vector<uint8_t> idx = {0, 1, 2, 1};
  Texture p = texture_bytes(TexelFormat::kPalette8, 2, 2, idx, palette);
  EXPECT_EQ(build_mip_chain(p, {}, storage), Status::kInvalidArgument);
  EXPECT_EQ(p.level_count, 1);
}

// Independent brute force: box bounds and rounded means written out directly, in double.
struct Box {
  int first, last;
};
Box ref_box(int i, int n) {
  const int m = n > 1 ? n / 2 : 1;
  if (n == 1) return {0, 0};
  return {2 * i, i == m - 1 ? n - 1 : 2 * i + 1};
}

TEST(MipChain, RandomNpotRgb888MatchesBruteForceBoxMeans) {
  std::mt19937 rng(11);
  for (auto [w, h] : {std::pair{7, 5}, {13, 1}, {1, 9}, {6, 11}, {31, 17}}) {
    std::vector<uint8_t> l0(size_t(w) * size_t(h) * 3);
    for (uint8_t& b : l0) b = static_cast<uint8_t>(rng());
    Texture t =
        texture_bytes(TexelFormat::kRgb888, static_cast<uint16_t>(w), static_cast<uint16_t>(h), l0);
    std::vector<uint8_t> storage(mip_chain_size(t));
    ASSERT_EQ(build_mip_chain(t, {}, storage), Status::kOk);
    ASSERT_EQ(validate(t), Status::kOk);
    ASSERT_EQ(t.level_count, mip_level_count(static_cast<uint16_t>(w), static_cast<uint16_t>(h)));
    for (int l = 1; l < t.level_count; ++l) {
      const TextureLevel& src = t.levels[static_cast<size_t>(l - 1)];
      const TextureLevel& dst = t.levels[static_cast<size_t>(l)];
      for (int y = 0; y < dst.height; ++y) {
        for (int x = 0; x < dst.width; ++x) {
          const Box bx = ref_box(x, src.width), by = ref_box(y, src.height);
          for (int c = 0; c < 3; ++c) {
            double sum = 0;
            int n = 0;
            for (int sy = by.first; sy <= by.last; ++sy)
              for (int sx = bx.first; sx <= bx.last; ++sx, ++n)
                sum += src.bytes[(size_t(sy) * src.width + size_t(sx)) * 3 + size_t(c)];
            const int expected = static_cast<int>(std::floor(sum / n + 0.5));
            ASSERT_EQ(dst.bytes[(size_t(y) * dst.width + size_t(x)) * 3 + size_t(c)], expected)
                << w << "x" << h << " level " << l << " texel " << x << "," << y;
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace lr
