// What a frame did: counted at every stage, reported by the CLI and the benchmarks.
#pragma once

#include <cstdint>

namespace lr {

struct FrameStats {
  // Triangles given to draw() and draw_screen() (but those of draws refused for another reason
  // than kCapacity, which count in draws_refused_* alone), and what became of them (each input
  // triangle is counted in exactly one of binned_inputs, culled_*, clipped_away,
  // rejected_invalid, dropped_*). Except
  // below the minimum capacities (render() returns kCapacity, docs/bands.md): a triangle
  // dropped from one band may be drawn in another, so dropped_* counts the drops of every band
  // and the sum may exceed triangles_in.
  uint32_t triangles_in = 0;
  uint32_t culled_backface = 0;
  uint32_t culled_zero_area = 0;
  uint32_t culled_offscreen = 0;  // outside the viewport, or covering no pixel centre
  uint32_t clipped_away = 0;      // entirely outside a clip plane
  uint32_t rejected_invalid = 0;  // vertex index out of range
  uint32_t dropped_vertex_capacity = 0;
  uint32_t dropped_triangle_capacity = 0;
  // Triangles crossing a clip plane in a renderer without the clipper (RendererFeatures::
  // clipping): render() returns kNotLinked.
  uint32_t dropped_unclipped = 0;
  // Draws refused whole, one counter per reason: draw() or draw_screen() returned that status
  // and added nothing (docs/api-errors.md). render() then returns the status of the frame's first
  // refused draw. Only a kCapacity refusal counts its triangles (in triangles_in and dropped_*):
  // the others count the draw alone.
  uint32_t draws_refused_invalid = 0;        // kInvalidArgument: the draw's arguments disagree
  uint32_t draws_refused_not_linked = 0;     // kNotLinked: a state outside the renderer's SpanSet
  uint32_t draws_refused_missing_store = 0;  // kMissingStore: a store the draw needs is missing
  uint32_t draws_refused_capacity = 0;       // kCapacity: a store it needs is full or too small
  uint32_t binned_inputs = 0;  // inputs that reached the edge table (at least one piece)
  // Pieces: triangles made by clipping, and what reached the edge table.
  uint32_t clipped = 0;           // input triangles that crossed a clip plane and were cut
  uint32_t triangles_binned = 0;  // records in the edge table (clipping can make several)
  // Raster work.
  uint32_t vertices_transformed = 0;
  // Of those, the vertices projected by the exact path on 64-bit clip coordinates: their w is
  // too small for the 32-bit short path's precision (near the eye or behind it), or their draw
  // reaches beyond its range (docs/numerics.md#the-short-path).
  uint32_t vertices_wide = 0;
  uint32_t strips = 0;
  uint32_t empty_strips = 0;    // strips with no active triangle (background fill only)
  uint32_t strips_skipped = 0;  // inputs unchanged since the last frame: not rendered at all
  // Bands the frame was binned in (1: the stores held it whole), and bands binned again
  // smaller because they did not fit (docs/bands.md).
  uint32_t bands = 0;
  uint32_t band_retries = 0;
  // Extra passes over strips whose triangles outnumbered the active list (each pass draws as
  // many as it holds, in submission order: the frame is the same, the work is more).
  uint32_t strip_passes = 0;
  uint32_t triangles_set_up = 0;  // binned triangles that reached triangle setup
  // Of those, untextured ones whose planes took the exact wide path (long needles, giants:
  // docs/numerics.md#untextured-planes); the rest took the 32-bit short path.
  uint32_t triangles_wide = 0;
  // Binned triangles whose rows cover no pixel centre, found at their first strip (edges only).
  uint32_t triangles_without_pixels = 0;
  uint32_t rows_walked = 0;  // rows the row loops walked (triangle x row, with a span or not)
  uint32_t spans = 0;
  uint32_t pixels_tested = 0;   // pixels inside spans
  uint32_t pixels_written = 0;  // pixels that passed the depth test and were written
  uint32_t max_active = 0;      // peak size of the active list
  // RAM figures (bytes), fixed by the formats.
  uint32_t bytes_per_vertex = 0;
  uint32_t bytes_per_binned_triangle = 0;
  uint32_t bytes_per_active_triangle = 0;
  uint32_t bytes_per_strip = 0;  // colour + depth of one strip
};

}  // namespace lr
