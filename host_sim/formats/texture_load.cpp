#include "lineraster/host_sim/formats/texture_load.hpp"

#include "lineraster/host_sim/formats/jpeg_io.hpp"

#include <utility>

#include "lineraster/core/texture/mipmap.hpp"

namespace lr::host {
namespace {

uint16_t to_rgb565(uint8_t r, uint8_t g, uint8_t b) {
  const unsigned r5 = (31u * r + 127u) / 255u, g6 = (63u * g + 127u) / 255u,
                 b5 = (31u * b + 127u) / 255u;
  return static_cast<uint16_t>((r5 << 11) | (g6 << 5) | b5);
}

Rgb8 expand565(uint16_t v) {
  const unsigned r5 = v >> 11, g6 = (v >> 5) & 63u, b5 = v & 31u;
  return {static_cast<uint8_t>((r5 << 3) | (r5 >> 2)), static_cast<uint8_t>((g6 << 2) | (g6 >> 4)),
          static_cast<uint8_t>((b5 << 3) | (b5 >> 2))};
}

size_t elements_per_texel(TexelFormat f) {
  return f == TexelFormat::kRgb565 ? 1 : bytes_per_texel(f);
}

bool fail(std::string& error, const std::string& name, const std::string& what) {
  error = name + ": " + what;
  return false;
}

bool convert(const ImageRgb8& img, TexelFormat format, bool mipmaps, const std::string& name,
             HostTexture& out, std::string& error) {
  if (img.width < 1 || img.height < 1 ||
      img.rgb.size() != size_t(img.width) * size_t(img.height) * 3)
    return fail(error, name, "invalid image");
  if (img.width > kMaxTextureSize || img.height > kMaxTextureSize)
    return fail(error, name,
                std::to_string(img.width) + "x" + std::to_string(img.height) +
                    " is larger than the largest texture (" + std::to_string(kMaxTextureSize) +
                    "x" + std::to_string(kMaxTextureSize) + ")");
  const size_t w = size_t(img.width), h = size_t(img.height);
  HostTexture t;
  t.texture.format = format;
  t.texture.levels[0].width = static_cast<uint16_t>(w);
  t.texture.levels[0].height = static_cast<uint16_t>(h);
  t.texture.level_count = 1;

  if (format == TexelFormat::kPalette8) {
    // Palette in order of first appearance in the file (top row first).
    std::vector<int> index_of(65536, -1);
    for (size_t p = 0; p < w * h; ++p) {
      const uint16_t c = to_rgb565(img.rgb[3 * p], img.rgb[3 * p + 1], img.rgb[3 * p + 2]);
      if (index_of[c] >= 0) continue;
      if (t.palette.size() == 256)
        return fail(error, name, "more than 256 colours; use rgb565 or rgb888");
      index_of[c] = static_cast<int>(t.palette.size());
      t.palette.push_back(c);
    }
    t.bytes.resize(w * h);
    for (size_t r = 0; r < h; ++r) {
      const size_t src_row = h - 1 - r;
      for (size_t x = 0; x < w; ++x) {
        const uint8_t* s = &img.rgb[(src_row * w + x) * 3];
        t.bytes[r * w + x] = static_cast<uint8_t>(index_of[to_rgb565(s[0], s[1], s[2])]);
      }
    }
  } else if (format == TexelFormat::kRgb565) {
    t.rgb565.resize(w * h);
    for (size_t r = 0; r < h; ++r) {
      const size_t src_row = h - 1 - r;
      for (size_t x = 0; x < w; ++x) {
        const uint8_t* s = &img.rgb[(src_row * w + x) * 3];
        t.rgb565[r * w + x] = to_rgb565(s[0], s[1], s[2]);
      }
    }
  } else {
    const size_t bpt = bytes_per_texel(format);
    t.bytes.resize(w * h * bpt);
    for (size_t r = 0; r < h; ++r) {
      const size_t src_row = h - 1 - r;
      for (size_t x = 0; x < w; ++x) {
        const uint8_t* s = &img.rgb[(src_row * w + x) * 3];
        uint8_t* d = &t.bytes[(r * w + x) * bpt];
        if (format == TexelFormat::kRgb888) {
          d[0] = s[0];
          d[1] = s[1];
          d[2] = s[2];
        } else {
          d[0] = static_cast<uint8_t>((299u * s[0] + 587u * s[1] + 114u * s[2] + 500u) / 1000u);
        }
      }
    }
  }
  t.repoint();

  if (mipmaps) {
    const size_t level0 = w * h * elements_per_texel(format);
    const size_t chain = mip_chain_size(t.texture);
    std::vector<uint16_t>& v565 = t.rgb565;
    std::vector<uint8_t>& vbytes = t.bytes;
    if (format == TexelFormat::kRgb565) {
      v565.resize(level0 + chain);
    } else {
      vbytes.resize(level0 + chain);
    }
    t.repoint();  // resizing may have moved level 0
    const Status s =
        build_mip_chain(t.texture, std::span<uint16_t>(v565).subspan(v565.empty() ? 0 : level0),
                        std::span<uint8_t>(vbytes).subspan(vbytes.empty() ? 0 : level0));
    if (s != Status::kOk) return fail(error, name, std::string("mip chain: ") + to_string(s));
  }
  if (validate(t.texture) != Status::kOk) return fail(error, name, "invalid texture");
  out = std::move(t);
  return true;
}

}  // namespace

HostTexture::HostTexture(const HostTexture& other)
    : texture(other.texture), rgb565(other.rgb565), bytes(other.bytes), palette(other.palette) {
  repoint();
}

HostTexture::HostTexture(HostTexture&& other) noexcept
    : texture(other.texture),
      rgb565(std::move(other.rgb565)),
      bytes(std::move(other.bytes)),
      palette(std::move(other.palette)) {
  repoint();
  other.texture = lr::Texture{};
  other.rgb565.clear();
  other.bytes.clear();
  other.palette.clear();
}

HostTexture& HostTexture::operator=(const HostTexture& other) {
  if (this != &other) {
    texture = other.texture;
    rgb565 = other.rgb565;
    bytes = other.bytes;
    palette = other.palette;
    repoint();
  }
  return *this;
}

HostTexture& HostTexture::operator=(HostTexture&& other) noexcept {
  if (this != &other) {
    texture = other.texture;
    rgb565 = std::move(other.rgb565);
    bytes = std::move(other.bytes);
    palette = std::move(other.palette);
    repoint();
    other.texture = lr::Texture{};
    other.rgb565.clear();
    other.bytes.clear();
    other.palette.clear();
  }
  return *this;
}

void HostTexture::repoint() {
  const bool is565 = texture.format == TexelFormat::kRgb565;
  const size_t per = elements_per_texel(texture.format);
  size_t offset = 0;
  for (size_t i = 0; i < kMaxMipLevels; ++i) {
    TextureLevel& l = texture.levels[i];
    l.rgb565 = {};
    l.bytes = {};
    if (i >= texture.level_count) continue;
    const size_t n = level_texels(l.width, l.height) * per;
    const size_t have = is565 ? rgb565.size() : bytes.size();
    const size_t take = offset <= have ? std::min(n, have - offset) : 0;
    if (is565) {
      l.rgb565 = std::span<const uint16_t>(rgb565).subspan(std::min(offset, have), take);
    } else {
      l.bytes = std::span<const uint8_t>(bytes).subspan(std::min(offset, have), take);
    }
    offset += n;
  }
  texture.palette = palette;
}

bool load_texture(const std::string& png_path, TexelFormat format, bool mipmaps, HostTexture& out,
                  std::string& error) {
  ImageRgb8 img;
  if (!(is_jpeg_name(png_path) ? read_jpeg(png_path, img, error) : read_png(png_path, img, error)))
    return false;
  return convert(img, format, mipmaps, png_path, out, error);
}

bool texture_from_image(const ImageRgb8& img, TexelFormat format, bool mipmaps, HostTexture& out,
                        std::string& error) {
  return convert(img, format, mipmaps, "texture", out, error);
}

Rgb8 texel_rgb8(const Texture& t, int level, int column, int storage_row) {
  if (level < 0 || level >= t.level_count || level >= kMaxMipLevels) return {};
  const TextureLevel& l = t.levels[static_cast<size_t>(level)];
  if (column < 0 || storage_row < 0 || column >= l.width || storage_row >= l.height) return {};
  const size_t k = size_t(storage_row) * l.width + size_t(column);
  switch (t.format) {
    case TexelFormat::kRgb565:
      return k < l.rgb565.size() ? expand565(l.rgb565[k]) : Rgb8{};
    case TexelFormat::kRgb888:
      return 3 * k + 2 < l.bytes.size()
                 ? Rgb8{l.bytes[3 * k], l.bytes[3 * k + 1], l.bytes[3 * k + 2]}
                 : Rgb8{};
    case TexelFormat::kL8:
      return k < l.bytes.size() ? Rgb8{l.bytes[k], l.bytes[k], l.bytes[k]} : Rgb8{};
    case TexelFormat::kPalette8:
      return k < l.bytes.size() && l.bytes[k] < t.palette.size() ? expand565(t.palette[l.bytes[k]])
                                                                 : Rgb8{};
  }
  return {};
}

const char* texel_format_name(TexelFormat format) {
  switch (format) {
    case TexelFormat::kRgb565:
      return "rgb565";
    case TexelFormat::kRgb888:
      return "rgb888";
    case TexelFormat::kL8:
      return "l8";
    case TexelFormat::kPalette8:
      return "palette8";
  }
  return "?";
}

bool parse_texel_format(std::string_view name, TexelFormat& out) {
  for (TexelFormat f :
       {TexelFormat::kRgb565, TexelFormat::kRgb888, TexelFormat::kL8, TexelFormat::kPalette8}) {
    if (name == texel_format_name(f)) {
      out = f;
      return true;
    }
  }
  return false;
}

}  // namespace lr::host
