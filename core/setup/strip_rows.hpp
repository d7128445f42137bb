// One strip as the row loops see it: where its pixels and depths are, its rows, the frame's
// stores a row loop may need, and what the row loops count in it. Filled by the strip loop
// (core/raster/strip_loop.hpp) per strip; read by every row loop.
#pragma once

#include <cstdint>

#include "lineraster/core/binning/binned_triangle.hpp"
#include "lineraster/core/binning/draw_record.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr {

// The most rows a strip visit has (the largest strip height).
inline constexpr int kMaxVisitRows = 32;

// The layout is read by the lanes row loop's Armv7E-M form (core/span/lane_rows.hpp).
struct StripRows {
  void* pixels = nullptr;     // the strip's first pixel (the renderer's PF::Storage)
  uint16_t* depth = nullptr;  // the strip's depth (width x rows)
  int32_t y0 = 0;             // first row of the strip
  int32_t y_last = 0;         // last row of the strip (inclusive)
  int32_t width = 0;
  const ScreenVertex* vertices = nullptr;     // the frame's vertex store (wide edges)
  const BinnedTriangle* triangles = nullptr;  // and its binned triangles
  const DrawRecord* draws = nullptr;          // the frame's draw records
  // Spans drawn, pixels inside them, pixels written (depth test passed), rows walked (a
  // triangle's rows in the strip, with a span or not).
  uint32_t spans = 0, tested = 0, written = 0, rows = 0;
};

}  // namespace lr
