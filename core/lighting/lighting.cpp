#include "lineraster/core/lighting/lighting.hpp"

#include "lineraster/core/math/wide_divide.hpp"

namespace lr {
namespace {

constexpr uint16_t mul15(uint16_t a, uint16_t b) {
  return static_cast<uint16_t>((uint32_t{a} * b + (1u << 14)) >> 15);
}

constexpr int64_t dot30(const Unit30& a, const Unit30& b) {
  return (int64_t{a.x} * b.x + int64_t{a.y} * b.y + int64_t{a.z} * b.z) >> 30;
}

Unit30 unit_of(Vec3 v) {
  Unit30 u{0, 0, 1 << 30};
  normalize_unit30(v.x.raw, v.y.raw, v.z.raw, u);
  return u;
}

// Unit vector from a to b: the difference of two Q16.16 values needs 33 bits.
Unit30 direction(Vec3 a, Vec3 b) {
  Unit30 u{0, 0, 1 << 30};
  normalize_unit30(int64_t{b.x.raw} - a.x.raw, int64_t{b.y.raw} - a.y.raw,
                   int64_t{b.z.raw} - a.z.raw, u);
  return u;
}

Unit30 half_vector(const Unit30& l, const Unit30& v) {
  Unit30 h = v;
  normalize_unit30(int64_t{l.x} + v.x, int64_t{l.y} + v.y, int64_t{l.z} + v.z, h);
  return h;
}

}  // namespace

PreparedLighting prepare_lighting(const LightSet& set, const Material& m, Vec3 view_dir, Vec3 eye) {
  PreparedLighting pl;
  prepare_lighting(set, m, view_dir, eye, pl);
  return pl;
}

namespace {
// prepare_lighting (kFull) or prepare_diffuse_lighting: the latter leaves out what only point
// lights, the local viewer and specular materials read (the half vectors, the specular
// products, the view direction, the point lights' terms).
template <bool kFull>
[[gnu::always_inline]] inline void prepare(const LightSet& set, const Material& m, Vec3 view_dir,
                                           Vec3 eye, PreparedLighting& pl) {
  pl = PreparedLighting{};
  pl.count = set.count > kMaxLights ? kMaxLights : set.count;
  pl.material = m;
  if constexpr (kFull) {
    pl.shininess_q8 = m.shininess_q8;
    pl.local_viewer = set.local_viewer;
    pl.eye = eye;
    pl.view = unit_of(view_dir);
  }
  for (int c = 0; c < 3; ++c)
    pl.base[c] =
        channel(m.emission, c) + mul15(channel(set.global_ambient, c), channel(m.ambient, c));
  for (int i = 0; i < pl.count; ++i) {
    const Light& src = set.lights[static_cast<size_t>(i)];
    PreparedLighting::Light& d = pl.lights[static_cast<size_t>(i)];
    d.point = kFull && src.kind == LightKind::kPoint;
    pl.any_point = pl.any_point || d.point;
    if (d.point) {
      d.position = src.position;
      d.kc = src.constant.raw < 0 ? 0 : src.constant.raw;
      d.kl = src.linear.raw < 0 ? 0 : src.linear.raw;
      d.kq = src.quadratic.raw < 0 ? 0 : src.quadratic.raw;
    } else {
      d.l = unit_of(src.position);
      if constexpr (kFull) d.h = half_vector(d.l, pl.view);
    }
    for (int c = 0; c < 3; ++c) {
      d.ka[c] = mul15(channel(src.ambient, c), channel(m.ambient, c));
      if (!d.point) pl.base[c] += d.ka[c];
      d.kd[c] = mul15(channel(src.diffuse, c), channel(m.diffuse, c));
      if constexpr (kFull) d.ks[c] = mul15(channel(src.specular, c), channel(m.specular, c));
    }
  }
}
}  // namespace

void prepare_lighting(const LightSet& set, const Material& m, Vec3 view_dir, Vec3 eye,
                      PreparedLighting& pl) {
  prepare<true>(set, m, view_dir, eye, pl);
}

void prepare_diffuse_lighting(const LightSet& set, const Material& m, Vec3 view_dir, Vec3 eye,
                              PreparedLighting& pl) {
  prepare<false>(set, m, view_dir, eye, pl);
}

namespace {

// a * b for a, b >= 0, saturated at 2^62.
int64_t mul_sat(int64_t a, int64_t b) {
  if (a == 0 || b == 0) return 0;
  const int bits = (64 - clz64(static_cast<uint64_t>(a))) + (64 - clz64(static_cast<uint64_t>(b)));
  return bits > 62 ? (int64_t{1} << 62) : a * b;
}

// GL's attenuation 1 / (kc + kl d + kq d^2) in Q4.15 (saturated at 16) for a distance d in
// Q16.16 (< 2^34): the denominator is formed in Q16.16 with saturating products.
uint32_t attenuation(const PreparedLighting::Light& li, int64_t d) {
  const int64_t d2 = mul_sat(d, d) >> 16;  // Q16.16
  int64_t den = li.kc + (mul_sat(li.kl, d) >> 16) + (mul_sat(li.kq, d2) >> 16);
  constexpr uint32_t kMax = 16u << 15;
  if (den <= 0) return kMax;
  // round(2^31 / den): 0 for den above 2^32, 1 at 2^32 (2^31 + 2^31 over 2^32); below, a 64-by-32
  // division whose quotient is at most 2^31.
  if (den >= (int64_t{1} << 32)) return den == (int64_t{1} << 32) ? 1u : 0u;
  const uint32_t a = divide_64by32((uint64_t{1} << 31) + static_cast<uint64_t>(den / 2),
                                   static_cast<uint32_t>(den))
                         .q;
  return a > kMax ? kMax : a;
}

}  // namespace

LitColor light_point_split(const PreparedLighting& pl, const Unit30& n, Vec3 p) {
  int32_t prim[3] = {pl.base[0], pl.base[1], pl.base[2]};
  int32_t spec[3] = {0, 0, 0};
  Unit30 v = pl.view;
  if (pl.local_viewer) v = direction(p, pl.eye);
  for (int i = 0; i < pl.count; ++i) {
    const PreparedLighting::Light& li = pl.lights[static_cast<size_t>(i)];
    if (li.point) {
      const int64_t dx = int64_t{li.position.x.raw} - p.x.raw,
                    dy = int64_t{li.position.y.raw} - p.y.raw,
                    dz = int64_t{li.position.z.raw} - p.z.raw;
      Unit30 l{0, 0, 1 << 30};
      normalize_unit30(dx, dy, dz, l);
      // |d| < 2^34 (Q16.16): each product with a Q1.30 component is below 2^62 after the shift.
      const int64_t d = ((dx >> 2) * l.x + (dy >> 2) * l.y + (dz >> 2) * l.z) >> 28;
      const int64_t att = attenuation(li, d < 0 ? 0 : d);
      for (int c = 0; c < 3; ++c)
        prim[c] += static_cast<int32_t>((att * li.ka[c] + (1 << 14)) >> 15);
      const int64_t ndl = dot30(n, l);
      if (ndl <= 0) continue;
      for (int c = 0; c < 3; ++c) {
        const int64_t dif = (ndl * li.kd[c] + (1 << 29)) >> 30;  // Q1.15
        prim[c] += static_cast<int32_t>((dif * att + (1 << 14)) >> 15);
      }
      const Unit30 h = half_vector(l, v);
      int64_t ndh = dot30(n, h);
      if (ndh <= 0) continue;
      if (ndh > (int64_t{1} << 30)) ndh = int64_t{1} << 30;
      const uint32_t sp = DefaultPowTable::pow_q15(static_cast<uint32_t>(ndh), pl.shininess_q8);
      for (int c = 0; c < 3; ++c) {
        const int64_t s = (int64_t{sp} * li.ks[c] + (1 << 14)) >> 15;
        spec[c] += static_cast<int32_t>((s * att + (1 << 14)) >> 15);
      }
      continue;
    }
    int64_t ndl = dot30(n, li.l);
    if (ndl <= 0) continue;  // no diffuse, and GL gives no specular where N.L <= 0
    // ndl <= 2^30: Q1.30 times Q1.15 is < 2^46 before the shift.
    for (int c = 0; c < 3; ++c) prim[c] += static_cast<int32_t>((ndl * li.kd[c] + (1 << 29)) >> 30);
    Unit30 h = pl.local_viewer ? half_vector(li.l, v) : li.h;
    int64_t ndh = dot30(n, h);
    if (ndh <= 0) continue;
    if (ndh > (int64_t{1} << 30)) ndh = int64_t{1} << 30;
    uint32_t sp = DefaultPowTable::pow_q15(static_cast<uint32_t>(ndh), pl.shininess_q8);
    for (int c = 0; c < 3; ++c)
      spec[c] += static_cast<int32_t>((sp * uint32_t{li.ks[c]} + (1u << 14)) >> 15);
  }
  auto clamp = [](int32_t x) {
    return static_cast<uint16_t>(x < 0 ? 0 : x > Color15::kOne ? Color15::kOne : x);
  };
  LitColor out;
  out.primary = {clamp(prim[0]), clamp(prim[1]), clamp(prim[2])};
  out.secondary = {clamp(spec[0]), clamp(spec[1]), clamp(spec[2])};
  return out;
}

Color15 light_point(const PreparedLighting& pl, const Unit30& n, Vec3 p) {
  // Every term is non-negative, so clamping the two sums first changes nothing.
  LitColor c = light_point_split(pl, n, p);
  auto sum = [](uint16_t a, uint16_t b) {
    uint32_t v = uint32_t{a} + b;
    return static_cast<uint16_t>(v > Color15::kOne ? Color15::kOne : v);
  };
  return {sum(c.primary.r, c.secondary.r), sum(c.primary.g, c.secondary.g),
          sum(c.primary.b, c.secondary.b)};
}

}  // namespace lr
