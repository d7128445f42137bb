// Image files: PNG through libpng, PPM/PGM by hand (see image_io.hpp).
//
// libpng reports errors with longjmp. Every function that calls setjmp here (png_write_all,
// png_read_header, png_read_pixels) has only trivially destructible locals, keeps its state in a
// context struct owned by its caller, and calls only C functions and callbacks that have no C++
// objects either; the png structs are destroyed by the caller whatever happened.
#include "lineraster/host_sim/formats/image_io.hpp"

#include <png.h>

#include <bit>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "lineraster/host_sim/formats/output_file.hpp"

namespace lr::host {
namespace {

constexpr int kMaxSide = 16384;
constexpr uint64_t kMaxPixels = uint64_t{64} << 20;

bool fail(std::string& error, const std::string& path, const std::string& what) {
  error = path + ": " + what;
  return false;
}

bool size_ok(uint64_t w, uint64_t h) {
  return w >= 1 && h >= 1 && w <= kMaxSide && h <= kMaxSide && w * h <= kMaxPixels;
}

std::string size_text(uint64_t w, uint64_t h) {
  return std::to_string(w) + "x" + std::to_string(h);
}

// fopen that refuses names with an embedded NUL (c_str() would silently cut them).
std::FILE* open_file(const std::string& path, const char* mode) {
  if (path.find('\0') != std::string::npos) {
    errno = EINVAL;
    return nullptr;
  }
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), mode);
  if (!f && errno == 0) errno = EIO;
  return f;
}

std::string lower_extension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return ext;
}

// ---------------------------------------------------------------------------------------------
// libpng glue

struct PngMessage {
  char text[256];
};

void png_on_error(png_structp png, png_const_charp msg) {
  auto* m = static_cast<PngMessage*>(png_get_error_ptr(png));
  if (m) std::snprintf(m->text, sizeof m->text, "%s", msg ? msg : "libpng error");
  png_longjmp(png, 1);
}

void png_on_warning(png_structp, png_const_charp) {}

// libpng's own allocations (chunk buffers, row buffers, zlib state) go through this cap: a
// corrupt chunk length made libpng 1.6.39 allocate 1.6 GB for a 112-byte file (found by the PNG
// fuzzer). Refusing makes libpng report "out of memory" through png_on_error. Pixels are read
// into our own vector, so its largest legitimate allocation is a row: far below the cap.
constexpr png_alloc_size_t kMaxLibpngAlloc = png_alloc_size_t{64} << 20;
png_voidp png_capped_malloc(png_structp, png_alloc_size_t size) {
  return size > kMaxLibpngAlloc ? nullptr : std::malloc(size);
}
void png_capped_free(png_structp, png_voidp p) {
  std::free(p);
}

struct PngWriteCtx {
  PngMessage msg;
  std::FILE* fp;
  png_structp png;
  png_infop info;
  const uint8_t* data;
  uint32_t width, height;
  size_t stride;
  int bit_depth, color_type;
  bool swap16;  // 16-bit samples are in host (little-endian) order
};

bool png_write_all(PngWriteCtx* c) {
  if (setjmp(png_jmpbuf(c->png))) return false;
  png_init_io(c->png, c->fp);
  png_set_IHDR(c->png, c->info, c->width, c->height, c->bit_depth, c->color_type,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(c->png, c->info);
  if (c->swap16) png_set_swap(c->png);
  for (uint32_t y = 0; y < c->height; ++y) png_write_row(c->png, c->data + y * c->stride);
  png_write_end(c->png, nullptr);
  return true;
}

bool write_png_data(const std::string& path, const uint8_t* data, int width, int height,
                    int bit_depth, int color_type, size_t stride, bool swap16, std::string& error) {
  return write_output(path, error, [&](std::FILE* f, std::string& what) {
    PngWriteCtx ctx{};
    std::snprintf(ctx.msg.text, sizeof ctx.msg.text, "libpng error");
    ctx.fp = f;
    ctx.data = data;
    ctx.width = static_cast<uint32_t>(width);
    ctx.height = static_cast<uint32_t>(height);
    ctx.stride = stride;
    ctx.bit_depth = bit_depth;
    ctx.color_type = color_type;
    ctx.swap16 = swap16;
    ctx.png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &ctx.msg, png_on_error, png_on_warning);
    if (!ctx.png) {
      what = "cannot initialise libpng";
      return false;
    }
    ctx.info = png_create_info_struct(ctx.png);
    errno = 0;
    const bool ok = ctx.info && png_write_all(&ctx);
    // The reason, before png_destroy_write_struct clears ctx.info: libpng's message, or for a
    // failed write ("Write Error") the system's.
    if (!ok && ctx.info == nullptr)
      what = "cannot initialise libpng";
    else if (!ok && std::ferror(f) != 0 && errno != 0)
      what = std::string("write failed: ") + std::strerror(errno);
    else if (!ok)
      what = ctx.msg.text;
    png_destroy_write_struct(&ctx.png, &ctx.info);
    return ok;
  });
}

struct PngReadCtx {
  PngMessage msg;
  std::FILE* fp;
  png_structp png;
  png_infop info;
  uint32_t width, height;
  size_t rowbytes;
  int passes;
};

void png_read_data(png_structp png, png_bytep data, size_t length) {
  auto* c = static_cast<PngReadCtx*>(png_get_io_ptr(png));
  if (std::fread(data, 1, length, c->fp) != length) {
    png_error(png, std::ferror(c->fp) ? "read error" : "truncated file (unexpected end of data)");
  }
}

bool png_read_header(PngReadCtx* c) {
  if (setjmp(png_jmpbuf(c->png))) return false;
  png_set_read_fn(c->png, c, png_read_data);
  png_set_sig_bytes(c->png, 8);
  png_set_user_limits(c->png, kMaxSide, kMaxSide);
  png_read_info(c->png, c->info);
  c->width = png_get_image_width(c->png, c->info);
  c->height = png_get_image_height(c->png, c->info);
  if (!size_ok(c->width, c->height)) png_error(c->png, "image too large");
  png_set_expand(c->png);       // palette -> RGB, grey < 8 bits -> 8 bits, tRNS -> alpha
  png_set_scale_16(c->png);     // 16 -> 8 bits, rounded
  png_set_strip_alpha(c->png);  // alpha dropped, not composited
  png_set_gray_to_rgb(c->png);
  c->passes = png_set_interlace_handling(c->png);
  png_read_update_info(c->png, c->info);
  c->rowbytes = png_get_rowbytes(c->png, c->info);
  if (png_get_channels(c->png, c->info) != 3 || png_get_bit_depth(c->png, c->info) != 8 ||
      c->rowbytes != size_t{c->width} * 3) {
    png_error(c->png, "unsupported pixel format");
  }
  return true;
}

bool png_read_pixels(PngReadCtx* c, uint8_t* dst) {
  if (setjmp(png_jmpbuf(c->png))) return false;
  for (int pass = 0; pass < c->passes; ++pass) {
    for (uint32_t y = 0; y < c->height; ++y) png_read_row(c->png, dst + y * c->rowbytes, nullptr);
  }
  png_read_end(c->png, nullptr);
  return true;
}

// ---------------------------------------------------------------------------------------------
// PPM / PGM header and ASCII samples

// Skips whitespace and '#' comments; returns the next character (or EOF) without consuming it.
int skip_space_and_comments(std::FILE* f) {
  for (;;) {
    int c = std::getc(f);
    if (c == '#') {
      while (c != '\n' && c != '\r' && c != EOF) c = std::getc(f);
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') continue;
    if (c != EOF) std::ungetc(c, f);
    return c;
  }
}

// Reads an unsigned decimal number (at most 9 digits' worth of value) and consumes the one
// character after it when it is whitespace. Returns false on no digits / too large / bad delimiter.
bool read_ascii_uint(std::FILE* f, uint32_t& value, bool& too_large) {
  too_large = false;
  int c = skip_space_and_comments(f);
  if (c < '0' || c > '9') return false;
  uint64_t v = 0;
  while ((c = std::getc(f)) >= '0' && c <= '9') {
    v = v * 10 + static_cast<uint64_t>(c - '0');
    if (v > 999999999) {
      too_large = true;
      return false;
    }
  }
  if (c == '#') {
    std::ungetc(c, f);
  } else if (c != EOF && c != ' ' && c != '\t' && c != '\n' && c != '\r' && c != '\v' &&
             c != '\f') {
    return false;
  }
  value = static_cast<uint32_t>(v);
  return true;
}

uint8_t to_8bit(uint32_t v, uint32_t maxval) {
  return static_cast<uint8_t>((uint64_t{v} * 510 + maxval) / (uint64_t{maxval} * 2));
}

bool read_ppm_file(std::FILE* f, const std::string& path, ImageRgb8& out, std::string& error) {
  char magic[2] = {0, 0};
  if (std::fread(magic, 1, 2, f) != 2 || magic[0] != 'P' ||
      (magic[1] != '2' && magic[1] != '3' && magic[1] != '5' && magic[1] != '6')) {
    return fail(error, path, "not a PPM/PGM file (expected P2, P3, P5 or P6)");
  }
  const bool binary = magic[1] == '5' || magic[1] == '6';
  const int channels = (magic[1] == '3' || magic[1] == '6') ? 3 : 1;
  uint32_t header[3] = {0, 0, 0};
  static const char* const kNames[3] = {"width", "height", "maxval"};
  for (int i = 0; i < 3; ++i) {
    bool too_large = false;
    if (!read_ascii_uint(f, header[i], too_large)) {
      return fail(
          error, path,
          std::string(too_large ? "header value too large: " : "bad or missing ") + kNames[i]);
    }
  }
  const uint32_t w = header[0], h = header[1], maxval = header[2];
  if (!size_ok(w, h)) return fail(error, path, "unsupported image size " + size_text(w, h));
  if (maxval < 1 || maxval > 65535) {
    return fail(error, path, "maxval " + std::to_string(maxval) + " out of range 1..65535");
  }
  const size_t samples = size_t{w} * h * static_cast<size_t>(channels);
  std::vector<uint8_t> rgb(size_t{w} * h * 3);
  auto store = [&](size_t i, uint32_t v) {
    const uint8_t b = to_8bit(v, maxval);
    if (channels == 3) {
      rgb[i] = b;
    } else {
      rgb[i * 3] = rgb[i * 3 + 1] = rgb[i * 3 + 2] = b;
    }
  };
  if (binary) {
    const size_t bps = maxval > 255 ? 2 : 1;
    std::vector<uint8_t> raw(samples * bps);
    if (std::fread(raw.data(), 1, raw.size(), f) != raw.size()) {
      return fail(error, path, "truncated pixel data");
    }
    for (size_t i = 0; i < samples; ++i) {
      const uint32_t v = bps == 2 ? (uint32_t{raw[2 * i]} << 8) | raw[2 * i + 1] : raw[i];
      if (v > maxval) return fail(error, path, "sample above maxval");
      store(i, v);
    }
  } else {
    for (size_t i = 0; i < samples; ++i) {
      uint32_t v = 0;
      bool too_large = false;
      if (!read_ascii_uint(f, v, too_large)) {
        return fail(error, path,
                    std::feof(f) ? "truncated pixel data" : "bad sample in pixel data");
      }
      if (v > maxval) return fail(error, path, "sample above maxval");
      store(i, v);
    }
  }
  if (std::ferror(f)) return fail(error, path, "read error");
  out.width = static_cast<int>(w);
  out.height = static_cast<int>(h);
  out.rgb = std::move(rgb);
  return true;
}

bool image_ok(const ImageRgb8& image) {
  return image.width > 0 && image.height > 0 &&
         size_ok(static_cast<uint64_t>(image.width), static_cast<uint64_t>(image.height)) &&
         image.rgb.size() ==
             static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 3;
}

std::string image_problem(const ImageRgb8& image) {
  return "invalid image (" + std::to_string(image.width) + "x" + std::to_string(image.height) +
         " with " + std::to_string(image.rgb.size()) + " bytes; sides must be 1.." +
         std::to_string(kMaxSide) + ")";
}

}  // namespace

bool write_png(const std::string& path, const ImageRgb8& image, std::string& error) {
  if (!image_ok(image)) return fail(error, path, image_problem(image));
  return write_png_data(path, image.rgb.data(), image.width, image.height, 8, PNG_COLOR_TYPE_RGB,
                        static_cast<size_t>(image.width) * 3, false, error);
}

bool write_png_gray16(const std::string& path, int width, int height,
                      const std::vector<uint16_t>& samples, std::string& error) {
  if (width <= 0 || height <= 0 ||
      !size_ok(static_cast<uint64_t>(width), static_cast<uint64_t>(height)) ||
      samples.size() != static_cast<size_t>(width) * static_cast<size_t>(height)) {
    return fail(error, path,
                "invalid image (" + std::to_string(width) + "x" + std::to_string(height) +
                    " with " + std::to_string(samples.size()) + " samples)");
  }
  return write_png_data(path, reinterpret_cast<const uint8_t*>(samples.data()), width, height, 16,
                        PNG_COLOR_TYPE_GRAY, static_cast<size_t>(width) * 2,
                        std::endian::native == std::endian::little, error);
}

bool write_ppm(const std::string& path, const ImageRgb8& image, std::string& error) {
  if (!image_ok(image)) return fail(error, path, image_problem(image));
  return write_output(path, error, [&](std::FILE* f, std::string& what) {
    const std::string header =
        "P6\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
    if (std::fwrite(header.data(), 1, header.size(), f) != header.size() ||
        std::fwrite(image.rgb.data(), 1, image.rgb.size(), f) != image.rgb.size()) {
      what = std::string("write failed: ") + std::strerror(errno);
      return false;
    }
    return true;
  });
}

bool write_image(const std::string& path, const ImageRgb8& image, std::string& error) {
  const std::string ext = lower_extension(path);
  if (ext == ".png") return write_png(path, image, error);
  if (ext == ".ppm") return write_ppm(path, image, error);
  return fail(error, path, "unknown image extension (expected .png or .ppm)");
}

bool read_png(const std::string& path, ImageRgb8& out, std::string& error) {
  std::FILE* f = open_file(path, "rb");
  if (!f) return fail(error, path, std::string("cannot open: ") + std::strerror(errno));
  png_byte sig[8] = {};
  if (std::fread(sig, 1, 8, f) != 8 || png_sig_cmp(sig, 0, 8) != 0) {
    std::fclose(f);
    return fail(error, path, "not a PNG file");
  }
  PngReadCtx ctx{};
  std::snprintf(ctx.msg.text, sizeof ctx.msg.text, "libpng error");
  ctx.fp = f;
  ctx.png = png_create_read_struct_2(PNG_LIBPNG_VER_STRING, &ctx.msg, png_on_error, png_on_warning,
                                     nullptr, png_capped_malloc, png_capped_free);
  if (ctx.png) ctx.info = png_create_info_struct(ctx.png);
  bool ok = ctx.png && ctx.info && png_read_header(&ctx);
  std::vector<uint8_t> rgb;
  if (ok) {
    rgb.resize(size_t{ctx.width} * ctx.height * 3);
    ok = png_read_pixels(&ctx, rgb.data());
  }
  const bool init_failed = !ctx.png || !ctx.info;
  if (ctx.png) png_destroy_read_struct(&ctx.png, ctx.info ? &ctx.info : nullptr, nullptr);
  std::fclose(f);
  if (!ok) return fail(error, path, init_failed ? "cannot initialise libpng" : ctx.msg.text);
  out.width = static_cast<int>(ctx.width);
  out.height = static_cast<int>(ctx.height);
  out.rgb = std::move(rgb);
  return true;
}

bool read_ppm(const std::string& path, ImageRgb8& out, std::string& error) {
  std::FILE* f = open_file(path, "rb");
  if (!f) return fail(error, path, std::string("cannot open: ") + std::strerror(errno));
  const bool ok = read_ppm_file(f, path, out, error);
  std::fclose(f);
  return ok;
}

bool read_image(const std::string& path, ImageRgb8& out, std::string& error) {
  std::FILE* f = open_file(path, "rb");
  if (!f) return fail(error, path, std::string("cannot open: ") + std::strerror(errno));
  unsigned char head[8] = {};
  const size_t n = std::fread(head, 1, sizeof head, f);
  std::fclose(f);
  if (n == 8 && png_sig_cmp(head, 0, 8) == 0) return read_png(path, out, error);
  if (n >= 2 && head[0] == 'P' &&
      (head[1] == '2' || head[1] == '3' || head[1] == '5' || head[1] == '6')) {
    return read_ppm(path, out, error);
  }
  return fail(error, path, "unknown image format (expected PNG or PPM)");
}

}  // namespace lr::host
