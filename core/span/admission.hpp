// Which span state a draw selects (its family and dimensions, span_state.hpp), and whether a
// renderer's SpanSet admits it and its textures: the front end refuses a draw that is not
// admitted (Renderer<PF, K, kSpans> hands it admits<kSpans> as its AdmitFn), so a restricted
// renderer never reaches a routine it did not link.
#pragma once

#include "lineraster/core/binning/draw_record.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/span/span_state.hpp"

namespace lr {

// The span state of a draw (draw(): kind as the front end decides it; draw_screen(): not
// Phong).
SpanState span_state_of(const DrawState& state, const DrawKind& kind);

// Whether `set` admits the draw's span state and the formats and wraps of its textures.
bool draw_admitted(const SpanSet& set, const DrawState& state, const DrawKind& kind);

// The AdmitFn of a renderer restricted to kSet. A set of untextured spans only admits what
// draw_admitted() does without the other families' states and samplers: a draw neither Phong
// nor textured whose depth test and colour planes it has (no code of theirs linked).
template <SpanSet kSet>
bool admits(const DrawState& state, const DrawKind& kind) {
  if constexpr (kSet.families == detail::bit(SpanFamily::kUntextured))
    return !kind.phong && state.texture == nullptr && detail::has(kSet.depth, state.depth_test) &&
           detail::has(kSet.colors, color_planes_of(state, kind.color_planes));
  else
    return draw_admitted(kSet, state, kind);
}

}  // namespace lr
