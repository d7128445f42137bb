// Fuzz target: the image readers (PNG, PPM / PGM, JPEG) and texture loading (see
// fuzz_targets.hpp).
#include <string>
#include <utility>

#include "lineraster/core/texture/mipmap.hpp"
#include "lineraster/core/texture/texture.hpp"
#include "lineraster/host_sim/formats/image_io.hpp"
#include "lineraster/host_sim/formats/jpeg_io.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "tests/fuzz/fuzz_files.hpp"
#include "tests/fuzz/fuzz_targets.hpp"

namespace lr::fuzz {
namespace {

void check_image(const host::ImageRgb8& img) {
  LR_FUZZ_CHECK(img.width >= 1 && img.height >= 1 && img.width <= 16384 && img.height <= 16384);
  LR_FUZZ_CHECK(img.rgb.size() == size_t(img.width) * size_t(img.height) * 3);
}

// A texture made from `img` is valid, has the image's size and level count, and (RGB888, L8 of a
// grey image) holds the image's bottom-left pixel in storage row 0, column 0.
void check_texture(const host::HostTexture& t, const host::ImageRgb8& img, TexelFormat format,
                   bool mipmaps) {
  LR_FUZZ_CHECK(validate(t.texture) == Status::kOk);
  LR_FUZZ_CHECK(t.texture.format == format);
  LR_FUZZ_CHECK(t.texture.levels[0].width == img.width && t.texture.levels[0].height == img.height);
  const int levels =
      mipmaps ? mip_level_count(t.texture.levels[0].width, t.texture.levels[0].height) : 1;
  LR_FUZZ_CHECK(t.texture.level_count == levels);
  const size_t bottom_left = size_t(img.height - 1) * size_t(img.width) * 3;
  const Rgb8 expect{img.rgb[bottom_left], img.rgb[bottom_left + 1], img.rgb[bottom_left + 2]};
  if (format == TexelFormat::kRgb888) LR_FUZZ_CHECK(host::texel_rgb8(t.texture, 0, 0, 0) == expect);
  if (format == TexelFormat::kPalette8) LR_FUZZ_CHECK(t.palette.size() <= 256);
}

}  // namespace

int png_target(const uint8_t* data, size_t size) {
  static MemFile file;
  file.set(data, size);
  // read_image picks the reader by content (PNG signature, else PPM / PGM magic); JPEG's reader
  // is chosen by name, so it reads every input too.
  std::string error;
  host::ImageRgb8 src;
  {
    host::ImageRgb8 jpeg;
    if (host::read_jpeg(file.path(), jpeg, error)) {
      check_image(jpeg);
    } else {
      LR_FUZZ_CHECK(!error.empty() && jpeg.rgb.empty());
    }
    error.clear();
  }
  const bool ok = host::read_image(file.path(), src, error);
  if (!ok) {
    LR_FUZZ_CHECK(!error.empty() && src.rgb.empty());
    return 0;
  }
  check_image(src);
  const bool is_png = size >= 8 && data[0] == 0x89 && data[1] == 'P';

  // load_texture from the file (PNG only; images too large for a texture are not decoded again),
  // then every format from memory for images up to 64 K texels.
  const bool fits = src.width <= kMaxTextureSize && src.height <= kMaxTextureSize;
  if (is_png && fits) {
    host::HostTexture tex;
    error.clear();
    LR_FUZZ_CHECK(host::load_texture(file.path(), TexelFormat::kRgb565, true, tex, error));
    check_texture(tex, src, TexelFormat::kRgb565, true);
    host::HostTexture copy = tex;  // copies and moves re-point the levels
    host::HostTexture moved = std::move(tex);
    LR_FUZZ_CHECK(validate(copy.texture) == Status::kOk);
    LR_FUZZ_CHECK(validate(moved.texture) == Status::kOk);
    LR_FUZZ_CHECK(tex.texture.level_count == 0);
  }
  if (!fits || size_t(src.width) * size_t(src.height) > (size_t{1} << 16)) return 0;
  for (TexelFormat f :
       {TexelFormat::kRgb565, TexelFormat::kRgb888, TexelFormat::kL8, TexelFormat::kPalette8}) {
    for (bool mipmaps : {false, true}) {
      host::HostTexture tex;
      error.clear();
      if (host::texture_from_image(src, f, mipmaps, tex, error)) {
        check_texture(tex, src, f, mipmaps);
      } else {
        // Only a palette of more than 256 colours may fail.
        LR_FUZZ_CHECK(f == TexelFormat::kPalette8 && !error.empty());
      }
    }
  }
  return 0;
}

}  // namespace lr::fuzz
