#include "lineraster/core/vertex/vertex_stage.hpp"

#include "lineraster/core/math/reciprocal.hpp"
#include "lineraster/core/math/wide_divide.hpp"

namespace lr {
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

LitColor light_point_at(const PreparedLighting& pl, const Unit30& n, const Mat4* model, Vec3 p) {
  return light_point_split(pl, n, model != nullptr ? transform_affine(*model, p) : p);
}

Unit30 transform_normal_call(const Mat4& nm, int64_t x, int64_t y, int64_t z) {
  return transform_normal(nm, x, y, z);
}

FineMat4 fine_model_view_projection(const Camera& camera, const FineMat4& model) {
  const FineMat4 projection =
      camera.fine_projection != nullptr ? *camera.fine_projection : to_fine(camera.projection);
  // An identity view leaves the model's entries as they are (its product is exact): skipped.
  if (camera.view == Mat4::identity()) return projection * model;
  return projection * (to_fine(camera.view) * model);
}

FineMat4 VertexStage::model_view_projection(const Camera& camera, const Mat4& model,
                                            const FineMat4* fine_model) {
  if (fine_model != nullptr) return fine_model_view_projection(camera, *fine_model);
  return to_fine(camera.projection * camera.view * model);
}

VertexStage::VertexStage(const Camera& camera, const Mat4& model, GuardBand guard, int width,
                         int height, uint32_t bound, int position_frac, const FineMat4* fine_model,
                         FineComposeFn compose)
    : model_(model),
      mvp_(fine_model != nullptr && compose != nullptr
               ? compose(camera, *fine_model)
               : to_fine(camera.projection * camera.view * model)),
      position_frac_(position_frac),
      nm_(normal_matrix(model)),
      guard_(guard),
      width_(width),
      height_(height),
      screen_(mvp_, position_frac, bound, width, height, guard) {
  rigid_ = rigid_normal_rows(nm_, rot_);
}

TransformSummary VertexStage::transform_range(const Mesh& mesh, const VertexColors& draw_colors,
                                              size_t first, size_t count, ScreenVertex* out,
                                              SurfaceVertex* surfaces, TexVertex* tex) const {
  const VertexColors colors = draw_colors;  // a copy: kept in registers across the calls below
  const Vec3* positions = mesh.positions.data() + first;
  const bool plain = surfaces == nullptr && tex == nullptr;
  // Lit vertices: colour 0 (lit Gouraud: lit on first use, light(); flat: per triangle).
  const Color15 fixed = colors.lit ? Color15{} : colors.material;
  const Rgb8* mesh_colors =
      colors.lit || mesh.colors.empty() ? nullptr : mesh.colors.data() + first;
  const uint8_t pending = colors.pending ? 1 : 0;
  // The last 8 bytes of a vertex without its own colour: the colour, outcode 0, pending flag.
  const uint32_t tail[2] = {uint32_t{fixed.r} | uint32_t{fixed.g} << 16,
                            uint32_t{fixed.b} | uint32_t{pending} << 24};
  // A vertex's own colour or attributes, after its position.
  auto finish = [&](size_t k) {
    if (plain) {
      if (mesh_colors != nullptr) out[k].color = from_rgb8(mesh_colors[k]);
    } else {
      (this->*colors.attributes)(mesh, colors, first + k, out[k],
                                 surfaces != nullptr ? &surfaces[k] : nullptr,
                                 tex != nullptr ? &tex[k] : nullptr);
    }
  };
  uint32_t wide = 0, outcodes = 0;
  for (size_t k = 0; k < count;) {
    // The short path's run (32-bit rows, one reciprocal of w), then the exact path (64-bit clip
    // coordinates) for the vertex it leaves.
    const size_t end = k + screen_.run(positions + k, count - k, out + k, tail);
    if (mesh_colors != nullptr || !plain)
      for (; k < end; ++k) finish(k);
    k = end;
    if (k == count) break;
    ScreenVertex& sv = out[k];
    project_exact(positions[k], sv);
    ++wide;
    outcodes |= sv.outcode;
    sv.color_pending = pending;
    sv.color = fixed;
    finish(k);
    ++k;
  }
  return {wide, static_cast<uint8_t>(outcodes)};
}

template <bool kSpecular, bool kWorld>
LitColor VertexStage::light(const VertexStage& stage, const Mesh& mesh, const VertexColors colors,
                            size_t i, bool back) {
  if constexpr (!kWorld) {
    // Admitted only with the lights in model space and unit normals (FrontEnd::draw): the
    // model-space path below, without its tests. (Black, never reached, were it not so.)
    if (colors.object == nullptr) return {};
    const LitColor c = light_object<kSpecular>(*colors.lighting, *colors.object, mesh.normals[i],
                                               normal_len2(mesh.normals[i]), back);
    if (colors.split) return c;
    return {sum_clamped(c.primary, c.secondary), Color15{}};
  }
  if (colors.object != nullptr) {
    const uint32_t len2 = normal_len2(mesh.normals[i]);
    if (unit_len2(len2)) {
      const LitColor c =
          light_object<kSpecular>(*colors.lighting, *colors.object, mesh.normals[i], len2, back);
      if (colors.split) return c;
      return {sum_clamped(c.primary, c.secondary), Color15{}};
    }
  }
  Unit30 nw = stage.world_normal(mesh.normals[i]);
  if (back) nw = negate(nw);
  if (!colors.need_position) {
    if (colors.split) return light_directional_split<kSpecular>(*colors.lighting, nw);
    return {light_directional<kSpecular>(*colors.lighting, nw), Color15{}};
  }
  const LitColor c =
      colors.point(*colors.lighting, nw, &stage.model_, stage.q16(mesh.positions[i]));
  if (colors.split) return c;
  return {sum_clamped(c.primary, c.secondary), Color15{}};
}
template LitColor VertexStage::light<true, true>(const VertexStage&, const Mesh&, VertexColors,
                                                 size_t, bool);
template LitColor VertexStage::light<true, false>(const VertexStage&, const Mesh&, VertexColors,
                                                  size_t, bool);
template LitColor VertexStage::light<false, true>(const VertexStage&, const Mesh&, VertexColors,
                                                  size_t, bool);
template LitColor VertexStage::light<false, false>(const VertexStage&, const Mesh&, VertexColors,
                                                   size_t, bool);

template <bool kSpecular>
LitColor VertexStage::light_face(const VertexColors colors, const Vec3& p0, const Vec3& p1,
                                 const Vec3& p2, bool back) const {
  const Unit30 fm = face_normal_model(p0, p1, p2);
  Unit30 fw = transform_normal_call(nm_, fm.x, fm.y, fm.z);
  if (back) fw = negate(fw);
  Vec3 centroid{};
  if (colors.need_position) {
    const Vec3 w0 = transform_affine(model_, q16(p0)), w1 = transform_affine(model_, q16(p1)),
               w2 = transform_affine(model_, q16(p2));
    // The mean of three int32, truncated (C's division): |sum| < 3 2^31, a 64-by-32 division of
    // its magnitude.
    auto mean = [](int32_t a, int32_t b, int32_t c) {
      const int64_t sum = int64_t{a} + b + c;
      const auto q = static_cast<int64_t>(divide_64by32(abs64(sum), 3).q);
      return Fixed::from_raw(static_cast<int32_t>(sum < 0 ? -q : q));
    };
    centroid = {mean(w0.x.raw, w1.x.raw, w2.x.raw), mean(w0.y.raw, w1.y.raw, w2.y.raw),
                mean(w0.z.raw, w1.z.raw, w2.z.raw)};
  }
  // Directional lights and the infinite viewer: the inline path (bit for bit the same).
  const LitColor c = colors.need_position
                         ? colors.point(*colors.lighting, fw, nullptr, centroid)
                         : light_directional_split<kSpecular>(*colors.lighting, fw);
  if (colors.split) return c;
  return {sum_clamped(c.primary, c.secondary), Color15{}};
}
template LitColor VertexStage::light_face<true>(VertexColors, const Vec3&, const Vec3&, const Vec3&,
                                                bool) const;
template LitColor VertexStage::light_face<false>(VertexColors, const Vec3&, const Vec3&,
                                                 const Vec3&, bool) const;

void VertexStage::project_exact(const Vec3& p, ScreenVertex& sv) const {
  const ClipCoord c = clip(p);
  sv.outcode = outcode(c, guard_);
  if (sv.outcode == 0) project(c, sv);
}

void VertexStage::attributes(const Mesh& mesh, const VertexColors& colors, size_t i,
                             ScreenVertex& sv, SurfaceVertex* surface, TexVertex* tex) const {
  if (tex != nullptr) {
    tex->u = mesh.uvs.empty() ? 0 : mesh.uvs[i].u;
    tex->v = mesh.uvs.empty() ? 0 : mesh.uvs[i].v;
    tex->spec = Color15{};
  }
  if (surface != nullptr) {
    sv.color = Color15{};
    SurfaceVertex& su = *surface;
    const Normal16& nn = mesh.normals[i];
    su.normal = transform_normal_call(nm_, nn.x, nn.y, nn.z);
    su.position = colors.need_position ? transform_affine(model_, q16(mesh.positions[i])) : Vec3{};
    if (colors.tangents) {
      transform_tangent(model_, mesh.tangents[i], su.tangent);
      su.handedness = mesh.tangents[i].w < 0 ? -16384 : 16384;
    } else {
      su.tangent[0] = su.tangent[1] = su.tangent[2] = 0;
      su.handedness = 16384;
    }
  } else if (!colors.lit) {
    sv.color = mesh.colors.empty() ? colors.material : from_rgb8(mesh.colors[i]);
  } else {
    sv.color = Color15{};  // lit Gouraud: lit on first use (light()); flat: per triangle
  }
}

bool VertexStage::project(const ClipCoord& c, ScreenVertex& v) const {
  // Inside every plane: w >= 2^-16, |x| <= gx w, |y| <= gy w, |z| <= w. Normalise so w < 2^31
  // (one shift: the same floor as halving repeatedly).
  int64_t x = c.x, y = c.y, z = c.z, w = c.w;
  if (w <= 0) return false;
  if (w >= (int64_t{1} << 31)) {
    const int s = 33 - clz64(static_cast<uint64_t>(w));
    x >>= s;
    y >>= s;
    z >>= s;
    w >>= s;
  }
  // Three quotients by the same w: one inverse limb of w normalised into [2^31, 2^32), then a
  // 2-by-1 division each (core/math/reciprocal.hpp), exact: the values of round_div(n, w), half
  // away from zero (n is negative left of and below the viewport). Every quotient is below
  // 2^32 (docs/numerics.md#projection-and-snapping), so n + w / 2 < 2^32 w and its shifted
  // value fits the division.
  const auto half = static_cast<uint64_t>(w / 2);
#if defined(__OPTIMIZE_SIZE__)
  // Built for size: divide_64by32 for each (its normalisation and reciprocal are these, per
  // quotient: the same integers in one copy of the code).
  auto quotient = [&](uint64_t n) { return divide_64by32(n + half, static_cast<uint32_t>(w)).q; };
#else
  const int sh = clz32(static_cast<uint32_t>(w));
  const uint32_t d = static_cast<uint32_t>(w) << sh;
  const uint32_t inv = recip32(d);
  auto quotient = [&](uint64_t n) { return divide_2by1((n + half) << sh, d, inv).q; };
#endif
  auto rounded = [&](int64_t n) {
    return n >= 0 ? static_cast<int64_t>(quotient(static_cast<uint64_t>(n)))
                  : -static_cast<int64_t>(quotient(static_cast<uint64_t>(-n)));
  };
  // (x + w) <= (gx + 1) w and (gx + 1) * width <= 8192 + width: product < 1.5 * 2^51.
  v.x = static_cast<int32_t>(rounded((x + w) * (int64_t{width_} * kHalfPixel)));
  v.y = static_cast<int32_t>(rounded((w - y) * (int64_t{height_} * kHalfPixel)));
  // z + w <= 2w < 2^32 and 65535 * 2^15 < 2^31: product < 2^63, quotient about kDepthMax at
  // most. (A clipped vertex may lie a rounding step outside the near or far plane: clamped.)
  const uint32_t zz =
      z + w <= 0 ? 0 : quotient(static_cast<uint64_t>(z + w) * (uint64_t{65535} << 15));
  v.z = zz > kDepthMax ? kDepthMax : zz;
  int64_t wq = c.w >> (ClipCoord::kFracBits - 16);
  v.w = static_cast<uint32_t>(wq < 1 ? 1 : wq > 0xFFFFFFFF ? 0xFFFFFFFF : wq);
  v.outcode = 0;
  return true;
}

bool front_facing_clip(const ClipCoord (&c)[3]) {
  // Coordinates are brought below 2^20 first so the products of three stay inside int64.
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

}  // namespace lr
