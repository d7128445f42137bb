// What became of a triangle given to the front end: binned, or why not. Every input triangle
// is counted once in FrameStats by its outcome (count_outcome).
#pragma once

#include <cstdint>

#include "lineraster/core/output/frame_stats.hpp"

namespace lr {

enum class Outcome : uint8_t {
  kBinned,          // in the edge table
  kBackface,        // culled by its facing
  kZeroArea,        // culled: no area on the display
  kOffscreen,       // culled: outside the viewport, or covering no pixel centre
  kCapacity,        // dropped: the triangle store is full
  kClippedAway,     // entirely outside a clip plane, or nothing left after clipping
  kVertexCapacity,  // dropped: the vertex store is full
  kInvalid,         // a vertex index out of range, or a vertex outside the coordinate budget
};

// Counts one input triangle: binned when any of its pieces was (clipping makes several), else
// by `last`, the outcome of its last piece.
inline void count_outcome(FrameStats& s, bool binned, Outcome last) {
  if (binned) {
    ++s.binned_inputs;
    return;
  }
  switch (last) {
    case Outcome::kBinned:
      ++s.binned_inputs;
      break;
    case Outcome::kBackface:
      ++s.culled_backface;
      break;
    case Outcome::kZeroArea:
      ++s.culled_zero_area;
      break;
    case Outcome::kOffscreen:
      ++s.culled_offscreen;
      break;
    case Outcome::kCapacity:
      ++s.dropped_triangle_capacity;
      break;
    case Outcome::kVertexCapacity:
      ++s.dropped_vertex_capacity;
      break;
    case Outcome::kClippedAway:
      ++s.clipped_away;
      break;
    case Outcome::kInvalid:
      ++s.rejected_invalid;
      break;
  }
}

}  // namespace lr
