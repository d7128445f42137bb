// Host textures (host_sim/formats/texture_load): every PNG colour type lands on the expected texels
// in every texel format, rows are flipped (storage row 0 = the file's bottom row), palettes (<= 256
// and > 256 colours), the L8 weights, NPOT sizes with a mip chain that validates, the size limit,
// copies and moves that keep their spans valid, and errors that name the file.
#include "lineraster/host_sim/formats/texture_load.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "lineraster/core/texture/mipmap.hpp"
#include "tests/support/file_bytes.hpp"
#include "tests/support/raw_png.hpp"
#include "tests/support/tmp_dir.hpp"

namespace lr::host {
namespace {

using test::raw_png;
using test::RawPng;
using test::read_bytes;
using test::scale16;
using test::TmpDir;
using test::write_bytes;
using test::write_raw_png;

// The 8-bit RGB colour of each pixel (row 0 = top), what the file stands for.
using Pixels = std::vector<Rgb8>;

// Independent expectations per format.
uint16_t expect565(Rgb8 c) {
  auto q = [](int v, int m) { return static_cast<unsigned>(std::lround(v * m / 255.0)); };
  return static_cast<uint16_t>((q(c.r, 31) << 11) | (q(c.g, 63) << 5) | q(c.b, 31));
}
Rgb8 expand(uint16_t v) {
  const int r5 = v >> 11, g6 = (v >> 5) & 63, b5 = v & 31;
  return {static_cast<uint8_t>(r5 * 8 + r5 / 4), static_cast<uint8_t>(g6 * 4 + g6 / 16),
          static_cast<uint8_t>(b5 * 8 + b5 / 4)};
}
uint8_t expect_l8(Rgb8 c) {
  // Exact in decimal: 299 r + 587 g + 114 b thousandths, rounded half up.
  const long t = 299L * c.r + 587L * c.g + 114L * c.b;
  return static_cast<uint8_t>(t / 1000 + (t % 1000 >= 500 ? 1 : 0));
}

const TexelFormat kFormats[] = {TexelFormat::kRgb565, TexelFormat::kRgb888, TexelFormat::kL8,
                                TexelFormat::kPalette8};

// Loads `path` in every format and checks every texel of level 0 against `px` (w x h, top first).
void expect_texels_all_formats(const std::string& path, int w, int h, const Pixels& px) {
  ASSERT_EQ(px.size(), size_t(w) * size_t(h));
  for (TexelFormat f : kFormats) {
    SCOPED_TRACE(texel_format_name(f));
    HostTexture t;
    std::string error;
    ASSERT_TRUE(load_texture(path, f, false, t, error)) << error;
    ASSERT_EQ(t.texture.format, f);
    ASSERT_EQ(t.texture.level_count, 1);
    ASSERT_EQ(t.texture.levels[0].width, w);
    ASSERT_EQ(t.texture.levels[0].height, h);
    ASSERT_EQ(validate(t.texture), Status::kOk);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const Rgb8 c = px[size_t(y) * size_t(w) + size_t(x)];
        const int row = h - 1 - y;  // storage row of image row y
        const size_t k = size_t(row) * size_t(w) + size_t(x);
        const Rgb8 got = texel_rgb8(t.texture, 0, x, row);
        switch (f) {
          case TexelFormat::kRgb565:
            ASSERT_EQ(t.texture.levels[0].rgb565[k], expect565(c)) << x << "," << y;
            ASSERT_EQ(got, expand(expect565(c)));
            break;
          case TexelFormat::kRgb888:
            ASSERT_EQ(got, c) << x << "," << y;
            ASSERT_EQ(t.texture.levels[0].bytes[3 * k + 1], c.g);
            break;
          case TexelFormat::kL8:
            ASSERT_EQ(t.texture.levels[0].bytes[k], expect_l8(c)) << x << "," << y;
            ASSERT_EQ(got, (Rgb8{expect_l8(c), expect_l8(c), expect_l8(c)}));
            break;
          case TexelFormat::kPalette8: {
            const uint8_t idx = t.texture.levels[0].bytes[k];
            ASSERT_LT(idx, t.texture.palette.size());
            ASSERT_EQ(t.texture.palette[idx], expect565(c)) << x << "," << y;
            ASSERT_EQ(got, expand(expect565(c)));
            break;
          }
        }
      }
    }
  }
}

TEST(TextureLoad, Grey8And16AndLowBitDepths) {
  TmpDir dir("lr_texture_test");
  {  // 8-bit grey, 3x2
    const std::vector<uint8_t> rows = {0, 10, 200, 255, 1, 128};
    ASSERT_TRUE(write_raw_png(raw_png(dir.file("g8.png"), 3, 2, 8, PNG_COLOR_TYPE_GRAY, rows, 3)));
    Pixels px;
    for (uint8_t g : rows) px.push_back({g, g, g});
    expect_texels_all_formats(dir.file("g8.png"), 3, 2, px);
  }
  {  // 16-bit grey, 2x2
    const unsigned v[4] = {0x0000, 0x12FF, 0x8080, 0xFFFF};
    std::vector<uint8_t> rows;
    Pixels px;
    for (unsigned s : v) {
      rows.push_back(static_cast<uint8_t>(s >> 8));
      rows.push_back(static_cast<uint8_t>(s & 0xFF));
      px.push_back({scale16(s), scale16(s), scale16(s)});
    }
    ASSERT_TRUE(
        write_raw_png(raw_png(dir.file("g16.png"), 2, 2, 16, PNG_COLOR_TYPE_GRAY, rows, 4)));
    expect_texels_all_formats(dir.file("g16.png"), 2, 2, px);
  }
  {                                                 // 1-, 2- and 4-bit grey, 4x1 each
    const std::vector<uint8_t> one = {0b10110000};  // 1 0 1 1
    ASSERT_TRUE(write_raw_png(raw_png(dir.file("g1.png"), 4, 1, 1, PNG_COLOR_TYPE_GRAY, one, 1)));
    expect_texels_all_formats(dir.file("g1.png"), 4, 1,
                              {{255, 255, 255}, {0, 0, 0}, {255, 255, 255}, {255, 255, 255}});
    const std::vector<uint8_t> two = {0b00011011};  // 0 1 2 3 -> 0 85 170 255
    ASSERT_TRUE(write_raw_png(raw_png(dir.file("g2.png"), 4, 1, 2, PNG_COLOR_TYPE_GRAY, two, 1)));
    expect_texels_all_formats(dir.file("g2.png"), 4, 1,
                              {{0, 0, 0}, {85, 85, 85}, {170, 170, 170}, {255, 255, 255}});
    const std::vector<uint8_t> four = {0x0F, 0x71};  // 0, 15, 7, 1 -> x17
    ASSERT_TRUE(write_raw_png(raw_png(dir.file("g4.png"), 4, 1, 4, PNG_COLOR_TYPE_GRAY, four, 2)));
    expect_texels_all_formats(dir.file("g4.png"), 4, 1,
                              {{0, 0, 0}, {255, 255, 255}, {119, 119, 119}, {17, 17, 17}});
  }
}

TEST(TextureLoad, GreyAlphaRgbRgbaIgnoreAlpha) {
  TmpDir dir("lr_texture_test");
  {  // grey + alpha, 8-bit, 3x1
    const std::vector<uint8_t> rows = {50, 0, 100, 128, 150, 255};
    ASSERT_TRUE(
        write_raw_png(raw_png(dir.file("ga.png"), 3, 1, 8, PNG_COLOR_TYPE_GRAY_ALPHA, rows, 6)));
    expect_texels_all_formats(dir.file("ga.png"), 3, 1,
                              {{50, 50, 50}, {100, 100, 100}, {150, 150, 150}});
  }
  {  // grey + alpha, 16-bit, 2x1
    const std::vector<uint8_t> rows = {0x12, 0xFF, 0, 0, 0xAB, 0xCD, 0xFF, 0xFF};
    ASSERT_TRUE(
        write_raw_png(raw_png(dir.file("ga16.png"), 2, 1, 16, PNG_COLOR_TYPE_GRAY_ALPHA, rows, 8)));
    const uint8_t a = scale16(0x12FF), b = scale16(0xABCD);
    expect_texels_all_formats(dir.file("ga16.png"), 2, 1, {{a, a, a}, {b, b, b}});
  }
  {  // RGB 8-bit, 3x2 (NPOT), primaries and mixtures
    const std::vector<uint8_t> rows = {255, 0,   0,  0,   255, 0,  0,   0,   255,  //
                                       10,  200, 30, 128, 64,  32, 255, 255, 255};
    ASSERT_TRUE(write_raw_png(raw_png(dir.file("rgb.png"), 3, 2, 8, PNG_COLOR_TYPE_RGB, rows, 9)));
    Pixels px;
    for (size_t i = 0; i < rows.size(); i += 3) px.push_back({rows[i], rows[i + 1], rows[i + 2]});
    expect_texels_all_formats(dir.file("rgb.png"), 3, 2, px);
  }
  {  // RGB 16-bit, 2x1
    const unsigned v[6] = {0xFFFF, 0x0000, 0x12FF, 0x0080, 0x7F7F, 0xABCD};
    std::vector<uint8_t> rows;
    for (unsigned s : v) {
      rows.push_back(static_cast<uint8_t>(s >> 8));
      rows.push_back(static_cast<uint8_t>(s & 0xFF));
    }
    ASSERT_TRUE(
        write_raw_png(raw_png(dir.file("rgb16.png"), 2, 1, 16, PNG_COLOR_TYPE_RGB, rows, 12)));
    expect_texels_all_formats(dir.file("rgb16.png"), 2, 1,
                              {{scale16(v[0]), scale16(v[1]), scale16(v[2])},
                               {scale16(v[3]), scale16(v[4]), scale16(v[5])}});
  }
  {  // RGBA 8-bit, 2x2
    const std::vector<uint8_t> rows = {1, 2, 3, 0, 4, 5, 6, 77, 7, 8, 9, 255, 10, 11, 12, 1};
    ASSERT_TRUE(
        write_raw_png(raw_png(dir.file("rgba.png"), 2, 2, 8, PNG_COLOR_TYPE_RGBA, rows, 8)));
    expect_texels_all_formats(dir.file("rgba.png"), 2, 2,
                              {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}, {10, 11, 12}});
  }
  {  // RGBA 16-bit, 1x2
    const std::vector<uint8_t> rows = {0xFF, 0xFF, 0x00, 0x80, 0x12, 0xFF, 0x00, 0x00,
                                       0x7F, 0x7F, 0xAB, 0xCD, 0x00, 0x00, 0xFF, 0xFF};
    ASSERT_TRUE(
        write_raw_png(raw_png(dir.file("rgba16.png"), 1, 2, 16, PNG_COLOR_TYPE_RGBA, rows, 8)));
    expect_texels_all_formats(
        dir.file("rgba16.png"), 1, 2,
        {{255, scale16(0x0080), scale16(0x12FF)}, {scale16(0x7F7F), scale16(0xABCD), 0}});
  }
}

TEST(TextureLoad, PaletteAndInterlacedFiles) {
  TmpDir dir("lr_texture_test");
  {  // 8-bit palette, 3x2
    const png_color pal[3] = {{255, 0, 0}, {0, 128, 0}, {10, 20, 30}};
    const std::vector<uint8_t> rows = {2, 0, 1, 1, 2, 0};
    RawPng r = raw_png(dir.file("pal.png"), 3, 2, 8, PNG_COLOR_TYPE_PALETTE, rows, 3);
    r.palette = pal;
    r.palette_size = 3;
    ASSERT_TRUE(write_raw_png(r));
    Pixels px;
    for (uint8_t i : rows) px.push_back({pal[i].red, pal[i].green, pal[i].blue});
    expect_texels_all_formats(dir.file("pal.png"), 3, 2, px);
  }
  {  // 4-bit palette, 5x1 (odd width)
    const png_color pal[4] = {{0, 0, 0}, {1, 2, 3}, {250, 5, 6}, {7, 8, 249}};
    const std::vector<uint8_t> rows = {0x32, 0x10, 0x20};  // 3 2 1 0 2
    RawPng r = raw_png(dir.file("pal4.png"), 5, 1, 4, PNG_COLOR_TYPE_PALETTE, rows, 3);
    r.palette = pal;
    r.palette_size = 4;
    ASSERT_TRUE(write_raw_png(r));
    Pixels px;
    for (int i : {3, 2, 1, 0, 2}) px.push_back({pal[i].red, pal[i].green, pal[i].blue});
    expect_texels_all_formats(dir.file("pal4.png"), 5, 1, px);
  }
  {  // interlaced RGB, 13x11
    std::mt19937 rng(4);
    std::vector<uint8_t> rows(13 * 11 * 3);
    for (uint8_t& b : rows) b = static_cast<uint8_t>(rng() % 6 * 51);  // <= 216 colours
    RawPng r = raw_png(dir.file("adam7.png"), 13, 11, 8, PNG_COLOR_TYPE_RGB, rows, 13 * 3);
    r.interlace = PNG_INTERLACE_ADAM7;
    ASSERT_TRUE(write_raw_png(r));
    Pixels px;
    for (size_t i = 0; i < rows.size(); i += 3) px.push_back({rows[i], rows[i + 1], rows[i + 2]});
    expect_texels_all_formats(dir.file("adam7.png"), 13, 11, px);
  }
}

ImageRgb8 image(int w, int h, const Pixels& px) {
  ImageRgb8 img;
  img.width = w;
  img.height = h;
  for (Rgb8 c : px) img.rgb.insert(img.rgb.end(), {c.r, c.g, c.b});
  return img;
}

TEST(TextureLoad, StorageRowZeroIsTheImagesBottomRow) {
  // Top row red green, bottom row blue white.
  const ImageRgb8 img = image(2, 2, {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}});
  HostTexture t;
  std::string error;
  ASSERT_TRUE(texture_from_image(img, TexelFormat::kRgb888, false, t, error)) << error;
  EXPECT_EQ(t.bytes, (std::vector<uint8_t>{0, 0, 255, 255, 255, 255, 255, 0, 0, 0, 255, 0}));
  EXPECT_EQ(texel_rgb8(t.texture, 0, 0, 0), (Rgb8{0, 0, 255}));
  EXPECT_EQ(texel_rgb8(t.texture, 0, 1, 1), (Rgb8{0, 255, 0}));
  ASSERT_TRUE(texture_from_image(img, TexelFormat::kRgb565, false, t, error)) << error;
  EXPECT_EQ(t.rgb565, (std::vector<uint16_t>{0x001F, 0xFFFF, 0xF800, 0x07E0}));
  // The project's checker: storage row r holds the file's row 7 - r.
  ImageRgb8 checker;
  ASSERT_TRUE(read_png(LR_SOURCE_DIR "/tests/host/data/checker.png", checker, error)) << error;
  ASSERT_TRUE(load_texture(LR_SOURCE_DIR "/tests/host/data/checker.png", TexelFormat::kRgb888,
                           false, t, error))
      << error;
  ASSERT_EQ(t.texture.levels[0].width, checker.width);
  for (int r = 0; r < checker.height; ++r)
    for (int x = 0; x < checker.width; ++x) {
      const size_t p = (size_t(checker.height - 1 - r) * size_t(checker.width) + size_t(x)) * 3;
      EXPECT_EQ(texel_rgb8(t.texture, 0, x, r),
                (Rgb8{checker.rgb[p], checker.rgb[p + 1], checker.rgb[p + 2]}));
    }
}

TEST(TextureLoad, L8UsesRec601WeightsRoundedToNearest) {
  const ImageRgb8 img = image(6, 1,
                              {{255, 0, 0},    // 76.245 -> 76
                               {0, 255, 0},    // 149.685 -> 150
                               {0, 0, 255},    // 29.07 -> 29
                               {10, 200, 30},  // 2.99 + 117.4 + 3.42 = 123.81 -> 124
                               {255, 255, 255},
                               {1, 0, 1}});  // 0.413 -> 0
  HostTexture t;
  std::string error;
  ASSERT_TRUE(texture_from_image(img, TexelFormat::kL8, false, t, error)) << error;
  EXPECT_EQ(t.bytes, (std::vector<uint8_t>{76, 150, 29, 124, 255, 0}));
  // Every grey level is exact.
  Pixels grey;
  for (int v = 0; v < 256; ++v) grey.push_back({uint8_t(v), uint8_t(v), uint8_t(v)});
  ASSERT_TRUE(texture_from_image(image(256, 1, grey), TexelFormat::kL8, false, t, error));
  for (int v = 0; v < 256; ++v) EXPECT_EQ(t.bytes[size_t(v)], v);
}

TEST(TextureLoad, PaletteKeepsFirstAppearanceOrderUpTo256Colours) {
  // Top row first: order of first appearance is green, red, then blue (which sits in the bottom
  // row, stored first).
  const ImageRgb8 img = image(2, 2, {{0, 255, 0}, {255, 0, 0}, {0, 0, 255}, {0, 255, 0}});
  HostTexture t;
  std::string error;
  ASSERT_TRUE(texture_from_image(img, TexelFormat::kPalette8, false, t, error)) << error;
  EXPECT_EQ(t.palette, (std::vector<uint16_t>{0x07E0, 0xF800, 0x001F}));
  EXPECT_EQ(t.bytes, (std::vector<uint8_t>{2, 0, 0, 1}));
  EXPECT_EQ(t.texture.palette.data(), t.palette.data());
  // Colours equal after RGB565 rounding share an entry: (0,0,0) and (3,1,3) both give 0x0000.
  ASSERT_TRUE(texture_from_image(image(2, 1, {{0, 0, 0}, {3, 1, 3}}), TexelFormat::kPalette8, false,
                                 t, error));
  EXPECT_EQ(t.palette, std::vector<uint16_t>{0});
  // Exactly 256 distinct colours: accepted, entry i is colour i.
  Pixels px;
  for (int i = 0; i < 256; ++i)  // RGB565 colours expanded: they convert back exactly
    px.push_back(expand(static_cast<uint16_t>(((i >> 3) << 11) | (((i & 7) * 9) << 5))));
  ASSERT_TRUE(texture_from_image(image(16, 16, px), TexelFormat::kPalette8, true, t, error))
      << error;
  ASSERT_EQ(t.palette.size(), 256u);
  for (int i = 0; i < 256; ++i) EXPECT_EQ(t.palette[size_t(i)], expect565(px[size_t(i)]));
  EXPECT_EQ(t.texture.level_count, 5);
  EXPECT_EQ(validate(t.texture), Status::kOk);
  // 257 colours: refused with the promised message, `out` untouched.
  px.push_back({255, 255, 255});
  px.resize(17 * 16, Rgb8{255, 255, 255});
  const TmpDir dir("lr_texture_test");
  ASSERT_TRUE(write_png(dir.file("many.png"), image(17, 16, px), error)) << error;
  HostTexture kept = t;
  EXPECT_FALSE(load_texture(dir.file("many.png"), TexelFormat::kPalette8, false, t, error));
  EXPECT_EQ(error, dir.file("many.png") + ": more than 256 colours; use rgb565 or rgb888");
  EXPECT_EQ(t.palette, kept.palette);
  EXPECT_EQ(t.bytes, kept.bytes);
  // The same file loads in the other formats.
  EXPECT_TRUE(load_texture(dir.file("many.png"), TexelFormat::kRgb565, true, t, error)) << error;
}

TEST(TextureLoad, NpotSizesGetAFullMipChainThatValidates) {
  std::mt19937 rng(9);
  for (auto [w, h] : {std::pair{5, 3}, {7, 1}, {1, 6}, {33, 17}, {100, 75}}) {
    Pixels px(size_t(w) * size_t(h));
    for (Rgb8& c : px)
      c = {uint8_t(rng() % 4 * 85), uint8_t(rng() % 4 * 85), uint8_t(rng() % 4 * 85)};
    const ImageRgb8 img = image(w, h, px);
    for (TexelFormat f : kFormats) {
      SCOPED_TRACE(std::string(texel_format_name(f)) + " " + std::to_string(w) + "x" +
                   std::to_string(h));
      HostTexture t;
      std::string error;
      ASSERT_TRUE(texture_from_image(img, f, true, t, error)) << error;
      ASSERT_EQ(t.texture.level_count,
                mip_level_count(static_cast<uint16_t>(w), static_cast<uint16_t>(h)));
      EXPECT_EQ(validate(t.texture), Status::kOk);
      const TextureLevel& last = t.texture.levels[t.texture.level_count - 1u];
      EXPECT_EQ(last.width, 1);
      EXPECT_EQ(last.height, 1);
      // The storage holds level 0 and the chain, nothing more.
      const size_t elements = f == TexelFormat::kRgb565 ? t.rgb565.size() : t.bytes.size();
      const size_t level0 =
          size_t(w) * size_t(h) * (f == TexelFormat::kRgb565 ? 1 : bytes_per_texel(f));
      EXPECT_EQ(elements, level0 + mip_chain_size(t.texture));
      // Level 1 is the core's box filter of level 0: rebuild it and compare.
      Texture copy = t.texture;
      std::vector<uint16_t> s565(mip_chain_size(copy));
      std::vector<uint8_t> sbytes(mip_chain_size(copy));
      ASSERT_EQ(build_mip_chain(copy, s565, sbytes), Status::kOk);
      for (int l = 1; l < copy.level_count; ++l)
        for (int y = 0; y < copy.levels[size_t(l)].height; ++y)
          for (int x = 0; x < copy.levels[size_t(l)].width; ++x)
            ASSERT_EQ(texel_rgb8(copy, l, x, y), texel_rgb8(t.texture, l, x, y));
    }
  }
  // Without mipmaps: level 0 only.
  HostTexture t;
  std::string error;
  ASSERT_TRUE(texture_from_image(image(3, 1, {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}}),
                                 TexelFormat::kRgb888, false, t, error));
  EXPECT_EQ(t.texture.level_count, 1);
  EXPECT_EQ(t.bytes.size(), 9u);
  // Mip texels for a known case: 2x2 RGB888 -> mean.
  ASSERT_TRUE(texture_from_image(image(2, 2, {{0, 0, 0}, {255, 255, 255}, {255, 0, 0}, {0, 0, 1}}),
                                 TexelFormat::kRgb888, true, t, error));
  ASSERT_EQ(t.texture.level_count, 2);
  EXPECT_EQ(texel_rgb8(t.texture, 1, 0, 0),
            (Rgb8{128, 64, 64}));  // (510+2)/4, (255+2)/4, (256+2)/4
}

TEST(TextureLoad, SidesAboveTheLimitAreRefused) {
  HostTexture t;
  std::string error;
  ImageRgb8 wide;
  wide.width = kMaxTextureSize + 1;
  wide.height = 1;
  wide.rgb.assign(size_t(wide.width) * 3, 0);
  EXPECT_FALSE(texture_from_image(wide, TexelFormat::kRgb565, false, t, error));
  EXPECT_EQ(error, "texture: 2049x1 is larger than the largest texture (2048x2048)");
  ImageRgb8 max = wide;
  max.width = kMaxTextureSize;
  max.rgb.resize(size_t(max.width) * 3);
  EXPECT_TRUE(texture_from_image(max, TexelFormat::kRgb565, true, t, error)) << error;
  EXPECT_EQ(t.texture.level_count, 12);
  ImageRgb8 empty;
  EXPECT_FALSE(texture_from_image(empty, TexelFormat::kRgb565, false, t, error));
  EXPECT_EQ(error, "texture: invalid image");
}

TEST(TextureLoad, CopiesAndMovesPointAtTheirOwnStorage) {
  std::string error;
  std::vector<HostTexture> many;
  for (int i = 0; i < 20; ++i) {  // reallocation moves the elements
    HostTexture t;
    ASSERT_TRUE(texture_from_image(
        image(3, 2, {{uint8_t(i), 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {9, 9, 9}}),
        TexelFormat::kPalette8, true, t, error));
    many.push_back(t);
  }
  for (int i = 0; i < 20; ++i) {
    const HostTexture& t = many[size_t(i)];
    EXPECT_EQ(t.texture.levels[0].bytes.data(), t.bytes.data());
    EXPECT_EQ(t.texture.levels[1].bytes.data(), t.bytes.data() + 6);
    EXPECT_EQ(t.texture.palette.data(), t.palette.data());
    EXPECT_EQ(texel_rgb8(t.texture, 0, 0, 1), expand(expect565({uint8_t(i), 0, 0})));
    EXPECT_EQ(validate(t.texture), Status::kOk);
  }
  HostTexture a;
  {
    HostTexture src;
    ASSERT_TRUE(texture_from_image(image(2, 1, {{255, 0, 0}, {0, 0, 255}}), TexelFormat::kRgb565,
                                   true, src, error));
    a = src;  // copy assignment, then src dies
    HostTexture b(std::move(src));
    EXPECT_EQ(src.texture.level_count, 0);
    EXPECT_EQ(b.texture.levels[0].rgb565.data(), b.rgb565.data());
  }
  EXPECT_EQ(a.texture.levels[0].rgb565.data(), a.rgb565.data());
  EXPECT_EQ(a.texture.levels[1].rgb565.data(), a.rgb565.data() + 2);
  EXPECT_EQ(texel_rgb8(a.texture, 0, 1, 0), (Rgb8{0, 0, 255}));
  HostTexture c;
  c = std::move(a);
  EXPECT_EQ(c.texture.levels[0].rgb565.data(), c.rgb565.data());
  EXPECT_EQ(validate(c.texture), Status::kOk);
  // Out of range reads are black.
  EXPECT_EQ(texel_rgb8(c.texture, 0, 2, 0), Rgb8{});
  EXPECT_EQ(texel_rgb8(c.texture, 2, 0, 0), Rgb8{});
  EXPECT_EQ(texel_rgb8(c.texture, -1, 0, 0), Rgb8{});
  EXPECT_EQ(texel_rgb8(c.texture, 0, 0, -1), Rgb8{});
}

TEST(TextureLoad, BadFilesGiveOneLineNamingTheFile) {
  TmpDir dir("lr_texture_test");
  std::string error;
  HostTexture t;
  ASSERT_TRUE(texture_from_image(image(1, 1, {{1, 2, 3}}), TexelFormat::kRgb888, false, t, error));
  const std::vector<uint8_t> before = t.bytes;
  // Missing.
  EXPECT_FALSE(load_texture(dir.file("missing.png"), TexelFormat::kRgb565, false, t, error));
  EXPECT_EQ(error, dir.file("missing.png") + ": cannot open: No such file or directory");
  // Truncated.
  std::mt19937 rng(3);
  ImageRgb8 noise;
  noise.width = 64;
  noise.height = 48;
  noise.rgb.resize(64 * 48 * 3);
  for (uint8_t& b : noise.rgb) b = static_cast<uint8_t>(rng());
  ASSERT_TRUE(write_png(dir.file("full.png"), noise, error)) << error;
  const std::vector<uint8_t> full = read_bytes(dir.file("full.png"));
  write_bytes(dir.file("cut.png"), std::vector<uint8_t>(full.begin(), full.begin() + 2000));
  EXPECT_FALSE(load_texture(dir.file("cut.png"), TexelFormat::kRgb888, true, t, error));
  EXPECT_EQ(error, dir.file("cut.png") + ": truncated file (unexpected end of data)");
  // Corrupt: a flipped bit in IHDR, and a file that is not a PNG.
  std::vector<uint8_t> bad = full;
  bad[20] ^= 1;
  write_bytes(dir.file("bad.png"), bad);
  EXPECT_FALSE(load_texture(dir.file("bad.png"), TexelFormat::kL8, false, t, error));
  EXPECT_EQ(error, dir.file("bad.png") + ": IHDR: CRC error");
  write_bytes(dir.file("text.png"), {'h', 'e', 'l', 'l', 'o', '\n', 0, 0, 0, 0});
  EXPECT_FALSE(load_texture(dir.file("text.png"), TexelFormat::kPalette8, false, t, error));
  EXPECT_EQ(error, dir.file("text.png") + ": not a PNG file");
  EXPECT_EQ(error.find('\n'), std::string::npos);
  // `out` was never touched.
  EXPECT_EQ(t.bytes, before);
  EXPECT_EQ(t.texture.levels[0].width, 1);
}

TEST(TextureLoad, FormatNames) {
  for (TexelFormat f : kFormats) {
    TexelFormat g = TexelFormat::kRgb565;
    EXPECT_TRUE(parse_texel_format(texel_format_name(f), g));
    EXPECT_EQ(g, f);
  }
  TexelFormat g;
  EXPECT_FALSE(parse_texel_format("RGB565", g));
  EXPECT_FALSE(parse_texel_format("", g));
}

}  // namespace
}  // namespace lr::host
