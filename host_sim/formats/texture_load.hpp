// Textures for the host: PNG files (or images in memory) converted to the core's texel formats,
// rows flipped to bottom-first storage (docs/conventions.md#textures), with an optional mip chain
// built by the core's own lr::build_mip_chain (so the simulator, the asset converter and firmware
// that builds its chain at run time all hold the same texels). Host only: uses the heap.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "lineraster/core/output/color.hpp"
#include "lineraster/core/texture/texture.hpp"
#include "lineraster/host_sim/formats/image_io.hpp"

namespace lr::host {

// A core texture together with the storage its spans point into. Levels are packed one after
// the other, level 0 first, in `rgb565` (kRgb565) or `bytes` (the other formats); `palette` holds
// the kPalette8 palette. Copies and moves re-point the spans at the new object's vectors, so a
// HostTexture can live in containers; a moved-from HostTexture is empty (level_count 0).
struct HostTexture {
  lr::Texture texture;
  std::vector<uint16_t> rgb565;
  std::vector<uint8_t> bytes;
  std::vector<uint16_t> palette;

  HostTexture() = default;
  HostTexture(const HostTexture& other);
  HostTexture(HostTexture&& other) noexcept;
  HostTexture& operator=(const HostTexture& other);
  HostTexture& operator=(HostTexture&& other) noexcept;
  ~HostTexture() = default;

  // Points texture.levels[0 .. level_count - 1] (packed in order from element 0) and
  // texture.palette at this object's vectors.
  void repoint();
};

// Loads a PNG (every colour type and bit depth read_png accepts) as a texture in `format`, the
// image's bottom row first (storage row 0 = the file's last row). Conversions from the 8-bit RGB
// image:
//   kRgb565   rounded to nearest: r5 = (31 r + 127) / 255, g6 = (63 g + 127) / 255, b5 likewise;
//   kRgb888   as is;
//   kL8       round(0.299 r + 0.587 g + 0.114 b) = (299 r + 587 g + 114 b + 500) / 1000 (grey
//             images are exact);
//   kPalette8 the image's distinct colours after RGB565 conversion, in the order they first
//             appear in the file (top row first, left to right), at most 256 (else the error
//             "FILE: more than 256 colours; use rgb565 or rgb888").
// `mipmaps`: levels 1.. down to 1 x 1 by lr::build_mip_chain (see core/texture/mipmap.hpp).
// Sides above lr::kMaxTextureSize are an error. On failure: false, `error` one line naming the
// file ("FILE: what is wrong"), `out` untouched. The result always passes lr::validate().
bool load_texture(const std::string& png_path, lr::TexelFormat format, bool mipmaps,
                  HostTexture& out, std::string& error);

// Same from an image in memory (row 0 = top); errors are named "texture: ...".
bool texture_from_image(const ImageRgb8& img, lr::TexelFormat format, bool mipmaps,
                        HostTexture& out, std::string& error);

// The colour of a texel as the core sees it, 8 bits per channel: RGB565 (and palette entries)
// expanded by bit replication ((r5 << 3) | (r5 >> 2), (g6 << 2) | (g6 >> 4)), L8 replicated.
// `storage_row` counts from the bottom row (row 0 = v near 0). Black for a level, column, row or
// palette index the texture does not hold.
lr::Rgb8 texel_rgb8(const lr::Texture& t, int level, int column, int storage_row);

// Format names as the tools spell them: "rgb565", "rgb888", "l8", "palette8".
const char* texel_format_name(lr::TexelFormat format);
bool parse_texel_format(std::string_view name, lr::TexelFormat& out);

}  // namespace lr::host
