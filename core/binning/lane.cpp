// The front end's lane: the common triangle of a draw (one-sided, Gouraud or one colour, inside
// every plane, the edge table neither full nor banded nor signed) culled, lit and binned in a
// small loop of its own; and the lighting of a drawn triangle's vertices on first use.
#include "lineraster/core/binning/front_end.hpp"
#include "lineraster/core/binning/mesh_draw.hpp"

namespace lr {

namespace {

#if defined(__ARM_FEATURE_DSP) && defined(__thumb2__)
inline constexpr bool kLaneRun = true;
#else
inline constexpr bool kLaneRun = false;
#endif

// What lane_run() reads (and the count it updates), in its order: word offsets in its code.
struct alignas(8) LaneWords {
  const ScreenVertex* vertices;        // 0: the draw's first vertex
  uint32_t n;                          // 4: its vertex count
  const std::array<uint16_t, 3>* end;  // 8: the end of its triangles
  int32_t last_row;                    // 12: height - 1
  int32_t width;                       // 16
  uint32_t strip_reciprocal;           // 20: EdgeTable::strip_of_row's
  uint16_t* buckets;                   // 24
  BinnedTriangle* triangles;           // 28
  uint32_t count, capacity;            // 32, 36: the edge table's
  uint32_t first;                      // 40: the draw's first vertex store index
  uint32_t pad;
};

// Why lane_run() stopped.
enum LaneStop : uint32_t { kLaneEnd, kLaneSlow, kLaneZero, kLaneOffscreen, kLanePending };

// The lane for back-face culling in draws with no vertex outside a plane, hand-allocated (about
// 34 instructions a back face, 110 a binned front face, where GCC 12's code for the loop of
// lane_triangles() takes about 47 and 125): from *tp on, back faces skipped, front faces binned
// as lane_triangles() bins them, until the end or a triangle that needs more (an index out of
// range or a full table: draw_triangle(); no area; no pixel centre; a pending vertex, with its
// first row in row). The same tests and the same records as the C loop, which the other cores
// run.
[[gnu::always_inline]] inline LaneStop lane_run(const std::array<uint16_t, 3>*& tp, LaneWords& k,
                                                uint32_t& row) {
#if defined(__ARM_FEATURE_DSP) && defined(__thumb2__)
  uint32_t a, b;
  asm volatile(
      "1:\n\t"
      "ldrh    r4, [%[tp]]\n\t"
      "ldrh    r5, [%[tp], #2]\n\t"
      "ldrh    r6, [%[tp], #4]\n\t"
      "ldr     r8, [%[k], #4]\n\t"  // n
      "cmp     r4, r8\n\t"
      "bhs     81f\n\t"
      "cmp     r5, r8\n\t"
      "bhs     81f\n\t"
      "cmp     r6, r8\n\t"
      "bhs     81f\n\t"
      "ldr     r8, [%[k]]\n\t"  // the vertices (24 bytes each)
      "add     r4, r4, r4, lsl #1\n\t"
      "add     r4, r8, r4, lsl #3\n\t"
      "add     r5, r5, r5, lsl #1\n\t"
      "add     r5, r8, r5, lsl #3\n\t"
      "add     r6, r6, r6, lsl #1\n\t"
      "add     r6, r8, r6, lsl #3\n\t"
      "ldrd    r8, r9, [r4]\n\t"  // x0 y0
      "ldrd    r10, r11, [r5]\n\t"
      "ldrd    r12, lr, [r6]\n\t"
      "sub     r10, r10, r8\n\t"  // dx1
      "sub     r11, r11, r9\n\t"  // dy1
      "sub     r12, r8, r12\n\t"  // -dx2
      "sub     lr, lr, r9\n\t"    // dy2
      "smull   %[a], %[b], r10, lr\n\t"
      "smlal   %[a], %[b], r12, r11\n\t"  // twice the signed area, exact (facing())
      "cmp     %[b], #0\n\t"
      "blt     4f\n\t"  // front-facing
      "bne     3f\n\t"
      "cmp     %[a], #0\n\t"
      "beq     82f\n\t"  // no area
      "3:\n\t"           // culled (back face) or binned: the next
      "add     %[tp], %[tp], #6\n\t"
      "ldr     %[a], [%[k], #8]\n\t"
      "cmp     %[tp], %[a]\n\t"
      "bne     1b\n\t"
      "mov     %[a], #0\n\t"  // kLaneEnd
      "b       9f\n"
      "4:\n\t"  // rows: y0 + min(0, dy1, dy2), y0 + max(...)
      "cmp     r11, lr\n\t"
      "itete   lt\n\t"
      "movlt   %[a], r11\n\t"
      "movge   %[a], lr\n\t"
      "movlt   %[b], lr\n\t"
      "movge   %[b], r11\n\t"
      "and     %[a], %[a], %[a], asr #31\n\t"
      "bic     %[b], %[b], %[b], asr #31\n\t"
      "add     %[a], %[a], r9\n\t"
      "add     %[b], %[b], r9\n\t"
      "sub     %[a], %[a], #128\n\t"
      "asr     %[a], %[a], #8\n\t"
      "add     %[a], %[a], #1\n\t"
      "bic     %[a], %[a], %[a], asr #31\n\t"  // r0 = max(first_row_below(ymin), 0)
      "sub     %[b], %[b], #128\n\t"
      "asr     %[b], %[b], #8\n\t"  // last_row_at_or_above(ymax)
      "ldr     r9, [%[k], #12]\n\t"
      "cmp     %[b], r9\n\t"
      "it      gt\n\t"
      "movgt   %[b], r9\n\t"
      "cmp     %[a], %[b]\n\t"
      "bgt     83f\n\t"           // no row centre
      "rsb     r12, r12, #0\n\t"  // columns: x0 + min(0, dx1, dx2), ...
      "cmp     r10, r12\n\t"
      "itete   lt\n\t"
      "movlt   r9, r10\n\t"
      "movge   r9, r12\n\t"
      "movlt   r11, r12\n\t"
      "movge   r11, r10\n\t"
      "and     r9, r9, r9, asr #31\n\t"
      "bic     r11, r11, r11, asr #31\n\t"
      "add     r9, r9, r8\n\t"
      "add     r11, r11, r8\n\t"
      "add     r9, r9, #127\n\t"
      "asr     r9, r9, #8\n\t"
      "bic     r9, r9, r9, asr #31\n\t"  // c0
      "add     r11, r11, #127\n\t"
      "asr     r11, r11, #8\n\t"
      "ldr     r10, [%[k], #16]\n\t"
      "cmp     r11, r10\n\t"
      "it      gt\n\t"
      "movgt   r11, r10\n\t"  // c1
      "cmp     r9, r11\n\t"
      "bge     83f\n\t"            // no column centre
      "ldrb    r9, [r4, #23]\n\t"  // a vertex waiting for its colour
      "ldrb    r10, [r5, #23]\n\t"
      "ldrb    r11, [r6, #23]\n\t"
      "orr     r9, r9, r10\n\t"
      "orrs    r9, r9, r11\n\t"
      "bne     84f\n\t"
      "ldrd    r9, r10, [%[k], #32]\n\t"  // count, capacity
      "cmp     r9, r10\n\t"
      "bhs     81f\n\t"
      "ldr     r10, [%[k], #20]\n\t"  // the strip of r0
      "mul     r10, %[a], r10\n\t"
      "lsr     r10, r10, #17\n\t"
      "ldr     r11, [%[k], #24]\n\t"
      "ldrh    r12, [r11, r10, lsl #1]\n\t"  // its head: the record's next
      "strh    r9, [r11, r10, lsl #1]\n\t"
      "ldr     r11, [%[k], #28]\n\t"
      "add     r11, r11, r9, lsl #3\n\t"
      "add     r9, r9, #1\n\t"
      "str     r9, [%[k], #32]\n\t"
      "ldrh    r4, [%[tp]]\n\t"
      "ldrh    r5, [%[tp], #2]\n\t"
      "ldrh    r6, [%[tp], #4]\n\t"
      "ldr     r10, [%[k], #40]\n\t"  // the draw's first store index
      "add     r4, r4, r10\n\t"
      "add     r5, r5, r10\n\t"
      "add     r6, r6, r10\n\t"
      "orr     r4, r4, r5, lsl #16\n\t"
      "orr     r6, r6, r12, lsl #16\n\t"
      "strd    r4, r6, [r11]\n\t"  // v0 v1, v2 next
      "b       3b\n"
      "81:\n\t"
      "mov     %[a], #1\n\t"
      "b       9f\n"
      "82:\n\t"
      "mov     %[a], #2\n\t"
      "b       9f\n"
      "83:\n\t"
      "mov     %[a], #3\n\t"
      "b       9f\n"
      "84:\n\t"
      "mov     %[b], %[a]\n\t"
      "mov     %[a], #4\n"
      "9:\n"
      : [tp] "+r"(tp), [a] "=&r"(a), [b] "=&r"(b)
      : [k] "r"(&k)
      : "r4", "r5", "r6", "r8", "r9", "r10", "r11", "r12", "lr", "cc", "memory");
  row = b;
  return static_cast<LaneStop>(a);
#else
  (void)tp;
  (void)k;
  (void)row;
  return kLaneSlow;
#endif
}

}  // namespace

// The lane, from triangle t on: one-sided, Gouraud or one colour (no per-triangle colours),
// inside every plane (a draw with no vertex outside one skips the outcode tests), the edge table
// neither full nor banded nor signed. Culled on its facing first, its pending vertices lit,
// appended to its strip's bucket, counted in locals. Returns the first triangle it leaves to
// draw_triangle() (or the count). Its own small stack frame, never live with draw_triangle()'s
// locals.
uint32_t FrontEnd::lane_triangles(MeshDraw& d, uint32_t t) {
  if (edges_.banding()) return t;  // (set only by draw_triangle())
  if constexpr (kLaneRun) {
    if (d.state.cull == Cull::kBack && !d.clipping) return lane_run_triangles(d, t);
  }
  const std::array<uint16_t, 3>* const tris = d.mesh.triangles.data();
  const std::array<uint16_t, 3>* const end = tris + d.mesh.triangles.size();
  const auto n = static_cast<uint32_t>(d.mesh.positions.size());
  const ScreenVertex* const base = store_.vertices_at(d.base);
  // Which facings are culled (bit 0: back faces, bit 1: front faces); lit Gouraud (vertices lit
  // on first use); a draw with a vertex outside a plane.
  const Cull cull = d.state.cull;
  const uint32_t culled = cull == Cull::kBack ? 1u : cull == Cull::kFront ? 2u : 0u;
  const bool pending = d.colors.pending, clipping = d.clipping;
  const uint32_t zero_before = stats_.culled_zero_area, off_before = stats_.culled_offscreen;
  EdgeTable::Run run(edges_);
  uint32_t binned = 0;
  const std::array<uint16_t, 3>* tp = tris + t;
  for (; tp != end; ++tp) {
    {
      const uint32_t i0 = (*tp)[0], i1 = (*tp)[1], i2 = (*tp)[2];
      if (i0 >= n || i1 >= n || i2 >= n) [[unlikely]]
        break;
      const ScreenVertex& v0 = base[i0];
      const ScreenVertex& v1 = base[i1];
      const ScreenVertex& v2 = base[i2];
      if (clipping && (v0.outcode | v1.outcode | v2.outcode) != 0) [[unlikely]]
        break;
      // The facing first: most culled triangles leave here.
      const int32_t x0 = v0.x, y0 = v0.y;
      const uint32_t f = facing(v1.x - x0, v1.y - y0, v2.x - x0, v2.y - y0);  // 1 back, 2 front
      if ((f & culled) != 0) continue;
      if (f == 0) [[unlikely]] {
        ++stats_.culled_zero_area;
        continue;
      }
    }
    // A face that is drawn: its rows and columns, its pending vertices, its bucket.
    const uint32_t i0 = (*tp)[0], i1 = (*tp)[1], i2 = (*tp)[2];
    const ScreenVertex& v0 = base[i0];
    const ScreenVertex& v1 = base[i1];
    const ScreenVertex& v2 = base[i2];
    int32_t r0;
    if (!edges_.covers(v0, v1, v2, r0)) {
      ++stats_.culled_offscreen;
      continue;
    }
    if (run.full()) [[unlikely]]
      break;
    if (pending && (v0.color_pending | v1.color_pending | v2.color_pending) != 0)
      light_corners(d, *tp);
    BinnedTriangle& bt = run.add(r0);
    const auto first = static_cast<uint16_t>(d.base);
    bt.v[0] = static_cast<uint16_t>(first + i0);
    bt.v[1] = static_cast<uint16_t>(first + i1);
    bt.v[2] = static_cast<uint16_t>(first + i2);
    ++binned;
  }
  run.finish();
  const auto done = static_cast<uint32_t>(tp - tris);
  stats_.triangles_binned += binned;
  stats_.binned_inputs += binned;
  // The rest of the lane's triangles were culled by their facing.
  stats_.culled_backface += done - t - binned - (stats_.culled_zero_area - zero_before) -
                            (stats_.culled_offscreen - off_before);
  return done;
}

// lane_triangles() through lane_run(): the C side takes the triangles it stops at (pending
// vertices lit, then binned; no area, no pixel centre counted), the rest goes to draw_triangle().
uint32_t FrontEnd::lane_run_triangles(MeshDraw& d, uint32_t t) {
  const std::array<uint16_t, 3>* const tris = d.mesh.triangles.data();
  const std::array<uint16_t, 3>* tp = tris + t;
  const std::array<uint16_t, 3>* const end = tris + d.mesh.triangles.size();
  if (tp == end) return t;
  const EdgeTable::Raw table = edges_.raw();
  LaneWords k{store_.vertices_at(d.base),
              static_cast<uint32_t>(d.mesh.positions.size()),
              end,
              height_ - 1,
              width_,
              table.strip_reciprocal,
              table.buckets,
              table.triangles,
              table.count,
              table.capacity,
              static_cast<uint32_t>(d.base),
              0};
  const uint32_t count_before = table.count;
  uint32_t zero = 0, off = 0;
  for (;;) {
    uint32_t row = 0;
    const LaneStop why = lane_run(tp, k, row);
    if (why == kLaneEnd || why == kLaneSlow) break;
    if (why == kLaneZero) {
      ++zero;
    } else if (why == kLaneOffscreen) {
      ++off;
    } else {  // pending vertices: lit, then the triangle binned as lane_run() bins it
      if (k.count >= k.capacity) break;
      light_corners(d, *tp);
      const uint32_t index = k.count++;
      BinnedTriangle& bt = k.triangles[index];
      uint16_t& head = k.buckets[(row * k.strip_reciprocal) >> 17];
      bt.next = head;
      head = static_cast<uint16_t>(index);
      for (size_t c = 0; c < 3; ++c) bt.v[c] = static_cast<uint16_t>(k.first + (*tp)[c]);
    }
    if (++tp == end) break;
  }
  edges_.set_size(k.count);
  const auto done = static_cast<uint32_t>(tp - tris);
  const uint32_t binned = k.count - count_before;
  stats_.triangles_binned += binned;
  stats_.binned_inputs += binned;
  stats_.culled_zero_area += zero;
  stats_.culled_offscreen += off;
  stats_.culled_backface += done - t - binned - zero - off;
  return done;
}

// A drawn triangle's vertices whose colour waits for their first use, lit (lit Gouraud). The
// common case here: diffuse directional lights in model space, a unit normal, one colour; the
// others through VertexStage::light (out of line).
void FrontEnd::light_corners(MeshDraw& d, const std::array<uint16_t, 3>& tri) {
  const ObjectLights* const ol = d.diffuse_lights;
  ScreenVertex* const base = store_.vertices_at(d.base);
  const Normal16* const normals = d.mesh.normals.data();
  for (size_t k = 0; k < 3; ++k) {
    const uint32_t i = tri[k];
    ScreenVertex& v = base[i];
    if (v.color_pending == 0) continue;
    v.color_pending = 0;
    if (ol != nullptr) {
      const Normal16& n = normals[i];
      const uint32_t len2 = normal_len2(n);
      if (unit_len2(len2)) [[likely]] {
        v.color = light_object_diffuse(*d.colors.lighting, *ol, n, len2);
        continue;
      }
    }
    const LitColor lc = d.stage.light(d.mesh, d.colors, i, false);
    v.color = lc.primary;
    if (d.colors.split) store_.tex(d.base + i).spec = lc.secondary;
  }
}

}  // namespace lr
