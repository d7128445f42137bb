#include "lineraster/host_sim/formats/jpeg_io.hpp"

#include <cerrno>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#ifdef LR_HAVE_JPEG
#include <jpeglib.h>
#endif

namespace lr::host {

bool is_jpeg_name(std::string_view path) {
  const size_t dot = path.rfind('.');
  if (dot == std::string_view::npos) return false;
  std::string ext(path.substr(dot + 1));
  for (char& c : ext) c = (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  return ext == "jpg" || ext == "jpeg";
}

#ifdef LR_HAVE_JPEG

bool jpeg_supported() {
  return true;
}

namespace {

// The same limits as PNG's (image_io.cpp): 16384 per side, 64 Mpixels.
constexpr JDIMENSION kMaxSide = 16384;
constexpr uint64_t kMaxPixels = uint64_t{64} << 20;

// libjpeg reports errors through error_exit, which must not return: back to the setjmp in
// decode(), with the library's message kept.
struct ErrorManager {
  jpeg_error_mgr base;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void on_error(j_common_ptr cinfo) {
  auto* e = reinterpret_cast<ErrorManager*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, e->message);
  std::longjmp(e->jump, 1);
}

// A warning (level -1: a truncated file, corrupt data that libjpeg would paint grey) is an error
// here: the texture would be drawn wrong in silence. Trace messages (level >= 0) are ignored.
void on_message(j_common_ptr cinfo, int level) {
  if (level < 0) on_error(cinfo);
}

// Decodes into `rgb` (and `cmyk`, a row's scratch for CMYK files), both the caller's: the
// longjmp from on_error lands in this frame and skips only libjpeg's, where nothing has a
// destructor. `what` is set on failure.
bool decode(std::FILE* f, std::vector<uint8_t>& rgb, std::vector<uint8_t>& cmyk, int& width,
            int& height, const char*& what, ErrorManager& err, jpeg_decompress_struct& cinfo) {
  cinfo.err = jpeg_std_error(&err.base);
  err.base.error_exit = on_error;
  err.base.emit_message = on_message;
  if (setjmp(err.jump)) {
    jpeg_destroy_decompress(&cinfo);
    what = err.message;
    return false;
  }
  jpeg_create_decompress(&cinfo);
  cinfo.mem->max_memory_to_use = 512L << 20;  // a corrupt progressive header's buffers
  jpeg_stdio_src(&cinfo, f);
  jpeg_read_header(&cinfo, TRUE);
  if (cinfo.image_width < 1 || cinfo.image_height < 1 || cinfo.image_width > kMaxSide ||
      cinfo.image_height > kMaxSide ||
      uint64_t{cinfo.image_width} * cinfo.image_height > kMaxPixels) {
    jpeg_destroy_decompress(&cinfo);
    what = "unsupported image size";
    return false;
  }
  // CMYK and YCCK (Adobe's, stored inverted) are converted here; libjpeg turns the rest into RGB.
  const bool is_cmyk = cinfo.jpeg_color_space == JCS_CMYK || cinfo.jpeg_color_space == JCS_YCCK;
  cinfo.out_color_space = is_cmyk ? JCS_CMYK : JCS_RGB;
  jpeg_start_decompress(&cinfo);
  const JDIMENSION w = cinfo.output_width, h = cinfo.output_height;
  rgb.resize(size_t{w} * h * 3);
  if (is_cmyk) cmyk.resize(size_t{w} * 4);
  while (cinfo.output_scanline < h) {
    uint8_t* dst = rgb.data() + size_t{cinfo.output_scanline} * w * 3;
    JSAMPROW row = is_cmyk ? cmyk.data() : dst;
    jpeg_read_scanlines(&cinfo, &row, 1);
    if (!is_cmyk) continue;
    for (JDIMENSION x = 0; x < w; ++x) {
      const unsigned k = cmyk[4 * x + 3];
      for (size_t c = 0; c < 3; ++c)
        dst[3 * x + c] = static_cast<uint8_t>(cmyk[4 * x + c] * k / 255);
    }
  }
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  width = static_cast<int>(w);
  height = static_cast<int>(h);
  return true;
}

}  // namespace

bool read_jpeg(const std::string& path, ImageRgb8& out, std::string& error) {
  if (path.find('\0') != std::string::npos) {
    error = path + ": cannot open: invalid file name";
    return false;
  }
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    error = path + ": cannot open: " + std::strerror(errno != 0 ? errno : EIO);
    return false;
  }
  std::vector<uint8_t> rgb, cmyk;
  int w = 0, h = 0;
  const char* what = "";
  ErrorManager err{};
  jpeg_decompress_struct cinfo{};
  const bool ok = decode(f, rgb, cmyk, w, h, what, err, cinfo);
  std::fclose(f);
  if (!ok) {
    error = path + ": not a readable JPEG: " + what;
    return false;
  }
  out.width = w;
  out.height = h;
  out.rgb = std::move(rgb);
  return true;
}

#else

bool jpeg_supported() {
  return false;
}

bool read_jpeg(const std::string& path, ImageRgb8& /*out*/, std::string& error) {
  error = path +
          ": JPEG textures need libjpeg, which this build was made without (install "
          "libjpeg-dev and configure again)";
  return false;
}

#endif

}  // namespace lr::host
