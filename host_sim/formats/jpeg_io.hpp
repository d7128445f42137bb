// JPEG images in, through libjpeg (Debian's libjpeg-dev: libjpeg-turbo): textures as people have
// them. Baseline and progressive, greyscale, YCbCr and CMYK; the image as 8-bit RGB, top row
// first, like read_png. Built only where libjpeg was found (LR_HAVE_JPEG); elsewhere
// read_jpeg fails with a message that says so.
#pragma once

#include <string>
#include <string_view>

#include "lineraster/host_sim/formats/image_io.hpp"

namespace lr::host {

// False with one line "PATH: what is wrong" (a missing file, a truncated or corrupt stream, a
// size beyond the limits of read_png) and `out` untouched.
bool read_jpeg(const std::string& path, ImageRgb8& out, std::string& error);

// Whether read_jpeg can read anything in this build.
bool jpeg_supported();

// A name ending in .jpg or .jpeg, in any case.
bool is_jpeg_name(std::string_view path);

}  // namespace lr::host
