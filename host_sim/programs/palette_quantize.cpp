#include "lineraster/host_sim/programs/palette_quantize.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lr::host {
namespace {

// One distinct colour of the image (0xRRGGBB) and how many pixels have it.
struct Entry {
  uint32_t rgb;
  uint32_t count;
};

int channel(uint32_t rgb, size_t c) {
  return static_cast<int>((rgb >> (16 - 8 * c)) & 0xFF);
}

// Entries [begin, end) of the colour list, with what the split order needs.
struct Box {
  size_t begin = 0, end = 0;
  double sse = 0;   // sum over pixels and channels of the squared distance to the mean
  size_t axis = 0;  // the channel with the largest squared deviation
  std::array<uint8_t, 3> mean{};
};

Box make_box(const std::vector<Entry>& e, size_t begin, size_t end) {
  Box b;
  b.begin = begin;
  b.end = end;
  double n = 0;
  std::array<double, 3> sum{}, squares{};
  for (size_t i = begin; i < end; ++i) {
    const double w = e[i].count;
    n += w;
    for (size_t c = 0; c < 3; ++c) {
      const double v = channel(e[i].rgb, c);
      sum[c] += w * v;
      squares[c] += w * v * v;
    }
  }
  double widest = -1;
  for (size_t c = 0; c < 3; ++c) {
    const double deviation = squares[c] - sum[c] * sum[c] / n;
    b.sse += deviation;
    if (deviation > widest) {
      widest = deviation;
      b.axis = c;
    }
    b.mean[c] = static_cast<uint8_t>(std::lround(sum[c] / n));
  }
  return b;
}

// Splits box b at the pixel-weighted median of its axis; both halves keep at least one colour.
std::array<Box, 2> split(std::vector<Entry>& e, const Box& b) {
  const auto first = e.begin() + static_cast<std::ptrdiff_t>(b.begin);
  const auto last = e.begin() + static_cast<std::ptrdiff_t>(b.end);
  std::sort(first, last, [axis = b.axis](const Entry& x, const Entry& y) {
    const int cx = channel(x.rgb, axis), cy = channel(y.rgb, axis);
    return cx != cy ? cx < cy : x.rgb < y.rgb;
  });
  uint64_t total = 0;
  for (size_t i = b.begin; i < b.end; ++i) total += e[i].count;
  uint64_t seen = 0;
  size_t cut = b.begin + 1;
  for (size_t i = b.begin; i < b.end; ++i) {
    seen += e[i].count;
    if (2 * seen >= total) {
      cut = i + 1;
      break;
    }
  }
  cut = std::clamp(cut, b.begin + 1, b.end - 1);
  return {make_box(e, b.begin, cut), make_box(e, cut, b.end)};
}

uint32_t pack(const uint8_t* p) {
  return (uint32_t{p[0]} << 16) | (uint32_t{p[1]} << 8) | p[2];
}

}  // namespace

PalettedImage quantize_median_cut(const ImageRgb8& image) {
  PalettedImage out;
  out.width = image.width;
  out.height = image.height;
  const size_t pixels = image.rgb.size() / 3;
  if (pixels == 0) return out;
  // The distinct colours with their pixel counts.
  std::vector<uint32_t> sorted(pixels);
  for (size_t p = 0; p < pixels; ++p) sorted[p] = pack(&image.rgb[3 * p]);
  std::sort(sorted.begin(), sorted.end());
  std::vector<Entry> colors;
  for (uint32_t c : sorted) {
    if (colors.empty() || colors.back().rgb != c) colors.push_back({c, 0});
    ++colors.back().count;
  }
  std::vector<uint32_t> distinct(colors.size());
  for (size_t i = 0; i < colors.size(); ++i) distinct[i] = colors[i].rgb;
  // The boxes, split largest error first.
  std::vector<Box> boxes{make_box(colors, 0, colors.size())};
  while (boxes.size() < kMaxPaletteColors) {
    size_t worst = boxes.size();
    for (size_t i = 0; i < boxes.size(); ++i)
      if (boxes[i].end - boxes[i].begin >= 2 &&
          (worst == boxes.size() || boxes[i].sse > boxes[worst].sse))
        worst = i;
    if (worst == boxes.size()) break;  // every box is one colour: the palette is exact
    const std::array<Box, 2> halves = split(colors, boxes[worst]);
    boxes[worst] = halves[0];
    boxes.push_back(halves[1]);
  }
  for (const Box& b : boxes) out.palette.push_back(b.mean);
  // Each distinct colour's nearest palette entry, then each pixel's.
  std::vector<uint8_t> nearest(distinct.size());
  for (size_t i = 0; i < distinct.size(); ++i) {
    int best = std::numeric_limits<int>::max();
    for (size_t k = 0; k < out.palette.size(); ++k) {
      int d = 0;
      for (size_t c = 0; c < 3; ++c) {
        const int diff = channel(distinct[i], c) - out.palette[k][c];
        d += diff * diff;
      }
      if (d < best) {
        best = d;
        nearest[i] = static_cast<uint8_t>(k);
      }
    }
  }
  out.indices.resize(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    const uint32_t c = pack(&image.rgb[3 * p]);
    const auto it = std::lower_bound(distinct.begin(), distinct.end(), c);
    out.indices[p] = nearest[static_cast<size_t>(it - distinct.begin())];
  }
  return out;
}

}  // namespace lr::host
