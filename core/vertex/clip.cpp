#include "lineraster/core/vertex/clip.hpp"

#include "lineraster/core/math/wide_divide.hpp"

namespace lr {
namespace {

constexpr int64_t kRangeLimit = int64_t{1} << 47;
constexpr int64_t kMinW = int64_t{1} << (ClipCoord::kFracBits - 16);  // w >= 2^-16

// Signed distance to plane i (>= 0 inside). |coordinates| < 2^47 and G <= 8192 keep it < 2^61.
int64_t distance(const ClipCoord& c, int i, GuardBand g) {
  switch (i) {
    case 0:
      return c.z + c.w;
    case 1:
      return c.w - c.z;
    case 2:
      return c.x + g.gx * c.w;
    case 3:
      return g.gx * c.w - c.x;
    case 4:
      return c.y + g.gy * c.w;
    case 5:
      return g.gy * c.w - c.y;
    default:
      return c.w - kMinW;
  }
}

// (a * t) >> 30 for |a| < 2^63 and 0 <= t <= 2^30, without a 128-bit product.
int64_t mul_frac30(int64_t a, uint32_t t) {
  uint64_t u = abs64(a);
  uint64_t hi = (u >> 32) * t;          // < 2^61
  uint64_t lo = (u & 0xFFFFFFFFu) * t;  // < 2^62
  uint64_t r = (hi << 2) + (lo >> 30);
  return a < 0 ? -static_cast<int64_t>(r) : static_cast<int64_t>(r);
}

// The point where the segment from `in` (inside) to `out` (outside) meets the plane. A corner's
// side is its outcode's: its distance may have the other sign by a rounding step, read as 0
// (inside) or -1 (outside), so that t stays in [0, 1). Without kAttributes only the position and
// the colour (the other members keep their defaults: zeros).
template <bool kAttributes>
ClipVertex intersect(const ClipVertex& in, const ClipVertex& out, int64_t d_in, int64_t d_out) {
  if (d_in < 0) d_in = 0;
  if (d_out >= 0) d_out = -1;
  uint64_t num = static_cast<uint64_t>(d_in), den = static_cast<uint64_t>(d_in - d_out);  // < 2^62
  int s = 0;
  while ((den >> s) >= (uint64_t{1} << 31)) ++s;
  num >>= s;
  den >>= s;
  // num < den < 2^31: t in [0, 2^30), num 2^30 < den 2^32 (one 64-by-32 division).
  const uint32_t t = divide_64by32(num << 30, static_cast<uint32_t>(den)).q;
  ClipVertex r;
  r.p.x = in.p.x + mul_frac30(out.p.x - in.p.x, t);
  r.p.y = in.p.y + mul_frac30(out.p.y - in.p.y, t);
  r.p.z = in.p.z + mul_frac30(out.p.z - in.p.z, t);
  r.p.w = in.p.w + mul_frac30(out.p.w - in.p.w, t);
  uint16_t c[3];
  for (int k = 0; k < 3; ++k) {
    int64_t a = channel(in.color, k), b = channel(out.color, k);
    c[k] = static_cast<uint16_t>(a + (((b - a) * t) >> 30));
  }
  r.color = make_color15(c);
  r.corner = 0;
  r.outcode = 0;
  if constexpr (!kAttributes) return r;
  for (int k = 0; k < 3; ++k) {
    int64_t a = channel(in.spec, k), b = channel(out.spec, k);
    c[k] = static_cast<uint16_t>(a + (((b - a) * t) >> 30));
  }
  r.spec = make_color15(c);
  // |u| < 2^31: the difference is < 2^32 and times t (< 2^30) stays inside int64.
  r.u = static_cast<int32_t>(in.u + ((int64_t{out.u} - in.u) * t >> 30));
  r.v = static_cast<int32_t>(in.v + ((int64_t{out.v} - in.v) * t >> 30));
  // Surface attributes: normal and tangent components are within [-1, 1], positions are
  // Q16.16 (differences < 2^32): every product with t stays inside int64. The normal needs no
  // renormalising here (spans renormalise per pixel).
  auto lerp32 = [t](int32_t a, int32_t b) {
    return static_cast<int32_t>(a + ((int64_t{b} - a) * t >> 30));
  };
  const SurfaceVertex &sa = in.surface, &sb = out.surface;
  r.surface.normal = {lerp32(sa.normal.x, sb.normal.x), lerp32(sa.normal.y, sb.normal.y),
                      lerp32(sa.normal.z, sb.normal.z)};
  r.surface.position = {Fixed::from_raw(lerp32(sa.position.x.raw, sb.position.x.raw)),
                        Fixed::from_raw(lerp32(sa.position.y.raw, sb.position.y.raw)),
                        Fixed::from_raw(lerp32(sa.position.z.raw, sb.position.z.raw))};
  for (int k = 0; k < 3; ++k)
    r.surface.tangent[k] = static_cast<int16_t>(lerp32(sa.tangent[k], sb.tangent[k]));
  r.surface.handedness = sa.handedness;
  return r;
}

}  // namespace

uint8_t outcode(const ClipCoord& c, GuardBand g) {
  if (c.x >= kRangeLimit || c.x <= -kRangeLimit || c.y >= kRangeLimit || c.y <= -kRangeLimit ||
      c.z >= kRangeLimit || c.z <= -kRangeLimit || c.w >= kRangeLimit || c.w <= -kRangeLimit)
    return kClipOutOfRange;
  uint8_t code = 0;
  for (int i = 0; i < kClipPlanes; ++i)
    if (distance(c, i, g) < 0) code = static_cast<uint8_t>(code | (1u << i));
  return code;
}

template <bool kAttributes>
int clip_polygon(ClipPolygon poly, ClipPolygon scratch, int n, uint8_t planes, GuardBand g) {
  for (int i = 0; i < kClipPlanes && n > 0; ++i) {
    if (!(planes & (1u << i))) continue;
    int m = 0;
    for (int k = 0; k < n; ++k) {
      const ClipVertex& a = poly[static_cast<size_t>(k)];
      const ClipVertex& b = poly[static_cast<size_t>((k + 1) % n)];
      int64_t da = distance(a.p, i, g), db = distance(b.p, i, g);
      const bool ina = a.corner != 0 ? !(a.outcode & (1u << i)) : da >= 0;
      const bool inb = b.corner != 0 ? !(b.outcode & (1u << i)) : db >= 0;
      // A convex polygon gains at most one vertex per plane; the bound only guards against
      // rounding making a sliver non-convex.
      if (ina && m < kMaxClipVertices) scratch[static_cast<size_t>(m++)] = a;
      if (ina != inb && m < kMaxClipVertices)
        scratch[static_cast<size_t>(m++)] =
            ina ? intersect<kAttributes>(a, b, da, db) : intersect<kAttributes>(b, a, db, da);
    }
    for (int k = 0; k < m; ++k) poly[static_cast<size_t>(k)] = scratch[static_cast<size_t>(k)];
    n = m;
  }
  return n;
}

template int clip_polygon<true>(ClipPolygon, ClipPolygon, int, uint8_t, GuardBand);
template int clip_polygon<false>(ClipPolygon, ClipPolygon, int, uint8_t, GuardBand);

}  // namespace lr
