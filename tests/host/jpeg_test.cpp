// JPEG textures: images written here with libjpeg read back within the codec's error, as RGB top
// row first; bad files give one line "PATH: ..." and leave the image untouched.
#include "lineraster/host_sim/formats/jpeg_io.hpp"

#include <gtest/gtest.h>
#include <jpeglib.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "lineraster/host_sim/formats/texture_load.hpp"
#include "tests/support/tmp_dir.hpp"

namespace lr::host {
namespace {

// Writes `img` (RGB, or grey when `grey`: the red channel) as a baseline JPEG, 4:4:4.
void write_jpeg(const std::string& path, const ImageRgb8& img, int quality, bool grey) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  jpeg_compress_struct c{};
  jpeg_error_mgr err{};
  c.err = jpeg_std_error(&err);
  jpeg_create_compress(&c);
  jpeg_stdio_dest(&c, f);
  c.image_width = static_cast<JDIMENSION>(img.width);
  c.image_height = static_cast<JDIMENSION>(img.height);
  c.input_components = grey ? 1 : 3;
  c.in_color_space = grey ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&c);
  jpeg_set_quality(&c, quality, TRUE);
  for (int i = 0; i < c.num_components; ++i)
    c.comp_info[i].h_samp_factor = c.comp_info[i].v_samp_factor = 1;
  jpeg_start_compress(&c, TRUE);
  std::vector<uint8_t> row(static_cast<size_t>(img.width) * 3);
  while (c.next_scanline < c.image_height) {
    const uint8_t* src =
        img.rgb.data() + size_t{c.next_scanline} * static_cast<size_t>(img.width) * 3;
    for (size_t x = 0; x < static_cast<size_t>(img.width); ++x)
      for (size_t k = 0; k < 3; ++k) row[grey ? x : 3 * x + k] = src[3 * x + (grey ? 0 : k)];
    JSAMPROW r = row.data();
    jpeg_write_scanlines(&c, &r, 1);
  }
  jpeg_finish_compress(&c);
  jpeg_destroy_compress(&c);
  std::fclose(f);
}

// A smooth image: a JPEG holds it closely.
ImageRgb8 gradient(int w, int h) {
  ImageRgb8 img;
  img.width = w;
  img.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.rgb.insert(img.rgb.end(), {static_cast<uint8_t>(255 * x / (w - 1)),
                                     static_cast<uint8_t>(255 * y / (h - 1)),
                                     static_cast<uint8_t>(128 + 100 * (x - y) / (w + h))});
  return img;
}

TEST(Jpeg, ReadsWhatLibjpegWroteWithinTheCodecsError) {
  ASSERT_TRUE(jpeg_supported());
  test::TmpDir dir("lr_jpeg_test");
  const ImageRgb8 want = gradient(64, 48);
  const std::string path = dir.file("g.jpg");
  write_jpeg(path, want, 95, false);
  ImageRgb8 got;
  std::string error;
  ASSERT_TRUE(read_jpeg(path, got, error)) << error;
  ASSERT_EQ(got.width, 64);
  ASSERT_EQ(got.height, 48);
  ASSERT_EQ(got.rgb.size(), want.rgb.size());
  int worst = 0;
  double sum = 0;
  for (size_t i = 0; i < want.rgb.size(); ++i) {
    const int d = std::abs(int{got.rgb[i]} - int{want.rgb[i]});
    worst = std::max(worst, d);
    sum += d;
  }
  EXPECT_LE(worst, 12);
  EXPECT_LE(sum / static_cast<double>(want.rgb.size()), 2.0);
  // The top row first, as read_png: the top-left pixel is dark red-free, the bottom-left green.
  EXPECT_LT(got.rgb[0], 16);
  EXPECT_LT(got.rgb[1], 16);
  EXPECT_GT(got.rgb[(47 * 64) * 3 + 1], 240);
}

TEST(Jpeg, GreyImagesComeBackAsEqualChannels) {
  test::TmpDir dir("lr_jpeg_test");
  const std::string path = dir.file("grey.JPEG");
  write_jpeg(path, gradient(32, 32), 90, true);
  ImageRgb8 got;
  std::string error;
  ASSERT_TRUE(read_jpeg(path, got, error)) << error;
  for (size_t p = 0; p < got.rgb.size() / 3; ++p) {
    ASSERT_EQ(got.rgb[3 * p], got.rgb[3 * p + 1]);
    ASSERT_EQ(got.rgb[3 * p], got.rgb[3 * p + 2]);
  }
  // As a texture, by its name (any case of .jpg / .jpeg).
  HostTexture t;
  ASSERT_TRUE(load_texture(path, TexelFormat::kRgb888, true, t, error)) << error;
  EXPECT_EQ(t.texture.levels[0].width, 32);
  EXPECT_EQ(t.texture.level_count, 6);
}

TEST(Jpeg, BadFilesAreOneLineErrorsAndLeaveTheImage) {
  test::TmpDir dir("lr_jpeg_test");
  const std::string good = dir.file("good.jpg");
  write_jpeg(good, gradient(64, 48), 90, false);
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 200u);
  std::ofstream(dir.file("half.jpg"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  std::ofstream(dir.file("empty.jpg"), std::ios::binary) << "";
  std::ofstream(dir.file("text.jpg"), std::ios::binary) << "not a JPEG at all\n";
  std::string corrupt = bytes;
  for (size_t i = 2; i < 40; ++i) corrupt[i] = '\x55';  // the header's markers
  std::ofstream(dir.file("corrupt.jpg"), std::ios::binary) << corrupt;
  struct Case {
    std::string file, expect;
  };
  const Case cases[] = {
      {"missing.jpg", ": cannot open: No such file or directory"},
      {"half.jpg", ": not a readable JPEG: "},
      {"empty.jpg", ": not a readable JPEG: "},
      {"text.jpg", ": not a readable JPEG: "},
      {"corrupt.jpg", ": not a readable JPEG: "},
  };
  for (const Case& c : cases) {
    ImageRgb8 img;
    img.width = 7;
    std::string error;
    EXPECT_FALSE(read_jpeg(dir.file(c.file), img, error)) << c.file;
    EXPECT_EQ(error.rfind(dir.file(c.file) + c.expect, 0), 0u) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    EXPECT_EQ(img.width, 7) << c.file;
    HostTexture t;
    EXPECT_FALSE(load_texture(dir.file(c.file), TexelFormat::kRgb565, false, t, error));
  }
}

}  // namespace
}  // namespace lr::host
