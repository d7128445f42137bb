#include "lineraster/core/binning/draw_records.hpp"

#include "lineraster/core/binning/strip_inputs.hpp"

namespace lr {

uint8_t DrawRecords::add(const DrawState& state, bool has_color_planes, uint16_t first_vertex) {
  DrawRecord r;
  r.depth = state.depth_test;
  r.flat = state.shading == Shading::kFlat;
  r.first_vertex = first_vertex;  // until it is binned
  r.filter = state.sampler.filter;
  r.wrap_s = state.sampler.wrap_s;
  r.wrap_t = state.sampler.wrap_t;
  r.colors = color_planes_of(state, has_color_planes);
  const auto index = static_cast<uint8_t>(count_);
  draws_[count_++] = r;
  return index;
}

void DrawRecords::texture_fields(DrawRecord& r, const DrawState& state) {
  r.texture = state.texture;
  r.uv = true;
  r.env = state.sampler.env;
  r.mip = state.sampler.mip;
  r.persp = tex_persp_of(state.perspective);
  r.span_len = state.perspective == Perspective::kSpan8    ? 8
               : state.perspective == Perspective::kSpan16 ? 16
               : state.perspective == Perspective::kSpan32 ? 32
                                                           : 0;
}

Status DrawRecords::add_phong_state(const DrawState& state, const PreparedLighting& pl,
                                    DrawRecord& r) {
  // Prepared lighting: shared by the draws of equal materials.
  const PreparedLighting* shared = nullptr;
  for (size_t i = 0; i < pixel_light_count_; ++i)
    if (pixel_lights_[i].material == pl.material) shared = &pixel_lights_[i];
  if (shared == nullptr) {
    if (pixel_light_count_ >= pixel_lights_.size()) return Status::kCapacity;
    pixel_lights_[pixel_light_count_] = pl;
    shared = &pixel_lights_[pixel_light_count_++];
  }
  r.phong = true;
  r.method = state.pixel_lighting;
  r.two_sided = two_sided_;
  r.position = pl.needs_position();
  r.lighting = shared;
  r.view = view_;
  r.flat = false;
  r.colors = ColorPlanes::kNone;
  r.envmap = state.envmap;
  r.normal_map = state.normal_map;
  if (state.normal_map != nullptr) r.uv = true;
  if (state.pixel_lighting != PixelLighting::kTable) return Status::kOk;
  const bool split = state.texture != nullptr || state.envmap != nullptr;
  const uint16_t size = state.table.size;
  r.table_bilinear = state.table.bilinear;
  // Tables of equal prepared lighting, size and layout are shared.
  for (size_t i = 0; i < count_; ++i) {
    const DrawRecord& o = draws_[i];
    if (&o != &r && o.phong && o.method == PixelLighting::kTable && o.lighting == shared &&
        o.table.size == size && o.table.split == split) {
      r.table = o.table;
      return Status::kOk;
    }
  }
  const size_t words = lighting_table_words(size, split);
  if (lighting_tables_.size() < table_words_used_ ||
      words > lighting_tables_.size() - table_words_used_)
    return Status::kCapacity;
  std::span<uint32_t> out = lighting_tables_.subspan(table_words_used_, words);
  fill_lighting_table(*shared, size, split, out);
  table_words_used_ += words;
  r.table = {out.data(), size, split};
  return Status::kOk;
}

void DrawRecords::sign(uint8_t index, const Material* per_pixel_material) {
  DrawRecord& d = draws_[index];
  InputHash h;
  h.add(d);
  if (per_pixel_material != nullptr) h.add(*per_pixel_material);
  d.inputs = h.value();
}

}  // namespace lr
