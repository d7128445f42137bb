// Test PNGs written with libpng directly: any colour type, bit depth and interlace, with an
// optional PLTE and tRNS, from packed rows as they stand in the file (to feed the readers inputs
// that the project's own writer never makes).
#pragma once

#include <png.h>

#include <cmath>
#include <csetjmp>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace lr::test {

struct RawPng {
  std::string path;  // used only outside the setjmp frame
  uint32_t width, height;
  int bit_depth, color_type, interlace;
  const uint8_t* rows;  // packed rows, big-endian 16-bit samples, `stride` bytes each
  size_t stride;
  const png_color* palette;  // PLTE, if not null
  int palette_size;
  const png_byte* trns;  // tRNS (palette alphas), if not null
  int trns_size;
};

// The libpng calls under setjmp: this frame holds no C++ objects (a longjmp skips destructors).
inline bool write_raw_png_impl(const RawPng* r, png_structp png, png_infop info, std::FILE* f) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, f);
  png_set_IHDR(png, info, r->width, r->height, r->bit_depth, r->color_type, r->interlace,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (r->palette) png_set_PLTE(png, info, r->palette, r->palette_size);
  if (r->trns) png_set_tRNS(png, info, r->trns, r->trns_size, nullptr);
  png_write_info(png, info);
  const int passes = png_set_interlace_handling(png);
  for (int pass = 0; pass < passes; ++pass) {
    for (uint32_t y = 0; y < r->height; ++y) png_write_row(png, r->rows + y * r->stride);
  }
  png_write_end(png, nullptr);
  return true;
}

// Writes `r` to r.path; false if the file cannot be opened or libpng rejects the parameters.
inline bool write_raw_png(const RawPng& r) {
  std::FILE* f = std::fopen(r.path.c_str(), "wb");
  if (!f) return false;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  const bool ok = write_raw_png_impl(&r, png, info, f);
  png_destroy_write_struct(&png, &info);
  std::fclose(f);
  return ok;
}

// A non-interlaced PNG without PLTE or tRNS (set those fields afterwards if needed). `rows` must
// outlive the RawPng.
inline RawPng raw_png(const std::string& path, uint32_t w, uint32_t h, int depth, int type,
                      const std::vector<uint8_t>& rows, size_t stride) {
  return RawPng{path,        w,      h,       depth, type,    PNG_INTERLACE_NONE,
                rows.data(), stride, nullptr, 0,     nullptr, 0};
}

// The 8-bit value a 16-bit sample should read as (rounded to nearest).
inline uint8_t scale16(unsigned v) {
  return static_cast<uint8_t>(std::lround(v * 255.0 / 65535.0));
}

}  // namespace lr::test
