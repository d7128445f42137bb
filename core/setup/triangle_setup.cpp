#include "lineraster/core/setup/triangle_setup.hpp"

#include "lineraster/core/math/divide.hpp"
#include "lineraster/core/math/reciprocal.hpp"
#include "lineraster/core/math/wide_divide.hpp"

#include <utility>

namespace lr {

void setup_phong(const PhongSetup& ps, const SurfaceVertex* const s[3], const PlaneBasis& pb,
                 const uint32_t q[3], ActiveTriangle& t);

namespace {

// 256 * n / area rounded half away from zero, for area > 0. Returns false when the truncated
// quotient n / area is 2^30 or more in magnitude (a sub-subpixel needle).
// |n| < 2^55 (always inside the guard band: |n| < 2 * 2^32 * 2^22): the rounded value is
// floor(N / area) with N = 256 |n| + area / 2 < 2^63, computed from the basis' reciprocal
// inv = floor((2^64 - 1) / area): q0 = floor(N inv / 2^64) is at most 2 below the quotient
// (N inv / 2^64 > N / area - N / 2^64 - 1 / 2^64... > N / area - 1), and the remainder
// N - q0 area corrects it exactly. Bit for bit the value of 256 q + round(256 r / area) with q, r
// the truncated quotient and remainder (tests/core/plane_test.cpp), which is the general path.
bool gradient(int64_t n, const PlaneBasis& pb, int64_t& g) {
  const uint64_t a = n < 0 ? 0 - static_cast<uint64_t>(n) : static_cast<uint64_t>(n);
  const auto d = static_cast<uint64_t>(pb.area);
  if ((a >> 30) >= d) return false;  // |n| >= 2^30 area, i.e. |q| >= 2^30
  if (a < (uint64_t{1} << 55)) {
    const uint64_t num = a * kSubpixel + d / 2;
    uint64_t q = mul_hi(num, pb.inv);
    uint64_t r = num - q * d;
    while (r >= d) {  // at most twice
      ++q;
      r -= d;
    }
    const auto m = static_cast<int64_t>(q);
    g = n < 0 ? -m : m;
    return true;
  }
  // 256 n is not formed here (n may be near 2^57). q 256 + round(256 r / area) with q, r the
  // quotient and remainder of |n| (< 2^63) by area and n's sign (C's truncating division and
  // round_div, which rounds half away from zero), each quotient from the reciprocal as above:
  // |n| < 2^63, and 256 r + area / 2 < 2^63 for any area below 2^54 (2^47 in the budget).
  auto divide = [&pb, d](uint64_t x, uint64_t& rem) {
    uint64_t q = mul_hi(x, pb.inv);
    rem = x - q * d;
    while (rem >= d) {  // at most twice
      ++q;
      rem -= d;
    }
    return q;
  };
  uint64_t r = 0, unused = 0;
  const uint64_t q = divide(a, r);
  const auto m = static_cast<int64_t>(q * kSubpixel + divide(r * kSubpixel + d / 2, unused));
  g = n < 0 ? -m : m;
  return true;
}

// A Q1.15 colour channel times q (Q1.30), in Q1.30: <= q.
uint32_t scale_by_q(uint32_t c15, uint32_t q) {
  return static_cast<uint32_t>((uint64_t{c15} * q + (1u << 14)) >> 15);
}

// One texture axis: coordinates (Q12.20) to level-0 texels in Q.8, relative to the triangle's
// own integer origin, so that the planes never hold more than the triangle's extent however far
// from 0 the coordinates are. Extent limit: 2^22 texels (e.g. |du| < 2048 on a 2048-texel
// texture); beyond it the relative coordinates saturate.
void texture_axis(const int32_t uv[3], uint32_t size, Wrap wrap, bool perspective,
                  const PlaneBasis& pb, const uint32_t q[3], Plane& plane, int32_t& off,
                  uint8_t& m) {
  int64_t c[3];
  for (int i = 0; i < 3; ++i) c[i] = (int64_t{uv[i]} * size) >> (TexCoord::kFracBits - 8);
  int64_t lo = c[0] < c[1] ? c[0] : c[1];
  lo = c[2] < lo ? c[2] : lo;
  const int64_t base = floor_div(lo, 256) * 256;
  // Repeat: only the origin's place in the period matters. Clamp: the origin itself
  // (|base| <= 2^30 + 256 since |u| < 2048 and size <= 2048, the period <= 2^19: the remainder
  // in 32 bits, no library call for a 64-bit division on cores without one).
  const auto base32 = static_cast<int32_t>(base);
  const auto period = static_cast<int32_t>(size * 256);
  int32_t rem = base32 % period;
  if (rem < 0) rem += period;
  off = wrap == Wrap::kRepeat ? rem : base32;
  constexpr int64_t kMaxRel = (int64_t{1} << 30) - 1;
  uint32_t rel[3];
  uint32_t hi = 0;
  for (int i = 0; i < 3; ++i) {
    int64_t r = c[i] - base;
    rel[i] = static_cast<uint32_t>(r > kMaxRel ? kMaxRel : r);
    hi |= rel[i];
  }
  const int bits = hi == 0 ? 0 : 32 - clz32(hi);
  if (perspective) {
    // s q < 2^(bits + 30): shifting by the bit length of s keeps the plane below 2^30.
    m = static_cast<uint8_t>(bits);
    for (int i = 0; i < 3; ++i) rel[i] = static_cast<uint32_t>((uint64_t{rel[i]} * q[i]) >> m);
  } else {
    // Affine: s itself, moved up to 2^30 so that the rounded gradient keeps 30 - bits more
    // fraction bits (its rounding would otherwise add up to half a Q.8 unit per pixel).
    m = static_cast<uint8_t>(30 - bits);
    for (int i = 0; i < 3; ++i) rel[i] <<= m;
  }
  plane = make_plane(pb, rel);
}

}  // namespace

// round(w_min 2^30 / w) as floor(n / w), n = w_min 2^30 + floor(w / 2) < 2^62: both scaled by
// 2^s so that the divisor is normalised (n 2^s < 2^63, the quotient <= 2^30), one 2-by-1 division
// by recip32 of it: the quotient of the 64-bit division exactly.
uint32_t perspective_factor(uint32_t wmin, uint32_t w) {
  const int s = clz32(w);
  const uint32_t d = w << s;
  const uint64_t n = ((uint64_t{wmin} << 30) + (w >> 1)) << s;
  const uint32_t q = divide_2by1(n, d, recip32(d)).q;
  return q == 0 ? 1u : q;
}

PlaneBasis::PlaneBasis(const ScreenVertex* const v[3]) {
  x0 = v[0]->x;
  y0 = v[0]->y;
  // |edge| < 2^23 (the coordinate budget): int32, and the products below int64.
  const int32_t e1x = v[1]->x - x0, e1y = v[1]->y - y0, e2x = v[2]->x - x0, e2y = v[2]->y - y0;
  const int64_t signed_area = int64_t{e1x} * e2y - int64_t{e2x} * e1y;
  const uint64_t d = abs64(signed_area);
  if (d != 0 && d < (uint64_t{1} << 32)) {
    // bm: the bit length of the largest edge component; sh: the shift normalising |D|.
    auto mag = [](int32_t e) { return static_cast<uint32_t>(e < 0 ? -e : e); };
    const int bm = 32 - clz32(mag(e1x) | mag(e1y) | mag(e2x) | mag(e2y));
    const int sh = clz32(static_cast<uint32_t>(d));
    if (2 * bm + sh <= kFastPlaneLimit) {
      fast = true;
      f = static_cast<uint8_t>(52 - bm - sh);
      // R = floor((2^64 - 1) / (|D| 2^sh)) < 2^33: K = round(e R / 2^(bm + 4)), |e R| < 2^56.
      const int64_t r = (int64_t{1} << 32) + recip32(static_cast<uint32_t>(d) << sh);
      const int s = bm + 4;
      const bool neg = signed_area < 0;
      auto k = [&](int32_t e) {
        return static_cast<int32_t>((int64_t{neg ? -e : e} * r + (int64_t{1} << (s - 1))) >> s);
      };
      kx1 = k(e2y);
      kx2 = k(-e1y);
      ky1 = k(-e2x);
      ky2 = k(e1x);
      fx = kHalfPixel - (x0 & (kSubpixel - 1));
      fy = kHalfPixel - (y0 & (kSubpixel - 1));
      c0 = static_cast<uint32_t>(x0 >> kSubpixelBits);
      r0 = static_cast<uint32_t>(y0 >> kSubpixelBits);
      return;
    }
  }
  ex1 = e1x;
  ey1 = e1y;
  ex2 = e2x;
  ey2 = e2y;
  flip = signed_area < 0;
  area = static_cast<int64_t>(d);
  inv = d > 0 ? reciprocal64(d) : 0;
}

Plane make_plane(const PlaneBasis& pb, const uint32_t a[3]) {
  const int64_t da1 = int64_t{a[1]} - a[0], da2 = int64_t{a[2]} - a[0];
  Plane p;
  if (pb.fast) {
    // |da| < 2^32 and |K| <= 2^29: each sum below 2^62; |g| < 2^(62 - f) <= 2^46.
    const int f = pb.f;
    const int64_t half = int64_t{1} << (f - 1);
    const int64_t gx = (da1 * pb.kx1 + da2 * pb.kx2 + half) >> f;
    const int64_t gy = (da1 * pb.ky1 + da2 * pb.ky2 + half) >> f;
    // The value at the centre of vertex 0's pixel, |g f| < 2^53, then back to pixel (0, 0)
    // modulo 2^32.
    const int64_t off = gx * pb.fx + gy * pb.fy;
    const auto ugx = static_cast<uint32_t>(static_cast<uint64_t>(gx));
    const auto ugy = static_cast<uint32_t>(static_cast<uint64_t>(gy));
    p.base = a[0] +
             static_cast<uint32_t>(static_cast<uint64_t>((off + kHalfPixel) >> kSubpixelBits)) -
             ugx * pb.c0 - ugy * pb.r0;
    p.gx = ugx;
    p.gy = ugy;
    return p;
  }
  int64_t nx = da1 * pb.ey2 - da2 * pb.ey1;
  int64_t ny = da2 * pb.ex1 - da1 * pb.ex2;
  if (pb.flip) {
    nx = -nx;
    ny = -ny;
  }
  int64_t gx = 0, gy = 0;
  if (pb.area == 0 || !gradient(nx, pb, gx) || !gradient(ny, pb, gy)) {
    // The sum of three uint32 is below 3 2^32: a 64-by-32 division.
    p.base = divide_64by32(uint64_t{a[0]} + a[1] + a[2], 3).q;
    return p;
  }
  // Value at the centre of pixel (0, 0): |g| < 2^38 and |128 - x0| < 2^22, so each product is
  // below 2^60 and the sum below 2^61.
  const int64_t off = gx * (kHalfPixel - pb.x0) + gy * (kHalfPixel - pb.y0);
  const int64_t base = int64_t{a[0]} + round_div(off, kSubpixel);
  p.base = static_cast<uint32_t>(static_cast<uint64_t>(base));
  p.gx = static_cast<uint32_t>(static_cast<uint64_t>(gx));
  p.gy = static_cast<uint32_t>(static_cast<uint64_t>(gy));
  return p;
}

Plane make_plane(const ScreenVertex* const v[3], const uint32_t a[3]) {
  return make_plane(PlaneBasis(v), a);
}

namespace {
// The vertices and their surfaces and texture entries sorted by y (display rows, top first), as
// sort_by_y (core/setup/triangle_rows.hpp) sorts: the planes' vertex 0 is the top vertex.
struct Sorted {
  const ScreenVertex* v[3];
  const SurfaceVertex* sf[3];
  const TexVertex* tv[3];
  Sorted(const ScreenVertex* const vs[3], const SurfaceVertex* const ss[3],
         const TexVertex* const ts[3])
      : v{vs[0], vs[1], vs[2]}, sf{ss[0], ss[1], ss[2]}, tv{ts[0], ts[1], ts[2]} {
    order(0, 1);
    order(1, 2);
    order(0, 1);
  }
  void order(int a, int b) {
    if (v[b]->y < v[a]->y) {
      std::swap(v[a], v[b]);
      std::swap(sf[a], sf[b]);
      std::swap(tv[a], tv[b]);
    }
  }
};
}  // namespace

template <bool kTexture, bool kPhong>
ColorPlanes setup_planes(const SetupInput& in, ActiveTriangle& t) {
  static_assert(kTexture || !kPhong, "Phong's maps use the texture planes");
  const Sorted sorted(in.v, in.phong.s, in.tex.tv);
  const ScreenVertex* const* v = sorted.v;
  const SurfaceVertex* const* sf = sorted.sf;
  const PlaneBasis pb(v);  // after the sort: the planes' vertex 0 is the top vertex, as before
  if (in.depth) {
    uint32_t z[3] = {v[0]->z, v[1]->z, v[2]->z};
    t.z = make_plane(pb, z);
  }
  const bool tex = kTexture && in.tex.texture != nullptr;
  uint32_t q[3] = {1u << 30, 1u << 30, 1u << 30};
  const bool phong = kPhong && sf[0] != nullptr;
  const ColorPlanes colors = in.colors;
  if (colors == ColorPlanes::kPerspective || (tex && in.tex.perspective) || phong) {
    uint32_t wmin = v[0]->w;
    for (int i = 1; i < 3; ++i) wmin = v[i]->w < wmin ? v[i]->w : wmin;
    for (int i = 0; i < 3; ++i) q[i] = perspective_factor(wmin, v[i]->w);
    t.q = make_plane(pb, q);
  }
  if (colors == ColorPlanes::kPerspective) {
    for (int c = 0; c < 3; ++c) {
      uint32_t cq[3];
      for (int i = 0; i < 3; ++i) cq[i] = scale_by_q(channel(v[i]->color, c), q[i]);
      t.c[c] = make_plane(pb, cq);
    }
  } else if (colors == ColorPlanes::kAffine) {
    for (int c = 0; c < 3; ++c) {
      uint32_t cv[3];
      for (int i = 0; i < 3; ++i) cv[i] = uint32_t{channel(v[i]->color, c)} << 15;
      t.c[c] = make_plane(pb, cv);
    }
  }
  if constexpr (kTexture)
    if (tex) setup_texture(in.tex, v, sorted.tv, pb, q, t);
  if constexpr (kPhong)
    if (phong) setup_phong(in.phong, sf, pb, q, t);
  return colors;
}

template ColorPlanes setup_planes<false, false>(const SetupInput&, ActiveTriangle&);
template ColorPlanes setup_planes<true, false>(const SetupInput&, ActiveTriangle&);
template ColorPlanes setup_planes<true, true>(const SetupInput&, ActiveTriangle&);

void setup_phong(const PhongSetup& ps, const SurfaceVertex* const s[3], const PlaneBasis& pb,
                 const uint32_t q[3], ActiveTriangle& t) {
  ActiveExtra& ex = *t.ext;
  // Q1.30 values times q (Q1.30), biased: |x q| <= 2^30.
  auto scaled = [&q](int64_t x, int i) {
    return static_cast<uint32_t>(((x * q[i]) >> 30) + kPlaneBias);
  };
  for (int c = 0; c < 3; ++c) {
    uint32_t a[3];
    for (int i = 0; i < 3; ++i) {
      const Unit30& n = s[i]->normal;
      const int64_t x = c == 0 ? n.x : c == 1 ? n.y : n.z;
      a[i] = scaled(ps.negate ? -x : x, i);
    }
    t.c[c] = make_plane(pb, a);
  }
  ex.handedness = s[0]->handedness;
  if (ps.tangent) {
    for (int c = 0; c < 3; ++c) {
      uint32_t a[3];
      for (int i = 0; i < 3; ++i) a[i] = scaled(int64_t{s[i]->tangent[c]} << 16, i);
      ex.tan[c] = make_plane(pb, a);
    }
  }
  if (ps.position) {
    const Vec3& o = s[0]->position;
    ex.org[0] = o.x.raw;
    ex.org[1] = o.y.raw;
    ex.org[2] = o.z.raw;
    int64_t rel[3][3];
    uint64_t hi = 0;
    for (int i = 0; i < 3; ++i) {
      const Vec3& p = s[i]->position;
      const int64_t d[3] = {int64_t{p.x.raw} - o.x.raw, int64_t{p.y.raw} - o.y.raw,
                            int64_t{p.z.raw} - o.z.raw};
      for (int c = 0; c < 3; ++c) {
        // Triangles wider than 32768 units saturate (the spans read int32 offsets).
        constexpr int64_t kMax = 0x7FFFFFFF;
        rel[i][c] = d[c] > kMax ? kMax : d[c] < -kMax ? -kMax : d[c];
        hi |= abs64(rel[i][c]);
      }
    }
    const int bits = hi == 0 ? 0 : 64 - clz64(hi);  // <= 31
    ex.m_p = static_cast<uint8_t>(bits);
    for (int c = 0; c < 3; ++c) {
      uint32_t a[3];
      // |rel| < 2^bits, q <= 2^30: |rel q| >> bits < 2^30.
      for (int i = 0; i < 3; ++i)
        a[i] = static_cast<uint32_t>(((rel[i][c] * q[i]) >> bits) + kPlaneBias);
      ex.extra.position[c] = make_plane(pb, a);
    }
  }
}

void setup_texture(const TextureSetup& ts, const ScreenVertex* const v[3],
                   const TexVertex* const tv[3], const PlaneBasis& pb, const uint32_t q[3],
                   ActiveTriangle& t) {
  ActiveExtra& ex = *t.ext;
  const TextureLevel& l0 = ts.texture->levels[0];
  const int32_t us[3] = {tv[0]->u, tv[1]->u, tv[2]->u}, vs[3] = {tv[0]->v, tv[1]->v, tv[2]->v};
  texture_axis(us, l0.width, ts.wrap_s, ts.perspective, pb, q, ex.s, ex.off_s, ex.m_s);
  texture_axis(vs, l0.height, ts.wrap_t, ts.perspective, pb, q, ex.t, ex.off_t, ex.m_t);
  ex.const_colors = false;
  if (!ts.colors) return;
  bool same = ts.flat;
  if (!same) {
    same = true;
    for (int i = 1; i < 3; ++i)
      same = same && v[i]->color == v[0]->color && tv[i]->spec == tv[0]->spec;
  }
  if (same) {
    const Color15 pc = ts.flat ? ts.flat_primary : v[0]->color;
    const Color15 sc = ts.flat ? ts.flat_secondary : tv[0]->spec;
    for (int c = 0; c < 3; ++c) {
      t.c[c] = Plane{channel(pc, c), 0, 0};
      ex.extra.spec[c] = Plane{channel(sc, c), 0, 0};
    }
    ex.const_colors = true;
    return;
  }
  for (int c = 0; c < 3; ++c) {
    uint32_t p[3], sp[3];
    for (int i = 0; i < 3; ++i) {
      uint32_t pc = channel(ts.flat ? ts.flat_primary : v[i]->color, c);
      uint32_t sc = channel(ts.flat ? ts.flat_secondary : tv[i]->spec, c);
      p[i] = ts.perspective ? scale_by_q(pc, q[i]) : pc << 15;
      sp[i] = ts.perspective ? scale_by_q(sc, q[i]) : sc << 15;
    }
    t.c[c] = make_plane(pb, p);
    ex.extra.spec[c] = make_plane(pb, sp);
  }
}

}  // namespace lr
