// Per-strip signatures: what a panel's RAM holds, remembered in a few words per strip, so that a
// strip whose pixels did not change is not sent again and a changed one sends only its changed
// columns.
//
// A strip of W x K pixels is cut into kSignatureBands column bands (band b: columns
// [W b / 8, W (b + 1) / 8)); each band gets a 32-bit hash of its pixels (row by row, left to
// right) and the strip one hash of the band hashes. Memory: 44 bytes per strip, O(height / K).
//
// The hash is FNV-1a over 16-bit words (core/math/hash.hpp): one step per pixel, v the RGB565
// value as it goes on the wire (so the hashes are the same on every CPU). Each step is a bijection
// of h for a given v and of v for a given h, so two strips that differ in one pixel always get
// different band hashes, and strips that differ in one band always different strip hashes; larger
// changes go unnoticed with a probability of about 2^-32 per band.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "lineraster/core/math/hash.hpp"
#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/output/strip_sink.hpp"

namespace lr {

inline constexpr int kSignatureBands = 8;

struct StripSignature {
  StripRect rect{};  // the strip described; width 0: nothing known
  uint32_t hash = 0;
  std::array<uint32_t, kSignatureBands> bands{};

  constexpr bool known() const { return rect.width != 0; }
  friend constexpr bool operator==(const StripSignature&, const StripSignature&) = default;
};

// Columns [begin, end) of a strip, relative to its left edge; empty when begin == end.
struct ColumnRange {
  uint16_t begin = 0, end = 0;
  constexpr bool empty() const { return begin >= end; }
  constexpr uint16_t width() const { return empty() ? uint16_t{0} : uint16_t(end - begin); }
  friend constexpr bool operator==(const ColumnRange&, const ColumnRange&) = default;
};

// First column of band b (b = kSignatureBands gives the width).
constexpr uint16_t band_begin(uint16_t width, int band) {
  return static_cast<uint16_t>(uint32_t{width} * static_cast<uint32_t>(band) /
                               static_cast<uint32_t>(kSignatureBands));
}

// Signs a strip of rect.width x rect.height Rgb565Be pixels, rows packed (pixels.size() must be
// at least width x height; fewer sign as an unknown strip).
constexpr StripSignature sign_strip(const StripRect& rect,
                                    std::span<const Rgb565Be::Storage> pixels) {
  StripSignature s;
  const size_t w = rect.width;
  if (w == 0 || rect.height == 0 || pixels.size() < w * rect.height) return s;
  std::array<uint16_t, kSignatureBands + 1> edge{};
  for (int b = 0; b <= kSignatureBands; ++b)
    edge[static_cast<size_t>(b)] = band_begin(rect.width, b);
  s.bands.fill(kFnv1a32Offset);
  for (size_t row = 0; row < rect.height; ++row) {
    const Rgb565Be::Storage* p = pixels.data() + row * w;
    for (size_t b = 0; b < static_cast<size_t>(kSignatureBands); ++b) {
      uint32_t h = s.bands[b];
      for (size_t c = edge[b]; c < edge[b + 1]; ++c) h = fnv1a32(h, Rgb565Be::to_value(p[c]));
      s.bands[b] = h;
    }
  }
  uint32_t h = kFnv1a32Offset;
  for (uint32_t band : s.bands) h = fnv1a32(h, band);
  s.hash = h;
  s.rect = rect;
  return s;
}

// The columns a panel holding `before` must be sent to show `now` (a signed strip): everything
// when `before` describes another rectangle (or nothing), nothing when the hashes agree, else from
// the first changed band's first column to the last changed band's last.
constexpr ColumnRange changed_columns(const StripSignature& before, const StripSignature& now) {
  if (!now.known()) return {};
  if (!before.known() || before.rect != now.rect) return {0, now.rect.width};
  if (before.hash == now.hash && before.bands == now.bands) return {};
  int first = kSignatureBands, last = -1;
  for (int b = 0; b < kSignatureBands; ++b) {
    if (before.bands[static_cast<size_t>(b)] != now.bands[static_cast<size_t>(b)]) {
      if (first == kSignatureBands) first = b;
      last = b;
    }
  }
  if (last < 0) return {0, now.rect.width};  // strip hash differs alone: cannot happen, send all
  return {band_begin(now.rect.width, first), band_begin(now.rect.width, last + 1)};
}

}  // namespace lr
