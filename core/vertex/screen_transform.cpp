#include "lineraster/core/vertex/screen_transform.hpp"

#include <cstddef>

namespace lr {
namespace {

// An unsigned 128-bit sum, for the per-draw bounds (products of up to 2^62 and 2^32).
struct Wide {
  uint64_t hi = 0, lo = 0;
  void add(uint64_t v) {
    lo += v;
    if (lo < v) ++hi;
  }
  // += u b, u < 2^64, b < 2^32: u = u1 2^32 + u0, u0 b < 2^64, u1 b < 2^64. Out of line (a
  // per-draw step: one copy, not 24, in small images).
  [[gnu::noinline]] void add_mul(uint64_t u, uint32_t b) {
    const uint64_t l = (u & 0xFFFFFFFFu) * b, h = (u >> 32) * b;
    add(l);
    add(h << 32);
    hi += h >> 32;
  }
  int bit_length() const { return hi != 0 ? 128 - clz64(hi) : lo != 0 ? 64 - clz64(lo) : 0; }
};

// c 2^sh as int32, rounded to nearest (|c| 2^sh < 2^31 by the caller's bound; the rounding may
// reach 2^31, which saturates).
[[gnu::noinline]] int32_t scaled(int64_t c, int sh) {
  const uint64_t m = abs64(c);
  uint64_t v;
  if (sh >= 0)
    v = m << sh;
  else if (sh > -63)
    v = (m + (uint64_t{1} << (-sh - 1))) >> -sh;
  else
    v = 0;
  if (v > 0x7FFFFFFFu) v = 0x7FFFFFFFu;
  return c < 0 ? -static_cast<int32_t>(v) : static_cast<int32_t>(v);
}

}  // namespace

uint32_t position_bound(const Vec3* positions, size_t n) {
  uint32_t b = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec3& p = positions[i];
    b |= static_cast<uint32_t>(p.x.raw ^ (p.x.raw >> 31)) |
         static_cast<uint32_t>(p.y.raw ^ (p.y.raw >> 31)) |
         static_cast<uint32_t>(p.z.raw ^ (p.z.raw >> 31));
  }
  return b;
}

ScreenTransform::ScreenTransform(const FineMat4& mvp, int p_frac, uint32_t bound, int width,
                                 int height, GuardBand guard) {
  // Coordinates lie in [-(bound + 1), bound]; with bound < 2^(31 - ps) they stay in int32 when
  // shifted by ps, and bound 2^ps >= 2^30 (so a row's factors fit int32, below).
  if (bound > 0x7FFFFFFFu) bound = 0x7FFFFFFFu;  // no int32 coordinate is beyond
  const int ps = bound == 0 ? 30 : clz32(bound) - 1;
  const uint32_t b = bound + 1;  // the largest magnitude, <= 2^31
  const int32_t sx = width * kHalfPixel, sy = height * kHalfPixel;
  const int32_t lx = guard.gx * sx, ly = guard.gy * sy;  // <= 2^20 (G W <= 8192)
  // Row factors: the row's value times K is what the quotient by w must give (subpixels from the
  // centre, window depth from the middle of the range).
  const int64_t k[4] = {sx, -int64_t{sy}, kHalfDepth, 1};
  // The sums below are in units of 2^-(F + P) (F the matrix's fraction bits, P the positions'):
  // fp less 32 in Q32.32 (0 for Q16.16 and Q16.16).
  const int fp = mvp.frac + p_frac - 32;
  int exponent[4];
  for (int i = 0; i < 4; ++i) {
    // |value| 2^32 <= (sum_j |K m_j| b + |K t| 2^P) 2^-fp < 2^L (the row times K, in Q32.32);
    // and the same without K, whose bound the exact path's range (|clip| < 2^19) must hold.
    // (|K m| < 2^62, b <= 2^31, 2^P <= 2^30: the 128-bit sums hold them.)
    Wide with_k, plain;
    for (int j = 0; j < 4; ++j) {  // the three factors of the position, then the translation
      const int64_t m = mvp.m[i][j];
      const uint32_t scale = j < 3 ? b : uint32_t{1} << p_frac;
      with_k.add_mul(abs64(k[i] * m), scale);
      plain.add_mul(abs64(m), scale);
    }
    // the exact path for every vertex (enabled_ false)
    if (plain.bit_length() - fp > 50) return;
    // V 2^32 < 2^L, E = 61 - L: every row sum |V| 2^E below 2^29.
    exponent[i] = 61 - (with_k.bit_length() - fp);
  }
  // The least w over the bound's cube when it lies inside the guard band (else 0): only now,
  // with every row below 2^50 in Q32.32, are the corners' clip coordinates below 2^46 in Q28.28
  // (guard_free_least_w's products by the band's factors below 2^59).
  const int64_t cube_w = guard_free_least_w(mvp, p_frac, bound, guard);
  const int ew = exponent[3];
  int exy = exponent[0] < exponent[1] ? exponent[0] : exponent[1];
  // n = clz(W) is at least 2 (W < 2^30). r = recip >> (n_max - n) is 2^(61 - n_max) / W, so
  // mul_hi(X, r) = (x - sx) 2^f with f = sxy - n_max, sxy = 29 + exy - ew. n_max: at most 9
  // (W >= 2^22: its own rounding moves x by 2^-20 of x - sx at most) and sxy - 5 (f >= 5).
  int n_max = 9;
  if (n_max > 29 + exy - ew - kShortPathFractionBits)
    n_max = 29 + exy - ew - kShortPathFractionBits;
  // W = w 2^ew, w's Q16.16 is W >> (ew - 16): the short path for |w| below 2^13 (ew >= 16).
  if (n_max < 2 || ew < 16) return;
  // The z row: mul_hi(Z, r) = (z_ndc D) 2^-kz, kz = n_max - cz with cz = 29 + ez - ew; ez
  // lowered so that kz >= 0, n_max so that kz <= 10 (z in units of 2^10, 1/64 of a 16-bit depth
  // step).
  int ez = exponent[2];
  if (n_max > ez - ew + 39) n_max = ez - ew + 39;
  if (n_max < 2) return;
  // A draw whose cube lies inside the band has every W at least its corners' least (w is linear
  // in the position), less 2^-12 of it for the row sums' few units and the corners' Q28.28
  // truncation (W >= 2^22 where it matters): n_max need only reach clz of that, W = w 2^(ew - 28)
  // from w in Q28.28, clz32(W) = clz64(w) - 4 - ew. Smaller, it leaves f more bits (up to 10,
  // beyond which x 2^f could leave int32): the error of x and y shrinks as 2^-f for no work per
  // vertex.
  if (cube_w > 0) {
    int n = clz64(static_cast<uint64_t>(cube_w - (cube_w >> 12))) - 4 - ew;
    if (n < 29 + exy - ew - 10) n = 29 + exy - ew - 10;  // f = 10 already
    if (n >= 2 && n < n_max) n_max = n;
  }
  if (ez > ew - 29 + n_max) ez = ew - 29 + n_max;
  // f at most 10 (x - sx and y - sy below 2^21, times 2^f below 2^31): exy lowered if need be.
  if (29 + exy - ew - n_max > 10) exy = n_max + 10 - 29 + ew;
  Words& w = k_;
  w.f = 29 + exy - ew - n_max;
  const int e[4] = {exy, exy, ez, ew};
  RowWords* const rows[4] = {&w.x, &w.y, &w.z, &w.w};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)  // the three factors, then the translation
      (j < 3 ? rows[i]->a[j] : rows[i]->t) =
          scaled(k[i] * mvp.m[i][j], j < 3 ? e[i] - ps - fp : e[i] - mvp.frac);
  if constexpr (kSplitWideProducts)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 3; ++j) split_[i][j] = halves(rows[i]->a[j]);
  w.ps = ps;
  w.n_max = n_max;
  w.w_shift = ew - 16;
  w.kz = n_max - (29 + ez - ew);
  w.c0 = kHalfDepth;
  // Inside the depth range: 0 <= D + m 2^kz <= 2 D, m in [-floor(D / 2^kz), floor(D / 2^kz)].
  w.m_lo = -static_cast<int32_t>(kHalfDepth >> w.kz);
  w.m_span = 2 * (kHalfDepth >> w.kz);
  // The w range: the precision's lower end 2^(31 - n_max), kMaxW above; and at least
  // 2^w_shift, so that w's Q16.16 is never 0 (a tiny w, 1 / w beyond every plane's range, takes
  // the exact path, which clamps it to one unit).
  const int lo_bits = 31 - n_max > w.w_shift ? 31 - n_max : w.w_shift;
  if (lo_bits > 29) return;
  w.w_lo = int32_t{1} << lo_bits;
  w.w_span = static_cast<uint32_t>(kMaxW - w.w_lo);
  w.acc_x = (sx << w.f) + (1 << (w.f - 1));
  w.acc_y = (sy << w.f) + (1 << (w.f - 1));
  w.x_lo = sx - lx;
  w.x_span = static_cast<uint32_t>(2 * lx);
  w.y_lo = sy - ly;
  w.y_span = static_cast<uint32_t>(2 * ly);
  guard_free_ = cube_w > 0;
  enabled_ = true;
}

size_t ScreenTransform::run(const Vec3* p, size_t count, ScreenVertex* out,
                            const uint32_t (&tail)[2]) const {
  if (!kShortPathRun || !guard_free_) {
    // The tail's fields assigned (a copy through a byte pointer made Armv6-M, which has no
    // unaligned access, call memcpy for every vertex).
    ScreenVertex proto;
    __builtin_memcpy(reinterpret_cast<unsigned char*>(&proto) + 16, tail, 8);
    size_t k = 0;
    for (; k < count; ++k) {
      if (!project(p[k], out[k])) break;
      out[k].color = proto.color;
      out[k].outcode = proto.outcode;
      out[k].color_pending = proto.color_pending;
    }
    return k;
  }
#if LR_SHORT_PATH_RUN
  {
    if (count == 0) return 0;
    static_assert(offsetof(Words, w) == 0 && offsetof(Words, x) == 16 && offsetof(Words, y) == 32 &&
                  offsetof(Words, z) == 48 && offsetof(Words, w_lo) == 64 &&
                  offsetof(Words, n_max) == 72 && offsetof(Words, acc_x) == 80 &&
                  offsetof(Words, ps) == 88 && offsetof(Words, c0) == 92 &&
                  offsetof(Words, kz) == 96 && offsetof(Words, m_lo) == 104);
    static_assert(sizeof(Vec3) == 12 && sizeof(ScreenVertex) == 24 &&
                  offsetof(ScreenVertex, color) == 16 && offsetof(ScreenVertex, outcode) == 22);
    const Vec3* const start = p;
    const Vec3* const end = p + count;
    const Words* const k = &k_;
    const uint32_t* const t = tail;
    // project() on the short path: each step as there, its integers the same (SMMLA is
    // mla_hi, SMMUL mul_hi, UMULL's high word mul_hi_u, UDIV recip16, SSAT saturate_signed).
    asm volatile(
        "1:\n\t"
        "ldmia   %[p]!, {r4, r5, r6}\n\t"  // the position, Q16.16
        "ldr     r8, [%[k], #88]\n\t"      // ps
        "lsl     r4, r4, r8\n\t"
        "lsl     r5, r5, r8\n\t"
        "lsl     r6, r6, r8\n\t"
        "ldrd    r8, r9, [%[k], #0]\n\t"  // the w row
        "ldrd    r10, r11, [%[k], #8]\n\t"
        "smmla   r11, r10, r6, r11\n\t"
        "smmla   r11, r9, r5, r11\n\t"
        "smmla   r11, r8, r4, r11\n\t"     // W
        "ldrd    r8, r9, [%[k], #64]\n\t"  // w_lo, w_span
        "sub     r8, r11, r8\n\t"
        "cmp     r8, r9\n\t"
        "bhi     2f\n\t"                   // not in the short path's range
        "ldrd    r8, r9, [%[k], #16]\n\t"  // the x row
        "ldrd    r10, r12, [%[k], #24]\n\t"
        "smmla   r12, r10, r6, r12\n\t"
        "smmla   r12, r9, r5, r12\n\t"
        "smmla   r12, r8, r4, r12\n\t"     // X
        "ldrd    r8, r9, [%[k], #32]\n\t"  // the y row
        "ldrd    r10, lr, [%[k], #40]\n\t"
        "smmla   lr, r10, r6, lr\n\t"
        "smmla   lr, r9, r5, lr\n\t"
        "smmla   lr, r8, r4, lr\n\t"       // Y
        "ldrd    r8, r9, [%[k], #56]\n\t"  // the z row: a2, t
        "smmla   r9, r8, r6, r9\n\t"
        "ldrd    r8, r10, [%[k], #48]\n\t"  // a0, a1
        "smmla   r9, r10, r5, r9\n\t"
        "smmla   r10, r8, r4, r9\n\t"  // Z
        "clz     r4, r11\n\t"          // n
        "lsl     r5, r11, r4\n\t"      // d = W 2^n
        "lsr     r6, r5, #16\n\t"
        "mvn     r8, #0\n\t"
        "udiv    r6, r8, r6\n\t"   // recip16(d >> 16)
        "lsl     r6, r6, #13\n\t"  // x0
        "umull   r8, r9, r5, r6\n\t"
        "rsb     r9, r9, #0x20000000\n\t"  // eh
        "lsl     r9, r9, #3\n\t"
        "smmla   r6, r6, r9, r6\n\t"       // recip_q61(d)
        "ldrd    r8, r9, [%[k], #72]\n\t"  // n_max, f
        "sub     r8, r8, r4\n\t"
        "lsr     r6, r6, r8\n\t"           // r
        "ldrd    r4, r5, [%[k], #80]\n\t"  // acc_x, acc_y
        "smmla   r12, r12, r6, r4\n\t"
        "asr     r12, r12, r9\n\t"
        "ssat    r12, #23, r12\n\t"  // x
        "smmla   lr, lr, r6, r5\n\t"
        "asr     lr, lr, r9\n\t"
        "ssat    lr, #23, lr\n\t"           // y
        "smmul   r10, r10, r6\n\t"          // m
        "ldrd    r4, r5, [%[k], #104]\n\t"  // m_lo, m_span: the depth range
        "sub     r4, r10, r4\n\t"
        "cmp     r4, r5\n\t"
        "bhi     2f\n\t"
        "ldrd    r4, r5, [%[k], #92]\n\t"  // c0, kz
        "lsl     r10, r10, r5\n\t"
        "add     r10, r10, r4\n\t"      // z
        "ldr     r5, [%[k], #100]\n\t"  // w_shift
        "lsr     r11, r11, r5\n\t"      // w, Q16.16
        "strd    r12, lr, [%[out]]\n\t"
        "strd    r10, r11, [%[out], #8]\n\t"
        "ldrd    r4, r5, [%[t]]\n\t"  // colour, outcode 0, pending
        "strd    r4, r5, [%[out], #16]\n\t"
        "add     %[out], %[out], #24\n\t"
        "cmp     %[p], %[end]\n\t"
        "bne     1b\n\t"
        "b       3f\n"
        "2:\n\t"
        "sub     %[p], %[p], #12\n"  // back to the vertex that left
        "3:\n"
        : [p] "+r"(p), [out] "+r"(out)
        : [end] "r"(end), [k] "r"(k), [t] "r"(t)
        : "r4", "r5", "r6", "r8", "r9", "r10", "r11", "r12", "lr", "cc", "memory");
    return static_cast<size_t>(p - start);
  }
#else
  return 0;  // (not reached: no short path on this target)
#endif
}

// Whether every position within the bound projects inside the guard band: the cube's corners
// (exact clip coordinates) in front of the eye and within 7/8 of the band (the projection is
// linear in clip space and the band convex: the cube's inside follows). Then the least of the
// corners' w (Q28.28, > 0), else 0.
int64_t ScreenTransform::guard_free_least_w(const FineMat4& mvp, int p_frac, uint32_t bound,
                                            GuardBand guard) {
  const int32_t hi = static_cast<int32_t>(bound), lo = -hi - 1;
  int64_t least = INT64_MAX;
  for (int c = 0; c < 8; ++c) {
    const Vec3 p{Fixed::from_raw(c & 1 ? hi : lo), Fixed::from_raw(c & 2 ? hi : lo),
                 Fixed::from_raw(c & 4 ? hi : lo)};
    const ClipCoord q = transform_point(mvp, p, p_frac);  // |coordinates| < 2^46 (the plain bound)
    if (q.w <= 0) return 0;
    const int64_t gx = q.w * guard.gx - ((q.w * guard.gx) >> 3);
    const int64_t gy = q.w * guard.gy - ((q.w * guard.gy) >> 3);
    if (q.x > gx || q.x < -gx || q.y > gy || q.y < -gy) return 0;
    if (q.w < least) least = q.w;
  }
  return least;
}

}  // namespace lr
