// The row loops of the families that keep their span routines of one call per row: textured and
// Phong. The rows and edges are every family's (for_each_span); per span the routine of the
// draw's state is called with the span's first column and row, as before.
#pragma once

#include <cstddef>
#include <cstdint>

#include "lineraster/core/binning/draw_record.hpp"
#include "lineraster/core/raster/row_loop.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/span/phong_span.hpp"
#include "lineraster/core/span/span.hpp"
#include "lineraster/core/span/span_state.hpp"
#include "lineraster/core/span/tex_span.hpp"

namespace lr {

// Calls fill(px, depth, col, row, count) -> pixels written for each span of t in the strip.
template <class PF, class Fill>
[[gnu::always_inline]] inline void per_row_spans(const ActiveTriangle& t, StripRows& s,
                                                 Fill&& fill) {
  using Pixel = typename PF::Storage;
  Pixel* const pixels = static_cast<Pixel*>(s.pixels);
  uint16_t* const depth = s.depth;
  const auto width = static_cast<size_t>(s.width);
  const int32_t y0 = s.y0;
  uint32_t spans = 0, tested = 0, written = 0;
  const int32_t rows = for_each_span(t, s, [&](int32_t r, int32_t left, int32_t n) {
    const size_t off = static_cast<size_t>(r - y0) * width + static_cast<size_t>(left);
    written += fill(pixels + off, depth + off, left, r, n);
    tested += static_cast<uint32_t>(n);
    ++spans;
  });
  s.spans += spans;
  s.tested += tested;
  s.written += written;
  s.rows += static_cast<uint32_t>(rows);
}

// Textured and Phong triangles: the draw's span routine (kSpans' tables), chosen per visit.
template <class PF, SpanSet kSpans>
void legacy_rows(const ActiveTriangle& t, StripRows& s) {
  const DrawRecord& dr = s.draws[t.draw];
  if constexpr (detail::has(kSpans.families, SpanFamily::kPhong)) {
    if (dr.phong) {
      const PhongSpanFn<PF> fn = phong_span_routine<PF, kSpans>(dr);
      per_row_spans<PF>(
          t, s, [&](typename PF::Storage* px, uint16_t* dp, int32_t c, int32_t r, int32_t n) {
            return fn(t, dr, px, dp, c, r, n);
          });
      return;
    }
  }
  if constexpr (detail::has(kSpans.families, SpanFamily::kTextured)) {
    const TexSpanFn<PF> fn = tex_span_routine<PF, kSpans>(dr);
    per_row_spans<PF>(t, s,
                      [&](typename PF::Storage* px, uint16_t* dp, int32_t c, int32_t r, int32_t n) {
                        return fn(t, dr, px, dp, c, r, n);
                      });
  }
}

}  // namespace lr
