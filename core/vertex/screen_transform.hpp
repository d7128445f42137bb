// The short path of the vertex stage: a draw's model-view-projection in 32-bit rows, taking a
// model position straight to display subpixels, window depth and clip w with high-word products
// (mla_hi: SMMLA on cores with the DSP extension) and one reciprocal of w (recip_q61), the same
// integers on every core.
//
// Per draw, each row of the model-view-projection is multiplied by its viewport factor (x: the
// half width in subpixels, y: minus the half height, z: half the depth range kDepthMax / 2, w: 1)
// and scaled by a power of two chosen from the row and the draw's position bound, so that no sum
// can leave int32; positions are shifted up to use 31 bits. Per vertex:
//   X, Y, Z, W = rows . (P, 1)              sums of three mla_hi each
//   n = clz(W), r = recip_q61(W << n) >> (n_max - n)      about 2^(61 - n_max) / W
//   x = mla_hi(X, r, (sx << f) + 2^(f - 1)) >> f          display subpixels, rounded
//   y = mla_hi(Y, r, (sy << f) + 2^(f - 1)) >> f
//   z = kDepthMax / 2 + mul_hi(Z, r) 2^kz                 window depth
// A vertex is projected here only when it is inside every plane with w large enough for that
// precision: w in a range (the precision's lower end), x and y in the guard band (a test per
// vertex, unless the cube of the draw's position bound lies inside the band: then only a clamp),
// z in the depth range. Every other vertex (near the eye, behind it,
// outside a plane, or a draw whose clip coordinates may reach the exact path's range limit) is
// left to the caller's exact path (VertexStage::project on 64-bit clip coordinates, and the exact
// outcode), which it counts (FrameStats::vertices_wide). Derivation and bounds:
// docs/numerics.md#the-short-path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/math/reciprocal.hpp"
#include "lineraster/core/math/saturate.hpp"
#include "lineraster/core/math/vec.hpp"
#include "lineraster/core/math/wide_mul.hpp"
#include "lineraster/core/vertex/clip.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr {

// Fraction bits of a subpixel the short path keeps in x / w and y / w before rounding (at least;
// up to 10 for a draw whose position bound's cube lies inside the guard band: fraction_bits()):
// x and y are within 2^-kShortPathFractionBits subpixels plus 2^-19 of their distance from the
// centre of the quotients of the draw's clip coordinates (before rounding; tests/core/vertex_test).
inline constexpr int kShortPathFractionBits = 5;

// Whether ScreenTransform::run() is the hand-written loop (else project() in a loop; so where the
// code is built for size: the same integers without the loop's 0.3 KB).
// (A macro as well: the loop's assembly names Arm registers, which other targets' compilers
// reject even in a discarded branch.)
#if defined(__ARM_FEATURE_DSP) && defined(__thumb2__) && defined(__ARM_FEATURE_SAT) && \
    defined(__ARM_FEATURE_IDIV) && !defined(__OPTIMIZE_SIZE__)
#define LR_SHORT_PATH_RUN 1
inline constexpr bool kShortPathRun = true;
#else
#define LR_SHORT_PATH_RUN 0
inline constexpr bool kShortPathRun = false;
#endif

// A bound of a draw's position coordinates (Q16.16 raw): every coordinate c lies in
// [-bound - 1, bound]. One pass over the positions: the OR of c ^ (c >> 31) (c, or -c - 1), less
// than twice the largest magnitude, which is all the short path's scaling needs.
uint32_t position_bound(const Vec3* positions, size_t n);

class ScreenTransform {
 public:
  // mvp: the draw's model-view-projection (a valid FineMat4: Q16.16 as to_fine gives it, or
  // finer); p_frac: the positions' fraction bits, in [16, 30] (Mesh::position_frac); bound:
  // every coordinate of the positions it will be given lies in [-bound - 1, bound] (raw:
  // position_bound, or Mesh::bound); the viewport (1..kMaxViewport) and its guard band. The
  // fraction counts change only the per-draw factors' exponents: the same code per vertex.
  ScreenTransform(const FineMat4& mvp, int p_frac, uint32_t bound, int width, int height,
                  GuardBand guard);
  // A Q16.16 model-view-projection and Q16.16 positions.
  ScreenTransform(const Mat4& mvp, uint32_t bound, int width, int height, GuardBand guard)
      : ScreenTransform(to_fine(mvp), 16, bound, width, height, guard) {}

  // Whether any vertex can take the short path (false: the draw's clip coordinates may reach the
  // exact path's range limit, or its rows leave no precision for it).
  bool enabled() const { return enabled_; }
  // Whether every position within the bound is inside the guard band (no test per vertex).
  bool guard_free() const { return guard_free_; }
  // The fraction bits of a subpixel x and y keep before rounding (f, in [5, 10] when enabled):
  // their error is a unit or so of 2^-f (docs/numerics.md#the-short-path).
  int fraction_bits() const { return k_.f; }

  // p into v's x, y, z, w and outcode 0 (nothing else of v) when p is inside every plane and
  // its w is in the short path's range; false (v unchanged) otherwise: the vertex needs the
  // exact path (always when !enabled()). A position outside the bound gives a wrong vertex
  // (never undefined behaviour, never one outside the coordinate budget).
  [[gnu::always_inline]] bool project(const Vec3& p, ScreenVertex& v) const;

  // project() as cores without a 64-bit product compute it (project() there): public for the
  // tests, which check that both give the same integers.
  [[gnu::always_inline]] bool project_halves(const Vec3& p, ScreenVertex& v) const;

  // project() over positions [p, p + count) into out (x, y, z, w, and the last 8 bytes from
  // tail: colour, outcode 0, pending flag) while each takes the short path; returns how many
  // did (the next needs the exact path). The one copy of project()'s code in an image; on cores
  // with the DSP extension, Thumb-2 and a divider (kShortPathRun), for draws that need no guard
  // test (guard_free()), hand-allocated registers instead: the same integers, in about 68
  // instructions a vertex where GCC 12's code for project() takes about 100 (it reloads and
  // spills the draw's constants).
  size_t run(const Vec3* p, size_t count, ScreenVertex* out, const uint32_t (&tail)[2]) const;

 private:
  // project()'s tail: screen x, y (subpixels), the depth numerator m and W to the vertex.
  [[gnu::always_inline]] bool store(int32_t xs, int32_t ys, int32_t m, int32_t w,
                                    ScreenVertex& v) const;
  static constexpr int32_t kMaxW = (int32_t{1} << 30) - 1;  // row sums are below 2^29 + 5
  static constexpr uint32_t kHalfDepth = kDepthMax / 2;     // 65535 * 2^15

  static int64_t guard_free_least_w(const FineMat4& mvp, int p_frac, uint32_t bound,
                                    GuardBand guard);

  // Rows x, y, z, w: a[j] = K_i m_ij 2^(E_i - ps + 32 - F - P), |a| < 2^31; t = K_i t_i
  // 2^(E_i - F), with m, t the raw entries of F fraction bits and P the positions' (16 and 16:
  // a[j] = K_i m_ij 2^(E_i - ps), t = K_i t_i 2^(E_i - 16)), K_i the row's viewport factor and E_i
  // its exponent (x and y share one): every row sum is below 2^29 + 5 in magnitude
  // (docs/numerics.md#the-short-path).
  struct alignas(8) RowWords {
    int32_t a[3];  // the row's factors of x, y, z
    int32_t t;     // its translation
  };
  // Everything a vertex reads, in the order run() reads it (ldrd pairs; its offsets in its code).
  struct alignas(8) Words {
    RowWords w, x, y, z;  // 0, 16, 32, 48
    // The short path when W is in [w_lo, w_lo + w_span]: w_lo >= 2^(31 - n_max) (the precision),
    // w_lo + w_span <= 2^30 - 1 (every shift below defined). Disabled: only W = INT32_MIN, which
    // no row sum reaches (nor the zero rows).
    int32_t w_lo = INT32_MIN;  // 64
    uint32_t w_span = 0;
    int32_t n_max = 0;    // 72: in [2, 9]
    int32_t f = 0;        // fraction bits of x and y before the rounding shift, in [5, 10]
    int32_t acc_x = 0;    // 80: (sx << f) + 2^(f - 1): sx the viewport's centre, subpixels
    int32_t acc_y = 0;    // (sy << f) + 2^(f - 1)
    int32_t ps = 0;       // 88: position shift: |p << ps| <= 2^31
    uint32_t c0 = 0;      // 92: z = c0 + m 2^kz (wrapping: exact inside the depth range)
    int32_t kz = 0;       // 96: in [0, 10]
    int32_t w_shift = 0;  // clip w in Q16.16: W >> w_shift (>= 0)
    int32_t m_lo = 0;     // 104: the depth range: m in [m_lo, m_lo + m_span]
    uint32_t m_span = 0;
    int32_t x_lo = 0;  // 112: the guard band: x in [x_lo, x_lo + x_span], subpixels
    uint32_t x_span = 0;
    int32_t y_lo = 0;
    uint32_t y_span = 0;
    const RowWords& row(int i) const { return i == 0 ? x : i == 1 ? y : i == 2 ? z : w; }
  };
  Words k_{};
  // The rows' factors split into halves once (project_halves), on cores without a 64-bit
  // product only; elsewhere split per use (the tests run project_halves on the host).
  struct NoSplit {  // (indexable, so that the code for the split arrays compiles everywhere)
    struct Row {
      Halves operator[](int /*unused*/) const { return {}; }
    };
    Row operator[](int /*unused*/) const { return {}; }
  };
  [[no_unique_address]] std::conditional_t<kSplitWideProducts, Halves[4][3], NoSplit> split_{};
  Halves split(int i, int j) const {
    if constexpr (kSplitWideProducts)
      return split_[i][j];
    else
      return halves(k_.row(i).a[j]);
  }
  bool guard_free_ = false;  // no x, y test: the bound's cube is inside the guard band
  bool enabled_ = false;
};

// clz of w for w in [2^22, 2^30) (n in [2, 9], the short path's range) in three compares: the
// form for cores without CLZ (Armv6-M, where libgcc's takes about 20 instructions).
constexpr int clz_short_path(uint32_t w) {
  int n = 2;
  if (w < (1u << 26)) {
    n += 4;
    w <<= 4;
  }
  if (w < (1u << 28)) {
    n += 2;
    w <<= 2;
  }
  if (w < (1u << 29)) n += 1;
  return n;
}

inline bool ScreenTransform::project(const Vec3& p, ScreenVertex& v) const {
  if constexpr (kSplitWideProducts) return project_halves(p, v);
  const Words& k = k_;
  // C++20 shifts are modular: a position beyond the bound gives a wrong vertex, never UB.
  const int32_t px = p.x.raw << k.ps, py = p.y.raw << k.ps, pz = p.z.raw << k.ps;
  auto row = [&](const RowWords& q) {
    return mla_hi(q.a[0], px, mla_hi(q.a[1], py, mla_hi(q.a[2], pz, q.t)));
  };
  const int32_t w = row(k.w);
  // One compare: w in the range keeps n = clz(w) in [2, n_max], every shift below defined.
  if (static_cast<uint32_t>(w) - static_cast<uint32_t>(k.w_lo) > k.w_span) return false;
  const int32_t x = row(k.x), y = row(k.y), z = row(k.z);
  const int n = clz32(static_cast<uint32_t>(w));
  const auto r = static_cast<int32_t>(recip_q61(static_cast<uint32_t>(w) << n) >> (k.n_max - n));
  int32_t xs = mla_hi(x, r, k.acc_x) >> k.f;
  int32_t ys = mla_hi(y, r, k.acc_y) >> k.f;
  return store(xs, ys, mul_hi(z, r), w, v);
}

// project() with split products (cores without a 64-bit product): each matrix entry split once
// per draw, each position coordinate and the reciprocal once per vertex; the same integers.
inline bool ScreenTransform::project_halves(const Vec3& p, ScreenVertex& v) const {
  const Words& k = k_;
  const Halves px = halves(p.x.raw << k.ps), py = halves(p.y.raw << k.ps),
               pz = halves(p.z.raw << k.ps);
  auto row = [&](int i) {
    return static_cast<int32_t>(static_cast<uint32_t>(k.row(i).t) +
                                static_cast<uint32_t>(mul_hi_halves(split(i, 2), pz)) +
                                static_cast<uint32_t>(mul_hi_halves(split(i, 1), py)) +
                                static_cast<uint32_t>(mul_hi_halves(split(i, 0), px)));
  };
  const int32_t w = row(3);
  if (static_cast<uint32_t>(w) - static_cast<uint32_t>(k.w_lo) > k.w_span) return false;
  const int32_t x = row(0), y = row(1);
  const int n = clz_short_path(static_cast<uint32_t>(w));
  const Halves r =
      halves(static_cast<int32_t>(recip_q61(static_cast<uint32_t>(w) << n) >> (k.n_max - n)));
  int32_t xs = static_cast<int32_t>(static_cast<uint32_t>(k.acc_x) +
                                    static_cast<uint32_t>(mul_hi_halves(halves(x), r))) >>
               k.f;
  int32_t ys = static_cast<int32_t>(static_cast<uint32_t>(k.acc_y) +
                                    static_cast<uint32_t>(mul_hi_halves(halves(y), r))) >>
               k.f;
  return store(xs, ys, mul_hi_halves(halves(row(2)), r), w, v);
}

// The tail both forms share: the guard band and depth range tests, then the vertex.
inline bool ScreenTransform::store(int32_t xs, int32_t ys, int32_t m, int32_t w,
                                   ScreenVertex& v) const {
  const Words& k = k_;
  if (guard_free_) {
    // Inside the band for every position within the bound; the clamp keeps a position beyond
    // it (a wrong Mesh::bound) inside the coordinate budget.
    xs = saturate_signed<23>(xs);
    ys = saturate_signed<23>(ys);
  } else if ((static_cast<uint32_t>(xs) - static_cast<uint32_t>(k.x_lo)) > k.x_span ||
             (static_cast<uint32_t>(ys) - static_cast<uint32_t>(k.y_lo)) > k.y_span) [[unlikely]] {
    return false;
  }
  if ((static_cast<uint32_t>(m) - static_cast<uint32_t>(k.m_lo)) > k.m_span) [[unlikely]]
    return false;
  v.x = xs;
  v.y = ys;
  v.z = k.c0 + (static_cast<uint32_t>(m) << k.kz);
  v.w = static_cast<uint32_t>(w) >> k.w_shift;
  v.outcode = 0;
  return true;
}

}  // namespace lr
