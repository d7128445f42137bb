// Mip chains for textures in RAM: levels 1.. built from level 0 by box filtering (the asset
// converter uses the same code at build time, so flash textures get identical chains).
//
// Sizes follow GL: each level is half the one before, rounded down, at least 1, down to 1 x 1.
// Box: along an axis of n input texels and m = max(1, n / 2) output texels, output texel i
// covers input texels 2i and 2i + 1; when n is odd (n > 1) the last output texel also covers
// the last input texel (its box is 3 texels wide: 2i, 2i + 1, 2i + 2 = n - 1), so every input
// texel contributes and the mean colour of a level is kept (e.g. 3 x 3 -> 1 x 1 is the mean of
// all nine texels); for n = 1 the box is that one texel. Boxes are therefore 1x1 .. 3x3 texels.
//
// Averages round to nearest (half up): (sum + count / 2) / count per channel, where a channel is
// the stored 5/6/5-bit field for kRgb565 and the byte for kRgb888 and kL8. kPalette8 averages the
// palette colours as 8-bit RGB (RGB565 expanded by bit replication, as the sampler sees them),
// then stores the palette entry nearest to that mean (squared RGB distance, lowest index on ties;
// only the first 256 palette entries are candidates).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "lineraster/core/output/status.hpp"
#include "lineraster/core/texture/texture.hpp"

namespace lr {

// Number of levels of a full chain for a level 0 of w x h (1..kMaxTextureSize each): 1 for 1 x 1,
// 12 for 2048 x 2048. 0 for a size outside the range.
constexpr int mip_level_count(uint16_t w, uint16_t h) {
  if (w < 1 || h < 1 || w > kMaxTextureSize || h > kMaxTextureSize) return 0;
  int n = 1;
  while (w > 1 || h > 1) {
    w = static_cast<uint16_t>(w > 1 ? w / 2 : 1);
    h = static_cast<uint16_t>(h > 1 ? h / 2 : 1);
    ++n;
  }
  return n;
}

// Elements of storage levels 1.. need (uint16 values for kRgb565, bytes for the other formats),
// from t.levels[0]'s size and t.format. 0 for a 1 x 1 level 0 or an invalid size.
size_t mip_chain_size(const Texture& t);

// Builds levels 1.. of `texture` (down to 1 x 1) from texture.levels[0] into the caller's
// storage: rgb565_storage for kRgb565, byte_storage for the others (the other span may be empty),
// levels packed one after the other from the start of the storage. Sets texture.levels[1..] and
// texture.level_count. Level 0 must be valid (as validate() checks it, palette included):
// kInvalidArgument otherwise; kCapacity when the storage holds fewer than mip_chain_size()
// elements. On any error `texture` and the storage are left unchanged.
Status build_mip_chain(Texture& texture, std::span<uint16_t> rgb565_storage,
                       std::span<uint8_t> byte_storage);

}  // namespace lr
