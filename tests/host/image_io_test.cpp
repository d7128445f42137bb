// Image files: exact round trips, every PNG colour type (files made here with libpng directly),
// PPM/PGM variants, and failures (truncated, corrupt, garbage, unwritable) that return an error,
// never crash and never leave a partial file.
#include "lineraster/host_sim/formats/image_io.hpp"

#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

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

bool exists(const std::string& path) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

ImageRgb8 random_image(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  ImageRgb8 img;
  img.width = w;
  img.height = h;
  img.rgb.resize(static_cast<size_t>(w) * static_cast<size_t>(h) * 3);
  for (uint8_t& b : img.rgb) b = static_cast<uint8_t>(rng());
  return img;
}

ImageRgb8 read_ok(const std::string& path) {
  ImageRgb8 img;
  std::string error;
  EXPECT_TRUE(read_png(path, img, error)) << error;
  return img;
}

// Reads a 16-bit grey PNG's raw samples with libpng (to check write_png_gray16 bit-exactly).
struct Gray16Read {
  uint32_t width, height;
  uint16_t* out;  // width * height
  size_t capacity;
};

bool read_gray16_impl(Gray16Read* g, png_structp png, png_infop info, std::FILE* f) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, f);
  png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  g->width = png_get_image_width(png, info);
  g->height = png_get_image_height(png, info);
  if (png_get_bit_depth(png, info) != 16 || png_get_color_type(png, info) != PNG_COLOR_TYPE_GRAY ||
      size_t{g->width} * g->height > g->capacity) {
    return false;
  }
  png_bytepp rows = png_get_rows(png, info);
  for (uint32_t y = 0; y < g->height; ++y) {
    for (uint32_t x = 0; x < g->width; ++x) {
      g->out[y * g->width + x] = static_cast<uint16_t>((rows[y][2 * x] << 8) | rows[y][2 * x + 1]);
    }
  }
  return true;
}

// --- Round trips -------------------------------------------------------------------------------

TEST(ImageIo, PngRoundTripIsExact) {
  TmpDir dir("lr_image_test");
  const ImageRgb8 img = random_image(37, 23, 1);
  std::string error;
  ASSERT_TRUE(write_png(dir.file("a.png"), img, error)) << error;
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"a.png"});  // no temporary file left
  const ImageRgb8 back = read_ok(dir.file("a.png"));
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 23);
  EXPECT_EQ(back.rgb, img.rgb);
}

TEST(ImageIo, PpmRoundTripIsExact) {
  TmpDir dir("lr_image_test");
  const ImageRgb8 img = random_image(19, 31, 2);
  std::string error;
  ASSERT_TRUE(write_ppm(dir.file("a.ppm"), img, error)) << error;
  const std::vector<uint8_t> bytes = read_bytes(dir.file("a.ppm"));
  const std::string header = "P6\n19 31\n255\n";
  ASSERT_EQ(bytes.size(), header.size() + img.rgb.size());
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + static_cast<long>(header.size())), header);
  ImageRgb8 back;
  ASSERT_TRUE(read_ppm(dir.file("a.ppm"), back, error)) << error;
  EXPECT_EQ(back.width, 19);
  EXPECT_EQ(back.height, 31);
  EXPECT_EQ(back.rgb, img.rgb);
}

TEST(ImageIo, WriteAndReadImageChooseTheFormat) {
  TmpDir dir("lr_image_test");
  const ImageRgb8 img = random_image(5, 4, 3);
  std::string error;
  ASSERT_TRUE(write_image(dir.file("x.PNG"), img, error)) << error;
  ASSERT_TRUE(write_image(dir.file("y.Ppm"), img, error)) << error;
  EXPECT_EQ(read_bytes(dir.file("x.PNG"))[1], 'P');  // \x89PNG
  EXPECT_EQ(read_bytes(dir.file("y.Ppm"))[0], 'P');
  ImageRgb8 a, b;
  ASSERT_TRUE(read_image(dir.file("x.PNG"), a, error)) << error;
  ASSERT_TRUE(read_image(dir.file("y.Ppm"), b, error)) << error;
  EXPECT_EQ(a.rgb, img.rgb);
  EXPECT_EQ(b.rgb, img.rgb);
  EXPECT_FALSE(write_image(dir.file("z.jpg"), img, error));
  EXPECT_EQ(error, dir.file("z.jpg") + ": unknown image extension (expected .png or .ppm)");
  EXPECT_FALSE(write_image(dir.file("png"), img, error));
  EXPECT_FALSE(exists(dir.file("z.jpg")));
  write_bytes(dir.file("t.txt"), {'h', 'e', 'l', 'l', 'o'});
  EXPECT_FALSE(read_image(dir.file("t.txt"), a, error));
  EXPECT_EQ(error, dir.file("t.txt") + ": unknown image format (expected PNG or PPM)");
}

TEST(ImageIo, Gray16PngKeepsAll16Bits) {
  TmpDir dir("lr_image_test");
  const std::vector<uint16_t> depth = {0, 1, 255, 256, 0x12FF, 0x8000, 0xFFFE, 0xFFFF};
  std::string error;
  ASSERT_TRUE(write_png_gray16(dir.file("d.png"), 4, 2, depth, error)) << error;
  std::vector<uint16_t> back(8, 0);
  Gray16Read g{0, 0, back.data(), back.size()};
  std::FILE* f = std::fopen(dir.file("d.png").c_str(), "rb");
  ASSERT_NE(f, nullptr);
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  const bool ok = read_gray16_impl(&g, png, info, f);
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(f);
  ASSERT_TRUE(ok);
  EXPECT_EQ(g.width, 4u);
  EXPECT_EQ(g.height, 2u);
  EXPECT_EQ(back, depth);
  // And read_png turns it into grey RGB8 with rounding.
  const ImageRgb8 rgb = read_ok(dir.file("d.png"));
  for (size_t i = 0; i < depth.size(); ++i) {
    for (size_t c = 0; c < 3; ++c) EXPECT_EQ(rgb.rgb[i * 3 + c], scale16(depth[i])) << i;
  }
  EXPECT_FALSE(write_png_gray16(dir.file("e.png"), 3, 3, depth, error));
  EXPECT_EQ(error, dir.file("e.png") + ": invalid image (3x3 with 8 samples)");
}

// --- Every PNG colour type --------------------------------------------------------------------

TEST(ImageIoPngTypes, Grey8) {
  TmpDir dir("lr_image_test");
  const std::vector<uint8_t> rows = {0, 10, 200, 255, 1, 128};
  ASSERT_TRUE(write_raw_png(raw_png(dir.file("g.png"), 3, 2, 8, PNG_COLOR_TYPE_GRAY, rows, 3)));
  const ImageRgb8 img = read_ok(dir.file("g.png"));
  ASSERT_EQ(img.rgb.size(), 18u);
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(img.rgb[3 * i], rows[i]);
    EXPECT_EQ(img.rgb[3 * i + 1], rows[i]);
    EXPECT_EQ(img.rgb[3 * i + 2], rows[i]);
  }
}

TEST(ImageIoPngTypes, Grey1And4BitAreScaledUp) {
  TmpDir dir("lr_image_test");
  const std::vector<uint8_t> one = {0b10110000};  // 4 pixels: 1 0 1 1
  ASSERT_TRUE(write_raw_png(raw_png(dir.file("g1.png"), 4, 1, 1, PNG_COLOR_TYPE_GRAY, one, 1)));
  const ImageRgb8 a = read_ok(dir.file("g1.png"));
  EXPECT_EQ(a.rgb, (std::vector<uint8_t>{255, 255, 255, 0, 0, 0, 255, 255, 255, 255, 255, 255}));
  const std::vector<uint8_t> four = {0x0F, 0x71};  // 0, 15, 7, 1
  ASSERT_TRUE(write_raw_png(raw_png(dir.file("g4.png"), 4, 1, 4, PNG_COLOR_TYPE_GRAY, four, 2)));
  const ImageRgb8 b = read_ok(dir.file("g4.png"));
  EXPECT_EQ(b.rgb, (std::vector<uint8_t>{0, 0, 0, 255, 255, 255, 119, 119, 119, 17, 17, 17}));
}

TEST(ImageIoPngTypes, Grey16IsRoundedTo8Bits) {
  TmpDir dir("lr_image_test");
  const unsigned v[4] = {0x0000, 0x12FF, 0x8080, 0xFFFF};
  std::vector<uint8_t> rows;
  for (unsigned s : v) {
    rows.push_back(static_cast<uint8_t>(s >> 8));
    rows.push_back(static_cast<uint8_t>(s & 0xFF));
  }
  ASSERT_TRUE(write_raw_png(raw_png(dir.file("g16.png"), 2, 2, 16, PNG_COLOR_TYPE_GRAY, rows, 4)));
  const ImageRgb8 img = read_ok(dir.file("g16.png"));
  ASSERT_EQ(img.rgb.size(), 12u);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(img.rgb[3 * i], scale16(v[i])) << i;
  EXPECT_EQ(img.rgb[3], 19);  // 0x12FF: rounded (truncating would give 18)
}

TEST(ImageIoPngTypes, GreyAlphaDropsAlpha) {
  TmpDir dir("lr_image_test");
  const std::vector<uint8_t> rows = {50, 0, 100, 128, 150, 255};
  ASSERT_TRUE(
      write_raw_png(raw_png(dir.file("ga.png"), 3, 1, 8, PNG_COLOR_TYPE_GRAY_ALPHA, rows, 6)));
  const ImageRgb8 img = read_ok(dir.file("ga.png"));
  EXPECT_EQ(img.rgb, (std::vector<uint8_t>{50, 50, 50, 100, 100, 100, 150, 150, 150}));
}

TEST(ImageIoPngTypes, Rgb16IsRoundedTo8Bits) {
  TmpDir dir("lr_image_test");
  const unsigned v[6] = {0xFFFF, 0x0000, 0x12FF, 0x0080, 0x7F7F, 0xABCD};
  std::vector<uint8_t> rows;
  for (unsigned s : v) {
    rows.push_back(static_cast<uint8_t>(s >> 8));
    rows.push_back(static_cast<uint8_t>(s & 0xFF));
  }
  ASSERT_TRUE(write_raw_png(raw_png(dir.file("c16.png"), 2, 1, 16, PNG_COLOR_TYPE_RGB, rows, 12)));
  const ImageRgb8 img = read_ok(dir.file("c16.png"));
  ASSERT_EQ(img.rgb.size(), 6u);
  for (size_t i = 0; i < 6; ++i) EXPECT_EQ(img.rgb[i], scale16(v[i])) << i;
}

TEST(ImageIoPngTypes, RgbaDropsAlpha) {
  TmpDir dir("lr_image_test");
  const std::vector<uint8_t> rows = {1, 2, 3, 0, 4, 5, 6, 77, 7, 8, 9, 255, 10, 11, 12, 1};
  ASSERT_TRUE(write_raw_png(raw_png(dir.file("rgba.png"), 2, 2, 8, PNG_COLOR_TYPE_RGBA, rows, 8)));
  const ImageRgb8 img = read_ok(dir.file("rgba.png"));
  EXPECT_EQ(img.rgb, (std::vector<uint8_t>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}));
}

TEST(ImageIoPngTypes, PaletteWithTransparencyIsExpanded) {
  TmpDir dir("lr_image_test");
  const png_color pal[3] = {{255, 0, 0}, {0, 128, 0}, {10, 20, 30}};
  const png_byte trns[2] = {0, 128};
  const std::vector<uint8_t> rows = {2, 0, 1, 1, 2, 0};
  RawPng r = raw_png(dir.file("pal.png"), 3, 2, 8, PNG_COLOR_TYPE_PALETTE, rows, 3);
  r.palette = pal;
  r.palette_size = 3;
  r.trns = trns;
  r.trns_size = 2;
  ASSERT_TRUE(write_raw_png(r));
  const ImageRgb8 img = read_ok(dir.file("pal.png"));
  EXPECT_EQ(img.rgb, (std::vector<uint8_t>{10, 20, 30, 255, 0, 0, 0, 128, 0,  //
                                           0, 128, 0, 10, 20, 30, 255, 0, 0}));
}

TEST(ImageIoPngTypes, Palette2Bit) {
  TmpDir dir("lr_image_test");
  const png_color pal[4] = {{0, 0, 0}, {1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
  const std::vector<uint8_t> rows = {0b11100100};  // 3 2 1 0
  RawPng r = raw_png(dir.file("pal2.png"), 4, 1, 2, PNG_COLOR_TYPE_PALETTE, rows, 1);
  r.palette = pal;
  r.palette_size = 4;
  ASSERT_TRUE(write_raw_png(r));
  const ImageRgb8 img = read_ok(dir.file("pal2.png"));
  EXPECT_EQ(img.rgb, (std::vector<uint8_t>{7, 8, 9, 4, 5, 6, 1, 2, 3, 0, 0, 0}));
}

TEST(ImageIoPngTypes, InterlacedRgb) {
  TmpDir dir("lr_image_test");
  const ImageRgb8 ref = random_image(13, 11, 4);
  RawPng r = raw_png(dir.file("adam7.png"), 13, 11, 8, PNG_COLOR_TYPE_RGB, ref.rgb, 13 * 3);
  r.interlace = PNG_INTERLACE_ADAM7;
  ASSERT_TRUE(write_raw_png(r));
  const ImageRgb8 img = read_ok(dir.file("adam7.png"));
  EXPECT_EQ(img.width, 13);
  EXPECT_EQ(img.height, 11);
  EXPECT_EQ(img.rgb, ref.rgb);
}

TEST(ImageIoPngTypes, InterlacedGreyAlpha16) {
  TmpDir dir("lr_image_test");
  std::vector<uint8_t> rows;
  std::vector<unsigned> grey;
  for (unsigned i = 0; i < 9 * 9; ++i) {
    const unsigned g = (i * 7919u) & 0xFFFF, a = (i * 31u) & 0xFFFF;
    grey.push_back(g);
    rows.insert(rows.end(), {static_cast<uint8_t>(g >> 8), static_cast<uint8_t>(g),
                             static_cast<uint8_t>(a >> 8), static_cast<uint8_t>(a)});
  }
  RawPng r = raw_png(dir.file("ga16i.png"), 9, 9, 16, PNG_COLOR_TYPE_GRAY_ALPHA, rows, 9 * 4);
  r.interlace = PNG_INTERLACE_ADAM7;
  ASSERT_TRUE(write_raw_png(r));
  const ImageRgb8 img = read_ok(dir.file("ga16i.png"));
  ASSERT_EQ(img.rgb.size(), 9u * 9u * 3u);
  for (size_t i = 0; i < grey.size(); ++i) EXPECT_EQ(img.rgb[3 * i + 1], scale16(grey[i])) << i;
}

// --- Failures -----------------------------------------------------------------------------------

TEST(ImageIoErrors, TruncatedPngFailsCleanly) {
  TmpDir dir("lr_image_test");
  const ImageRgb8 img = random_image(64, 48, 5);
  std::string error;
  ASSERT_TRUE(write_png(dir.file("full.png"), img, error));
  const std::vector<uint8_t> full = read_bytes(dir.file("full.png"));
  ASSERT_GT(full.size(), 1000u);
  const std::string cut = dir.file("cut.png");
  for (size_t len = 0; len < full.size(); len += (len < 120 ? 1 : 211)) {
    write_bytes(cut, std::vector<uint8_t>(full.begin(), full.begin() + static_cast<long>(len)));
    ImageRgb8 out;
    out.width = 99;
    EXPECT_FALSE(read_png(cut, out, error)) << len;
    EXPECT_EQ(error.rfind(cut + ": ", 0), 0u) << error;
    EXPECT_EQ(out.width, 99);
    EXPECT_TRUE(out.rgb.empty());
  }
  write_bytes(cut, std::vector<uint8_t>(full.begin(), full.begin() + 2000));
  ImageRgb8 out;
  EXPECT_FALSE(read_png(cut, out, error));
  EXPECT_EQ(error, cut + ": truncated file (unexpected end of data)");
  write_bytes(cut, std::vector<uint8_t>(full.begin(), full.begin() + 5));
  EXPECT_FALSE(read_png(cut, out, error));
  EXPECT_EQ(error, cut + ": not a PNG file");
}

TEST(ImageIoErrors, CorruptCrcAndGarbageFail) {
  TmpDir dir("lr_image_test");
  const ImageRgb8 img = random_image(16, 16, 6);
  std::string error;
  ASSERT_TRUE(write_png(dir.file("ok.png"), img, error));
  const std::vector<uint8_t> good = read_bytes(dir.file("ok.png"));
  ImageRgb8 out;
  // Byte 20 is inside IHDR's data (width/height/depth...), byte 60 inside IDAT's data.
  for (size_t pos : {size_t{20}, size_t{29}, size_t{60}, good.size() - 6}) {
    std::vector<uint8_t> bad = good;
    bad[pos] ^= 0x5A;
    write_bytes(dir.file("bad.png"), bad);
    EXPECT_FALSE(read_png(dir.file("bad.png"), out, error)) << pos;
    EXPECT_EQ(error.rfind(dir.file("bad.png") + ": ", 0), 0u) << error;
  }
  std::vector<uint8_t> bad = good;
  bad[20] ^= 1;
  write_bytes(dir.file("bad.png"), bad);
  EXPECT_FALSE(read_png(dir.file("bad.png"), out, error));
  EXPECT_EQ(error, dir.file("bad.png") + ": IHDR: CRC error");
  // Garbage, and garbage after a valid signature.
  std::mt19937 rng(7);
  std::vector<uint8_t> junk(3000);
  for (uint8_t& b : junk) b = static_cast<uint8_t>(rng());
  write_bytes(dir.file("junk.png"), junk);
  EXPECT_FALSE(read_png(dir.file("junk.png"), out, error));
  EXPECT_EQ(error, dir.file("junk.png") + ": not a PNG file");
  std::copy(good.begin(), good.begin() + 8, junk.begin());
  write_bytes(dir.file("junk.png"), junk);
  EXPECT_FALSE(read_png(dir.file("junk.png"), out, error));
  EXPECT_EQ(error.rfind(dir.file("junk.png") + ": ", 0), 0u);
  EXPECT_EQ(out.width, 0);
  EXPECT_FALSE(read_png(dir.file("missing.png"), out, error));
  EXPECT_EQ(error, dir.file("missing.png") + ": cannot open: No such file or directory");
}

TEST(ImageIoErrors, RandomByteFlipsNeverCrash) {
  TmpDir dir("lr_image_test");
  const ImageRgb8 img = random_image(24, 24, 8);
  std::string error;
  ASSERT_TRUE(write_png(dir.file("ok.png"), img, error));
  const std::vector<uint8_t> good = read_bytes(dir.file("ok.png"));
  std::mt19937 rng(9);
  for (int iter = 0; iter < 300; ++iter) {
    std::vector<uint8_t> bad = good;
    const int flips = 1 + static_cast<int>(rng() % 3);
    for (int k = 0; k < flips; ++k)
      bad[8 + rng() % (bad.size() - 8)] ^= static_cast<uint8_t>(1 + rng() % 255);
    write_bytes(dir.file("f.png"), bad);
    ImageRgb8 out;
    if (read_png(dir.file("f.png"), out, error)) {
      EXPECT_EQ(out.rgb.size(),
                static_cast<size_t>(out.width) * static_cast<size_t>(out.height) * 3);
    } else {
      EXPECT_EQ(error.rfind(dir.file("f.png") + ": ", 0), 0u);
    }
  }
}

TEST(ImageIoErrors, HugeDimensionsAreRefusedBeforeAllocating) {
  TmpDir dir("lr_image_test");
  // A valid 1x1 PNG whose IHDR is then patched to 100000 x 100000 (CRC fixed up).
  const std::vector<uint8_t> px = {1, 2, 3};
  ASSERT_TRUE(write_raw_png(raw_png(dir.file("one.png"), 1, 1, 8, PNG_COLOR_TYPE_RGB, px, 3)));
  std::vector<uint8_t> data = read_bytes(dir.file("one.png"));
  const uint8_t big[4] = {0x00, 0x01, 0x86, 0xA0};  // 100000
  for (size_t i = 0; i < 4; ++i) data[16 + i] = data[20 + i] = big[i];
  const uLong crc = crc32(crc32(0, nullptr, 0), data.data() + 12, 17);
  for (size_t i = 0; i < 4; ++i) data[29 + i] = static_cast<uint8_t>(crc >> (24 - 8 * i));
  write_bytes(dir.file("huge.png"), data);
  ImageRgb8 out;
  std::string error;
  EXPECT_FALSE(read_png(dir.file("huge.png"), out, error));
  EXPECT_EQ(error.rfind(dir.file("huge.png") + ": ", 0), 0u);
  write_bytes(dir.file("huge.ppm"), {'P', '6', ' ', '9', '9', '9', '9', '9', ' ', '9', '9', '9',
                                     '9', '9', ' ', '2', '5', '5', '\n'});
  EXPECT_FALSE(read_ppm(dir.file("huge.ppm"), out, error));
  EXPECT_EQ(error, dir.file("huge.ppm") + ": unsupported image size 99999x99999");
}

TEST(ImageIoErrors, WriteIntoMissingDirectoryFailsAndLeavesNoFile) {
  TmpDir dir("lr_image_test");
  const ImageRgb8 img = random_image(4, 4, 10);
  std::string error;
  const std::string png = dir.file("no/such/dir/a.png");
  EXPECT_FALSE(write_png(png, img, error));
  EXPECT_EQ(error, png + ": cannot open for writing: No such file or directory");
  EXPECT_FALSE(exists(png));
  const std::string ppm = dir.file("no/such/dir/a.ppm");
  EXPECT_FALSE(write_ppm(ppm, img, error));
  EXPECT_EQ(error, ppm + ": cannot open for writing: No such file or directory");
  EXPECT_FALSE(exists(ppm));
  EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageIoErrors, InvalidImageIsRefusedAndExistingFileKept) {
  TmpDir dir("lr_image_test");
  const ImageRgb8 img = random_image(4, 4, 11);
  std::string error;
  ASSERT_TRUE(write_png(dir.file("keep.png"), img, error));
  const std::vector<uint8_t> before = read_bytes(dir.file("keep.png"));
  ImageRgb8 bad = img;
  bad.rgb.pop_back();
  EXPECT_FALSE(write_png(dir.file("keep.png"), bad, error));
  EXPECT_EQ(error,
            dir.file("keep.png") + ": invalid image (4x4 with 47 bytes; sides must be 1..16384)");
  EXPECT_EQ(read_bytes(dir.file("keep.png")), before);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"keep.png"});  // no temporary file left
  ImageRgb8 empty;
  EXPECT_FALSE(write_ppm(dir.file("e.ppm"), empty, error));
  EXPECT_FALSE(exists(dir.file("e.ppm")));
}

// --- PPM / PGM reading --------------------------------------------------------------------------

ImageRgb8 read_ppm_text(const TmpDir& dir, const std::string& content, bool expect_ok,
                        std::string* error_out = nullptr) {
  write_bytes(dir.file("p.ppm"), std::vector<uint8_t>(content.begin(), content.end()));
  ImageRgb8 img;
  std::string error;
  EXPECT_EQ(read_ppm(dir.file("p.ppm"), img, error), expect_ok) << error;
  if (error_out) *error_out = error;
  return img;
}

TEST(ImageIoPpm, AsciiP3WithComments) {
  TmpDir dir("lr_image_test");
  const ImageRgb8 img = read_ppm_text(dir,
                                      "P3\n# a comment\n2 # width\n1\n255\n"
                                      "255 0 0  # red\n 0 128 7\n",
                                      true);
  EXPECT_EQ(img.width, 2);
  EXPECT_EQ(img.height, 1);
  EXPECT_EQ(img.rgb, (std::vector<uint8_t>{255, 0, 0, 0, 128, 7}));
}

TEST(ImageIoPpm, OtherMaxvalsAreScaled) {
  TmpDir dir("lr_image_test");
  ImageRgb8 img = read_ppm_text(dir, "P3 1 1 15 15 7 0", true);
  EXPECT_EQ(img.rgb, (std::vector<uint8_t>{255, 119, 0}));
  // P6 with 16-bit big-endian samples.
  const std::string p6 = std::string("P6 2 1 65535\n") + '\xFF' + '\xFF' + '\x12' + '\xFF' + '\0' +
                         '\0' + '\x80' + '\x80' + '\x00' + '\x80' + '\x7F' + '\x7F';
  img = read_ppm_text(dir, p6, true);
  EXPECT_EQ(img.rgb, (std::vector<uint8_t>{255, scale16(0x12FF), 0, scale16(0x8080),
                                           scale16(0x0080), scale16(0x7F7F)}));
}

TEST(ImageIoPpm, GreyPgmIsReplicated) {
  TmpDir dir("lr_image_test");
  ImageRgb8 img =
      read_ppm_text(dir, std::string("P5\n3 1\n255\n") + '\x00' + '\x40' + '\xFF', true);
  EXPECT_EQ(img.rgb, (std::vector<uint8_t>{0, 0, 0, 64, 64, 64, 255, 255, 255}));
  img = read_ppm_text(dir, "P2 2 1 1 1 0", true);
  EXPECT_EQ(img.rgb, (std::vector<uint8_t>{255, 255, 255, 0, 0, 0}));
}

TEST(ImageIoPpm, MalformedFilesGiveErrors) {
  TmpDir dir("lr_image_test");
  const std::string f = dir.file("p.ppm");
  std::string error;
  read_ppm_text(dir, "P6\n2 2\n255\nabc", false, &error);
  EXPECT_EQ(error, f + ": truncated pixel data");
  read_ppm_text(dir, "P3 1 1 255 1 2", false, &error);
  EXPECT_EQ(error, f + ": truncated pixel data");
  read_ppm_text(dir, "P3 1 1 100 1 2 101", false, &error);
  EXPECT_EQ(error, f + ": sample above maxval");
  read_ppm_text(dir, "P3 1 1 255 1 x 3", false, &error);
  EXPECT_EQ(error, f + ": bad sample in pixel data");
  read_ppm_text(dir, "P7 1 1 255\n", false, &error);
  EXPECT_EQ(error, f + ": not a PPM/PGM file (expected P2, P3, P5 or P6)");
  read_ppm_text(dir, "P6 0 1 255\n", false, &error);
  EXPECT_EQ(error, f + ": unsupported image size 0x1");
  read_ppm_text(dir, "P6 1 1 0\n", false, &error);
  EXPECT_EQ(error, f + ": maxval 0 out of range 1..65535");
  read_ppm_text(dir, "P6 1 1 65536\n", false, &error);
  EXPECT_EQ(error, f + ": maxval 65536 out of range 1..65535");
  read_ppm_text(dir, "P6 1x 1 255\n", false, &error);
  EXPECT_EQ(error, f + ": bad or missing width");
  read_ppm_text(dir, "P6 1 ", false, &error);
  EXPECT_EQ(error, f + ": bad or missing height");
  read_ppm_text(dir, "P6 1 1 99999999999999999999\n", false, &error);
  EXPECT_EQ(error, f + ": header value too large: maxval");
  read_ppm_text(dir, "", false, &error);
  EXPECT_EQ(error, f + ": not a PPM/PGM file (expected P2, P3, P5 or P6)");
}

}  // namespace
}  // namespace lr::host
