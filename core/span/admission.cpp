#include "lineraster/core/span/admission.hpp"

namespace lr {

SpanState span_state_of(const DrawState& state, const DrawKind& kind) {
  SpanState s;
  s.depth = state.depth_test;
  if (kind.phong) {
    s.family = SpanFamily::kPhong;
    s.method = state.pixel_lighting;
    // As the draw record: position planes when the lighting needs the surface position.
    if (s.method == PixelLighting::kExact)
      s.position = kind.position;
    else
      s.table_bilinear = state.table.bilinear;
    s.texture = state.texture != nullptr;
    s.normal_map = state.normal_map != nullptr;
    s.envmap = state.envmap != nullptr;
    if (s.texture || s.normal_map) s.filter = state.sampler.filter;
    if (s.texture) s.mip = state.sampler.mip;
  } else if (state.texture != nullptr) {
    s.family = SpanFamily::kTextured;
    s.persp = tex_persp_of(state.perspective);
    s.env = state.sampler.env;
    s.mip = state.sampler.mip;
    s.filter = state.sampler.filter;
  } else {
    s.colors = color_planes_of(state, kind.color_planes);
  }
  return s;
}

bool draw_admitted(const SpanSet& set, const DrawState& state, const DrawKind& kind) {
  const SpanState s = span_state_of(state, kind);
  if (!set.admits(s)) return false;
  const Sampler& sm = state.sampler;
  if ((s.family == SpanFamily::kTextured || s.texture) &&
      !set.admits_sampler(state.texture->format, sm.wrap_s, sm.wrap_t))
    return false;
  if (s.normal_map && !set.admits_sampler(state.normal_map->format, sm.wrap_s, sm.wrap_t))
    return false;
  return !s.envmap || set.admits_envmap(state.envmap->format);
}

}  // namespace lr
