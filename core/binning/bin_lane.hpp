// The front end's bin lane: the common triangles of a draw (back faces culled, no vertex outside
// a plane, the edge table neither banded nor signed) culled and appended to their buckets in one
// small loop: bin_lane_portable() in C, bin_lane_asm() hand-allocated for Armv7E-M (the same
// tests, the same records, the same counts and the same list of vertices to light; the firmware
// check lr_bin_check compares them on random meshes). Internal to core/binning (lane.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "lineraster/core/binning/binned_triangle.hpp"
#include "lineraster/core/binning/edge_table.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr {

// The lane by hand where it exists, except at -Os: there the C lane (which every core links for
// the other cull modes) bins alone, 1.4 KB less flash (docs/measurements/footprint.md).
#if defined(__ARM_FEATURE_DSP) && defined(__thumb2__) && !defined(__OPTIMIZE_SIZE__)
inline constexpr bool kBinLaneAsm = true;
#else
inline constexpr bool kBinLaneAsm = false;
#endif
static_assert(kBinLaneAsm == kBinnedSorted);  // its tails store store_sorted's order

// What the lane reads and updates, in the order bin_lane_asm() addresses it (byte offsets in
// its code, asserted below: do not reorder).
struct alignas(8) BinLane {
  uint32_t count;             // 0: the edge table's triangles
  uint32_t strip_reciprocal;  // 4: EdgeTable::strip_of_row's: strip = (row m) >> 17
  uint16_t* buckets;          // 8
  BinnedTriangle* triangles;  // 12
  uint32_t first2;            // 16: the draw's first store index in both halves (x 0x10001)
  ScreenVertex* vertices;     // 20: the draw's first vertex
  uint32_t stride;            // 24: sizeof(ScreenVertex) (the asm's multiplier, kept in a register)
  int32_t height, width;      // 28, 32: the viewport
  ScreenVertex** list;        // 36: the next free entry of the list of vertices to light
  ScreenVertex** list_limit;  // 40: the last entry at which three more still fit
  uint32_t zero;              // 44: triangles without area, counted
  uint32_t offscreen;         // 48: triangles whose bounds hold no pixel centre, counted
  uint32_t capacity;          // 52: the edge table's room (the lane's driver reads it)
  uint32_t n;                 // 56: the draw's vertex count (first_out_of_range())
  const std::array<uint16_t, 3>* end;  // 60: the end of its triangles (the asm: in a register)
};
static_assert(sizeof(void*) != 4 || sizeof(BinLane) == 64);
static_assert(sizeof(void*) != 4 ||
              (offsetof(BinLane, strip_reciprocal) == 4 && offsetof(BinLane, first2) == 16 &&
               offsetof(BinLane, vertices) == 20 && offsetof(BinLane, stride) == 24 &&
               offsetof(BinLane, height) == 28 && offsetof(BinLane, width) == 32 &&
               offsetof(BinLane, list) == 36 && offsetof(BinLane, list_limit) == 40 &&
               offsetof(BinLane, zero) == 44 && offsetof(BinLane, offscreen) == 48));

// Why the lane stopped: at the end; at a triangle whose pending vertices do not fit on the list
// (nothing of it done).
enum BinLaneStop : uint32_t { kBinLaneEnd, kBinLaneFlush };

// From *tp to end (every index below n: first_out_of_range(); room in the table for every
// triangle up to end: the caller ends a run there): back faces skipped; faces
// without area and faces whose bounds (clamped to the viewport) hold no pixel centre counted; every
// other face's vertices whose colour waits for their first use (color_pending) put on the list,
// their flags cleared; the face appended to the bucket of its first row's strip as EdgeTable::add()
// appends it, its vertices in store_binned()'s order. Exact: twice the signed area in 64 bits
// (the deltas are below 2^23 inside the guard band, each product below 2^46).
inline BinLaneStop bin_lane_portable(const std::array<uint16_t, 3>*& tp, BinLane& k) {
  for (; tp != k.end; ++tp) {
    const uint32_t i0 = (*tp)[0], i1 = (*tp)[1], i2 = (*tp)[2];
    ScreenVertex& v0 = k.vertices[i0];
    ScreenVertex& v1 = k.vertices[i1];
    ScreenVertex& v2 = k.vertices[i2];
    const int32_t dx1 = v1.x - v0.x, dy1 = v1.y - v0.y, dx2 = v2.x - v0.x, dy2 = v2.y - v0.y;
    const int64_t area = int64_t{dx1} * dy2 - int64_t{dx2} * dy1;
    if (back_facing(area)) continue;
    if (area == 0) {
      ++k.zero;
      continue;
    }
    // Rows [a, b) and columns [c0, c1) whose centres the bounds can hold, clamped to the
    // viewport: a = first_row_below(ymin), b = last_row_at_or_above(ymax) + 1.
    const int32_t ymin = dy1 < dy2 ? dy1 : dy2, ymax = dy1 < dy2 ? dy2 : dy1;
    const int32_t xmin = dx1 < dx2 ? dx1 : dx2, xmax = dx1 < dx2 ? dx2 : dx1;
    const int32_t y = v0.y + kHalfPixel, x = v0.x + kHalfPixel - 1;
    int32_t a = (y + (ymin < 0 ? ymin : 0)) >> kSubpixelBits;
    const int32_t b = (y + (ymax > 0 ? ymax : 0)) >> kSubpixelBits;
    int32_t c0 = (x + (xmin < 0 ? xmin : 0)) >> kSubpixelBits;
    const int32_t c1 = (x + (xmax > 0 ? xmax : 0)) >> kSubpixelBits;
    // (USAT's clamps: [0, 65535])
    a = a < 0 ? 0 : a > 0xFFFF ? 0xFFFF : a;
    c0 = c0 < 0 ? 0 : c0 > 0xFFFF ? 0xFFFF : c0;
    if (a >= b || a >= k.height || c0 >= c1 || c0 >= k.width ||
        (one_centre(a, b, c0, c1) && !holds_centre(v0, v1, v2, c0, a))) {
      ++k.offscreen;
      continue;
    }
    if ((v0.color_pending | v1.color_pending | v2.color_pending) != 0) {
      if (k.list > k.list_limit) return kBinLaneFlush;
      for (ScreenVertex* v : {&v0, &v1, &v2}) {
        if (v->color_pending == 0) continue;
        v->color_pending = 0;
        *k.list++ = v;
      }
    }
    const uint32_t index = k.count++;
    uint16_t& head = k.buckets[(static_cast<uint32_t>(a) * k.strip_reciprocal) >> 17];
    BinnedTriangle& t = k.triangles[index];
    const auto first = static_cast<uint16_t>(k.first2);
    store_binned(t.v, static_cast<uint16_t>(first + i0), static_cast<uint16_t>(first + i1),
                 static_cast<uint16_t>(first + i2), dy1, dy2);
    t.next = head;
    head = static_cast<uint16_t>(index);
  }
  return kBinLaneEnd;
}

// The first triangle of [tp, end) with an index of n or more, or end: the lane's triangles
// before it need no index test of their own. On Armv7E-M 16 indices at a time (LDM and UQSUB16:
// about 3.6 instructions a triangle), else one at a time.
inline const std::array<uint16_t, 3>* first_out_of_range(const std::array<uint16_t, 3>* tp,
                                                         const std::array<uint16_t, 3>* end,
                                                         uint32_t n) {
  if (tp == end || n == 0) return tp;
  const uint16_t* p = tp->data();
  const uint16_t* const e = p + 3 * (end - tp);
#if defined(__ARM_FEATURE_DSP) && defined(__thumb2__)
  if ((reinterpret_cast<uintptr_t>(p) & 2) != 0 && p != e) {
    if (*p >= n) return tp;
    ++p;
  }
  const uint32_t blocks = static_cast<uint32_t>(e - p) / 16;
  if (blocks != 0) {
    const uint16_t* const block_end = p + 16 * blocks;
    // n - 1 in both halves (every index is below n > 0xFFFF)
    const uint32_t limit = (n > 0x10000 ? 0xFFFFu : n - 1) * 0x10001u;
    asm volatile(
        "1:\n\t"
        "ldm     %[p]!, {r4, r5, r6, r8, r9, r10, r11, r12}\n\t"
        "uqsub16 r4, r4, %[l]\n\t"  // non-zero where an index is above n - 1
        "uqsub16 r5, r5, %[l]\n\t"
        "uqsub16 r6, r6, %[l]\n\t"
        "uqsub16 r8, r8, %[l]\n\t"
        "uqsub16 r9, r9, %[l]\n\t"
        "uqsub16 r10, r10, %[l]\n\t"
        "uqsub16 r11, r11, %[l]\n\t"
        "uqsub16 r12, r12, %[l]\n\t"
        "orr     r4, r4, r5\n\t"
        "orr     r6, r6, r8\n\t"
        "orr     r9, r9, r10\n\t"
        "orr     r11, r11, r12\n\t"
        "orr     r4, r4, r6\n\t"
        "orr     r9, r9, r11\n\t"
        "orrs    r4, r4, r9\n\t"
        "bne     2f\n\t"
        "cmp     %[p], %[e]\n\t"
        "bne     1b\n\t"
        "b       3f\n"
        "2:\n\t"
        "sub     %[p], %[p], #32\n"  // the block with the index: found one at a time below
        "3:\n"
        : [p] "+r"(p)
        : [l] "r"(limit), [e] "r"(block_end)
        : "r4", "r5", "r6", "r8", "r9", "r10", "r11", "r12", "cc", "memory");
  }
#endif
  while (p != e && *p < n) ++p;
  return tp + (p - tp->data()) / 3;
}

#if defined(__ARM_FEATURE_DSP) && defined(__thumb2__)
// bin_lane_asm()'s rows [a, b) into r11 and r9 from r1 = y0, r9 = dy1 and r11 = -dy2, one macro
// per vertex on top (store_sorted): a on top with dy2 or dy1 the larger (min(0, ..) = 0, so
// a = y0's row, b from the larger); b on top (a from dy1 < 0, b from max(0, dy2)); c on top (a
// from dy2 < 0, b from max(0, dy1)). a = max(0, (y0 + 128 + min(0, dy1, dy2)) >> 8) (USAT),
// b = (y0 + 128 + max(0, dy1, dy2)) >> 8.
#define LR_BIN_LANE_ROWS_A_DY2       \
  "add     r1, r1, #128\n\t"         \
  "sub     r9, r1, r11\n\t"          \
  "usat    r11, #16, r1, asr #8\n\t" \
  "asr     r9, r9, #8\n\t"
#define LR_BIN_LANE_ROWS_A_DY1       \
  "add     r1, r1, #128\n\t"         \
  "add     r9, r1, r9\n\t"           \
  "usat    r11, #16, r1, asr #8\n\t" \
  "asr     r9, r9, #8\n\t"
#define LR_BIN_LANE_ROWS_B                                \
  "add     r1, r1, #128\n\t"                              \
  "add     r9, r1, r9\n\t"                                \
  "and     r11, r11, r11, asr #31\n\t" /* min(0, -dy2) */ \
  "sub     r1, r1, r11\n\t"                               \
  "usat    r11, #16, r9, asr #8\n\t"                      \
  "asr     r9, r1, #8\n\t"
#define LR_BIN_LANE_ROWS_C                            \
  "add     r1, r1, #128\n\t"                          \
  "bic     r9, r9, r9, asr #31\n\t" /* max(0, dy1) */ \
  "add     r9, r1, r9\n\t"                            \
  "sub     r1, r1, r11\n\t"                           \
  "usat    r11, #16, r1, asr #8\n\t"                  \
  "asr     r9, r9, #8\n\t"
// The one centre (column r1, row r11) of bounds that hold one (one_centre: a and c0 not 0, else
// on to BACK), tested as holds_centre() tests it: the vertices r4-r6 in the mesh's order (a
// front face: inside, every edge function is negative), per edge e = dx (yc - ya) - dy (xc - xa)
// against 1 when a centre on the edge is in (dy > 0, or dy = 0 and dx > 0), else 0 (as e - 1
// against 0: a compare inside an IT block would set the flags the next one reads): e at or above
// it is outside (to 83, counted). r11 and r12 kept on the stack; r0, r8-r10 scratch.
#define LR_BIN_LANE_EDGE(A, B)             \
  "ldrd    r8, r9, [" A                    \
  "]\n\t"                                  \
  "ldrd    r10, r11, [" B                  \
  "]\n\t"                                  \
  "sub     r10, r10, r8\n\t" /* dx */      \
  "sub     r11, r11, r9\n\t" /* dy */      \
  "sub     r9, r0, r9\n\t"   /* yc - ya */ \
  "sub     r8, r1, r8\n\t"   /* xc - xa */ \
  "mul     r12, r10, r9\n\t"               \
  "mls     r12, r11, r8, r12\n\t"          \
  "cmp     r11, #0\n\t"                    \
  "it      eq\n\t"                         \
  "moveq   r11, r10\n\t"                   \
  "cmp     r11, #0\n\t"                    \
  "it      gt\n\t"                         \
  "subgt   r12, r12, #1\n\t"               \
  "cmp     r12, #0\n\t"                    \
  "bge     85f\n\t"
#define LR_BIN_LANE_ONE_CENTRE(BACK) \
  "cmp     r11, #0\n\t"                \
  "it      ne\n\t"                     \
  "cmpne   r1, #0\n\t"                 \
  "beq     " BACK "\n\t"               \
  "push    {r11, r12}\n\t"             \
  "lsl     r0, r11, #8\n\t"            \
  "add     r0, r0, #128\n\t" /* yc */  \
  "lsl     r1, r1, #8\n\t"             \
  "add     r1, r1, #128\n\t" /* xc */  \
  LR_BIN_LANE_EDGE("r4", "r5")         \
  LR_BIN_LANE_EDGE("r5", "r6")         \
  LR_BIN_LANE_EDGE("r6", "r4")         \
  "pop     {r11, r12}\n\t"             \
  "b       " BACK "\n\t"
// The rest of bin_lane_asm() for one vertex on top (N: the labels' digit): the rows (ROWS), the
// columns [c0, c1) into r1 and r8 from r0 = x0, r8 = dx1 and r10 = dx2 (min and max with 0 by
// conditional AND and BIC), the four tests in one chain of conditional compares, the pending
// vertices and the record, its indices read from the triangle at byte offsets O0, O1 and O2
// (store_sorted's order; tp is on the next triangle already).
#define LR_BIN_LANE_TAIL(N, ROWS, O0, O1, O2)                                      \
  "7" N ":\n\t" ROWS                                                               \
  "add     r0, r0, #127\n\t"                                                       \
  "cmp     r8, r10\n\t"                                                            \
  "itete   lt\n\t"                                                                 \
  "andlt   r1, r8, r8, asr #31\n\t"                                                \
  "andge   r1, r10, r10, asr #31\n\t"                                              \
  "biclt   r8, r10, r10, asr #31\n\t"                                              \
  "bicge   r8, r8, r8, asr #31\n\t"                                                \
  "add     r1, r1, r0\n\t"                                                         \
  "add     r8, r8, r0\n\t"                                                         \
  "usat    r1, #16, r1, asr #8\n\t"                                                \
  "asr     r8, r8, #8\n\t"                                                         \
  "ldrd    r0, r10, [%[k], #28]\n\t" /* height, width */                           \
  "cmp     r11, r9\n\t"              /* a < b, a < height, c0 < c1, c0 < width */  \
  "ittt    lt\n\t"                                                                 \
  "cmplt   r11, r0\n\t"                                                            \
  "cmplt   r1, r8\n\t"                                                             \
  "cmplt   r1, r10\n\t"                                                            \
  "bge     83f\n\t"                                                                \
  "sub     r0, r9, r11\n\t" /* bounds of one centre: its own test (10N) */         \
  "sub     r10, r8, r1\n\t"                                                        \
  "add     r0, r0, r10\n\t"                                                        \
  "cmp     r0, #2\n\t"                                                             \
  "beq     10" N                                                                   \
  "f\n\t"                                                                          \
  "11" N                                                                           \
  ":\n\t"                                                                          \
  "ldrb    r0, [r4, #23]\n\t" /* a vertex waiting for its colour */                \
  "ldrb    r1, [r5, #23]\n\t"                                                      \
  "ldrb    r8, [r6, #23]\n\t"                                                      \
  "orr     r9, r0, r1\n\t" /* (the three flags kept for 5N) */                     \
  "orrs    r9, r9, r8\n\t"                                                         \
  "bne     5" N                                                                    \
  "f\n\t"                                                                          \
  "6" N                                                                            \
  ":\n\t"                                                                          \
  "ldm     %[k], {r0, r1, r8, r9, r10}\n\t" /* count m buckets triangles first2 */ \
  "mul     r1, r11, r1\n\t"                                                        \
  "lsr     r1, r1, #17\n\t"           /* the strip */                              \
  "ldrh    r11, [r8, r1, lsl #1]\n\t" /* its head: the record's next */            \
  "strh    r0, [r8, r1, lsl #1]\n\t"                                               \
  "add     r9, r9, r0, lsl #3\n\t"                                                 \
  "add     r0, r0, #1\n\t"                                                         \
  "str     r0, [%[k]]\n\t"                                                         \
  "ldrh    r4, [%[tp], " O0                                                        \
  "]\n\t"                                                                          \
  "ldrh    r5, [%[tp], " O1                                                        \
  "]\n\t"                                                                          \
  "ldrh    r6, [%[tp], " O2                                                        \
  "]\n\t"                                                                          \
  "orr     r4, r4, r5, lsl #16\n\t"                                                \
  "add     r4, r4, r10\n\t" /* v0 v1 */                                            \
  "add     r6, r6, r10\n\t"                                                        \
  "pkhbt   r6, r6, r11, lsl #16\n\t" /* v2 next */                                 \
  "strd    r4, r6, [r9]\n\t"                                                       \
  "cmp     %[tp], %[e]\n\t" /* the next (3b's, its branch back here) */            \
  "bls     21b\n\t"                                                                \
  "b       30b\n"                                                                  \
  "5" N                                                                            \
  ":\n\t" /* pending vertices onto the list, their flags (r0, r1, r8) cleared */   \
  "ldrd    r9, r10, [%[k], #36]\n\t"                                               \
  "cmp     r9, r10\n\t"                                                            \
  "bhi     84f\n\t"                                                                \
  "mov     r10, #0\n\t"                                                            \
  "cbz     r0, 5" N                                                                \
  "1f\n\t"                                                                         \
  "strb    r10, [r4, #23]\n\t"                                                     \
  "str     r4, [r9], #4\n"                                                         \
  "5" N                                                                            \
  "1:\n\t"                                                                         \
  "cbz     r1, 5" N                                                                \
  "2f\n\t"                                                                         \
  "strb    r10, [r5, #23]\n\t"                                                     \
  "str     r5, [r9], #4\n"                                                         \
  "5" N                                                                            \
  "2:\n\t"                                                                         \
  "cmp     r8, #0\n\t"                                                             \
  "beq     5" N                                                                    \
  "3f\n\t"                                                                         \
  "strb    r10, [r6, #23]\n\t"                                                     \
  "str     r6, [r9], #4\n"                                                         \
  "5" N                                                                            \
  "3:\n\t"                                                                         \
  "str     r9, [%[k], #36]\n\t"                                                    \
  "b       6" N                                                                    \
  "b\n"                                                                            \
  "10" N ":\n\t" LR_BIN_LANE_ONE_CENTRE("11" N "b")
// The first part of bin_lane_asm() for one triangle (four copies): the indices read with
// post-increment (tp on the next triangle from there on), the vertices' addresses, the deltas
// (dx1 r8, dy1 r9, dx2 r10, -dy2 r11) and minus twice the signed area in r1:r0, its sign in the
// flags.
#define LR_BIN_LANE_FRONT                                                \
  "ldrh    r4, [%[tp]], #2\n\t"                                          \
  "ldrh    r5, [%[tp]], #2\n\t"                                          \
  "ldrh    r6, [%[tp]], #2\n\t"                                          \
  "mla     r4, r4, lr, r12\n\t"                                          \
  "mla     r5, r5, lr, r12\n\t"                                          \
  "mla     r6, r6, lr, r12\n\t"                                          \
  "ldrd    r0, r1, [r4]\n\t" /* x0 y0 */                                 \
  "ldrd    r8, r9, [r5]\n\t"                                             \
  "ldrd    r10, r11, [r6]\n\t"                                           \
  "sub     r8, r8, r0\n\t"   /* dx1 */                                   \
  "sub     r9, r9, r1\n\t"   /* dy1 */                                   \
  "sub     r10, r10, r0\n\t" /* dx2 */                                   \
  "sub     r11, r1, r11\n\t" /* -dy2 */                                  \
  "smull   r0, r1, r10, r9\n\t"                                          \
  "smlal   r0, r1, r8, r11\n\t" /* minus twice the signed area, exact */ \
  "cmp     r1, #0\n\t"
#endif

// bin_lane_portable() hand-allocated (Armv7E-M; elsewhere the C loop): 17 or 19 instructions a
// back face and 74 to 76 a binned front face without pending vertices. The vertices' base and
// stride in registers for the whole run (an index to an address is one MLA); minus twice the
// signed area, so that its high word's sign alone tells a back face, and x0 and y0 read again for
// the faces that stay (their registers take the area); four copies of that first part, so that
// a back face in the first three needs no test of the end; rows as
// (y + 128 + min(0, dy1, dy2)) >> 8 with USAT for the clamp at 0, in one of four tails picked by
// the vertex on top and the order of the other two (store_sorted), which also stores the indices in
// that order; the four
// tests of the bounds in one chain of conditional compares; the constants of a binned face read
// with one LDM; the record's halves built with one ORR and PKHBT; bounds of one centre tested
// at it (holds_centre). Where the front end does not take it (kBinLaneAsm false: -Os, whose C
// lane leaves the one-centre test out) it is the C loop.
inline BinLaneStop bin_lane_asm(const std::array<uint16_t, 3>*& tp, BinLane& k) {
#if defined(__ARM_FEATURE_DSP) && defined(__thumb2__) && !defined(__OPTIMIZE_SIZE__)
  static_assert(kBinLaneAsm && kOneCentreTest);
  // Low registers: CBZ tests them.
  register uint32_t a asm("r0");
  register uint32_t b asm("r1");
  const std::array<uint16_t, 3>* last = k.end - 1;
  asm volatile(
      "ldrd    r12, lr, [%[k], #20]\n\t"  // the vertices, 24 bytes each
      // e: from the last triangle to the fourth from the end (not below the address 24:
      // the vector table is there).
      "sub     %[e], %[e], #18\n\t"
      "cmp     %[tp], %[e]\n\t"
      "bhi     30f\n"  // fewer than four
      // Four copies of the first part: a back face in the first three goes on to the next
      // without a test of the end (at least four triangles are left when the first starts).
      "21:\n\t" LR_BIN_LANE_FRONT
      "bpl     4f\n"  // no back face: area <= 0
      "22:\n\t" LR_BIN_LANE_FRONT
      "bpl     4f\n"
      "23:\n\t" LR_BIN_LANE_FRONT
      "bpl     4f\n"
      "24:\n\t" LR_BIN_LANE_FRONT
      "bpl     4f\n"
      "3:\n\t"  // the next: four or more left, three, two, one, none
      "cmp     %[tp], %[e]\n\t"
      "bls     21b\n"
      "30:\n\t"
      "sub     r0, %[tp], %[e]\n\t"  // 6, 12, 18, 24: three, two, one, none left
      "cmp     r0, #12\n\t"
      "blo     22b\n\t"
      "beq     23b\n\t"
      "cmp     r0, #18\n\t"
      "beq     24b\n\t"
      "mov     %[a], #0\n\t"  // kBinLaneEnd
      "b       9f\n"
      "4:\n\t"
      "cbnz    r0, 41f\n\t"  // the low word is 0: no area if the high word is 0 too
      "cmp     r1, #0\n\t"
      "bne     41f\n\t"
      "ldr     r8, [%[k], #44]\n\t"
      "add     r8, r8, #1\n\t"
      "str     r8, [%[k], #44]\n\t"
      "b       3b\n"
      "41:\n\t"
      // x0 and y0 again; the vertex on top and the order below it (store_sorted) pick the tail
      // that stores the vertices in that order.
      "ldrd    r0, r1, [r4]\n\t"
      "cmn     r9, r11\n\t"  // dy1 - dy2
      "bgt     42f\n\t"
      "cmp     r9, #0\n\t"  // dy1 <= dy2
      "bge     70f\n\t"     // a on top
      // b on top: (b, c, a), or (b, a, c) where a lies strictly above c (store_sorted)
      "cmp     r11, #0\n\t"  // dy2 > 0
      "blt     75f\n\t"
      LR_BIN_LANE_TAIL("1", LR_BIN_LANE_ROWS_B, "#-4", "#-2", "#-6")
      "42:\n\t"
      "cmp     r11, #0\n\t"  // dy2 < dy1
      "ble     74f\n\t"      // a on top
      // c on top: (c, a, b), or (c, b, a) where b lies strictly above a
      "cmp     r9, #0\n\t"  // dy1 < 0
      "blt     76f\n\t"
      LR_BIN_LANE_TAIL("2", LR_BIN_LANE_ROWS_C, "#-2", "#-6", "#-4")
      LR_BIN_LANE_TAIL("0", LR_BIN_LANE_ROWS_A_DY2, "#-6", "#-4", "#-2")
      // a on top with c strictly above b: (a, c, b)
      LR_BIN_LANE_TAIL("4", LR_BIN_LANE_ROWS_A_DY1, "#-6", "#-2", "#-4")
      LR_BIN_LANE_TAIL("5", LR_BIN_LANE_ROWS_B, "#-4", "#-6", "#-2")
      LR_BIN_LANE_TAIL("6", LR_BIN_LANE_ROWS_C, "#-2", "#-4", "#-6")
      "85:\n\t"  // a centre outside (LR_BIN_LANE_ONE_CENTRE)
      "pop     {r11, r12}\n"
      "83:\n\t"
      "ldr     r8, [%[k], #48]\n\t"
      "add     r8, r8, #1\n\t"
      "str     r8, [%[k], #48]\n\t"
      "b       3b\n"
      "84:\n\t"
      "sub     %[tp], %[tp], #6\n\t"  // the triangle not done
      "mov     %[a], #1\n"             // kBinLaneFlush
      "9:\n"
      : [tp] "+r"(tp), [a] "=&r"(a), [b] "=&r"(b), [e] "+r"(last)
      : [k] "r"(&k)
      : "r4", "r5", "r6", "r8", "r9", "r10", "r11", "r12", "lr", "cc", "memory");
  return static_cast<BinLaneStop>(a);
#else
  return bin_lane_portable(tp, k);
#endif
}

#if defined(__ARM_FEATURE_DSP) && defined(__thumb2__)
#undef LR_BIN_LANE_TAIL
#undef LR_BIN_LANE_ONE_CENTRE
#undef LR_BIN_LANE_EDGE
#undef LR_BIN_LANE_FRONT
#undef LR_BIN_LANE_ROWS_A_DY2
#undef LR_BIN_LANE_ROWS_A_DY1
#undef LR_BIN_LANE_ROWS_B
#undef LR_BIN_LANE_ROWS_C
#endif

}  // namespace lr
