#include "core/binning/frame_builder.hpp"

#include "core/math/divide.hpp"

namespace lr {
namespace {

// Model-space vector times a normal matrix (Q16.16 entries) as int64, then normalised.
Unit30 transform_normal(const Mat4& nm, int64_t x, int64_t y, int64_t z) {
  int64_t r[3];
  for (int i = 0; i < 3; ++i)
    r[i] = int64_t{nm.m[i][0].raw} * x + int64_t{nm.m[i][1].raw} * y + int64_t{nm.m[i][2].raw} * z;
  Unit30 u{0, 0, 1 << 30};
  normalize_unit30(r[0], r[1], r[2], u);
  return u;
}

// Face normal of a model-space triangle as a Q1.30 unit vector (counter-clockwise winding).
Unit30 face_normal_model(Vec3 p0, Vec3 p1, Vec3 p2) {
  int64_t e1[3] = {int64_t{p1.x.raw} - p0.x.raw, int64_t{p1.y.raw} - p0.y.raw,
                   int64_t{p1.z.raw} - p0.z.raw};
  int64_t e2[3] = {int64_t{p2.x.raw} - p0.x.raw, int64_t{p2.y.raw} - p0.y.raw,
                   int64_t{p2.z.raw} - p0.z.raw};
  // Edges are < 2^32; bring them below 2^30 so the cross products stay below 2^61.
  uint64_t m = 0;
  for (int i = 0; i < 3; ++i) m |= abs64(e1[i]) | abs64(e2[i]);
  if (m >= (uint64_t{1} << 30)) {
    int s = (63 - clz64(m)) - 29;
    for (int i = 0; i < 3; ++i) {
      e1[i] >>= s;
      e2[i] >>= s;
    }
  }
  Unit30 u{0, 0, 1 << 30};
  normalize_unit30(e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0], u);
  return u;
}

// A model-space tangent (Q1.14) to world space (the model's upper 3x3), unit Q1.14.
void transform_tangent(const Mat4& model, const Tangent16& t, int16_t out[3]) {
  int64_t r[3];
  for (int i = 0; i < 3; ++i)
    r[i] = int64_t{model.m[i][0].raw} * t.x + int64_t{model.m[i][1].raw} * t.y +
           int64_t{model.m[i][2].raw} * t.z;
  Unit30 u{1 << 30, 0, 0};
  normalize_unit30(r[0], r[1], r[2], u);
  out[0] = static_cast<int16_t>(round_shift(u.x, 16));
  out[1] = static_cast<int16_t>(round_shift(u.y, 16));
  out[2] = static_cast<int16_t>(round_shift(u.z, 16));
}

constexpr Unit30 negate(Unit30 u) {
  return {-u.x, -u.y, -u.z};
}

// Facing of a clip-space triangle from the sign of det[x y w] (homogeneous: valid for the part
// in front of the eye even when a vertex is behind it): true when front-facing. Coordinates are
// brought below 2^20 first so the products of three stay inside int64.
bool front_facing_clip(const ClipCoord (&c)[3]) {
  uint64_t m = 0;
  for (const ClipCoord& p : c) m |= abs64(p.x) | abs64(p.y) | abs64(p.w);
  const int s = m == 0 ? 0 : (63 - clz64(m)) - 19;
  auto sh = [s](int64_t v) { return s > 0 ? v >> s : v; };
  int64_t x[3], y[3], w[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = sh(c[i].x);
    y[i] = sh(c[i].y);
    w[i] = sh(c[i].w);
  }
  const int64_t det = x[0] * (y[1] * w[2] - y[2] * w[1]) - x[1] * (y[0] * w[2] - y[2] * w[0]) +
                      x[2] * (y[0] * w[1] - y[1] * w[0]);
  return det > 0;  // counter-clockwise in NDC
}

// The colour planes of an untextured draw (add_draw_record and span_state agree through this).
ColorPlanes color_planes_of(const DrawState& state, bool has_color_planes) {
  if (state.shading == Shading::kFlat || !has_color_planes) return ColorPlanes::kNone;
  return state.perspective == Perspective::kAffine ? ColorPlanes::kAffine
                                                   : ColorPlanes::kPerspective;
}

TexPersp tex_persp_of(Perspective p) {
  return p == Perspective::kExact    ? TexPersp::kExact
         : p == Perspective::kAffine ? TexPersp::kAffine
                                     : TexPersp::kSpan;
}

Rgb8 to_rgb8_sat(Color15 c) {
  auto b = [](uint16_t v) { return to_byte(clamp_c15(v)); };
  return {b(c.r), b(c.g), b(c.b)};
}

}  // namespace

Status FrameBuilder::configure(const FrameStorage& s, int width, int height, int strip_height) {
  configured_ = false;
  if (width < 1 || height < 1 || width > kMaxViewport || height > kMaxViewport)
    return Status::kInvalidArgument;
  if (strip_height < 1 || strip_height > 32) return Status::kInvalidArgument;
  int strips = (height + strip_height - 1) / strip_height;
  if (s.buckets.size() < static_cast<size_t>(strips)) return Status::kInvalidArgument;
  if (s.depth.size() < static_cast<size_t>(width) * static_cast<size_t>(strip_height))
    return Status::kInvalidArgument;
  if (s.active_index.size() < 2 * s.active.size() || s.active.size() > kMaxStoreEntries)
    return Status::kInvalidArgument;
  if (s.draws.empty() || s.draws.size() > 256) return Status::kInvalidArgument;
  if (!s.strip_inputs.empty() && s.strip_inputs.size() < 2 * static_cast<size_t>(strips))
    return Status::kInvalidArgument;
  inputs_known_ = false;
  storage_ = s;
  if (storage_.vertices.size() > kMaxStoreEntries)
    storage_.vertices = storage_.vertices.first(kMaxStoreEntries);
  if (storage_.triangles.size() > kMaxStoreEntries - 1)
    storage_.triangles = storage_.triangles.first(kMaxStoreEntries - 1);
  width_ = width;
  height_ = height;
  strip_height_ = strip_height;
  strips_ = strips;
  guard_.gx = 8192 / width > 1 ? 8192 / width : 1;
  guard_.gy = 8192 / height > 1 ? 8192 / height : 1;
  configured_ = true;
  return Status::kOk;
}

Status FrameBuilder::begin_frame(const Camera& camera, const LightSet& lights, Rgb8 background) {
  if (!configured_) return Status::kInvalidArgument;
  if (lights.count > kMaxLights) return Status::kInvalidArgument;
  camera_ = camera;
  lights_ = lights;
  background_ = background;
  vertex_count_ = triangle_count_ = draw_count_ = 0;
  pixel_light_count_ = table_words_used_ = 0;
  for (int i = 0; i < strips_; ++i) storage_.buckets[static_cast<size_t>(i)] = kNoTriangle;
  if (skipping()) {
    // What every strip depends on: the viewport, the background, the camera (per-pixel lighting
    // and environment maps read it) and the lights (per-pixel lighting).
    InputHash h;
    h.add(static_cast<uint32_t>(width_) | static_cast<uint32_t>(height_) << 16);
    h.add(static_cast<uint32_t>(strip_height_));
    h.add(background);
    h.add(camera);
    h.add(lights);
    for (int i = 0; i < strips_; ++i) storage_.strip_inputs[static_cast<size_t>(i)] = h.value();
  }
  stats_ = FrameStats{};
  stats_.bytes_per_vertex = sizeof(ScreenVertex);
  stats_.bytes_per_binned_triangle = sizeof(BinnedTriangle);
  stats_.bytes_per_active_triangle = sizeof(ActiveTriangle) + 2 * sizeof(uint16_t);
  return Status::kOk;
}

bool FrameBuilder::project(const ClipCoord& c, ScreenVertex& v) const {
  // Inside every plane: w >= 2^-16, |x| <= gx w, |y| <= gy w, |z| <= w. Normalise so w < 2^31.
  int64_t x = c.x, y = c.y, z = c.z, w = c.w;
  if (w <= 0) return false;
  while (w >= (int64_t{1} << 31)) {
    x >>= 1;
    y >>= 1;
    z >>= 1;
    w >>= 1;
  }
  // Three quotients by the same w: one reciprocal (core/math/divide.hpp), exact, the values of
  // round_div(n, w) (half away from zero; n is negative left of and below the viewport).
  const Divider by_w(static_cast<uint64_t>(w));
  auto rounded = [&](int64_t n) {
    const auto half = static_cast<uint64_t>(w / 2);
    return n >= 0 ? static_cast<int64_t>(by_w.quotient(static_cast<uint64_t>(n) + half))
                  : -static_cast<int64_t>(by_w.quotient(static_cast<uint64_t>(-n) + half));
  };
  // (x + w) <= (gx + 1) w and (gx + 1) * width <= 8192 + width: product < 1.5 * 2^51.
  v.x = static_cast<int32_t>(rounded((x + w) * (int64_t{width_} * kHalfPixel)));
  v.y = static_cast<int32_t>(rounded((w - y) * (int64_t{height_} * kHalfPixel)));
  // (z + w) <= 2w < 2^32 and 65535 * 2^15 < 2^31: product < 2^63.
  int64_t zz = rounded((z + w) * (int64_t{65535} << 15));
  v.z = static_cast<uint32_t>(zz < 0 ? 0 : zz > kDepthMax ? kDepthMax : zz);
  int64_t wq = c.w >> (ClipCoord::kFracBits - 16);
  v.w = static_cast<uint32_t>(wq < 1 ? 1 : wq > 0xFFFFFFFF ? 0xFFFFFFFF : wq);
  v.outcode = 0;
  return true;
}

void FrameBuilder::sign_draw(uint8_t index, const Material* per_pixel_material) {
  DrawRecord& d = storage_.draws[index];
  InputHash h;
  h.add(d);
  if (per_pixel_material != nullptr) h.add(*per_pixel_material);
  d.inputs = h.value();
}

Status FrameBuilder::add_draw_record(const DrawState& state, bool has_color_planes, size_t vertices,
                                     uint32_t triangles, uint8_t& index) {
  // Without a draw record or room for every vertex the whole draw is dropped, and counted.
  if (draw_count_ >= storage_.draws.size()) {
    stats_.dropped_triangle_capacity += triangles;
    return Status::kCapacity;
  }
  if (vertices > storage_.vertices.size() - vertex_count_) {
    stats_.dropped_vertex_capacity += triangles;
    return Status::kCapacity;
  }
  DrawRecord r;
  r.depth = state.depth_test;
  r.flat = state.shading == Shading::kFlat;
  r.filter = state.sampler.filter;
  r.wrap_s = state.sampler.wrap_s;
  r.wrap_t = state.sampler.wrap_t;
  if (state.texture != nullptr) {
    const Texture& tex = *state.texture;
    r.texture = &tex;
    r.env = state.sampler.env;
    r.mip = state.sampler.mip;
    switch (state.perspective) {
      case Perspective::kExact:
        r.persp = TexPersp::kExact;
        break;
      case Perspective::kAffine:
        r.persp = TexPersp::kAffine;
        break;
      case Perspective::kSpan8:
        r.persp = TexPersp::kSpan;
        r.span_len = 8;
        break;
      case Perspective::kSpan16:
        r.persp = TexPersp::kSpan;
        r.span_len = 16;
        break;
      case Perspective::kSpan32:
        r.persp = TexPersp::kSpan;
        r.span_len = 32;
        break;
    }
  }
  r.colors = color_planes_of(state, has_color_planes);
  index = static_cast<uint8_t>(draw_count_);
  storage_.draws[draw_count_++] = r;
  return Status::kOk;
}

Status FrameBuilder::add_phong_state(const DrawState& state, const PreparedLighting& pl,
                                     DrawRecord& r) {
  // Prepared lighting: shared by the draws of equal materials.
  const PreparedLighting* shared = nullptr;
  for (size_t i = 0; i < pixel_light_count_; ++i)
    if (storage_.pixel_lights[i].material == pl.material) shared = &storage_.pixel_lights[i];
  if (shared == nullptr) {
    if (pixel_light_count_ >= storage_.pixel_lights.size()) return Status::kCapacity;
    storage_.pixel_lights[pixel_light_count_] = pl;
    shared = &storage_.pixel_lights[pixel_light_count_++];
  }
  r.phong = true;
  r.method = state.pixel_lighting;
  r.two_sided = lights_.two_sided;
  r.position = pl.needs_position();
  r.lighting = shared;
  r.view = camera_.view;
  r.flat = false;
  r.colors = ColorPlanes::kNone;
  if (state.envmap != nullptr) {
    r.envmap = state.envmap;
  }
  if (state.normal_map != nullptr) {
    r.normal_map = state.normal_map;
  }
  if (state.pixel_lighting == PixelLighting::kTable) {
    const bool split = state.texture != nullptr || state.envmap != nullptr;
    const uint16_t size = state.table.size;
    r.table_bilinear = state.table.bilinear;
    // Tables of equal prepared lighting, size and layout are shared.
    for (size_t i = 0; i < draw_count_; ++i) {
      const DrawRecord& o = storage_.draws[i];
      if (&o != &r && o.phong && o.method == PixelLighting::kTable && o.lighting == shared &&
          o.table.size == size && o.table.split == split) {
        r.table = o.table;
        return Status::kOk;
      }
    }
    const size_t words = lighting_table_words(size, split);
    if (storage_.lighting_tables.size() < table_words_used_ ||
        words > storage_.lighting_tables.size() - table_words_used_)
      return Status::kCapacity;
    std::span<uint32_t> out = storage_.lighting_tables.subspan(table_words_used_, words);
    fill_lighting_table(*shared, size, split, out);
    table_words_used_ += words;
    r.table = {out.data(), size, split};
  }
  return Status::kOk;
}

SpanState FrameBuilder::span_state(const DrawState& state, bool phong, bool color_planes) const {
  SpanState s;
  s.depth = state.depth_test;
  if (phong) {
    s.family = SpanFamily::kPhong;
    s.method = state.pixel_lighting;
    // As add_phong_state: position planes when the lighting needs the surface position.
    if (s.method == PixelLighting::kExact)
      s.position = !lights_.normal_only();
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
    s.colors = color_planes_of(state, color_planes);
  }
  return s;
}

bool FrameBuilder::admitted(const DrawState& state, bool phong, bool color_planes) const {
  const SpanState s = span_state(state, phong, color_planes);
  if (!span_set_->admits(s)) return false;
  const Sampler& sm = state.sampler;
  if ((s.family == SpanFamily::kTextured || s.texture) &&
      !span_set_->admits_sampler(state.texture->format, sm.wrap_s, sm.wrap_t))
    return false;
  if (s.normal_map && !span_set_->admits_sampler(state.normal_map->format, sm.wrap_s, sm.wrap_t))
    return false;
  return !s.envmap || span_set_->admits_envmap(state.envmap->format);
}

FrameBuilder::BinResult FrameBuilder::classify(const ScreenVertex& v0, const ScreenVertex& v1,
                                               const ScreenVertex& v2, Cull cull, int32_t& r0,
                                               int32_t& r1) const {
  int64_t area = (int64_t{v1.x} - v0.x) * (int64_t{v2.y} - v0.y) -
                 (int64_t{v2.x} - v0.x) * (int64_t{v1.y} - v0.y);
  if (area == 0) return BinResult::kZeroArea;
  // Counter-clockwise in NDC (y up) is clockwise on the display (y down): negative area.
  bool front = area < 0;
  if ((cull == Cull::kBack && !front) || (cull == Cull::kFront && front))
    return BinResult::kBackface;
  int32_t ymin = v0.y < v1.y ? v0.y : v1.y, ymax = v0.y > v1.y ? v0.y : v1.y;
  ymin = v2.y < ymin ? v2.y : ymin;
  ymax = v2.y > ymax ? v2.y : ymax;
  int32_t xmin = v0.x < v1.x ? v0.x : v1.x, xmax = v0.x > v1.x ? v0.x : v1.x;
  xmin = v2.x < xmin ? v2.x : xmin;
  xmax = v2.x > xmax ? v2.x : xmax;
  r0 = first_row_below(ymin);
  r1 = last_row_at_or_above(ymax);
  if (r0 < 0) r0 = 0;
  if (r1 > height_ - 1) r1 = height_ - 1;
  // Columns whose centres can pass both edge tests: [ceil((xmin-128)/256), ceil((xmax-128)/256)).
  int32_t c0 = (xmin - kHalfPixel + kSubpixel - 1) >> kSubpixelBits;
  int32_t c1 = (xmax - kHalfPixel + kSubpixel - 1) >> kSubpixelBits;
  if (c0 < 0) c0 = 0;
  if (c1 > width_) c1 = width_;
  if (r0 > r1 || c0 >= c1) return BinResult::kOffscreen;
  return BinResult::kBinned;
}

FrameBuilder::BinResult FrameBuilder::bin(uint16_t a, uint16_t b, uint16_t c, uint8_t draw,
                                          Rgb8 flat, Rgb8 flat_spec, Cull cull,
                                          const int32_t* rows) {
  const ScreenVertex& v0 = storage_.vertices[a];
  const ScreenVertex& v1 = storage_.vertices[b];
  const ScreenVertex& v2 = storage_.vertices[c];
  int32_t r0 = 0, r1 = 0;
  if (rows != nullptr) {
    r0 = rows[0];
    r1 = rows[1];
  } else {
    const BinResult result = classify(v0, v1, v2, cull, r0, r1);
    if (result != BinResult::kBinned) return result;
  }
  if (triangle_count_ >= storage_.triangles.size()) return BinResult::kCapacity;
  auto index = static_cast<uint16_t>(triangle_count_++);
  BinnedTriangle& t = storage_.triangles[index];
  t.v[0] = a;
  t.v[1] = b;
  t.v[2] = c;
  t.draw = draw;
  t.flat = flat;
  t.flat_spec = flat_spec;
  t.reserved = 0;
  if (skipping()) {
    const DrawRecord& d = storage_.draws[draw];
    InputHash h(d.inputs);
    h.add(v0);
    h.add(v1);
    h.add(v2);
    if (d.phong) {
      h.add(storage_.surfaces[a]);
      h.add(storage_.surfaces[b]);
      h.add(storage_.surfaces[c]);
    }
    h.add(flat);
    h.add(flat_spec);
    for (int32_t s = r0 / strip_height_; s <= r1 / strip_height_; ++s) {
      uint32_t& sig = storage_.strip_inputs[static_cast<size_t>(s)];
      InputHash hs(sig);
      hs.add(h.value());
      sig = hs.value();
    }
  }
  uint16_t& head = storage_.buckets[static_cast<size_t>(r0 / strip_height_)];
  t.next = head;
  head = index;
  ++stats_.triangles_binned;
  return BinResult::kBinned;
}

namespace {
void count_outcome(FrameStats& s, int binned, int last_reason) {
  // last_reason: 1 backface, 2 zero area, 3 offscreen, 4 capacity, 5 clipped away, 6 vertex
  // capacity
  if (binned > 0) {
    ++s.binned_inputs;
    return;
  }
  switch (last_reason) {
    case 1:
      ++s.culled_backface;
      break;
    case 2:
      ++s.culled_zero_area;
      break;
    case 3:
      ++s.culled_offscreen;
      break;
    case 4:
      ++s.dropped_triangle_capacity;
      break;
    case 6:
      ++s.dropped_vertex_capacity;
      break;
    default:
      ++s.clipped_away;
      break;
  }
}
}  // namespace

Status FrameBuilder::draw(const Mesh& mesh, const Mat4& model, const Material& material,
                          const DrawState& state) {
  if (!configured_) return Status::kInvalidArgument;
  const size_t n = mesh.positions.size();
  if ((!mesh.normals.empty() && mesh.normals.size() != n) ||
      (!mesh.colors.empty() && mesh.colors.size() != n))
    return Status::kInvalidArgument;
  const bool lit = state.lighting;
  // Phong is per-pixel lighting; unlit, it is the same as Gouraud.
  const bool phong = lit && state.shading == Shading::kPhong;
  const bool gouraud = state.shading != Shading::kFlat && !phong;
  if (lit && state.shading != Shading::kFlat && mesh.normals.empty())
    return Status::kInvalidArgument;
  const bool textured = state.texture != nullptr;
  // Unlit meshes without vertex colours have one colour: no colour planes needed.
  const bool color_planes = gouraud && (lit || !mesh.colors.empty() || textured);
  // A state the renderer links no routine for is refused (nothing added, nothing counted).
  if (!admitted(state, phong, color_planes)) return Status::kInvalidArgument;
  if (textured) {
    if (validate(*state.texture) != Status::kOk) return Status::kInvalidArgument;
    if (state.sampler.mip != MipMode::kNone && state.texture->level_count < 2)
      return Status::kInvalidArgument;
  }
  if ((textured || (phong && state.normal_map)) && !mesh.uvs.empty() && mesh.uvs.size() != n)
    return Status::kInvalidArgument;
  if (phong) {
    if (state.envmap && validate(*state.envmap) != Status::kOk) return Status::kInvalidArgument;
    if (state.normal_map && (validate(*state.normal_map) != Status::kOk ||
                             mesh.tangents.size() != n || mesh.uvs.size() != n))
      return Status::kInvalidArgument;
    if (state.pixel_lighting == PixelLighting::kTable &&
        (!lights_.normal_only() || state.table.size < kMinLightingTable ||
         state.table.size > kMaxLightingTable))
      return Status::kInvalidArgument;
  }
  // Textured, lit and modulated: primary and specular colours kept apart (GL's separate
  // specular colour), so that the texel modulates the primary only.
  const bool split = textured && lit && state.sampler.env == TexEnv::kModulate;
  const bool two_sided = lit && lights_.two_sided && !phong;  // Phong flips at setup
  const auto tri_count = static_cast<uint32_t>(mesh.triangles.size());
  stats_.triangles_in += tri_count;

  if (phong && !surfaces_fit(n)) {
    stats_.dropped_vertex_capacity += tri_count;
    return Status::kCapacity;
  }
  uint8_t draw_index = 0;
  if (add_draw_record(state, color_planes, n, tri_count, draw_index) != Status::kOk)
    return Status::kCapacity;

  const Mat4 mvp = camera_.projection * camera_.view * model;
  const Mat4 nm = normal_matrix(model);
  const Vec3 view_dir{camera_.view.m[2][0], camera_.view.m[2][1], camera_.view.m[2][2]};
  PreparedLighting pl;
  if (lit) pl = prepare_lighting(lights_, material, view_dir, camera_.eye);
  if (phong && add_phong_state(state, pl, storage_.draws[draw_index]) != Status::kOk) {
    --draw_count_;
    stats_.dropped_triangle_capacity += tri_count;
    return Status::kCapacity;
  }
  if (skipping()) sign_draw(draw_index, phong ? &material : nullptr);
  const uint32_t dropped_before = stats_.dropped_triangle_capacity + stats_.dropped_vertex_capacity;
  const Color15 material_color = material.diffuse;
  const bool need_position = pl.needs_position();

  // Lit colour(s) of mesh vertex i with the normal negated or not.
  auto light_vertex = [&](size_t i, bool back, ScreenVertex& sv) {
    const Normal16& nn = mesh.normals[i];
    Unit30 nw = transform_normal(nm, nn.x, nn.y, nn.z);
    if (back) nw = negate(nw);
    Vec3 pw = need_position ? transform_affine(model, mesh.positions[i]) : Vec3{};
    if (split) {
      LitColor lc = light_point_split(pl, nw, pw);
      sv.color = lc.primary;
      sv.spec = lc.secondary;
    } else {
      sv.color = light_point(pl, nw, pw);
    }
  };

  const size_t base = vertex_count_;
  vertex_count_ += n;
  stats_.vertices_transformed += static_cast<uint32_t>(n);
  for (size_t i = 0; i < n; ++i) {
    ScreenVertex& sv = storage_.vertices[base + i];
    sv.unlit = lit && gouraud ? 1 : 0;
    ClipCoord c = transform_point(mvp, mesh.positions[i]);
    sv.outcode = outcode(c, guard_);
    if (sv.outcode == 0) project(c, sv);
    sv.u = mesh.uvs.empty() ? 0 : mesh.uvs[i].u;
    sv.v = mesh.uvs.empty() ? 0 : mesh.uvs[i].v;
    sv.spec = Color15{};
    if (phong) {
      sv.color = Color15{};
      SurfaceVertex& su = storage_.surfaces[base + i];
      const Normal16& nn = mesh.normals[i];
      su.normal = transform_normal(nm, nn.x, nn.y, nn.z);
      su.position = need_position ? transform_affine(model, mesh.positions[i]) : Vec3{};
      if (state.normal_map) {
        transform_tangent(model, mesh.tangents[i], su.tangent);
        su.handedness = mesh.tangents[i].w < 0 ? -16384 : 16384;
      } else {
        su.tangent[0] = su.tangent[1] = su.tangent[2] = 0;
        su.handedness = 16384;
      }
    } else if (lit && gouraud) {
      sv.color = Color15{};  // lit when a triangle that is drawn first uses it (below)
    } else if (!lit) {
      sv.color = mesh.colors.empty() ? material_color : from_rgb8(mesh.colors[i]);
    } else {
      sv.color = Color15{};
    }
  }

  // Back faces' colours (two-sided Gouraud): written before use on each back face; declared once
  // here because a value-initialised local per triangle cost a 120-byte memset each.
  ScreenVertex back_colors[3];
  for (uint32_t t = 0; t < tri_count; ++t) {
    const auto& tri = mesh.triangles[t];
    if (tri[0] >= n || tri[1] >= n || tri[2] >= n) {
      ++stats_.rejected_invalid;
      continue;
    }
    uint16_t vi[3] = {static_cast<uint16_t>(base + tri[0]), static_cast<uint16_t>(base + tri[1]),
                      static_cast<uint16_t>(base + tri[2])};
    const ScreenVertex* sv[3] = {&storage_.vertices[vi[0]], &storage_.vertices[vi[1]],
                                 &storage_.vertices[vi[2]]};
    uint8_t oc_or = sv[0]->outcode | sv[1]->outcode | sv[2]->outcode;
    uint8_t oc_and = sv[0]->outcode & sv[1]->outcode & sv[2]->outcode;
    if (oc_or & kClipOutOfRange) {
      ++stats_.rejected_invalid;
      continue;
    }
    if (oc_and != 0) {
      ++stats_.clipped_away;
      continue;
    }
    int32_t classified_rows[2] = {0, 0};
    bool classified = false;
    if (lit && gouraud) {
      // Vertices are lit on first use by a triangle that is drawn: those only culled, off-screen
      // or covering no pixel centre are never lit. bin() takes the rows found here.
      if (oc_or == 0 && !two_sided) {
        const BinResult r =
            classify(*sv[0], *sv[1], *sv[2], state.cull, classified_rows[0], classified_rows[1]);
        classified = true;
        if (r != BinResult::kBinned) {
          count_outcome(stats_, 0, static_cast<int>(r));
          continue;
        }
      }
      for (int k = 0; k < 3; ++k) {
        ScreenVertex& v = storage_.vertices[vi[k]];
        if (v.unlit) {
          light_vertex(tri[static_cast<size_t>(k)], false, v);
          v.unlit = 0;
        }
      }
    }
    // Two-sided lighting: back faces are lit with the negated normal (GL decides per polygon).
    bool back = false;
    ClipCoord clip[3];
    if (oc_or != 0)
      for (int k = 0; k < 3; ++k)
        clip[k] = transform_point(mvp, mesh.positions[tri[static_cast<size_t>(k)]]);
    if (two_sided) {
      if (oc_or == 0) {
        back = (int64_t{sv[1]->x} - sv[0]->x) * (int64_t{sv[2]->y} - sv[0]->y) -
                   (int64_t{sv[2]->x} - sv[0]->x) * (int64_t{sv[1]->y} - sv[0]->y) >
               0;
      } else {
        back = !front_facing_clip(clip);
      }
    }
    if (back && gouraud)
      for (int k = 0; k < 3; ++k) light_vertex(tri[static_cast<size_t>(k)], true, back_colors[k]);

    Rgb8 flat{}, flat_spec{};
    if (!gouraud && !phong) {
      if (lit) {
        const Vec3& p0 = mesh.positions[tri[0]];
        const Vec3& p1 = mesh.positions[tri[1]];
        const Vec3& p2 = mesh.positions[tri[2]];
        Unit30 fm = face_normal_model(p0, p1, p2);
        Unit30 fw = transform_normal(nm, fm.x, fm.y, fm.z);
        if (back) fw = negate(fw);
        Vec3 centroid{};
        if (need_position) {
          Vec3 w0 = transform_affine(model, p0), w1 = transform_affine(model, p1),
               w2 = transform_affine(model, p2);
          centroid = {
              Fixed::from_raw(static_cast<int32_t>((int64_t{w0.x.raw} + w1.x.raw + w2.x.raw) / 3)),
              Fixed::from_raw(static_cast<int32_t>((int64_t{w0.y.raw} + w1.y.raw + w2.y.raw) / 3)),
              Fixed::from_raw(static_cast<int32_t>((int64_t{w0.z.raw} + w1.z.raw + w2.z.raw) / 3))};
        }
        if (split) {
          LitColor lc = light_point_split(pl, fw, centroid);
          flat = to_rgb8_sat(lc.primary);
          flat_spec = to_rgb8_sat(lc.secondary);
        } else {
          flat = to_rgb8_sat(light_point(pl, fw, centroid));
        }
      } else {
        flat = to_rgb8_sat(sv[2]->color);  // GL's provoking vertex: the last one
      }
    } else if (!color_planes && !phong) {
      flat = to_rgb8_sat(material_color);
    }

    if (oc_or == 0) {
      if (back && gouraud) {
        // The back face's own copies of its vertices, with the back colours.
        if (storage_.vertices.size() - vertex_count_ < 3) {
          count_outcome(stats_, 0, 6);
          continue;
        }
        for (int k = 0; k < 3; ++k) {
          ScreenVertex& nv = storage_.vertices[vertex_count_ + static_cast<size_t>(k)];
          nv = *sv[k];
          nv.color = back_colors[k].color;
          nv.spec = back_colors[k].spec;
          vi[k] = static_cast<uint16_t>(vertex_count_ + static_cast<size_t>(k));
        }
        vertex_count_ += 3;
      }
      BinResult r = bin(vi[0], vi[1], vi[2], draw_index, flat, flat_spec, state.cull,
                        classified ? classified_rows : nullptr);
      count_outcome(stats_, r == BinResult::kBinned ? 1 : 0, static_cast<int>(r));
      continue;
    }

    // Clip in homogeneous space. Clip coordinates are recomputed from the mesh rather than
    // stored per vertex: only triangles that cross a plane pay for it.
    ++stats_.clipped;
    ClipVertex poly[kMaxClipVertices];
    for (int k = 0; k < 3; ++k) {
      const ScreenVertex& src = back && gouraud ? back_colors[k] : *sv[k];
      poly[k].p = clip[k];
      poly[k].color = src.color;
      poly[k].spec = src.spec;
      poly[k].u = sv[k]->u;
      poly[k].v = sv[k]->v;
      if (phong) poly[k].surface = storage_.surfaces[vi[k]];
    }
    int m = clip_polygon(poly, 3, oc_or, guard_);
    if (m < 3) {
      ++stats_.clipped_away;
      continue;
    }
    if (static_cast<size_t>(m) > storage_.vertices.size() - vertex_count_ ||
        (phong && !surfaces_fit(static_cast<size_t>(m)))) {
      ++stats_.dropped_vertex_capacity;
      continue;
    }
    uint16_t first = static_cast<uint16_t>(vertex_count_);
    int projected = 0;
    for (int k = 0; k < m; ++k) {
      ScreenVertex& nv = storage_.vertices[vertex_count_ + static_cast<size_t>(k)];
      nv.color = poly[k].color;
      nv.spec = poly[k].spec;
      nv.u = poly[k].u;
      nv.v = poly[k].v;
      nv.outcode = 0;
      if (project(poly[k].p, nv)) ++projected;
      if (phong) storage_.surfaces[vertex_count_ + static_cast<size_t>(k)] = poly[k].surface;
    }
    if (projected != m) {
      ++stats_.clipped_away;
      continue;
    }
    vertex_count_ += static_cast<size_t>(m);
    int binned = 0, last = 5;
    for (int k = 1; k + 1 < m; ++k) {
      BinResult r =
          bin(first, static_cast<uint16_t>(first + k), static_cast<uint16_t>(first + k + 1),
              draw_index, flat, flat_spec, state.cull);
      if (r == BinResult::kBinned)
        ++binned;
      else
        last = static_cast<int>(r);
    }
    count_outcome(stats_, binned, last);
  }
  bool dropped = stats_.dropped_triangle_capacity + stats_.dropped_vertex_capacity > dropped_before;
  return dropped ? Status::kCapacity : Status::kOk;
}

Status FrameBuilder::draw_screen(std::span<const ScreenVertex> vertices,
                                 std::span<const std::array<uint16_t, 3>> triangles,
                                 const DrawState& state) {
  if (!configured_) return Status::kInvalidArgument;
  const bool gouraud = state.shading == Shading::kGouraud;
  if (!admitted(state, false, gouraud)) return Status::kInvalidArgument;
  const size_t n = vertices.size();
  const auto tri_count = static_cast<uint32_t>(triangles.size());
  stats_.triangles_in += tri_count;
  uint8_t draw_index = 0;
  if (add_draw_record(state, gouraud, n, tri_count, draw_index) != Status::kOk)
    return Status::kCapacity;
  if (skipping()) sign_draw(draw_index, nullptr);
  const uint32_t dropped_before = stats_.dropped_triangle_capacity + stats_.dropped_vertex_capacity;
  const size_t base = vertex_count_;
  const int32_t limit = (kMaxViewport * 3) << kSubpixelBits;  // inside the coordinate budget
  for (size_t i = 0; i < n; ++i) {
    ScreenVertex v = vertices[i];
    if (v.w == 0) v.w = 1u << 16;
    bool ok = v.x > -limit && v.x < limit && v.y > -limit && v.y < limit && v.z <= kDepthMax;
    v.outcode = ok ? 0 : kClipOutOfRange;
    storage_.vertices[base + i] = v;
  }
  vertex_count_ += n;
  for (uint32_t t = 0; t < tri_count; ++t) {
    const auto& tri = triangles[t];
    if (tri[0] >= n || tri[1] >= n || tri[2] >= n) {
      ++stats_.rejected_invalid;
      continue;
    }
    uint16_t vi[3] = {static_cast<uint16_t>(base + tri[0]), static_cast<uint16_t>(base + tri[1]),
                      static_cast<uint16_t>(base + tri[2])};
    uint8_t oc = storage_.vertices[vi[0]].outcode | storage_.vertices[vi[1]].outcode |
                 storage_.vertices[vi[2]].outcode;
    if (oc != 0) {
      ++stats_.rejected_invalid;
      continue;
    }
    Rgb8 flat = to_rgb8_sat(storage_.vertices[vi[2]].color);
    Rgb8 flat_spec = to_rgb8_sat(storage_.vertices[vi[2]].spec);
    BinResult r = bin(vi[0], vi[1], vi[2], draw_index, flat, flat_spec, state.cull);
    count_outcome(stats_, r == BinResult::kBinned ? 1 : 0, static_cast<int>(r));
  }
  bool dropped = stats_.dropped_triangle_capacity + stats_.dropped_vertex_capacity > dropped_before;
  return dropped ? Status::kCapacity : Status::kOk;
}

}  // namespace lr
