// The front end's lane: the common triangle of a draw (one-sided, Gouraud or one colour, inside
// every plane, the edge table neither full nor banded nor signed) culled, lit and binned in a
// small loop of its own; and the lighting of a drawn triangle's vertices on first use.
#include "lineraster/core/binning/bin_lane.hpp"
#include "lineraster/core/binning/front_end.hpp"
#include "lineraster/core/binning/mesh_draw.hpp"

namespace lr {

// The lane, from triangle t on: one-sided, Gouraud or one colour (no per-triangle colours),
// inside every plane (a draw with no vertex outside one skips the outcode tests), the edge table
// neither full nor banded nor signed. Culled on its facing first, its pending vertices lit,
// appended to its strip's bucket, counted in locals. Returns the first triangle it leaves to
// draw_triangle() (or the count). Its own small stack frame, never live with draw_triangle()'s
// locals.
uint32_t FrontEnd::lane_triangles(MeshDraw& d, uint32_t t) {
  if (edges_.banding()) return t;  // (set only by draw_triangle())
  if constexpr (kBinLaneAsm) {
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
    int32_t r0, r1;
    if (!edges_.covers(v0, v1, v2, r0, &r1) ||
        (r0 == r1 && kOneCentreTest && edges_.misses_its_centre(v0, v1, v2))) {
      ++stats_.culled_offscreen;
      continue;
    }
    if (run.full()) [[unlikely]]
      break;
    if (pending && (v0.color_pending | v1.color_pending | v2.color_pending) != 0)
      light_corners(d, *tp);
    BinnedTriangle& bt = run.add(r0);
    const auto first = static_cast<uint16_t>(d.base);
    // The y read again for the order (on Armv6-M, kept from the tests above, they took stack
    // slots in the loop that most faces leave at the facing: 17 instructions a triangle on S1).
    asm volatile("" ::: "memory");
    store_binned(bt.v, static_cast<uint16_t>(first + i0), static_cast<uint16_t>(first + i1),
                 static_cast<uint16_t>(first + i2), v1.y - v0.y, v2.y - v0.y);
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

// lane_triangles() through bin_lane_asm(): its list of vertices to light lit each time it
// stops; the triangle it leaves to draw_triangle() (an index out of range, a full table)
// returned to the caller.
uint32_t FrontEnd::lane_run_triangles(MeshDraw& d, uint32_t t) {
  const std::array<uint16_t, 3>* const tris = d.mesh.triangles.data();
  const std::array<uint16_t, 3>* tp = tris + t;
  const std::array<uint16_t, 3>* const end = tris + d.mesh.triangles.size();
  if (tp == end) return t;
  const EdgeTable::Raw table = edges_.raw();
  ScreenVertex* list[kLightList];
  BinLane k{table.count,
            table.strip_reciprocal,
            table.buckets,
            table.triangles,
            static_cast<uint32_t>(d.base) * 0x10001u,
            store_.vertices_at(d.base),
            sizeof(ScreenVertex),
            height_,
            width_,
            list,
            list + kLightList - 3,
            0,
            0,
            table.capacity,
            static_cast<uint32_t>(d.mesh.positions.size()),
            end};
  const uint32_t count_before = table.count;
  // Up to the first triangle with an index out of range (draw_triangle() rejects it), in runs
  // that cannot fill the table (a full one: draw_triangle() bins in bands).
  const std::array<uint16_t, 3>* const stop = first_out_of_range(tp, end, k.n);
  while (tp != stop && k.count < k.capacity) {
    const auto room = static_cast<size_t>(k.capacity - k.count);
    k.end = static_cast<size_t>(stop - tp) > room ? tp + room : stop;
    bin_lane_asm(tp, k);  // (at k.end, or with the list full)
    light_list(d, std::span<ScreenVertex* const>(list, static_cast<size_t>(k.list - list)));
    k.list = list;
  }
  edges_.set_size(k.count);
  const auto done = static_cast<uint32_t>(tp - tris);
  const uint32_t binned = k.count - count_before;
  stats_.triangles_binned += binned;
  stats_.binned_inputs += binned;
  stats_.culled_zero_area += k.zero;
  stats_.culled_offscreen += k.offscreen;
  stats_.culled_backface += done - t - binned - k.zero - k.offscreen;
  return done;
}

// light_list() with a loop without the clamps for lights that cannot pass 1 (OneDiffuseLight::
// never_clamps()), but not where the code is built for size.
#if defined(__OPTIMIZE_SIZE__)
constexpr bool kOneLightUnclamped = false;
#else
constexpr bool kOneLightUnclamped = true;
#endif

// The vertices bin_lane_asm() found waiting for their colour (their flags cleared), lit as
// light_corners() lights them (a copy of its code: through one function the C lane, which
// Armv6-M runs, took 2 % longer on S1 and S1x): the common case here (diffuse directional lights in
// model space, a unit normal, one colour), the others through light_other() (out of line). One
// light, the usual draw, by a loop of its own that holds it in registers (OneDiffuseLight).
void FrontEnd::light_list(MeshDraw& d, std::span<ScreenVertex* const> list) {
  const ObjectLights* const ol = d.diffuse_lights;
  ScreenVertex* const base = store_.vertices_at(d.base);
  const Normal16* const normals = d.mesh.normals.data();
  // A vertex's normal from its byte offset in the store, without the division by 24 that its
  // index takes: 24 bytes a vertex, 6 a normal.
  static_assert(sizeof(ScreenVertex) == 4 * sizeof(Normal16));
  auto normal_of = [base, normals](const ScreenVertex* v) -> const Normal16& {
    const auto offset =
        static_cast<size_t>(reinterpret_cast<const char*>(v) - reinterpret_cast<const char*>(base));
    return *reinterpret_cast<const Normal16*>(reinterpret_cast<const char*>(normals) + offset / 4);
  };
  if (ol != nullptr && ol->count == 1) {
    const OneDiffuseLight one(*d.colors.lighting, *ol);
    auto run = [&]<bool kClamp>() {
      for (ScreenVertex* const v : list) {
        const Normal16& n = normal_of(v);
        const uint32_t len2 = normal_len2(n);
        if (unit_len2(len2)) [[likely]]
          v->color = one.template operator()<kClamp>(n, len2);
        else
          light_other(d, static_cast<uint32_t>(v - base));
      }
    };
    // Without the clamps where no sum can pass 1 (9 instructions a vertex on Armv7-M), but not
    // where the code is built for size (a second loop).
    if (kOneLightUnclamped && one.never_clamps())
      run.template operator()<false>();
    else
      run.template operator()<true>();
    return;
  }
  for (ScreenVertex* const v : list) {
    if (ol != nullptr) {
      const Normal16& n = normal_of(v);
      const uint32_t len2 = normal_len2(n);
      if (unit_len2(len2)) [[likely]] {
        v->color = light_object_diffuse(*d.colors.lighting, *ol, n, len2);
        continue;
      }
    }
    light_other(d, static_cast<uint32_t>(v - base));
  }
}

// Vertex i of draw d lit through VertexStage::light: the cases light_list() does not take
// inline (out of line, off its loops' registers).
void FrontEnd::light_other(MeshDraw& d, uint32_t i) {
  const LitColor lc = d.light_vertex(i, false);
  store_.vertices_at(d.base)[i].color = lc.primary;
  if (d.colors.split) store_.tex(d.base + i).spec = lc.secondary;
}

// light_corners() with one light through OneDiffuseLight (on Armv6-M 6 instructions a vertex
// less), but not where the code is built for size (150 bytes more).
#if defined(__OPTIMIZE_SIZE__)
constexpr bool kOneLightCorners = false;
#else
constexpr bool kOneLightCorners = true;
#endif

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
        v.color = kOneLightCorners && ol->count == 1
                      ? OneDiffuseLight(*d.colors.lighting, *ol)(n, len2)
                      : light_object_diffuse(*d.colors.lighting, *ol, n, len2);
        continue;
      }
    }
    const LitColor lc = d.light_vertex(i, false);
    v.color = lc.primary;
    if (d.colors.split) store_.tex(d.base + i).spec = lc.secondary;
  }
}

}  // namespace lr
