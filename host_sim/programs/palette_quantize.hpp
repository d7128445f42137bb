// An RGB image reduced to at most 256 colours, for GIF (gif_writer.hpp).
//
// Median cut (Heckbert 1982) on the image's own colours: all the colours start in one box; the
// box whose colours are farthest from their mean (the largest sum of squared deviations,
// weighted by pixel count) is split across its widest channel at the pixel-weighted median,
// until there are 256 boxes or none holds two colours; each box's colour is the pixel-weighted
// mean of its colours, and each pixel takes the nearest of them. Why this and not a fixed
// palette: a rendered frame is mostly a few smooth ramps of one material's colours, which a
// fixed 6x7x6 cube covers with steps of 36 to 51 levels (visible bands); median cut spends the
// 256 entries where the frame's colours are. An image of at most 256 colours is kept exactly.
// No dithering: in an animation the dither pattern crawls from frame to frame.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "lineraster/host_sim/formats/image_io.hpp"

namespace lr::host {

// An image in palette form: rows top to bottom as ImageRgb8's.
struct PalettedImage {
  int width = 0, height = 0;
  std::vector<std::array<uint8_t, 3>> palette;  // 1..256 colours (none for an empty image)
  std::vector<uint8_t> indices;                 // width * height entries of `palette`
};

inline constexpr size_t kMaxPaletteColors = 256;

PalettedImage quantize_median_cut(const ImageRgb8& image);

}  // namespace lr::host
