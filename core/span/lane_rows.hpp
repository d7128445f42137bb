// One strip visit of a lanes triangle with the depth test (RGB565 formats) in one loop: the
// triangle picked up at the strip's first row, then per row its edges, its span clamped to the
// viewport's columns, the planes at the span's first pixel and the depth and colour loop
// (lane_span.hpp). On Armv7E-M its registers are allocated by hand (one asm block: GCC 12 spills
// the row state around the pixel loop and fills the visit's state one word at a time);
// lane_visit_portable is the same loop in C, which tests/core/lane_rows_test.cpp and
// firmware/span_check compare with it, and the generic row loop
// (core/raster/untextured_rows.hpp) gives the same pixels.
//
// The triangle's edges must fit their records (no kWideEdges): per row the left and right
// columns are col_base + Q / dy (exact: core/setup/row_edge.hpp); after mid_row the bottom edge
// replaces the top one on the short side.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/setup/strip_rows.hpp"
#include "lineraster/core/span/lane_span.hpp"

namespace lr {

template <class PF>
inline void lane_visit_portable(const ActiveTriangle& t, StripRows& s) {
  using Pixel = typename PF::Storage;
  int32_t row = std::max<int32_t>(t.first_row, s.y0);
  const int32_t last = std::min<int32_t>(t.last_row, s.y_last), mid = t.mid_row;
  s.rows += static_cast<uint32_t>(last - row + 1);
  const auto k = static_cast<uint32_t>(row - t.first_row);
  uint32_t q[2] = {t.edge_q[0] + static_cast<uint32_t>(t.edge_dx[0]) * k,
                   t.edge_q[1] + static_cast<uint32_t>(t.edge_dx[1]) * k};
  int32_t dx[2] = {t.edge_dx[0], t.edge_dx[1]};
  uint32_t dy[2] = {t.edge_dy[0], t.edge_dy[1]};
  const int ss = t.short_side();
  int32_t stop = std::min(mid, last);
  if (row > mid) {  // below the middle vertex from the start
    q[ss] = t.bottom.q + static_cast<uint32_t>(t.bottom.dx) * static_cast<uint32_t>(row - mid - 1);
    dx[ss] = t.bottom.dx;
    dy[ss] = t.bottom.dy;
    stop = last;
  }
  auto* const pixels = static_cast<Pixel*>(s.pixels);
  const Plane* p = &t.z;
  uint32_t spans = 0, tested = 0, rejected = 0;
  for (;;) {
    for (; row <= stop; ++row) {
      const int32_t left = std::max<int32_t>(t.col_base + static_cast<int32_t>(q[0] / dy[0]), 0);
      const int32_t right =
          std::min<int32_t>(t.col_base + static_cast<int32_t>(q[1] / dy[1]), s.width);
      q[0] += static_cast<uint32_t>(dx[0]);
      q[1] += static_cast<uint32_t>(dx[1]);
      if (left >= right) continue;
      ++spans;
      tested += static_cast<uint32_t>(right - left);
      const auto r = static_cast<uint32_t>(row), c = static_cast<uint32_t>(left);
      const size_t o = static_cast<size_t>(row - s.y0) * static_cast<size_t>(s.width) +
                       static_cast<size_t>(left);
      rejected += lane_span_portable<PF, true>(pixels + o, s.depth + o, right - left,
                                               p[0].base + p[0].gy * r + p[0].gx * c, p[0].gx,
                                               p[1].base + p[1].gy * r + p[1].gx * c, p[1].gx,
                                               p[2].base + p[2].gy * r + p[2].gx * c, p[2].gx);
    }
    if (row > last) break;
    q[ss] = t.bottom.q;  // at row mid + 1
    dx[ss] = t.bottom.dx;
    dy[ss] = t.bottom.dy;
    stop = last;
  }
  s.spans += spans;
  s.tested += tested;
  s.written += tested - rejected;
}

// A run: consecutive lanes triangles of a strip's active list (those whose rows are `lanes`),
// visited in one call from the order entry `next` on, each then retired as StripLoop::visit
// retires: its slot to the free list when it ends in the strip (last_row <= y_last), else to
// the kept list. The call returns at the first entry of another kind, or at `end`, with next,
// kept and free past what it did. The layout is read by the Armv7E-M form.
struct LaneRun {
  const uint16_t* next;          // the order entry of the run's first triangle
  uint16_t* kept;                // where the next kept slot goes (the order, compacted)
  uint16_t* free;                // where the next free slot goes
  const uint16_t* end;           // one past the active list's last entry
  const ActiveTriangle* active;  // the active slots
  // The strip's words the Armv7E-M form reads with the run's between two triangles, in one LDM
  // (it fills them; unused elsewhere): the bytes per row, the first row, and the address of row
  // 0's first pixel (modulo 2^32: the strip's first pixel less y0 rows).
  uint32_t stride;
  RowFn lanes;  // the rows of the triangles the run takes
  int32_t y0;
  int32_t y_last;  // the strip's last row
  uintptr_t pix0;
  // A run from `next` on (field by field: the words the Armv7E-M form fills stay as they are).
  void start(const uint16_t* n, uint16_t* k, uint16_t* f, const uint16_t* e,
             const ActiveTriangle* a, RowFn l, int32_t last) {
    next = n;
    kept = k;
    free = f;
    end = e;
    active = a;
    lanes = l;
    y_last = last;
  }
};

// The run in C: lane_visit_portable per triangle.
template <class PF>
inline void lane_run_portable(const ActiveTriangle& t, LaneRun& run, StripRows& s) {
  const ActiveTriangle* u = &t;
  for (;;) {
    const uint16_t slot = *run.next++;
    lane_visit_portable<PF>(*u, s);
    *(u->last_row <= run.y_last ? run.free : run.kept)++ = slot;
    if (run.next == run.end) return;
    u = &run.active[*run.next];
    if (u->rows != run.lanes) return;
  }
}

// The strip visit of lanes triangles by hand (below) on Armv7-M with the DSP extension, but not
// where the code is built for size: there lanes triangles take the shared row walk with the
// span's loop by hand (untextured_rows.hpp, lane_span.hpp), the same pixels without the visit's
// 0.7 KB (the footprint's torus +17 % at -Os on Cortex-M4F; +25 % with the C span loop).
#if defined(__thumb2__) && (defined(__ARM_ARCH_7EM__) || defined(__ARM_ARCH_8M_MAIN__)) && \
    !defined(__OPTIMIZE_SIZE__)
inline constexpr bool kLaneVisitAsm = true;
#else
inline constexpr bool kLaneVisitAsm = false;
#endif

namespace detail {
// The visit by hand (Armv7E-M: LDM/STM, UDIV, MLA, REV16). The one operand (in r7, the register
// the loop leaves to the compiler: Thumb's frame pointer) points to the visit's frame, a local
// array of 17 words: the run's address at 56 (LaneRun), the first triangle's address at 60
// (then in lr) and the strip's at 64, and the visit's state:
//   0 q[0]  4 q[1]  8 px (the row's pixel in column 0)  12 row  16 dx[0]  20 dx[1]
//   24 stride (bytes per row)  28 dy[0]  32 dy[1]  36 col_base  40 stop (the last row of the
//   edges in the frame)  44 width  48 last  52 depth offset (bytes from a pixel to its depth;
//   it and width stored once per run)
// and r12 counts the pixels in spans (bits 0..19), the rows without a span (20..25) and the rows
// (26..31: minus the first row, plus the row after the last at the end). Per row: the first eleven
// words in r0-r6, r8-r11, the row tested against stop at once; left r0 and right r1 (clamped unless
// kInside: width read then); the index r6 from left - right up to 0; the planes at (left, row):
// z r4 (step r5), br r9 (r10), g r3 (r8); the pixels' end r1, the depths' end r2; per pixel the
// depth and the pixel in r0, green in r11. A rejected pixel is taken off the strip's written
// count at once (the visit adds every pixel in its spans at the end). Instructions: per written
// pixel 16, per rejected one 8 (plus the count); per row with a span 26 (kInside; clamped 33),
// without one 14 (21); per visit about 47 (the next triangle's test with the run's words and
// the strip's (stride, y0, y_last, pix0: then in r6, r9-r11) in one LDM: label 10; then the
// pick-up (label 0), which retires the triangle at once (its slot to the free or the kept list,
// and the run's next, kept and free stored) and fills the row loop's registers, entering past
// its LDM; a triangle that starts and ends in the strip, label 41, takes no clamp and no pick-up
// product: 8 fewer). The counts of a run stay in r12 and go to the strip at the run's end or once
// it has 32 rows or more (its fields then hold the next visit: at most 63 rows and 63 x
// kMaxViewport pixels). The row loop, its labels numbered from N, with CLAMP between the columns
// and the span; TO the label of a row past stop, SWITCH its code when it is the loop's own
// (LR_LANE_SWITCH). The span's set-up (N5) and pixel loop come before the row's part (N1), into
// which the pixel loop falls: a row with a span takes no branch back.
#define LR_LANE_ROWS(N1, N8, N5, N2, N3, N4, TO, CLAMP, SWAP, SWITCH)            \
  N5 ":\n\t"                                                                     \
     "sub    r12, r12, r6\n\t"                                                   \
     "add    r1, r2, r1, lsl #1\n\t"                                             \
     "add    r8, lr, #52\n\t"                                                    \
     "ldm    r8!, {r4, r5, r9}\n\t"                                              \
     "mla    r4, r9, r3, r4\n\t"                                                 \
     "mla    r4, r5, r0, r4\n\t"                                                 \
     "ldm    r8!, {r9, r10, r11}\n\t"                                            \
     "mla    r9, r11, r3, r9\n\t"                                                \
     "mla    r9, r10, r0, r9\n\t"                                                \
     "ldm    r8, {r2, r8, r11}\n\t"                                              \
     "mla    r2, r11, r3, r2\n\t"                                                \
     "mla    r3, r8, r0, r2\n\t"                                                 \
     "ldr    r2, [%[a], #52]\n\t"                                                \
     "add    r2, r1\n\t" N2                                                      \
     ":\n\t"                                                                     \
     "ldrh   r0, [r2, r6, lsl #1]\n\t"                                           \
     "cmp    r0, r4, lsr #15\n\t"                                                \
     "bls    " N3                                                                \
     "f\n\t"                                                                     \
     "lsrs   r0, r4, #15\n\t"                                                    \
     "strh   r0, [r2, r6, lsl #1]\n\t"                                           \
     "and    r0, r9, #0xF800F800\n\t"                                            \
     "orr    r0, r0, r0, lsr #27\n\t"                                            \
     "and    r11, r3, #0xFC000000\n\t"                                           \
     "orr    r0, r0, r11, lsr #21\n\t" SWAP "strh   r0, [r1, r6, lsl #1]\n\t" N4 \
     ":\n\t"                                                                     \
     "add    r4, r5\n\t"                                                         \
     "add    r9, r10\n\t"                                                        \
     "add    r3, r8\n\t"                                                         \
     "adds   r6, #1\n\t"                                                         \
     "bne    " N2 "b\n\t" N1                                                     \
     ":\n\t"                                                                     \
     "ldm    %[a], {r0, r1, r2, r3, r4, r5, r6, r8, r9, r10, r11}\n\t"           \
     "cmp    r3, r11\n\t"                                                        \
     "bgt    " TO "\n\t" N8                                                      \
     ":\n\t"                                                                     \
     "add    r4, r0, r4\n\t"                                                     \
     "add    r5, r1, r5\n\t"                                                     \
     "udiv   r0, r0, r8\n\t"                                                     \
     "udiv   r1, r1, r9\n\t"                                                     \
     "add    r6, r2, r6\n\t"                                                     \
     "add    r8, r3, #1\n\t"                                                     \
     "stm    %[a], {r4, r5, r6, r8}\n\t" CLAMP                                   \
     "subs   r6, r0, r1\n\t"                                                     \
     "blt    " N5                                                                \
     "b\n\t"                                                                     \
     "add    r12, r12, #0x100000\n\t"                                            \
     "b      " N1 "b\n\t" SWITCH N3                                              \
     ":\n\t"                                                                     \
     "ldr    r0, [%[a], #64]\n\t"                                                \
     "ldr    r11, [r0, #40]\n\t"                                                 \
     "subs   r11, #1\n\t"                                                        \
     "str    r11, [r0, #40]\n\t"                                                 \
     "b      " N4 "b\n\t"
// The end of the edges in the frame (label N7, the row past stop in r3): the end of the visit
// (label 9 in direction E) past the last row, else the bottom edge in place of the short side's
// and stop = last, then BACK (to the row loop).
#define LR_LANE_SWITCH(N7, E, BACK)    \
  N7 ":\n\t"                           \
     "ldr    r1, [%[a], #48]\n\t"      \
     "cmp    r3, r1\n\t"               \
     "bgt    9" E                      \
     "\n\t"                            \
     "ldrb   r2, [lr, #47]\n\t"        \
     "and    r0, r2, #1\n\t"           \
     "add    r0, %[a], r0, lsl #2\n\t" \
     "add    r4, lr, #24\n\t"          \
     "ldm    r4, {r4, r5, r6}\n\t"     \
     "str    r4, [r0]\n\t"             \
     "str    r5, [r0, #16]\n\t"        \
     "str    r6, [r0, #28]\n\t"        \
     "str    r1, [%[a], #40]\n\t" BACK
#define LR_LANE_SWITCH_INSIDE LR_LANE_SWITCH("17", "f", "b      11b\n\t")
#define LR_LANE_SWITCH_CLAMPED LR_LANE_SWITCH("7", "b", "b      1b\n\t")
#define LR_LANE_TO_CLAMPED "7f"
#define LR_LANE_FLUSH_RUN LR_LANE_FLUSH "mov    r12, #0\n\t"
#define LR_LANE_FLUSH_END LR_LANE_FLUSH
// The columns relative to col_base, clamped to [0, width).
#define LR_LANE_CLAMP              \
  "add    r0, r10\n\t"             \
  "add    r1, r10\n\t"             \
  "bic    r0, r0, r0, asr #31\n\t" \
  "ldr    r4, [%[a], #44]\n\t"     \
  "cmp    r1, r4\n\t"              \
  "it     gt\n\t"                  \
  "movgt  r1, r4\n\t"
// The counts of r12 added to the strip's (StripRows::spans, tested, written, rows; the spans
// are the rows less those without one).
#define LR_LANE_FLUSH               \
  "ldr    r5, [%[a], #64]\n\t"      \
  "add    r5, #32\n\t"              \
  "ldm    r5, {r1, r2, r3, r6}\n\t" \
  "ubfx   r4, r12, #20, #6\n\t"     \
  "sub    r1, r4\n\t"               \
  "add    r1, r1, r12, lsr #26\n\t" \
  "ubfx   r4, r12, #0, #20\n\t"     \
  "add    r2, r4\n\t"               \
  "add    r3, r4\n\t"               \
  "add    r6, r6, r12, lsr #26\n\t" \
  "stm    r5, {r1, r2, r3, r6}\n\t"
// The run: the strip's words (pixels, depth, y0, y_last, width) in one LDM, the run's from
// stride on filled and the frame's width and depth offset stored once, the first triangle's
// address in lr and its slot in r4; then the row loop of kInside, the end of a visit (the
// counts, the next triangle's test) and the pick-up (label 0): the retire, the rows, then the
// edges straight into the row loop's registers (q, dx, dy: the record's first six words),
// stored as the frame. Below the
// middle vertex from the start, the short side's edge is the bottom one. Then the row loop with
// the clamp and at the run's end the counts.
#define LR_LANE_VISIT(SWAP) \
  asm volatile(                                                            \
      "ldr    r0, [%[a], #64]\n\t"                                         \
      "ldm    r0, {r0, r1, r9, r10, r11}\n\t"                              \
      "subs   r1, r1, r0\n\t"                                              \
      "str    r1, [%[a], #52]\n\t"                                         \
      "str    r11, [%[a], #44]\n\t"                                        \
      "lsl    r6, r11, #1\n\t"                                             \
      "mls    r11, r6, r9, r0\n\t"                                         \
      "ldr    r0, [%[a], #56]\n\t"                                         \
      "str    r6, [r0, #20]\n\t"                                           \
      "add    r1, r0, #28\n\t"                                             \
      "stm    r1, {r9, r10, r11}\n\t"                                      \
      "ldm    r0, {r1, r2, r3}\n\t"                                        \
      "ldrh   r4, [r1], #2\n\t"                                            \
      "ldr    lr, [%[a], #60]\n\t"                                         \
      "mov    r12, #0\n\t"                                                 \
      "b      0f\n\t"                                                      \
      LR_LANE_ROWS("11", "18", "16", "12", "13", "14", "17f", "", SWAP,   \
                   LR_LANE_SWITCH_INSIDE)                                 \
      "9:\n\t"                                                             \
      "adds   r12, r12, r3, lsl #26\n\t"                                   \
      "bpl    10f\n\t" LR_LANE_FLUSH_RUN                                   \
      "10:\n\t"                                                            \
      "ldr    r0, [%[a], #56]\n\t"                                         \
      "ldm    r0, {r1, r2, r3, r4, r5, r6, r8, r9, r10, r11}\n\t"          \
      "cmp    r1, r4\n\t"                                                  \
      "beq    19f\n\t"                                                     \
      "ldrh   r4, [r1], #2\n\t"                                            \
      "mov    lr, %[size]\n\t"                                             \
      "mla    lr, r4, lr, r5\n\t"                                          \
      "ldr    r5, [lr, %[rows]]\n\t"                                       \
      "cmp    r5, r8\n\t"                                                  \
      "bne    19f\n\t"                                                     \
      "0:\n\t"                                                             \
      "ldrsh  r5, [lr, #40]\n\t"                                           \
      "cmp    r5, r10\n\t"                                                 \
      "ite    le\n\t"                                                      \
      "strhle r4, [r3], #2\n\t"                                            \
      "strhgt r4, [r2], #2\n\t"                                            \
      "stm    r0, {r1, r2, r3}\n\t"                                        \
      "ldrsh  r4, [lr, #36]\n\t"                                           \
      "bgt    40f\n\t"                                                     \
      "cmp    r4, r9\n\t"                                                  \
      "bge    41f\n\t"                                                     \
      "mov    r3, r9\n\t"                                                  \
      "b      43f\n\t"                                                     \
      "40:\n\t"                                                            \
      "mov    r5, r10\n\t"                                                 \
      "cmp    r4, r9\n\t"                                                  \
      "ite    ge\n\t"                                                      \
      "movge  r3, r4\n\t"                                                  \
      "movlt  r3, r9\n\t"                                                  \
      "43:\n\t"                                                            \
      "mla    r2, r3, r6, r11\n\t"                                         \
      "ldrsh  r11, [lr, #38]\n\t"                                          \
      "ldrsh  r10, [lr, #42]\n\t"                                          \
      "subs   r9, r3, r4\n\t"                                              \
      "str    r5, [%[a], #48]\n\t"                                         \
      "cmp    r3, r11\n\t"                                                 \
      "bgt    5f\n\t"                                                      \
      "cmp    r11, r5\n\t"                                                 \
      "it     gt\n\t"                                                      \
      "movgt  r11, r5\n\t"                                                 \
      "ldrb   r0, [lr, #47]\n\t"                                           \
      "tst    r0, #4\n\t"                                                  \
      "ldm    lr, {r0, r1, r4, r5}\n\t"                                    \
      "mla    r0, r4, r9, r0\n\t"                                          \
      "mla    r1, r5, r9, r1\n\t"                                          \
      "ldrd   r8, r9, [lr, #16]\n\t"                                       \
      "stm    %[a], {r0, r1, r2, r3, r4, r5, r6, r8, r9, r10, r11}\n\t"    \
      "sub    r12, r12, r3, lsl #26\n\t"                                   \
      "bne    18b\n\t"                                                     \
      "b      8f\n\t"                                                      \
      /* a triangle that starts and ends in the strip (most small ones): from its first */ \
      /* row (no pick-up products), its rows and mid_row (<= last_row) unclamped */         \
      "41:\n\t"                                                            \
      "mov    r3, r4\n\t"                                                  \
      "mla    r2, r4, r6, r11\n\t"                                         \
      "ldrsh  r11, [lr, #38]\n\t"                                          \
      "ldrsh  r10, [lr, #42]\n\t"                                          \
      "str    r5, [%[a], #48]\n\t"                                         \
      "cmp    r4, r11\n\t"                                                 \
      "bgt    44f\n\t"                                                     \
      "ldrb   r0, [lr, #47]\n\t"                                           \
      "tst    r0, #4\n\t"                                                  \
      "ldm    lr, {r0, r1, r4, r5}\n\t"                                    \
      "ldrd   r8, r9, [lr, #16]\n\t"                                       \
      "stm    %[a], {r0, r1, r2, r3, r4, r5, r6, r8, r9, r10, r11}\n\t"    \
      "sub    r12, r12, r3, lsl #26\n\t"                                   \
      "bne    18b\n\t"                                                     \
      "b      8f\n\t"                                                      \
      "44:\n\t" /* mid_row = first_row - 1: the bottom edge's record is at this row */ \
      "mov    r11, r5\n\t"                                                 \
      "ldm    lr, {r0, r1, r4, r5}\n\t"                                    \
      "ldrd   r8, r9, [lr, #16]\n\t"                                       \
      "stm    %[a], {r0, r1, r2, r3, r4, r5, r6, r8, r9, r10, r11}\n\t"    \
      "sub    r12, r12, r3, lsl #26\n\t"                                   \
      "add    r1, lr, #24\n\t"                                             \
      "ldm    r1, {r1, r4, r5}\n\t"                                        \
      "b      45f\n\t"                                                     \
      "5:\n\t"                                                             \
      "mov    r11, r5\n\t"                                                 \
      "ldm    lr, {r0, r1, r4, r5}\n\t"                                    \
      "mla    r0, r4, r9, r0\n\t"                                          \
      "mla    r1, r5, r9, r1\n\t"                                          \
      "ldrd   r8, r9, [lr, #16]\n\t"                                       \
      "stm    %[a], {r0, r1, r2, r3, r4, r5, r6, r8, r9, r10, r11}\n\t"    \
      "sub    r12, r12, r3, lsl #26\n\t"                                   \
      "ldrsh  r0, [lr, #38]\n\t"                                           \
      "subs   r0, r3, r0\n\t"                                              \
      "subs   r0, #1\n\t"                                                  \
      "add    r1, lr, #24\n\t"                                             \
      "ldm    r1, {r1, r4, r5}\n\t"                                        \
      "mla    r1, r4, r0, r1\n\t"                                          \
      "45:\n\t"                                                            \
      "ldrb   r2, [lr, #47]\n\t"                                           \
      "and    r0, r2, #1\n\t"                                              \
      "add    r0, %[a], r0, lsl #2\n\t"                                    \
      "str    r1, [r0]\n\t"                                                \
      "str    r4, [r0, #16]\n\t"                                           \
      "str    r5, [r0, #28]\n\t"                                           \
      "tst    r2, #4\n\t"                                                  \
      "bne    11b\n\t"                                                     \
      "b      1f\n\t"                                                      \
      LR_LANE_ROWS("1", "8", "6", "2", "3", "4", LR_LANE_TO_CLAMPED, LR_LANE_CLAMP, SWAP, \
                   LR_LANE_SWITCH_CLAMPED)                                \
      "19:\n\t" LR_LANE_FLUSH_END                                           \
      :                                                                    \
      : [a] "r"(ts), [size] "i"(sizeof(ActiveTriangle)),                   \
        [rows] "i"(offsetof(ActiveTriangle, rows))                         \
      : "r0", "r1", "r2", "r3", "r4", "r5", "r6", "r8", "r9", "r10", "r11", "r12", "lr", \
        "cc", "memory")

template <bool kSwap>
[[gnu::always_inline]] inline void lane_run_asm(const ActiveTriangle& t, LaneRun& run,
                                                StripRows& s) {
#if defined(__thumb2__) && (defined(__ARM_ARCH_7EM__) || defined(__ARM_ARCH_8M_MAIN__))
  static_assert(offsetof(ActiveTriangle, edge_q) == 0 && offsetof(ActiveTriangle, edge_dx) == 8 &&
                offsetof(ActiveTriangle, edge_dy) == 16 && offsetof(ActiveTriangle, bottom) == 24 &&
                offsetof(ActiveTriangle, first_row) == 36 &&
                offsetof(ActiveTriangle, mid_row) == 38 &&
                offsetof(ActiveTriangle, last_row) == 40 &&
                offsetof(ActiveTriangle, col_base) == 42 && offsetof(ActiveTriangle, flags) == 47 &&
                offsetof(ActiveTriangle, z) == 52 && offsetof(ActiveTriangle, c) == 64);
  static_assert(ActiveTriangle::kBottomRight == 1 && ActiveTriangle::kInside == 4);
  static_assert(sizeof(ActiveTriangle) < 256 && offsetof(ActiveTriangle, rows) < 4096);
  static_assert(offsetof(LaneRun, next) == 0 && offsetof(LaneRun, kept) == 4 &&
                offsetof(LaneRun, free) == 8 && offsetof(LaneRun, end) == 12 &&
                offsetof(LaneRun, active) == 16 && offsetof(LaneRun, stride) == 20 &&
                offsetof(LaneRun, lanes) == 24 && offsetof(LaneRun, y0) == 28 &&
                offsetof(LaneRun, y_last) == 32 && offsetof(LaneRun, pix0) == 36);
  static_assert(offsetof(StripRows, pixels) == 0 && offsetof(StripRows, depth) == 4 &&
                offsetof(StripRows, y0) == 8 && offsetof(StripRows, y_last) == 12 &&
                offsetof(StripRows, width) == 16 && offsetof(StripRows, spans) == 32 &&
                offsetof(StripRows, tested) == 36 && offsetof(StripRows, written) == 40 &&
                offsetof(StripRows, rows) == 44);
  // The visit's frame, then the run's, the triangle's and the strip's addresses (a local array,
  // so that the compiler's stack figures, and scripts/stack_usage.py's, include it).
  uint32_t frame[17];
  frame[14] = reinterpret_cast<uintptr_t>(&run);
  frame[15] = reinterpret_cast<uintptr_t>(&t);
  frame[16] = reinterpret_cast<uintptr_t>(&s);
  uint32_t* const ts = frame;
  if constexpr (kSwap)
    LR_LANE_VISIT("rev16  r0, r0\n\t");
  else
    LR_LANE_VISIT("");
#else
  (void)t;
  (void)run;
  (void)s;
#endif
}
#undef LR_LANE_VISIT
#undef LR_LANE_FLUSH
#undef LR_LANE_CLAMP
#undef LR_LANE_ROWS
#undef LR_LANE_SWITCH
#undef LR_LANE_SWITCH_INSIDE
#undef LR_LANE_SWITCH_CLAMPED
#undef LR_LANE_TO_CLAMPED
#undef LR_LANE_FLUSH_RUN
#undef LR_LANE_FLUSH_END
}  // namespace detail

// The run: by hand on Armv7E-M for the RGB565 formats (whose from_value is the value or its
// byte swap), in C elsewhere. t is run.active[*run.next].
template <class PF>
[[gnu::always_inline]] inline void lane_run(const ActiveTriangle& t, LaneRun& run, StripRows& s) {
  constexpr unsigned kProbe = PF::from_value(0x1234u);
  if constexpr (kLaneVisitAsm && (kProbe == 0x1234u || kProbe == 0x3412u))
    detail::lane_run_asm<kProbe == 0x3412u>(t, run, s);
  else
    lane_run_portable<PF>(t, run, s);
}

// One visit (a run of one triangle, its slot in neither list).
template <class PF>
[[gnu::always_inline]] inline void lane_visit(const ActiveTriangle& t, StripRows& s) {
  uint16_t slot = 0, list = 0;
  LaneRun run;
  run.start(&slot, &list, &list, &slot + 1, &t, nullptr, s.y_last);
  lane_run<PF>(t, run, s);
}

}  // namespace lr
