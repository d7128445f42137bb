#include "lineraster/core/setup/untextured_setup.hpp"

#include <algorithm>
#include <cstddef>
#include <optional>

#include "lineraster/core/binning/binned_triangle.hpp"
#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/reciprocal.hpp"
#include "lineraster/core/math/wide_mul.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/setup/row_edge.hpp"
#include "lineraster/core/setup/small_plane.hpp"
#include "lineraster/core/setup/triangle_rows.hpp"
#include "lineraster/core/setup/triangle_setup.hpp"

namespace lr {

namespace {

constexpr int bit_length(uint32_t v) {
  return v == 0 ? 0 : 32 - clz32(v);
}

LR_SIZE_NOINLINE constexpr uint32_t magnitude(int32_t v) {
  return v < 0 ? 0u - static_cast<uint32_t>(v) : static_cast<uint32_t>(v);
}

// The least and the largest of three: std::min({...}) is a loop over an array on the stack, out
// of line at -Os (two such functions and their calls).
constexpr uint32_t min3(uint32_t a, uint32_t b, uint32_t c) {
  return std::min(a, std::min(b, c));
}
constexpr uint32_t max3(uint32_t a, uint32_t b, uint32_t c) {
  return std::max(a, std::max(b, c));
}

// ~ 2^62 / d for d in [2^31, 2^32), in (2^30, 2^31): a 17-bit estimate (recip16: one division,
// or a table on Armv6-M) and one Newton step in high-word products; relative error below 2^-28
// (docs/numerics.md#untextured-planes). The same integers on every core.
int32_t recip62(uint32_t d) {
  const uint32_t x0 = recip16(d >> 16) << 14;  // < 2^31, within 2^-15 of 2^62 / d
  // e = 2^30 - d x0 / 2^32: minus the estimate's relative error times 2^30 (|e| < 2^16).
  const auto e = static_cast<int32_t>((1u << 30) - mul_hi_u(d, x0));
  const int64_t x1 = int64_t{static_cast<int32_t>(x0)} + mul_hi(static_cast<int32_t>(x0), e * 4);
  return x1 > INT32_MAX ? INT32_MAX : static_cast<int32_t>(x1);
}

// v 2^s modulo 2^32: shifted left, or right with rounding (|v| < 2^30).
uint32_t scale(int32_t v, int s) {
  if (s >= 0) return static_cast<uint32_t>(v) << s;
  const int r = s < -31 ? 31 : -s;
  return static_cast<uint32_t>((v + (int32_t{1} << (r - 1))) >> r);
}

// v 2^s modulo 2^32 as two shifts and a rounding half, s fixed per triangle (|v| < 2^30).
class Scale {
 public:
  explicit Scale(int s)
      : left_(s > 0 ? s : 0),
        right_(s >= 0    ? 0
               : s < -31 ? 31
                         : -s),
        half_(s >= 0 ? 0 : int32_t{1} << (right_ - 1)) {}
  uint32_t operator()(int32_t v) const {
    return static_cast<uint32_t>(
        (static_cast<int32_t>(static_cast<uint32_t>(v) << left_) + half_) >> right_);
  }

 private:
  int left_, right_;
  int32_t half_;
};

// mul_hi(a, ratio) for a one-hue ratio (OneHue: a multiple of 2^15 below 2^31): a 32 x 16
// product, floor(a q / 2^17) with q = ratio / 2^15, as (ah q + floor(al q / 2^16)) / 2 (floored;
// |ah q| < 2^31) on Armv6-M, where mul_hi is four 16 x 16 products; SMMUL elsewhere.
inline int32_t times_ratio(int32_t a, int32_t ratio) {
#if defined(__thumb__) && !defined(__thumb2__)
  const int32_t q = ratio >> 15;
  const int32_t ah = a >> 16;
  const auto al = static_cast<uint32_t>(a) & 0xFFFFu;
  return (ah * q + static_cast<int32_t>((al * static_cast<uint32_t>(q)) >> 16)) >> 1;
#else
  return mul_hi(a, ratio);
#endif
}

// a b as uint64 without a 64 x 64 library multiply on Armv6-M.
uint64_t umul64(uint32_t a, uint32_t b) {
  return (uint64_t{mul_hi_u(a, b)} << 32) | uint64_t{static_cast<uint32_t>(a * b)};
}

// q = w_min 2^30 / w in Q1.30 (w_min <= w), at least 1: from ~2^62 / (w normalised) and one
// high-word product.
uint32_t perspective_q(uint32_t wmin, uint32_t w) {
  const int s = clz32(w);
  const uint32_t q = mul_hi_u(wmin << s, static_cast<uint32_t>(recip62(w << s)));
  return q == 0 ? 1u : q;
}

// A plane of the wide path: make_plane's exact one.
Plane wide_plane(const PlaneBasis& pb, const int32_t a[3]) {
  const uint32_t u[3] = {static_cast<uint32_t>(a[0]), static_cast<uint32_t>(a[1]),
                         static_cast<uint32_t>(a[2])};
  return make_plane(pb, u);
}

// The lane of a 5-bit channel (Q1.15), rounded: 31 c 2^11 / 2^15 + 2^10, a level plus half a
// level in the lane's top five bits; green as 63 c 2^26 / 2^15 + 2^25, halved (63 c 2^10 + 2^24:
// below 2^31, the plane doubled afterwards).
constexpr int32_t lane5(uint32_t c15) {
  return static_cast<int32_t>(((31 * c15 + 8) >> 4) + (1u << 10));
}
constexpr int32_t lane6(uint32_t c15) {
  return static_cast<int32_t>(63 * 1024 * c15 + (1u << 24));
}
static_assert(lane5(Color15::kOne) == (1 << 16) - (1 << 10));
static_assert(lane6(Color15::kOne) < INT32_MAX);

// The window's words of the hand-made blocks' frames: its width (word 23) and its first_min and
// last_max (32, 33), set once per window rather than read through a pointer per triangle.
[[maybe_unused]] void set_window(uint32_t* frame, const RowWindow& w) {
  frame[23] = static_cast<uint32_t>(w.width);
  frame[32] = static_cast<uint32_t>(w.first_min);
  frame[33] = static_cast<uint32_t>(w.last_max);
}

}  // namespace

bool fast_basis(const ScreenVertex* const v[3], int max_spread, FastBasis& b) {
  const int32_t x0 = v[0]->x, y0 = v[0]->y;
  const int32_t e1x = v[1]->x - x0, e1y = v[1]->y - y0, e2x = v[2]->x - x0, e2y = v[2]->y - y0;
  const int bm = bit_length(magnitude(e1x) | magnitude(e1y) | magnitude(e2x) | magnitude(e2y));
  b.bm = bm;
  if (bm > kFastMaxEdgeBits) return false;
  // Twice the signed area, normalised: |D| 2^(32 - L) (truncated when |D| >= 2^32).
  bool neg;
  uint32_t dn;
  int L;
  if (bm <= 15) {  // products below 2^30: int32
    const int32_t d = e1x * e2y - e2x * e1y;
    neg = d < 0;
    const uint32_t m = magnitude(d);
    if (m == 0) return false;
    L = bit_length(m);
    dn = m << (32 - L);
  } else {
    const int64_t d = mul_wide(e1x, e2y) - mul_wide(e2x, e1y);
    neg = d < 0;
    const uint64_t m = abs64(d);
    if (m == 0) return false;
    L = 64 - clz64(m);
    dn = L <= 32 ? static_cast<uint32_t>(m) << (32 - L) : static_cast<uint32_t>(m >> (L - 32));
  }
  b.spread = 2 * bm - L;
  if (b.spread > max_spread) return false;
  // k = e 2^(31 - bm) R / 2^32 = 256 e / D x 2^(21 - bm + L), |k| <= 2^30.
  const int32_t r = recip62(dn);
  const int sh = 31 - bm;
  auto k = [&](int32_t e) {
    return mul_hi(static_cast<int32_t>(static_cast<uint32_t>(neg ? -e : e) << sh), r);
  };
  b.kx1 = k(e2y);
  b.kx2 = k(-e1y);
  b.ky1 = k(-e2x);
  b.ky2 = k(e1x);
  b.p = 11 + bm - L;
  b.fx = (kHalfPixel - (x0 & (kSubpixel - 1))) * (1 << 23);
  b.fy = (kHalfPixel - (y0 & (kSubpixel - 1))) * (1 << 23);
  b.c0 = static_cast<uint32_t>(x0 >> kSubpixelBits);
  b.r0 = static_cast<uint32_t>(y0 >> kSubpixelBits);
  return true;
}

Plane fast_plane(const FastBasis& b, const int32_t a[3], int u) {
  const int32_t d1 = a[1] - a[0], d2 = a[2] - a[0];
  const int32_t n1 = u >= 0 ? static_cast<int32_t>(static_cast<uint32_t>(d1) << u) : d1 >> 1;
  const int32_t n2 = u >= 0 ? static_cast<int32_t>(static_cast<uint32_t>(d2) << u) : d2 >> 1;
  // The gradients times 2^-s, |g| < 2^29.
  const int32_t gx = mla_hi(n1, b.kx1, mul_hi(n2, b.kx2));
  const int32_t gy = mla_hi(n1, b.ky1, mul_hi(n2, b.ky2));
  const int s = b.p - u;
  Plane p;
  p.gx = scale(gx, s);
  p.gy = scale(gy, s);
  // The value at the centre of vertex 0's pixel, a0 + (gx fx + gy fy) / 256, moved to pixel
  // (0, 0) in modular arithmetic.
  const uint32_t off = scale(mla_hi(gx, b.fx, mul_hi(gy, b.fy)), s + 1);
  p.base = static_cast<uint32_t>(a[0]) + off - p.gx * b.c0 - p.gy * b.r0;
  return p;
}

namespace {
// The affine colour test's quick part (AffineBound::quick_shift) first, but where the code is
// built for size: the colour test alone gives the same answer (the quick test implies it).
#if defined(__OPTIMIZE_SIZE__)
constexpr bool kQuickAffineTest = false;
#else
constexpr bool kQuickAffineTest = true;
#endif

// affine_within's colour test, for w_max - w_min above the quick test's bound.
[[gnu::noinline]] bool colors_within(const ScreenVertex* const v[3], uint32_t wmin, uint32_t wmax,
                                     const AffineBound& bound) {
  uint32_t d = 0;
  for (int c = 0; c < 3; ++c) {
    const uint32_t a = channel(v[0]->color, c), b = channel(v[1]->color, c),
                   e = channel(v[2]->color, c);
    const uint32_t range = max3(a, b, e) - min3(a, b, e);
    d = std::max(d, c == 1 ? range * bound.green_weight : range);
  }
  return umul64(wmax - wmin, d) <= umul64(bound.bound, wmin);
}
}  // namespace

bool affine_within(const ScreenVertex* const v[3], const AffineBound& bound) {
  const uint32_t wmin = min3(v[0]->w, v[1]->w, v[2]->w);
  const uint32_t wmax = max3(v[0]->w, v[1]->w, v[2]->w);
  if (kQuickAffineTest && wmax - wmin <= wmin >> bound.quick_shift) return true;  // any colours
  return colors_within(v, wmin, wmax, bound);
}

namespace {

// The edge columns of rows from..t.last_row: whether one has a pixel centre in [0, width).
[[gnu::noinline]] bool later_rows_have_pixels(const ActiveTriangle& t, int32_t from,
                                              int32_t width) {
  // The long edge stepped row by row; the short side's picked up per row (it changes at mid).
  const int ss = t.short_side();
  const int32_t first = t.first_row, mid = t.mid_row;
  DivideEdge long_edge(t.side_edge(1 - ss), t.col_base, from - first);
  for (int32_t r = from; r <= t.last_row; ++r, long_edge.step()) {
    const int32_t cl = long_edge.column();
    const int32_t cs = r <= mid ? DivideEdge(t.side_edge(ss), t.col_base, r - first).column()
                                : DivideEdge(t.bottom, t.col_base, r - mid - 1).column();
    const int32_t left = ss != 0 ? cl : cs, right = ss != 0 ? cs : cl;
    if (left < width && right > 0 && left < right) return true;
  }
  return false;
}

}  // namespace

namespace {
// small_planes: a call where the lanes planes are made by hand (the other kinds are rare
// there), inlined into setup_untextured_triangle elsewhere (fewer spills on Armv6-M).
#if defined(__thumb2__) && defined(__ARM_FEATURE_DSP) && defined(__ARM_FEATURE_IDIV) && \
    !defined(__OPTIMIZE_SIZE__)
#define LR_SMALL_PLANES_INLINE [[gnu::noinline]]
#else
#define LR_SMALL_PLANES_INLINE [[gnu::always_inline]] inline
#endif
LR_SMALL_PLANES_INLINE bool small_planes_c(const ScreenVertex* const v[3], int32_t d, uint32_t m,
                                           const UntexturedInput& in, UntexturedKind kind,
                                           ActiveTriangle& t) {
  const ScreenVertex &va = *v[0], &vb = *v[1], &vc = *v[2];
  const int lz = clz32(magnitude(d));
  const int bm = 32 - clz32(m);
  const int spread = 2 * bm - 32 + lz;
  const int32_t z0 = static_cast<int32_t>(va.z >> 1);
  int32_t dz1 = static_cast<int32_t>(vb.z >> 1) - z0;
  int32_t dz2 = static_cast<int32_t>(vc.z >> 1) - z0;
  const int zbits = in.depth ? bit_length(magnitude(dz1) | magnitude(dz2)) : 0;
  if (spread > kFastMaxSpread || zbits > kSmallMaxDepthBits || spread + zbits > kFastMaxDepthSpread)
    return false;
  SmallBasis b;
  const int k = kSmallEdgeBits - bm;  // the edges normalised to 14 bits
  {
    const int32_t x0 = va.x, y0 = va.y;
    b.e1x = (vb.x - x0) * (1 << k);
    b.e1y = (vb.y - y0) * (1 << k);
    b.e2x = (vc.x - x0) * (1 << k);
    b.e2y = (vc.y - y0) * (1 << k);
    // The reference pixel (c0, r0): the one whose centre is within [-128, 127] subpixels of
    // vertex 0 on both axes, so that the offset f fits f 2^24.
    const int32_t c0 = (x0 - 1) >> kSubpixelBits, r0 = (y0 - 1) >> kSubpixelBits;
    b.fx = (c0 * kSubpixel + kHalfPixel - x0) * (1 << 24);
    b.fy = (r0 * kSubpixel + kHalfPixel - y0) * (1 << 24);
    b.c0 = static_cast<uint32_t>(c0);
    b.r0 = static_cast<uint32_t>(r0);
  }
  // rs ~ 2^(30 + L) / d: mul_hi(n, rs) is the gradient of n's attribute times 2^tg.
  const int32_t r = recip62(magnitude(d) << lz);
  const int32_t rs = d < 0 ? -r : r;
  const int tg = 36 - lz - bm;  // L - bm + 4
  if (in.depth) {
    // Differences below 2^16: the low bits of larger ones dropped (below 2^10 half units).
    const int zsh = zbits > 16 ? zbits - 16 : 0;
    dz1 >>= zsh;
    dz2 >>= zsh;
    small_plane(b, dz1, dz2, static_cast<uint32_t>(z0) + (1u << 14), plane_scale(rs, zsh - tg),
                t.z);
  }
  if (kind == UntexturedKind::kFlat) {
    t.c[0].base = in.flat_pixel;
    return true;
  }
  const int32_t cr = va.color.r, cg = va.color.g, cbl = va.color.b;
  if (kind == UntexturedKind::kLanes) {
    // Red and blue in lane units (31 c / 16: rs 31 / 32, 2^(1 - tg)), green in 63 c 2^11
    // (rs 63 / 64, 2^(17 - tg)), from the Q1.15 differences. One hue (docs/numerics.md#one-hue):
    // red and blue from green's differences, their factor times the hue's ratios.
    const int32_t rc = rs - (rs >> 5);
    const OneHue& h = in.hue;
    const bool hue = h.valid;
    // One hue: rc rho / 4 2^(3 - tg), red's factor times the ratio (below 2^30).
    const PlaneScale sr = plane_scale(hue ? times_ratio(rc, h.red) : rc, (hue ? 3 : 1) - tg);
    const PlaneScale sb = plane_scale(hue ? times_ratio(rc, h.blue) : rc, (hue ? 3 : 1) - tg);
    const int32_t dg1 = vb.color.g - cg, dg2 = vc.color.g - cg;
    const int32_t dr1 = hue ? dg1 : vb.color.r - cr, dr2 = hue ? dg2 : vc.color.r - cr;
    const int32_t db1 = hue ? dg1 : vb.color.b - cbl, db2 = hue ? dg2 : vc.color.b - cbl;
    Plane pr, pb;
    small_plane(b, dr1, dr2, ((31 * static_cast<uint32_t>(cr)) >> 4) + 1024, sr, pr);
    small_plane(b, db1, db2, ((31 * static_cast<uint32_t>(cbl)) >> 4) + 1024, sb, pb);
    t.c[0] = Plane{(pb.base << 16) + pr.base, (pb.gx << 16) + pr.gx, (pb.gy << 16) + pr.gy};
    small_plane(b, dg1, dg2, 63 * 2048 * static_cast<uint32_t>(cg) + (1u << 25),
                plane_scale(rs - (rs >> 6), 17 - tg), t.c[1]);
    return true;
  }
  const PlaneScale c = plane_scale(rs, 15 - tg);
  small_plane(b, vb.color.r - cr, vc.color.r - cr, static_cast<uint32_t>(cr) << 15, c, t.c[0]);
  small_plane(b, vb.color.g - cg, vc.color.g - cg, static_cast<uint32_t>(cg) << 15, c, t.c[1]);
  small_plane(b, vb.color.b - cbl, vc.color.b - cbl, static_cast<uint32_t>(cbl) << 15, c, t.c[2]);
  return true;
}
#undef LR_SMALL_PLANES_INLINE
}  // namespace

bool small_planes(const ScreenVertex* const v[3], int32_t d, uint32_t m, const UntexturedInput& in,
                  UntexturedKind kind, ActiveTriangle& t) {
  return small_planes_c(v, d, m, in, kind, t);
}

namespace {
// small_rows first tries one candidate column on the middle vertex's row before dividing: the
// same answer, mostly without the divisions (a library call on Armv6-M). A candidate's offset
// from the column base stays below kMaxCandidate, so that its products with an edge's dy (below
// 2^14) fit 32 bits.
constexpr uint32_t kMaxCandidate = 1u << 16;

// small_rows, inlined into setup_untextured_triangle (one copy in an image without
// small_rows_by_hand; at -Os setup_rows makes the rows instead).
[[gnu::always_inline]] inline SmallRows small_rows_c(const ScreenVertex* const v[3],
                                                     const RowWindow& w, ActiveTriangle& t) {
  const ScreenVertex &va = *v[0], &vb = *v[1], &vc = *v[2];
  const int32_t x0 = va.x, y0 = va.y;
  const int32_t e1x = vb.x - x0, e1y = vb.y - y0, e2x = vc.x - x0, e2y = vc.y - y0;
  // Rows (|y| < 2^22: the arithmetic shift is the floor).
  const int32_t first = std::max(((y0 - kHalfPixel) >> kSubpixelBits) + 1, w.first_min);
  const int32_t last = std::min((vc.y - kHalfPixel) >> kSubpixelBits, w.last_max);
  SmallRows out{};
  out.m = magnitude(e1x) | magnitude(e2x) | static_cast<uint32_t>(e2y);
  if (out.m >= (1u << kSmallEdgeBits) || first > last) return out;
  // Within 2^kSmallEdgeBits subpixels: every product below is below 2^30 (docs/numerics.md).
  const int32_t mid = std::clamp((vb.y - kHalfPixel) >> kSubpixelBits, first - 1, last);
  const int32_t d = e1x * e2y - e2x * e1y;  // twice the signed area
  out.d = d;
  const bool long_left = d > 0;
  const int32_t cb = (x0 + std::min({int32_t{0}, e1x, e2x}) - kHalfPixel) >> kSubpixelBits;
  const int32_t cmax =
      (x0 + std::max({int32_t{0}, e1x, e2x}) - kHalfPixel + kSubpixel - 1) >> kSubpixelBits;
  const bool inside = cb >= 0 && cmax <= w.width;
  // The long, top and bottom edges' records (the bottom one at row mid + 1), relative to cb, or
  // to column 0 when the triangle lies inside the columns [0, width] (below 2^26 here):
  // floor(((xa - 128) dy + dx (yc - ya) + 256 dy - 1) / 256) with xa - 128 + 256 relative to cb
  // in xa.
  const int32_t t0 = first * kSubpixel + kHalfPixel - y0;
  const int32_t xa = x0 + kHalfPixel - cb * kSubpixel;
  const auto top_dy = static_cast<uint32_t>(e1y > 0 ? e1y : 1);
  const int32_t bdx = e2x - e1x, bdy = e2y - e1y;
  const auto btm_dy = static_cast<uint32_t>(bdy > 0 ? bdy : 1);
  const auto ucb = static_cast<uint32_t>(inside ? cb : 0);
  const uint32_t ql =
      static_cast<uint32_t>((xa * e2y + e2x * t0 - 1) >> kSubpixelBits) + ucb * uint32_t(e2y);
  const uint32_t qt =
      static_cast<uint32_t>((xa * e1y + e1x * t0 - 1) >> kSubpixelBits) + ucb * top_dy;
  const uint32_t qb =
      static_cast<uint32_t>(
          ((xa + e1x) * bdy + bdx * (t0 - e1y + (mid + 1 - first) * kSubpixel) - 1) >>
          kSubpixelBits) +
      ucb * btm_dy;
  const int32_t base = inside ? 0 : cb;
  // The record, left edge first.
  const int ll = long_left ? 0 : 1;
  t.edge_q[ll] = ql;
  t.edge_q[1 - ll] = qt;
  t.edge_dx[ll] = e2x;
  t.edge_dx[1 - ll] = e1x;
  t.edge_dy[ll] = static_cast<uint32_t>(e2y);
  t.edge_dy[1 - ll] = top_dy;
  t.bottom = RowEdge{qb, bdx, btm_dy};
  t.first_row = static_cast<int16_t>(first);
  t.mid_row = static_cast<int16_t>(mid);
  t.last_row = static_cast<int16_t>(last);
  t.col_base = static_cast<int16_t>(base);
  t.flags = static_cast<uint8_t>((long_left ? ActiveTriangle::kBottomRight : 0) |
                                 (inside ? ActiveTriangle::kInside : 0));
  // A triangle of kSurelyPixelsArea2 or more nearly always has a pixel centre in the window: no
  // test (one that has none gets planes that its rows never use).
  if (surely_pixels(d)) {
    out.result = SmallRows::kPixels;
    return out;
  }
  // A row with a pixel centre in the viewport's columns: the middle vertex's row (the top
  // edge's last), where the triangle is widest, or another.
  const int32_t rm = mid >= first ? mid : first;
  const auto k = static_cast<uint32_t>(rm - first);
  const uint32_t q_long = ql + static_cast<uint32_t>(e2x) * k;
  const uint32_t q_short = mid >= first ? qt + static_cast<uint32_t>(e1x) * k : qb;
  const uint32_t dy_short = mid >= first ? top_dy : btm_dy;
  {
    // The column of (about: 5/16 for 1/3) the centroid: its centre on row rm is inside when the
    // left edge's column is at or left of it and the right edge's right of it
    // (floor(Q / dy) <= c < floor(Q' / dy') as products); mostly so, and then no division.
    const int32_t c = (x0 + (((e1x + e2x) * 5) >> 4)) >> kSubpixelBits;
    const uint32_t rel = static_cast<uint32_t>(c - base) + 1;  // 0 when c - base = -1
    const uint32_t q_left = long_left ? q_long : q_short, q_right = long_left ? q_short : q_long;
    const uint32_t dy_left = long_left ? static_cast<uint32_t>(e2y) : dy_short;
    const uint32_t dy_right = long_left ? dy_short : static_cast<uint32_t>(e2y);
    if (c >= 0 && c < w.width && rel - 1 <= kMaxCandidate && q_left < rel * dy_left &&
        rel * dy_right <= q_right) {
      out.result = SmallRows::kPixels;
      return out;
    }
  }
  const int32_t cl = base + static_cast<int32_t>(q_long / static_cast<uint32_t>(e2y));
  const int32_t cs = base + static_cast<int32_t>(q_short / dy_short);
  const int32_t left = long_left ? cl : cs, right = long_left ? cs : cl;
  out.result =
      left < w.width && right > 0 && left < right ? SmallRows::kPixels : SmallRows::kLaterRows;
  return out;
}
}  // namespace

namespace {
// setup_untextured_triangle after the rows (rows: their result; tried: lanes planes by hand were
// tried with them, made: and made).
[[gnu::always_inline]] inline UntexturedTriangle finish_triangle(const ScreenVertex* const v[3],
                                                                 const RowWindow& w,
                                                                 const UntexturedInput& in,
                                                                 ActiveTriangle& t, SmallRows rows,
                                                                 bool tried, bool made) {
  if (rows.result == SmallRows::kSlow) [[unlikely]] {
    const int32_t first = std::max(first_row_below(v[0]->y), w.first_min);
    const int32_t last = std::min(last_row_at_or_above(v[2]->y), w.last_max);
    if (!setup_rows(v, first, last, w.width, t)) return UntexturedTriangle::sliver();
    const UntexturedSetup u = setup_untextured(v, in, t);
    return UntexturedTriangle::made(u.kind, u.wide);
  }
  if (rows.result == SmallRows::kLaterRows && !later_rows_have_pixels(t, t.first_row, w.width))
      [[unlikely]]
    return UntexturedTriangle::sliver();
  const int32_t d = rows.d;
  const uint32_t m = rows.m;
  const ScreenVertex &va = *v[0], &vb = *v[1], &vc = *v[2];

  if (in.colors == ColorPlanes::kNone && !in.depth) {  // no plane at all
    t.c[0].base = in.flat_pixel;
    return UntexturedTriangle::made(UntexturedKind::kFlat, false);
  }
  UntexturedKind kind = in.colors == ColorPlanes::kNone     ? UntexturedKind::kFlat
                        : in.colors == ColorPlanes::kAffine ? UntexturedKind::kAffine
                                                            : UntexturedKind::kPerspective;
  if (kind == UntexturedKind::kPerspective && in.affine_ok) {
    const uint32_t wmin = min3(va.w, vb.w, vc.w), wmax = max3(va.w, vb.w, vc.w);
    if ((kQuickAffineTest && wmax - wmin <= wmin >> in.affine.quick_shift) ||
        colors_within(v, wmin, wmax, in.affine))
      kind = UntexturedKind::kAffine;
  }
  if (kind == UntexturedKind::kAffine && in.lanes) kind = UntexturedKind::kLanes;
  if (!tried)
    made = kind == UntexturedKind::kLanes && in.depth && kSmallPlanesByHand
               ? small_lanes_planes_by_hand(v, d, m, in, t)
               : kind != UntexturedKind::kPerspective && small_planes_c(v, d, m, in, kind, t);
  else
    made = made && kind == UntexturedKind::kLanes;  // else the planes made are not the kind's
  if (!made) [[unlikely]] {
    const UntexturedSetup u = setup_untextured(v, in, t);
    return UntexturedTriangle::made(u.kind, u.wide);
  }
  return UntexturedTriangle::made(kind, false);
}

}  // namespace

SmallRows small_rows(const ScreenVertex* const v[3], const RowWindow& w, ActiveTriangle& t) {
  return small_rows_c(v, w, t);
}

#if defined(__thumb2__) && defined(__ARM_FEATURE_IDIV) && !defined(__OPTIMIZE_SIZE__)
// small_rows by hand (Armv7-M with a divider): GCC 12 spilled a quarter of it. The one operand
// (left to the compiler) points to the frame of small_lanes_asm below: the vertices (0, 4, 8),
// the triangle (16), then d (20), m (24), the result (28), the window's width (92), the edge
// vectors e1x, e1y, e2x, e2y (112, for the planes) and the window's first_min and last_max (128);
// a frame of kLanesFrameWords words, the window's set once per window, not per triangle. Ends
// with the result in r0.
#define LR_SMALL_ROWS_ASM \
  "ldm    %[f], {r0, r1, r2}\n\t" LR_SMALL_ROWS_BODY "str    r0, [%[f], #28]\n\t"
// LR_SMALL_ROWS_ASM with the vertices already in r0-r2, the result left in r0 only (what follows
// stores it at word 7 where C reads it).
#define LR_SMALL_ROWS_BODY                                                                      \
  "ldrd   r3, r4, [r0]\n\t"                                                                     \
  "ldrd   r5, r6, [r1]\n\t"                                                                     \
  "ldrd   r8, r9, [r2]\n\t"                                                                     \
  "add    r10, r4, #128\n\t" /* first r10, last r11: ((y0 - 128) >> 8) + 1 = (y0 + 128) >> 8 */ \
  "asr    r10, r10, #8\n\t"                                                                     \
  "ldrd   r12, r1, [%[f], #128]\n\t" /* first_min, last_max */                                  \
  "cmp    r10, r12\n\t"                                                                         \
  "it     lt\n\t"                                                                               \
  "movlt  r10, r12\n\t"                                                                         \
  "sub    r11, r9, #128\n\t"                                                                    \
  "asr    r11, r11, #8\n\t"                                                                     \
  "cmp    r11, r1\n\t"                                                                          \
  "it     gt\n\t"                                                                               \
  "movgt  r11, r1\n\t" /* e1x r5, e1y r6, e2x r8, e2y r9; m */                                  \
  "sub    r5, r5, r3\n\t"                                                                       \
  "sub    r1, r6, #128\n\t" /* yb - 128 (mid) */                                                \
  "sub    r6, r6, r4\n\t"                                                                       \
  "sub    r8, r8, r3\n\t"                                                                       \
  "sub    r9, r9, r4\n\t"                                                                       \
  "strd   r5, r6, [%[f], #112]\n\t" /* the edge vectors, for the planes */                      \
  "strd   r8, r9, [%[f], #120]\n\t"                                                             \
  "eor    r12, r5, r5, asr #31\n\t"                                                             \
  "sub    r12, r12, r5, asr #31\n\t"                                                            \
  "eor    r0, r8, r8, asr #31\n\t"                                                              \
  "sub    r0, r0, r8, asr #31\n\t"                                                              \
  "orr    r12, r12, r0\n\t"                                                                     \
  "orr    r12, r12, r9\n\t"                                                                     \
  "str    r12, [%[f], #24]\n\t"                                                                 \
  "cmp    r12, #16384\n\t"                                                                      \
  "bhs    8f\n\t"                                                                               \
  "cmp    r10, r11\n\t"                                                                         \
  "bgt    8f\n\t" /* mid r0 = clamp((yb - 128) >> 8, first - 1, last); the rows */              \
  "asr    r0, r1, #8\n\t"                                                                       \
  "sub    r1, r10, #1\n\t"                                                                      \
  "cmp    r0, r1\n\t"                                                                           \
  "it     lt\n\t"                                                                               \
  "movlt  r0, r1\n\t"                                                                           \
  "cmp    r0, r11\n\t"                                                                          \
  "it     gt\n\t"                                                                               \
  "movgt  r0, r11\n\t"                                                                          \
  "ldr    r1, [%[f], #16]\n\t"                                                                  \
  "strh   r10, [r1, #36]\n\t"                                                                   \
  "strh   r0, [r1, #38]\n\t"                                                                    \
  "strh   r11, [r1, #40]\n\t" /* cb r11, xmax - 128 r12, xa r3 = x0 + 128 - 256 cb, width lr */ \
  "cmp    r5, r8\n\t"                                                                           \
  "itete  lt\n\t"                                                                               \
  "andlt  r11, r5, r5, asr #31\n\t"                                                             \
  "andge  r11, r8, r8, asr #31\n\t"                                                             \
  "biclt  r12, r8, r8, asr #31\n\t"                                                             \
  "bicge  r12, r5, r5, asr #31\n\t"                                                             \
  "sub    r3, r3, #128\n\t"                                                                     \
  "add    r11, r11, r3\n\t"                                                                     \
  "asr    r11, r11, #8\n\t"                                                                     \
  "add    r12, r12, r3\n\t" /* xmax - 128: cmax <= width exactly when it is <= 256 width */     \
  "add    r3, r3, #256\n\t"                                                                     \
  "sub    r3, r3, r11, lsl #8\n\t"                                                              \
  "ldr    lr, [%[f], #92]\n\t" /* the width; inside: ucb r12 = cb, base 0, flags 4; else ucb 0, \
                                 base cb, flags 0 (in r2) */                                    \
  "cmp    r11, #0\n\t"                                                                          \
  "blt    1f\n\t"                                                                               \
  "cmp    r12, lr, lsl #8\n\t"                                                                  \
  "bgt    1f\n\t"                                                                               \
  "mov    r12, r11\n\t"                                                                         \
  "movs   r11, #0\n\t"                                                                          \
  "movs   r2, #4\n\t"                                                                           \
  "b      2f\n\t"                                                                               \
  "1:\n\t"                                                                                      \
  "movs   r12, #0\n\t"                                                                          \
  "movs   r2, #0\n\t"                                                                           \
  "2:\n\t"                                                                                      \
  "strh   r11, [r1, #42]\n\t" /* d, the flags (kBottomRight when d > 0) */                      \
  "mul    r11, r5, r9\n\t"                                                                      \
  "mls    r11, r8, r6, r11\n\t"                                                                 \
  "str    r11, [%[f], #20]\n\t"                                                                 \
  "rsb    r11, r11, #0\n\t" /* d > 0: -d < 0 (|d| < 2^29 here) */                               \
  "orr    r2, r2, r11, lsr #31\n\t"                                                             \
  "strb   r2, [r1, #47]\n\t" /* t0 r4 = 256 first + 128 - y0; the bottom edge at row mid + 1 */ \
  "rsb    r4, r4, #128\n\t"                                                                     \
  "add    r4, r4, r10, lsl #8\n\t"                                                              \
  "sub    r11, r0, r10\n\t"                                                                     \
  "add    r11, r11, #1\n\t"                                                                     \
  "add    r11, r4, r11, lsl #8\n\t"                                                             \
  "sub    r11, r11, r6\n\t"                                                                     \
  "sub    lr, r8, r5\n\t"                                                                       \
  "mul    r11, lr, r11\n\t"                                                                     \
  "str    lr, [r1, #28]\n\t"                                                                    \
  "sub    lr, r9, r6\n\t"                                                                       \
  "add    r0, r3, r5\n\t"                                                                       \
  "mla    r11, r0, lr, r11\n\t"                                                                 \
  "sub    r11, r11, #1\n\t"                                                                     \
  "asr    r11, r11, #8\n\t"                                                                     \
  "clz    r0, lr\n\t" /* max(dy, 1) for dy >= 0: dy | (clz(dy) >> 5) */                         \
  "orr    lr, lr, r0, lsr #5\n\t"                                                               \
  "mla    r11, r12, lr, r11\n\t"                                                                \
  "str    r11, [r1, #24]\n\t"                                                                   \
  "str    lr, [r1, #32]\n\t" /* the long edge ql r11, the top edge qt lr (top_dy in r6) */      \
  "mul    r11, r3, r9\n\t"                                                                      \
  "mla    r11, r8, r4, r11\n\t"                                                                 \
  "sub    r11, r11, #1\n\t"                                                                     \
  "asr    r11, r11, #8\n\t"                                                                     \
  "mla    r11, r12, r9, r11\n\t"                                                                \
  "mul    lr, r3, r6\n\t"                                                                       \
  "mla    lr, r5, r4, lr\n\t"                                                                   \
  "sub    lr, lr, #1\n\t"                                                                       \
  "asr    lr, lr, #8\n\t"                                                                       \
  "clz    r0, r6\n\t"                                                                           \
  "orr    r6, r6, r0, lsr #5\n\t"                                                               \
  "mla    lr, r12, r6, lr\n\t" /* the record, left edge first */                                \
  "tst    r2, #1\n\t"                                                                           \
  "beq    3f\n\t"                                                                               \
  "strd   r11, lr, [r1]\n\t"                                                                    \
  "strd   r8, r5, [r1, #8]\n\t"                                                                 \
  "strd   r9, r6, [r1, #16]\n\t"                                                                \
  "b      4f\n\t"                                                                               \
  "3:\n\t"                                                                                      \
  "strd   lr, r11, [r1]\n\t"                                                                    \
  "strd   r5, r8, [r1, #8]\n\t"                                                                 \
  "strd   r6, r9, [r1, #16]\n\t"                                                                \
  "4:\n\t" /* twice the area (word 5) at or above kSurelyPixelsArea2: kPixels */                \
  "ldr    r0, [%[f], #20]\n\t"                                                                  \
  "eor    r0, r0, r0, asr #31\n\t"                                                              \
  "cmp    r0, #0x20000\n\t"                                                                     \
  "bhs    41f\n\t" /* the columns at the row max(mid, first): long cl r11, short cs lr */       \
  "ldrsh  r0, [r1, #38]\n\t"                                                                    \
  "subs   r3, r0, r10\n\t"                                                                      \
  "bge    5f\n\t"                                                                               \
  "udiv   r11, r11, r9\n\t"                                                                     \
  "ldr    r4, [r1, #24]\n\t"                                                                    \
  "ldr    r12, [r1, #32]\n\t"                                                                   \
  "udiv   lr, r4, r12\n\t"                                                                      \
  "b      6f\n\t"                                                                               \
  "5:\n\t"                                                                                      \
  "mla    r11, r8, r3, r11\n\t"                                                                 \
  "udiv   r11, r11, r9\n\t"                                                                     \
  "mla    lr, r5, r3, lr\n\t"                                                                   \
  "udiv   lr, lr, r6\n\t"                                                                       \
  "6:\n\t"                                                                                      \
  "ldrsh  r3, [r1, #42]\n\t" /* the column base, the width */                                   \
  "ldr    r12, [%[f], #92]\n\t"                                                                 \
  "tst    r2, #1\n\t" /* left quotient r11, right lr */                                         \
  "ittt   eq\n\t"                                                                               \
  "eoreq  r11, r11, lr\n\t"                                                                     \
  "eoreq  lr, lr, r11\n\t"                                                                      \
  "eoreq  r11, r11, lr\n\t"                                                                     \
  "sub    r12, r12, r3\n\t" /* left < width - base */                                           \
  "movs   r0, #2\n\t"                                                                           \
  "cmp    r11, r12\n\t"                                                                         \
  "bge    9f\n\t"                                                                               \
  "cmn    lr, r3\n\t" /* right + base > 0 */                                                    \
  "ble    9f\n\t"                                                                               \
  "cmp    r11, lr\n\t"                                                                          \
  "bge    9f\n\t"                                                                               \
  "41:\n\t"                                                                                     \
  "movs   r0, #1\n\t"                                                                           \
  "b      9f\n\t"                                                                               \
  "8:\n\t"                                                                                      \
  "movs   r0, #0\n\t"                                                                           \
  "9:\n\t"
#endif

#if defined(__thumb2__) && defined(__ARM_FEATURE_DSP) && defined(__ARM_FEATURE_IDIV) && \
    !defined(__OPTIMIZE_SIZE__)
// small_planes of a lanes triangle with depth by hand (Armv7E-M): GCC 12 spilled the edges and
// the plane kind's factor around every plane. The frame as the rows' (d at 20, m at 24, the
// triangle at 16), then fx, fy (32), c0, r0 (40), rs, tg (48), the depth differences (56), its a0
// and scale exponent (64), a plane's a0 (72), blue's differences or the one-hue ratios (76), the
// result (88, 1 when the planes were made) and the rows' edge vectors (112). While the planes are
// made: E1x r3, E1y r4, E2x r5, E2y r6, the factor r12, left lr. LR_SP_SCALE: plane_scale of rs in
// r8 and s in r9: r12 = rs >> min(-s, 31) (or rs), lr = s or 0.
#define LR_SP_SCALE       \
  "usat   lr, #5, r9\n\t" \
  "rsb    r9, r9, #0\n\t" \
  "usat   r9, #5, r9\n\t" \
  "asr    r12, r8, r9\n\t"
// LR_SP_PLANE: d1 r0, d2 r1 -> off - px c0 - py r0 in r2, px r8, py r9 (r0, r1, r10, r11 scratch).
#define LR_SP_PLANE                  \
  "mul    r8, r0, r6\n\t"            \
  "mls    r8, r1, r4, r8\n\t"        \
  "mul    r9, r1, r3\n\t"            \
  "mls    r9, r0, r5, r9\n\t"        \
  "smmul  r8, r8, r12\n\t"           \
  "smmul  r9, r9, r12\n\t"           \
  "ldrd   r10, r11, [%[f], #32]\n\t" \
  "smmul  r2, r9, r11\n\t"           \
  "smmla  r2, r8, r10, r2\n\t"       \
  "ldrd   r10, r11, [%[f], #40]\n\t" \
  "mls    r2, r8, r10, r2\n\t"       \
  "mls    r2, r9, r11, r2\n\t"
// LR_SP_FINISH: the base (a0 from the frame's word 72, or OFF) and the gradients times 2^left;
// the triangle in r10.
#define LR_SP_FINISH(OFF) LR_SP_FINISH_A0("ldr    r10, [%[f], #" OFF "]\n\t")
// LR_SP_FINISH with a0 in r10 once A0 has run.
#define LR_SP_FINISH_A0(A0)  \
  "lsl    r2, r2, lr\n\t"    \
  "lsl    r8, r8, lr\n\t"    \
  "lsl    r9, r9, lr\n\t" A0 \
  "add    r2, r2, r10\n\t"   \
  "ldr    r10, [%[f], #16]\n\t"
#define LR_SMALL_PLANES_ASM(Z_BASE)          \
  /* zbits r6, lz r11, bm r12, the limits */ \
  "ldm    %[f], {r0, r1, r2}\n\t" \
  "ldr    r3, [r0, #8]\n\t" \
  "ldr    r4, [r1, #8]\n\t" \
  "ldr    r5, [r2, #8]\n\t" \
  "lsr    r3, r3, #1\n\t" \
  "rsb    r4, r3, r4, lsr #1\n\t" \
  "rsb    r5, r3, r5, lsr #1\n\t" \
  "eor    r6, r4, r4, asr #31\n\t" \
  "sub    r6, r6, r4, asr #31\n\t" \
  "eor    r8, r5, r5, asr #31\n\t" \
  "sub    r8, r8, r5, asr #31\n\t" \
  "orr    r6, r6, r8\n\t" \
  "clz    r6, r6\n\t" /* 32 - zbits */ \
  "ldrd   r8, r9, [%[f], #20]\n\t" \
  "eor    r10, r8, r8, asr #31\n\t" \
  "sub    r10, r10, r8, asr #31\n\t" \
  "clz    r11, r10\n\t" \
  "clz    r12, r9\n\t" /* 32 - bm */ \
  "sub    lr, r11, r12, lsl #1\n\t" /* lz + 2 bm - 64 (> 42: wide) */ \
  "cmn    lr, #22\n\t" \
  "bgt    18f\n\t" \
  "cmp    r6, #6\n\t" /* zbits > 26 */ \
  "blt    18f\n\t" \
  "sub    lr, lr, r6\n\t" /* lz + 2 bm + zbits - 96 (> 67: wide) */ \
  "cmn    lr, #29\n\t" \
  "bgt    18f\n\t" \
  /* tg r9; the depth differences below 2^16 (zsh = zbits - 16 or 0) */ \
  "rsb    r9, r11, #4\n\t" /* tg = 36 - lz - bm = 4 - lz + (32 - bm) */ \
  "add    r9, r9, r12\n\t" \
  "rsb    r6, r6, #16\n\t" /* zbits - 16 */ \
  "bic    r6, r6, r6, asr #31\n\t" \
  "asr    r4, r4, r6\n\t" \
  "asr    r5, r5, r6\n\t" \
  "add    r3, r3, #16384\n\t" \
  "sub    r6, r6, r9\n\t" \
  "strd   r4, r5, [%[f], #56]\n\t" \
  "strd   r3, r6, [%[f], #64]\n\t" \
  /* rs = recip62(|d| << lz), signed like d */ \
  "lsl    r10, r10, r11\n\t" \
  "lsr    r3, r10, #16\n\t" \
  "mov    r4, #-1\n\t" \
  "udiv   r3, r4, r3\n\t" \
  "lsl    r3, r3, #14\n\t" \
  "umull  r4, r5, r10, r3\n\t" \
  "rsb    r5, r5, #0x40000000\n\t" \
  "lsl    r5, r5, #2\n\t" \
  "smmul  r5, r3, r5\n\t" \
  "qadd   r3, r3, r5\n\t" /* (r3 in (0, 2^31): only a positive overflow) */ \
  "eor    r3, r3, r8, asr #31\n\t" /* signed like d */ \
  "sub    r3, r3, r8, asr #31\n\t" \
  "strd   r3, r9, [%[f], #48]\n\t" \
  /* the reference pixel and the edges times 2^(14 - bm) */ \
  "sub    r12, r12, #18\n\t" /* 14 - bm */ \
  "ldrd   r4, r5, [r0]\n\t" \
  "ldrd   r8, r9, [%[f], #112]\n\t" /* the rows' edge vectors */ \
  "ldrd   r10, r11, [%[f], #120]\n\t" \
  /* c0 = (x0 - 1) >> 8 and fx = (c0 256 + 128 - x0) 2^24 = (127 - ((x0 - 1) & 255)) 2^24 */ \
  /* = 0x7F000000 - (x0 - 1) 2^24 modulo 2^32; r0 and fy likewise */                           \
  "sub    r6, r4, #1\n\t" \
  "lsl    lr, r6, #24\n\t" \
  "rsb    lr, lr, #0x7F000000\n\t" \
  "asr    r6, r6, #8\n\t" \
  "sub    r4, r5, #1\n\t" \
  "lsl    r3, r4, #24\n\t" \
  "rsb    r3, r3, #0x7F000000\n\t" \
  "asr    r4, r4, #8\n\t" \
  "strd   lr, r3, [%[f], #32]\n\t" \
  "strd   r6, r4, [%[f], #40]\n\t" \
  "lsl    r3, r8, r12\n\t" \
  "lsl    r4, r9, r12\n\t" \
  "lsl    r5, r10, r12\n\t" \
  "lsl    r6, r11, r12\n\t" \
  /* depth: rs, 2^(zsh - tg) */ \
  "ldr    r8, [%[f], #48]\n\t" \
  "ldr    r9, [%[f], #68]\n\t" LR_SP_SCALE \
  "ldrd   r0, r1, [%[f], #56]\n\t" LR_SP_PLANE LR_SP_FINISH("64") Z_BASE \
  "strd   r8, r9, [r10, #56]\n\t" \
  /* green: rs 63 / 64, 2^(17 - tg), a0 63 c 2^11 + 2^25 */ \
  "ldrd   r8, r9, [%[f], #48]\n\t" \
  "sub    r8, r8, r8, asr #6\n\t" \
  "rsb    r9, r9, #17\n\t" LR_SP_SCALE \
  "ldm    %[f], {r0, r1, r2}\n\t" \
  "ldrh   r10, [r0, #18]\n\t" \
  "ldrh   r0, [r1, #18]\n\t" \
  "ldrh   r1, [r2, #18]\n\t" \
  "sub    r0, r0, r10\n\t" \
  "sub    r1, r1, r10\n\t" \
  "mov    r11, #129024\n\t" \
  "mul    r10, r10, r11\n\t" \
  "add    r10, r10, #0x2000000\n\t" /* green's a0, kept in r10 on the one-hue path */ \
  "ldr    r11, [%[f], #84]\n\t" /* kHueStep: red and blue from green's differences */ \
  "tst    r11, #16\n\t" \
  "bne    26f\n\t" \
  "str    r10, [%[f], #72]\n\t" LR_SP_PLANE LR_SP_FINISH("72") \
  "str    r2, [r10, #76]\n\t" \
  "strd   r8, r9, [r10, #80]\n\t" \
  /* red and blue: rs 31 / 32, 2^(1 - tg), a0 (31 c >> 4) + 2^10 in each lane */ \
  "ldrd   r8, r9, [%[f], #48]\n\t" \
  "sub    r8, r8, r8, asr #5\n\t" \
  "rsb    r9, r9, #1\n\t" LR_SP_SCALE \
  "ldm    %[f], {r0, r1, r2}\n\t" \
  "ldrh   r10, [r0, #16]\n\t" \
  "ldrh   r11, [r0, #20]\n\t" \
  "rsb    r8, r10, r10, lsl #5\n\t" \
  "lsr    r8, r8, #4\n\t" \
  "rsb    r9, r11, r11, lsl #5\n\t" \
  "lsr    r9, r9, #4\n\t" \
  "add    r8, r8, r9, lsl #16\n\t" \
  "add    r8, r8, #0x04000400\n\t" /* 2^10 in each lane */ \
  "str    r8, [%[f], #72]\n\t" \
  "ldrh   r8, [r1, #20]\n\t" \
  "ldrh   r9, [r2, #20]\n\t" \
  "sub    r8, r8, r11\n\t" \
  "sub    r9, r9, r11\n\t" \
  "strd   r8, r9, [%[f], #76]\n\t" \
  "ldrh   r0, [r1, #16]\n\t" \
  "ldrh   r1, [r2, #16]\n\t" \
  "sub    r0, r0, r10\n\t" \
  "sub    r1, r1, r10\n\t" LR_SP_PLANE \
  /* blue into r11 (off - px c0 - py r0), r0 (px), r10 (py) */ \
  "ldrd   r0, r1, [%[f], #76]\n\t" \
  "mul    r10, r1, r3\n\t" \
  "mls    r10, r0, r5, r10\n\t" \
  "mul    r0, r0, r6\n\t" \
  "mls    r0, r1, r4, r0\n\t" \
  "smmul  r0, r0, r12\n\t" \
  "smmul  r10, r10, r12\n\t" \
  "ldrd   r1, r11, [%[f], #32]\n\t" \
  "smmul  r11, r10, r11\n\t" \
  "smmla  r11, r0, r1, r11\n\t" \
  "ldr    r1, [%[f], #40]\n\t" \
  "mls    r11, r0, r1, r11\n\t" \
  "ldr    r1, [%[f], #44]\n\t" \
  "mls    r11, r10, r1, r11\n\t" \
  "add    r2, r2, r11, lsl #16\n\t" \
  "add    r8, r8, r0, lsl #16\n\t" \
  "add    r9, r9, r10, lsl #16\n\t" LR_SP_FINISH("72") \
  "str    r2, [r10, #64]\n\t" \
  "strd   r8, r9, [r10, #68]\n\t" \
  "ldr    r11, [%[f], #84]\n\t" /* the steps, for the affine test (the one-hue path keeps them) */ \
  "b      27f\n\t" \
  /* one hue: green's numerators made into r6 (x) and r5 (y), kept (the edges are not needed */ \
  /* after them); red's and blue's factors mul_hi(rs 31 / 32, ratio) 2^(3 - tg) (the ratios */ \
  /* at words 19 and 20) */ \
  "26:\n\t" \
  "mul    r9, r1, r3\n\t" \
  "mls    r5, r0, r5, r9\n\t" \
  "mul    r9, r0, r6\n\t" \
  "mls    r6, r1, r4, r9\n\t" \
  "smmul  r8, r6, r12\n\t" \
  "smmul  r9, r5, r12\n\t" \
  "ldrd   r0, r1, [%[f], #32]\n\t" \
  "smmul  r2, r9, r1\n\t" \
  "smmla  r2, r8, r0, r2\n\t" \
  "ldrd   r0, r1, [%[f], #40]\n\t" \
  "mls    r2, r8, r0, r2\n\t" \
  "mls    r2, r9, r1, r2\n\t" LR_SP_FINISH_A0("") /* green's a0 in r10 */ \
  "str    r2, [r10, #76]\n\t" \
  "strd   r8, r9, [r10, #80]\n\t" \
  "ldrd   r8, r9, [%[f], #48]\n\t" \
  "sub    r8, r8, r8, asr #5\n\t" \
  "ldrd   r0, r1, [%[f], #76]\n\t" \
  "smmul  r0, r8, r0\n\t" \
  "smmul  r1, r8, r1\n\t" \
  "rsb    r9, r9, #3\n\t" \
  "usat   lr, #5, r9\n\t" \
  "rsb    r9, r9, #0\n\t" \
  "usat   r9, #5, r9\n\t" \
  "asr    r0, r0, r9\n\t" \
  "asr    r1, r1, r9\n\t" \
  "smmul  r3, r6, r0\n\t" /* red px r3, py r4; blue px r6, py r5 */ \
  "smmul  r4, r5, r0\n\t" \
  "smmul  r6, r6, r1\n\t" \
  "smmul  r5, r5, r1\n\t" \
  "ldrd   r0, r1, [%[f], #32]\n\t" /* fx, fy */ \
  "smmul  r2, r4, r1\n\t" \
  "smmla  r2, r3, r0, r2\n\t" \
  "smmul  r8, r5, r1\n\t" \
  "smmla  r8, r6, r0, r8\n\t" \
  "add    r2, r2, r8, lsl #16\n\t" /* the offsets, gradients packed (blue high) */ \
  "add    r3, r3, r6, lsl #16\n\t" \
  "add    r4, r4, r5, lsl #16\n\t" \
  "ldrd   r0, r1, [%[f], #40]\n\t" /* c0, r0 */ \
  "mls    r2, r3, r0, r2\n\t" \
  "mls    r2, r4, r1, r2\n\t" \
  "lsl    r2, r2, lr\n\t" \
  "lsl    r3, r3, lr\n\t" \
  "lsl    r4, r4, lr\n\t" \
  "ldr    r0, [%[f], #0]\n\t" /* a0: (31 c >> 4) + 2^10 in each lane */ \
  "ldrh   r5, [r0, #16]\n\t" \
  "ldrh   r6, [r0, #20]\n\t" \
  "rsb    r5, r5, r5, lsl #5\n\t" \
  "lsr    r5, r5, #4\n\t" \
  "rsb    r6, r6, r6, lsl #5\n\t" \
  "lsr    r6, r6, #4\n\t" \
  "add    r5, r5, r6, lsl #16\n\t" \
  "add    r5, r5, #0x04000400\n\t" \
  "add    r2, r2, r5\n\t" \
  "str    r2, [r10, #64]\n\t" \
  "strd   r3, r4, [r10, #68]\n\t" \
  "27:\n\t" \
  "movs   r0, #1\n\t" /* made (the failure, label 18, is the block's: 0 at word 88) */

// The block's text. STEP_SORT: the test of kSortStep at its start; AFTER_SORT: what follows the
// sort (the path without it, into the rows with the vertices from the frame); STEP_PLANES: the
// test of kPlanesStep after the rows found pixels on their first rows. LanesSetup::block() takes
// every step but the affine test always, so its copy has none of them (8 instructions a triangle).
// PASSED: where a triangle that passes the affine test goes: block()'s copy to its end (its
// result is r0 alone), the steps' copy to the store of word 22 (LanesFrame::planes() reads it).
#define LR_LANES_STEP(BIT, LABEL) \
  "ldr    r0, [%[f], #84]\n\t"    \
  "tst    r0, #" BIT              \
  "\n\t"                          \
  "beq    " LABEL "\n\t"
#define LR_LANES_NO_SORT          \
  "b      12f\n\t"                \
  "11:\n\t"                       \
  "tst    r0, #1\n\t"             \
  "beq    10f\n\t"                \
  "ldm    %[f], {r0, r1, r2}\n\t" \
  "12:\n\t"
// LanesSetup's step after the rows when their result is kLaterRows (only a row other than the
// middle vertex's may have a pixel centre): later_rows_have_pixels from the record just stored,
// every row from first_row on, the left and right edges from edge_q[0] and [1] (the record is
// left edge first), the short side's switched to the bottom edge after mid_row. Columns are
// compared as quotients: left < width - col_base, right > -col_base, left < right. The result
// (word 7) becomes kPixels when a row has a pixel centre, and the triangle goes on to its planes;
// else kNoPixels, and the block returns 4 (LanesSetup's sliver) at once.
// The step after the rows where the later rows are not tested: on to the planes with kPixels.
#define LR_LANES_ROWS_MADE     \
  "str    r0, [%[f], #28]\n\t" \
  "cmp    r0, #1\n\t"          \
  "bne    20f\n\t"
#define LR_LANES_LATER_ROWS                                                       \
  "cmp    r0, #1\n\t" /* kPixels: word 7 stored only where C reads it (18, 28) */ \
  "beq    39f\n\t"                                                                \
  "str    r0, [%[f], #28]\n\t"                                                    \
  "cmp    r0, #2\n\t"                                                             \
  "bne    20f\n\t"                                                                \
  "ldr    r1, [%[f], #16]\n\t"                                                    \
  "ldrsh  r3, [r1, #36]\n\t"                                                      \
  "ldrsh  r4, [r1, #38]\n\t"                                                      \
  "ldrsh  r5, [r1, #40]\n\t"                                                      \
  "ldrsh  r6, [r1, #42]\n\t"                                                      \
  "ldr    r12, [%[f], #92]\n\t"                                                   \
  "sub    r12, r12, r6\n\t"                                                       \
  "rsb    r6, r6, #0\n\t"                                                         \
  "ldrd   r8, r11, [r1]\n\t"                                                      \
  "ldrd   r9, lr, [r1, #8]\n\t"                                                   \
  "ldrd   r10, r0, [r1, #16]\n\t"                                                 \
  "31:\n\t"                                                                       \
  "cmp    r3, r4\n\t"                                                             \
  "bgt    34f\n\t"                                                                \
  "32:\n\t"                                                                       \
  "udiv   r1, r8, r10\n\t"                                                        \
  "udiv   r2, r11, r0\n\t"                                                        \
  "add    r8, r8, r9\n\t"                                                         \
  "add    r11, r11, lr\n\t"                                                       \
  "cmp    r1, r12\n\t" /* left < width - base, right > -base, left < right */     \
  "itt    lt\n\t"                                                                 \
  "cmplt  r6, r2\n\t"                                                             \
  "cmplt  r1, r2\n\t"                                                             \
  "blt    35f\n\t"                                                                \
  "33:\n\t"                                                                       \
  "add    r3, r3, #1\n\t"                                                         \
  "cmp    r3, r5\n\t"                                                             \
  "ble    31b\n\t"                                                                \
  "movs   r0, #3\n\t"                                                             \
  "str    r0, [%[f], #28]\n\t"                                                    \
  "movs   r0, #4\n\t" /* the block's status for a sliver */                       \
  "b      20f\n\t"                                                                \
  "34:\n\t" /* past mid_row: the bottom edge on the short side, once */           \
  "movw   r4, #32767\n\t"                                                         \
  "ldr    r1, [%[f], #16]\n\t"                                                    \
  "ldrb   r2, [r1, #47]\n\t"                                                      \
  "tst    r2, #1\n\t"                                                             \
  "beq    37f\n\t"                                                                \
  "ldrd   r11, lr, [r1, #24]\n\t"                                                 \
  "ldr    r0, [r1, #32]\n\t"                                                      \
  "b      32b\n\t"                                                                \
  "37:\n\t"                                                                       \
  "ldrd   r8, r9, [r1, #24]\n\t"                                                  \
  "ldr    r10, [r1, #32]\n\t"                                                     \
  "b      32b\n\t"                                                                \
  "35:\n\t"                                                                       \
  "movs   r0, #1\n\t"                                                             \
  "str    r0, [%[f], #28]\n\t"                                                    \
  "39:\n\t"
// The least of the unsigned r5, r6, r12 into MIN and their range (largest less least) into RANGE.
#define LR_RANGE3(MIN, RANGE) \
  "cmp    r5, r6\n\t"         \
  "itete  lo\n\t"             \
  "movlo  " MIN               \
  ", r5\n\t"                  \
  "movhs  " MIN               \
  ", r6\n\t"                  \
  "movlo  " RANGE             \
  ", r6\n\t"                  \
  "movhs  " RANGE             \
  ", r5\n\t"                  \
  "cmp    r12, " MIN          \
  "\n\t"                      \
  "it     lo\n\t"             \
  "movlo  " MIN               \
  ", r12\n\t"                 \
  "cmp    r12, " RANGE        \
  "\n\t"                      \
  "it     hi\n\t"             \
  "movhi  " RANGE             \
  ", r12\n\t"                 \
  "sub    " RANGE ", " RANGE ", " MIN "\n\t"
// The depth plane's base into the record (the triangle in r10): the steps' copy; LanesSetup's
// with the row loop of its lanes triangles (frame word 34: the prepared draw's) beside it in one
// STRD, which the strip loop then need not store (its result 1 is exactly such a triangle).
#define LR_LANES_Z_BASE "str    r2, [r10, #52]\n\t"
#define LR_LANES_Z_AND_ROWS      \
  "ldr    r11, [%[f], #136]\n\t" \
  "strd   r11, r2, [r10, #48]\n\t"
#define LR_LANES_BLOCK_ASM(STEP_SORT, AFTER_SORT, STEP_PLANES, AFTER_ROWS, PASSED, Z_BASE) \
  "str    r1, [%[f], #16]\n\t" STEP_SORT /* the vertices: r0-r2 (binned sorted by y:           \
                                            store_sorted, kBinnedSorted) */                     \
  "ldrd   r3, r12, [%[f], #96]\n\t" /* the vertex store, sizeof(ScreenVertex) */              \
  "ldrh   r4, [r2]\n\t"                                                                         \
  "ldrh   r5, [r2, #2]\n\t"                                                                     \
  "ldrh   r6, [r2, #4]\n\t"                                                                     \
  "mla    r0, r4, r12, r3\n\t" \
  "mla    r1, r5, r12, r3\n\t" \
  "mla    r2, r6, r12, r3\n\t" \
  "stm    %[f], {r0, r1, r2}\n\t"                                                               \
  AFTER_SORT LR_SMALL_ROWS_BODY AFTER_ROWS STEP_PLANES \
      "10:\n\t" LR_SMALL_PLANES_ASM(Z_BASE) \
      /* the affine colour test (affine_within, kAffineBound565): w_max - w_min <= w_min >> 5, */ \
      /* or (w_max - w_min) D <= bound w_min with D the largest channel range (green's times */ \
      /* its weight); else the result 3. w_min r8, w_max - w_min r9. One hue first: D within */ \
      /* range_g F + kHueRangeSlack (LanesFrame), F at word 3: when that passes, D does. */ \
      "tst    r11, #8\n\t" /* the steps, in r11 from the planes */ \
      "beq    " PASSED "\n\t" \
      "ldm    %[f], {r2, r3, r4}\n\t" \
      "ldr    r5, [r2, #12]\n\t" \
      "ldr    r6, [r3, #12]\n\t" \
      "ldr    r12, [r4, #12]\n\t" LR_RANGE3("r8", "r9") \
      "cmp    r9, r8, lsr #5\n\t" \
      "bls    " PASSED "\n\t" \
      "tst    r11, #16\n\t" /* kHueStep */ \
      "beq    28f\n\t" \
      "ldrh   r5, [r2, #18]\n\t" \
      "ldrh   r6, [r3, #18]\n\t" \
      "ldrh   r12, [r4, #18]\n\t" LR_RANGE3("r10", "r1") \
      "ldr    lr, [%[f], #12]\n\t" \
      "mov    r10, #0xC0000\n\t" /* kHueRangeSlack 2^15 */ \
      "mla    r1, r1, lr, r10\n\t" /* at least D 2^15, below 2^32 */ \
      "umull  r5, r6, r9, r1\n\t" \
      "mov    r10, #0x4100000\n\t" /* bound 2^15 */ \
      "umull  r10, r12, r10, r8\n\t" \
      "subs   r10, r10, r5\n\t" \
      "sbcs   r12, r12, r6\n\t" \
      "bhs    " PASSED "\n\t" \
      "28:\n\t" \
      /* the ranges of (g, r) as 16-bit lanes: maximum r10, minimum r11, then r10 - r11 */ \
      "ldr    r5, [r2, #16]\n\t" \
      "ldr    r6, [r3, #16]\n\t" \
      "ldr    r1, [r4, #16]\n\t" \
      "usub16 r10, r5, r6\n\t" \
      "sel    r10, r5, r6\n\t" \
      "sel    r11, r6, r5\n\t" \
      "usub16 r12, r10, r1\n\t" \
      "sel    r10, r10, r1\n\t" \
      "usub16 r12, r11, r1\n\t" \
      "sel    r11, r1, r11\n\t" \
      "usub16 r10, r10, r11\n\t" \
      /* blue's: the low lanes of the words at 20 */ \
      "ldr    r5, [r2, #20]\n\t" \
      "ldr    r6, [r3, #20]\n\t" \
      "ldr    r1, [r4, #20]\n\t" \
      "usub16 r11, r5, r6\n\t" \
      "sel    r11, r5, r6\n\t" \
      "sel    r12, r6, r5\n\t" \
      "usub16 r5, r11, r1\n\t" \
      "sel    r11, r11, r1\n\t" \
      "usub16 r5, r12, r1\n\t" \
      "sel    r12, r1, r12\n\t" \
      "usub16 r11, r11, r12\n\t" \
      /* D r11: the largest of blue's, red's and green's times its weight */ \
      "uxth   r11, r11\n\t" \
      "uxth   r12, r10\n\t" \
      "lsr    r10, r10, #16\n\t" \
      "ldrd   r5, r6, [%[f], #104]\n\t" \
      "mul    r10, r10, r6\n\t" \
      "cmp    r11, r12\n\t" \
      "it     lo\n\t" \
      "movlo  r11, r12\n\t" \
      "cmp    r11, r10\n\t" \
      "it     lo\n\t" \
      "movlo  r11, r10\n\t" \
      "umull  r1, r2, r9, r11\n\t" \
      "umull  r3, r4, r5, r8\n\t" \
      "subs   r3, r3, r1\n\t" \
      "sbcs   r4, r4, r2\n\t" \
      "it     lo\n\t" \
      "movlo  r0, #3\n\t" \
      "movs   r1, #1\n\t" /* the rows' result, kPixels, for LanesSetup::rest */ \
      "str    r1, [%[f], #28]\n\t" \
      "b      21f\n\t" \
      "18:\n\t" /* the planes were not made (the rows' result kPixels at word 7) */ \
      "movs   r0, #1\n\t" \
      "str    r0, [%[f], #28]\n\t" \
      "movs   r0, #0\n\t" \
      "21:\n\t" \
      "str    r0, [%[f], #88]\n\t" \
      "20:\n\t"

namespace {
// The frame of the small lanes setup by hand (the words above), with the steps to take in word 21:
// kRowsStep, kPlanesStep or both (the planes then only when the rows' result is kPixels), and
// LanesSetup's: kSortStep (the vertices from the three indices (small_lanes_asm's index) into the
// vertex store at word 24 and the size of a vertex at 25, binned sorted by y: store_sorted,
// kBinnedSorted) and kAffineStep (when the planes were made, kAffineBound565's colour test, the
// bound and green's weight at 26 and 27: the result 3 when it fails). kHueStep: the input is one
// hue (UntexturedInput::hue), its ratios at words 19 (red) and 20 (blue; the other path's scratch
// words for blue's differences), the affine test's F at 3.
constexpr uint32_t kRowsStep = 1, kPlanesStep = 2, kSortStep = 4, kAffineStep = 8, kHueStep = 16;
static_assert(kBinnedSorted);  // LanesSetup's block reads the vertices in their binned order
// The affine colour test of a one-hue draw bounds D, the largest channel range of a triangle
// (green's counted twice), by green's range times F = max(2, rho_r, rho_b) plus this many units
// of Q1.15: each vertex colour lies within 9.5 units of rho green (docs/numerics.md#one-hue), so
// a red or blue range exceeds rho times green's by at most 19, and the stored rho (floored to
// 2^-15) by one more; the rest is margin (clipped vertices' colours are interpolated, rounded).
// When (w_max - w_min) (range_g F + slack) <= bound w_min holds, the exact test holds: the
// result is the same, only found sooner.
inline constexpr uint32_t kHueRangeSlack = 24;
static_assert((kHueRangeSlack << 15) == 0xC0000 && (kAffineBound565.bound << 15) == 0x4100000 &&
              kAffineBound565.quick_shift == 5);  // the block's immediates
// The steps' kHueStep and its factors for input `in`; F = max(2, rho_r, rho_b) in Q15 (at most
// 2^16: the ratios are below 2) for the affine test.
void set_hue(uint32_t* w, const UntexturedInput& in) {
  if (!in.hue.valid) return;
  w[21] |= kHueStep;
  w[19] = static_cast<uint32_t>(in.hue.red);
  w[20] = static_cast<uint32_t>(in.hue.blue);
  w[3] = std::max({uint32_t{2} << 15, static_cast<uint32_t>(in.hue.red) >> 15,
                   static_cast<uint32_t>(in.hue.blue) >> 15});
}
struct LanesFrame {
  uint32_t w[kLanesFrameWords];
  LanesFrame() = default;
  LanesFrame(const ScreenVertex* const v[3], uint32_t steps) {
    w[0] = reinterpret_cast<uintptr_t>(v[0]);
    w[1] = reinterpret_cast<uintptr_t>(v[1]);
    w[2] = reinterpret_cast<uintptr_t>(v[2]);
    w[21] = steps;
    w[22] = 0;
  }
  SmallRows rows() const {
    SmallRows out;
    out.d = static_cast<int32_t>(w[5]);
    out.m = w[6];
    out.result = static_cast<uint8_t>(w[7]);
    return out;
  }
  bool planes() const { return w[22] != 0; }
};
// Both steps in one block: a triangle that has pixels on its first rows (the common one) gets its
// rows and planes in one call, nothing reloaded from C between them.
//
// t goes to word 4 from the block; index (LanesSetup's, for kSortStep: else unused) is read
// from its register. Returns 1 exactly when the rows and planes were made and the affine test
// (when a step) held: LanesSetup's usual result, read from no frame word; 4 (kBlock only) when no
// row has a pixel centre (LR_LANES_LATER_ROWS).
template <bool kBlock>
[[gnu::always_inline]] inline uint32_t small_lanes_asm(LanesFrame& frame, ActiveTriangle* t,
                                                       const uint16_t* index) {
  static_assert(offsetof(RowWindow, first_min) == 0 && offsetof(RowWindow, last_max) == 4 &&
                offsetof(RowWindow, width) == 8);
  static_assert(offsetof(ActiveTriangle, edge_q) == 0 && offsetof(ActiveTriangle, edge_dx) == 8 &&
                offsetof(ActiveTriangle, edge_dy) == 16 && offsetof(ActiveTriangle, bottom) == 24 &&
                offsetof(ActiveTriangle, first_row) == 36 &&
                offsetof(ActiveTriangle, mid_row) == 38 &&
                offsetof(ActiveTriangle, last_row) == 40 &&
                offsetof(ActiveTriangle, col_base) == 42 && offsetof(ActiveTriangle, flags) == 47);
  static_assert(kSurelyPixelsArea2 == 0x20000);  // the rows' test at label 4
  static_assert(ActiveTriangle::kBottomRight == 1 && ActiveTriangle::kInside == 4 &&
                kSmallEdgeBits == 14 && kSubpixelBits == 8);
  static_assert(SmallRows::kSlow == 0 && SmallRows::kPixels == 1 && SmallRows::kLaterRows == 2 &&
                SmallRows::kNoPixels == 3);
  static_assert(offsetof(ScreenVertex, z) == 8 && offsetof(ScreenVertex, color) == 16 &&
                offsetof(Color15, g) == 2 && offsetof(Color15, b) == 4);
  static_assert(offsetof(ActiveTriangle, rows) == 48 && offsetof(ActiveTriangle, z) == 52 &&
                offsetof(ActiveTriangle, c) == 64 && sizeof(Plane) == 12 &&
                offsetof(Plane, base) == 0 && offsetof(Plane, gx) == 4);
  static_assert(kFastMaxSpread == 10 && kFastMaxDepthSpread == 35 && kSmallMaxDepthBits == 26);
  static_assert(offsetof(ScreenVertex, y) == 4 && offsetof(ScreenVertex, w) == 12 &&
                offsetof(Color15, r) == 0 && sizeof(ScreenVertex) == 24);
  uint32_t* const f = frame.w;
  // The status in r0; t and index in r1, r2 (operands, so as not to be clobbers).
  register uint32_t status asm("r0");
  register ActiveTriangle* t_reg asm("r1") = t;
  register const uint16_t* index_reg asm("r2") = index;
  if constexpr (kBlock)
    asm volatile(LR_LANES_BLOCK_ASM("", "", "", LR_LANES_LATER_ROWS, "20f", LR_LANES_Z_AND_ROWS)
                 : "=&r"(status), "+r"(t_reg), "+r"(index_reg)
                 : [f] "r"(f)
                 : "r3", "r4", "r5", "r6", "r8", "r9", "r10", "r11", "r12", "lr", "cc", "memory");
  else
    asm volatile(
        LR_LANES_BLOCK_ASM(LR_LANES_STEP("4", "11f"), LR_LANES_NO_SORT, LR_LANES_STEP("2", "20f"),
                           LR_LANES_ROWS_MADE, "21f", LR_LANES_Z_BASE)
        : "=&r"(status), "+r"(t_reg), "+r"(index_reg)
        : [f] "r"(f)
        : "r3", "r4", "r5", "r6", "r8", "r9", "r10", "r11", "r12", "lr", "cc", "memory");
  return status;
}
// The steps' copy for the by-hand entries below (one, out of line); LanesSetup::block has its own.
[[gnu::noinline]] uint32_t small_lanes_steps(LanesFrame& frame, ActiveTriangle* t) {
  return small_lanes_asm<false>(frame, t, nullptr);
}
}  // namespace

SmallRows small_rows_by_hand(const ScreenVertex* const v[3], const RowWindow& w,
                             ActiveTriangle& t) {
  LanesFrame frame(v, kRowsStep);
  set_window(frame.w, w);
  small_lanes_steps(frame, &t);
  return frame.rows();
}

bool small_lanes_triangle_by_hand(const ScreenVertex* const v[3], const RowWindow& w,
                                  const UntexturedInput& in, ActiveTriangle& t, SmallRows& rows) {
  LanesFrame frame(v, kRowsStep | kPlanesStep);
  set_window(frame.w, w);
  set_hue(frame.w, in);
  small_lanes_steps(frame, &t);
  rows = frame.rows();
  return frame.planes();
}

bool small_lanes_planes_by_hand(const ScreenVertex* const v[3], int32_t d, uint32_t m,
                                const UntexturedInput& in, ActiveTriangle& t) {
  LanesFrame frame(v, kPlanesStep);
  set_hue(frame.w, in);
  frame.w[5] = static_cast<uint32_t>(d);
  frame.w[6] = m;
  // The edge vectors the rows would have left (words 28 to 31).
  frame.w[28] = static_cast<uint32_t>(v[1]->x - v[0]->x);
  frame.w[29] = static_cast<uint32_t>(v[1]->y - v[0]->y);
  frame.w[30] = static_cast<uint32_t>(v[2]->x - v[0]->x);
  frame.w[31] = static_cast<uint32_t>(v[2]->y - v[0]->y);
  small_lanes_steps(frame, &t);
  return frame.planes();
}

namespace {
[[gnu::noinline]] UntexturedTriangle finish_after_hand(LanesFrame& f, const RowWindow& w,
                                                       const UntexturedInput& in,
                                                       ActiveTriangle& t) {
  const ScreenVertex* const v[3] = {reinterpret_cast<const ScreenVertex*>(f.w[0]),
                                    reinterpret_cast<const ScreenVertex*>(f.w[1]),
                                    reinterpret_cast<const ScreenVertex*>(f.w[2])};
  const SmallRows rows = f.rows();
  // The block went through the later rows itself (LR_LANES_LATER_ROWS): kNoPixels is a sliver;
  // a triangle with a pixel centre on a later row came back as kPixels.
  if (rows.result == SmallRows::kNoPixels) return UntexturedTriangle::sliver();
  return finish_triangle(v, w, in, t, rows, rows.result == SmallRows::kPixels, f.w[22] != 0);
}
}  // namespace

void LanesSetup::prepare(const RowWindow& w, const UntexturedInput& in,
                         const ScreenVertex* vertices, RowFn lanes_rows) {
  static_assert(sizeof(frame_) == sizeof(LanesFrame) && alignof(LanesSetup) >= 4);
  w_ = &w;
  in_ = &in;
  lanes_rows_ = lanes_rows;
  frame_[34] = reinterpret_cast<uintptr_t>(lanes_rows);
  frame_[21] = kSortStep | kRowsStep | kPlanesStep |
               (in.colors == ColorPlanes::kPerspective ? kAffineStep : 0u);
  set_hue(frame_, in);
  set_window(frame_, w);
  frame_[24] = reinterpret_cast<uintptr_t>(vertices);
  frame_[25] = sizeof(ScreenVertex);
  frame_[26] = in.affine.bound;
  frame_[27] = in.affine.green_weight;
}

uint32_t LanesSetup::block(uint32_t* frame, ActiveTriangle& t, const uint16_t index[3]) {
  return small_lanes_asm<true>(*reinterpret_cast<LanesFrame*>(frame), &t, index);
}

UntexturedTriangle LanesSetup::rest(const uint16_t /*index*/[3], ActiveTriangle& t) {
  return finish_after_hand(*reinterpret_cast<LanesFrame*>(frame_), *w_, *in_, t);
}
#undef LR_SP_FINISH
#undef LR_SP_FINISH_A0
#undef LR_SP_PLANE
#undef LR_SP_SCALE
#undef LR_SMALL_PLANES_ASM
#undef LR_LANES_STEP
#undef LR_LANES_NO_SORT
#undef LR_LANES_BLOCK_ASM
#undef LR_RANGE3
#undef LR_LANES_Z_BASE
#undef LR_LANES_Z_AND_ROWS
#undef LR_LANES_LATER_ROWS
#undef LR_LANES_ROWS_MADE
#else
bool small_lanes_planes_by_hand(const ScreenVertex* const /*v*/[3], int32_t /*d*/, uint32_t /*m*/,
                                const UntexturedInput& /*in*/, ActiveTriangle& /*t*/) {
  return false;
}
#if defined(__thumb2__) && defined(__ARM_FEATURE_IDIV) && !defined(__OPTIMIZE_SIZE__)
SmallRows small_rows_by_hand(const ScreenVertex* const v[3], const RowWindow& w,
                             ActiveTriangle& t) {
  uint32_t frame[kLanesFrameWords];  // (the rows store the edge vectors at words 28 to 31)
  frame[0] = reinterpret_cast<uintptr_t>(v[0]);
  frame[1] = reinterpret_cast<uintptr_t>(v[1]);
  frame[2] = reinterpret_cast<uintptr_t>(v[2]);
  frame[4] = reinterpret_cast<uintptr_t>(&t);
  set_window(frame, w);
  uint32_t* const f = frame;
  asm volatile(LR_SMALL_ROWS_ASM
               :
               : [f] "r"(f)
               : "r0", "r1", "r2", "r3", "r4", "r5", "r6", "r8", "r9", "r10", "r11", "r12", "lr",
                 "cc", "memory");
  SmallRows out;
  out.d = static_cast<int32_t>(frame[5]);
  out.m = frame[6];
  out.result = static_cast<uint8_t>(frame[7]);
  return out;
}
#else
SmallRows small_rows_by_hand(const ScreenVertex* const v[3], const RowWindow& w,
                             ActiveTriangle& t) {
  return small_rows_c(v, w, t);
}
#endif
bool small_lanes_triangle_by_hand(const ScreenVertex* const v[3], const RowWindow& w,
                                  const UntexturedInput& /*in*/, ActiveTriangle& t,
                                  SmallRows& rows) {
  rows = small_rows_by_hand(v, w, t);
  return false;
}

void LanesSetup::prepare(const RowWindow& w, const UntexturedInput& in,
                         const ScreenVertex* vertices, RowFn lanes_rows) {
  lanes_rows_ = lanes_rows;
  w_ = &w;
  in_ = &in;
  vertices_ = vertices;
}

uint32_t LanesSetup::block(uint32_t* /*frame*/, ActiveTriangle& /*t*/,
                           const uint16_t /*index*/[3]) {
  return 0;
}

UntexturedTriangle LanesSetup::rest(const uint16_t index[3], ActiveTriangle& t) {
  const ScreenVertex* v[3] = {&vertices_[index[0]], &vertices_[index[1]], &vertices_[index[2]]};
  sort_below_top(v);
  return setup_untextured_triangle(v, *w_, *in_, t);
}
#endif
#ifdef LR_SMALL_ROWS_ASM
#undef LR_SMALL_ROWS_ASM
#undef LR_SMALL_ROWS_BODY
#endif

UntexturedTriangle setup_untextured_triangle(const ScreenVertex* const v[3], const RowWindow& w,
                                             const UntexturedInput& in, ActiveTriangle& t) {
#if defined(__OPTIMIZE_SIZE__)
  // Where code size comes first, every triangle's rows by setup_rows, whose records are exact as
  // small_rows' are (the same rows, columns, flags and slivers; only the words of an edge no row
  // reads may differ) and which the triangles beyond the small path need anyway: one routine
  // for the rows instead of two (about 0.5 KB), at some instructions per triangle.
  const int32_t first = std::max(first_row_below(v[0]->y), w.first_min);
  const int32_t last = std::min(last_row_at_or_above(v[2]->y), w.last_max);
  if (!setup_rows(v, first, last, w.width, t)) return UntexturedTriangle::sliver();
  const int32_t e1x = v[1]->x - v[0]->x, e1y = v[1]->y - v[0]->y;
  const int32_t e2x = v[2]->x - v[0]->x, e2y = v[2]->y - v[0]->y;
  SmallRows rows;
  rows.m = magnitude(e1x) | magnitude(e2x) | static_cast<uint32_t>(e2y);  // e2y >= e1y >= 0
  if (rows.m >= (1u << kSmallEdgeBits)) {
    const UntexturedSetup u = setup_untextured(v, in, t);
    return UntexturedTriangle::made(u.kind, u.wide);
  }
  rows.d = e1x * e2y - e2x * e1y;  // below 2^29 in magnitude: edges below 2^14
  rows.result = SmallRows::kPixels;
  return finish_triangle(v, w, in, t, rows, false, false);
#else
  SmallRows rows;
  // Lanes planes by hand made with the rows (tried: the rows had pixels on their first rows).
  bool tried = false, made = false;
  if (kSmallPlanesByHand && in.lanes_first) {
    made = small_lanes_triangle_by_hand(v, w, in, t, rows);
    tried = rows.result == SmallRows::kPixels;
  } else {
    rows = kSmallRowsByHand ? small_rows_by_hand(v, w, t) : small_rows_c(v, w, t);
  }
  return finish_triangle(v, w, in, t, rows, tried, made);
#endif
}

UntexturedSetup setup_untextured(const ScreenVertex* const v[3], const UntexturedInput& in,
                                 ActiveTriangle& t) {
  UntexturedKind kind = in.colors == ColorPlanes::kNone     ? UntexturedKind::kFlat
                        : in.colors == ColorPlanes::kAffine ? UntexturedKind::kAffine
                                                            : UntexturedKind::kPerspective;
  if (kind == UntexturedKind::kPerspective && in.affine_ok && affine_within(v, in.affine))
    kind = UntexturedKind::kAffine;
  if (kind == UntexturedKind::kFlat && !in.depth) {  // no plane at all
    t.c[0].base = in.flat_pixel;
    return {kind, false};
  }
  const bool persp = kind == UntexturedKind::kPerspective;
  FastBasis b;
  bool fast = fast_basis(v, persp ? kFastMaxSpreadPerspective : kFastMaxSpread, b);
  const int32_t z[3] = {static_cast<int32_t>(v[0]->z >> 1), static_cast<int32_t>(v[1]->z >> 1),
                        static_cast<int32_t>(v[2]->z >> 1)};
  int zu = 30;
  if (in.depth) {
    const int zbits = bit_length(std::max(magnitude(z[1] - z[0]), magnitude(z[2] - z[0])));
    fast = fast && b.spread + zbits <= kFastMaxDepthSpread;
    zu = 30 - zbits;
  }
  if (kind == UntexturedKind::kAffine && in.lanes && b.bm <= kLanesMaxEdgeBits)
    kind = UntexturedKind::kLanes;
  // The planes, on the short path or the wide one.
  std::optional<PlaneBasis> pb;
  if (!fast) pb.emplace(v);
  auto planes = [&](const int32_t a[3], int u) {
    return fast ? fast_plane(b, a, u) : wide_plane(*pb, a);
  };
  if (in.depth) {
    t.z = planes(z, zu);
    t.z.base += 1u << 14;  // the 16-bit depth's rounding
  }
  auto values = [&](auto f, int32_t a[3]) {
    for (int i = 0; i < 3; ++i) a[i] = f(*v[i]);
  };
  switch (kind) {
    case UntexturedKind::kFlat:
      t.c[0].base = in.flat_pixel;
      break;
    case UntexturedKind::kLanes: {
      int32_t r[3], bl[3], g[3];
      values([](const ScreenVertex& x) { return lane5(x.color.r); }, r);
      values([](const ScreenVertex& x) { return lane5(x.color.b); }, bl);
      values([](const ScreenVertex& x) { return lane6(x.color.g); }, g);
      const Plane pr = planes(r, 14), pbl = planes(bl, 14), pg = planes(g, -1);
      t.c[0] = Plane{(pbl.base << 16) + pr.base, (pbl.gx << 16) + pr.gx, (pbl.gy << 16) + pr.gy};
      t.c[1] = Plane{pg.base << 1, pg.gx << 1, pg.gy << 1};  // green in 63 c 2^11 + 2^25
      break;
    }
    case UntexturedKind::kAffine:
      for (int c = 0; c < 3; ++c) {
        int32_t a[3];
        for (int i = 0; i < 3; ++i) a[i] = int32_t{channel(v[i]->color, c)} << 15;
        t.c[c] = planes(a, 0);
      }
      break;
    case UntexturedKind::kPerspective: {
      const uint32_t wmin = min3(v[0]->w, v[1]->w, v[2]->w);
      uint32_t q[3];
      for (int i = 0; i < 3; ++i) q[i] = perspective_q(wmin, v[i]->w);
      const int32_t qs[3] = {static_cast<int32_t>(q[0]), static_cast<int32_t>(q[1]),
                             static_cast<int32_t>(q[2])};
      t.q = planes(qs, 0);
      for (int c = 0; c < 3; ++c) {
        int32_t a[3];
        // A Q1.15 channel times q, in Q1.30: c 2^16 x 2 q / 2^32 (at most q).
        for (int i = 0; i < 3; ++i)
          a[i] = static_cast<int32_t>(mul_hi_u(uint32_t{channel(v[i]->color, c)} << 16, q[i] << 1));
        t.c[c] = planes(a, 0);
      }
      break;
    }
  }
  return {kind, !fast};
}

}  // namespace lr
