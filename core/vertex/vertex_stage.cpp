#include "lineraster/core/vertex/vertex_stage.hpp"

#include "lineraster/core/math/reciprocal.hpp"

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

Unit30 transform_normal_call(const Mat4& nm, int64_t x, int64_t y, int64_t z) {
  return transform_normal(nm, x, y, z);
}

VertexStage::VertexStage(const Camera& camera, const Mat4& model, GuardBand guard, int width,
                         int height, uint32_t bound)
    : model_(model),
      mvp_(camera.projection * camera.view * model),
      nm_(normal_matrix(model)),
      guard_(guard),
      width_(width),
      height_(height),
      screen_(mvp_, bound, width, height, guard) {
  rigid_ = rigid_normal_rows(nm_, rot_);
}

bool VertexStage::transform_one(const Mesh& mesh, const VertexColors& colors, size_t i,
                                ScreenVertex& sv, SurfaceVertex* surface, TexVertex* tex) const {
  return transform_vertex(mesh, colors, i, sv, surface, tex);
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
  const int sh = clz32(static_cast<uint32_t>(w));
  const uint32_t d = static_cast<uint32_t>(w) << sh;
  const uint32_t inv = recip32(d);
  const auto half = static_cast<uint64_t>(w / 2);
  auto quotient = [&](uint64_t n) { return divide_2by1((n + half) << sh, d, inv).q; };
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
