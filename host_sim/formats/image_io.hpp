// Image files for the host simulator: PNG (libpng) and binary/ASCII PPM. Host only.
//
// Every function returns false on failure with `error` set to one line "FILE: what is wrong" and,
// for readers, `out` left untouched. Writers write regular files only and never leave a partial
// file: through output_file.hpp (a temporary file beside the target, renamed over it once
// complete; a device, FIFO, socket or directory is refused, a symbolic link followed).
// Readers accept images up to 16384 pixels per side and 64 Mpixel in all (larger: error), so a
// corrupt header cannot make them allocate gigabytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lr::host {

// 8-bit RGB image, rows top to bottom (row 0 = top, docs/conventions.md#coordinates), 3 bytes per
// pixel, no padding: rgb.size() == width * height * 3.
struct ImageRgb8 {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
};

// PNG, 8-bit RGB, not interlaced.
bool write_png(const std::string& path, const ImageRgb8& image, std::string& error);
// Binary PPM (P6, maxval 255).
bool write_ppm(const std::string& path, const ImageRgb8& image, std::string& error);
// By extension: .png or .ppm (case-insensitive); anything else is an error.
bool write_image(const std::string& path, const ImageRgb8& image, std::string& error);
// 16-bit greyscale PNG (for depth output): `samples` holds width * height values, row 0 = top.
bool write_png_gray16(const std::string& path, int width, int height,
                      const std::vector<uint16_t>& samples, std::string& error);

// Any PNG colour type and bit depth -> RGB8: grey (1/2/4/8/16 bit) is replicated, palettes are
// expanded, alpha (and tRNS) is dropped without compositing, 16-bit samples are scaled to 8 bits
// with rounding (round(v * 255 / 65535)), interlaced images are de-interlaced. No gamma correction.
bool read_png(const std::string& path, ImageRgb8& out, std::string& error);
// PPM P6 (binary) and P3 (ASCII), also the greyscale PGM forms P5 and P2 (grey replicated to RGB);
// '#' comments in the header; maxval 1..65535 (two bytes per binary sample above 255, big-endian),
// converted to 8 bits as round(v * 255 / maxval); a sample above maxval is an error.
bool read_ppm(const std::string& path, ImageRgb8& out, std::string& error);
// By content: the PNG signature or a 'P2'/'P3'/'P5'/'P6' magic; anything else is an error.
bool read_image(const std::string& path, ImageRgb8& out, std::string& error);

}  // namespace lr::host
