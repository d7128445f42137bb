#include "lineraster/core/binning/front_end.hpp"

#include <algorithm>

#include "lineraster/core/binning/mesh_draw.hpp"

#include "lineraster/core/lighting/lighting_table.hpp"
#include "lineraster/core/vertex/vertex_stage.hpp"

namespace lr {

namespace {

// The checks of draw() (kInvalidArgument: nothing is added, nothing counted), and its plan.
// maps: FrontEndRoutines::maps (nullptr: the renderer refuses textured and Phong draws,
// kNotLinked, and links no test of their maps).
Status plan_draw(const Mesh& mesh, const DrawState& state, const LightSet& lights, DrawPlan& p,
                 const MapRoutines* maps) {
  const size_t n = mesh.positions.size();
  if (!mesh.valid_position_frac()) return Status::kInvalidArgument;
  if ((!mesh.normals.empty() && mesh.normals.size() != n) ||
      (!mesh.colors.empty() && mesh.colors.size() != n))
    return Status::kInvalidArgument;
  p.lit = state.lighting;
  // Phong is per-pixel lighting; unlit, it is the same as Gouraud.
  p.kind.phong = p.lit && state.shading == Shading::kPhong;
  p.gouraud = state.shading != Shading::kFlat && !p.kind.phong;
  if (p.lit && state.shading != Shading::kFlat && mesh.normals.empty())
    return Status::kInvalidArgument;
  p.textured = state.texture != nullptr;
  // Unlit meshes without vertex colours have one colour: no colour planes needed.
  p.kind.color_planes = p.gouraud && (p.lit || !mesh.colors.empty() || p.textured);
  p.kind.position = !lights.normal_only();
  if ((p.textured || p.kind.phong) && maps != nullptr &&
      maps->check(mesh, state, lights, p) != Status::kOk)
    return Status::kInvalidArgument;
  // Textured, lit and modulated: primary and specular colours kept apart (GL's separate
  // specular colour), so that the texel modulates the primary only.
  p.split = p.textured && p.lit && state.sampler.env == TexEnv::kModulate;
  p.uv = p.textured || (p.kind.phong && state.normal_map != nullptr);
  p.two_sided = p.lit && lights.two_sided && !p.kind.phong;  // Phong flips at setup
  return Status::kOk;
}

}  // namespace

bool FrontEndParts::maps_store_missing(const FrontEnd& fe, const DrawPlan& p,
                                       const DrawState& state) {
  return (p.uv && !fe.store_.has_tex()) || ((p.textured || p.kind.phong) && !fe.active_extra_) ||
         (p.kind.phong &&
          (!fe.store_.has_surfaces() || !fe.records_.has_pixel_lights() ||
           (state.pixel_lighting == PixelLighting::kTable && !fe.records_.has_lighting_tables())));
}

Status FrontEndParts::check_maps(const Mesh& mesh, const DrawState& state, const LightSet& lights,
                                 const DrawPlan& p) {
  auto invalid = [](const Texture& t) { return validate(t) != Status::kOk; };
  const size_t n = mesh.positions.size();
  if (p.textured) {
    if (invalid(*state.texture)) return Status::kInvalidArgument;
    if (state.sampler.mip != MipMode::kNone && state.texture->level_count < 2)
      return Status::kInvalidArgument;
  }
  if ((p.textured || (p.kind.phong && state.normal_map)) && !mesh.uvs.empty() &&
      mesh.uvs.size() != n)
    return Status::kInvalidArgument;
  if (p.kind.phong) {
    if (state.envmap && invalid(*state.envmap)) return Status::kInvalidArgument;
    if (state.normal_map &&
        (invalid(*state.normal_map) || mesh.tangents.size() != n || mesh.uvs.size() != n))
      return Status::kInvalidArgument;
    if (state.pixel_lighting == PixelLighting::kTable &&
        (!lights.normal_only() || state.table.size < kMinLightingTable ||
         state.table.size > kMaxLightingTable))
      return Status::kInvalidArgument;
  }
  return Status::kOk;
}

namespace {

// Whether a lit Gouraud or textured draw can be lit in model space alone (a renderer without
// RendererFeatures::world_lighting): directional lights and the infinite viewer (no position), a
// rigid model matrix (the vertex stage's test, VertexStage::object_lights) and unit normals (its
// per-vertex test, VertexStage::light).
bool model_space_lighting(const Mesh& mesh, const Mat4& model, bool position) {
  if (position) return false;
  NormalRotation rows;
  if (!rigid_normal_rows(normal_matrix(model), rows)) return false;
  return std::ranges::all_of(mesh.normals, [](const Normal16& n) { return unit_normal(n); });
}

// Whether the draw's triangles have colours of their own, not planes (MeshDraw::flat_colors):
// flat shading, or an unlit mesh's one colour.
bool needs_flat_colors(const DrawPlan& p) {
  return !p.kind.phong && (!p.gouraud || !p.kind.color_planes);
}

}  // namespace

// Whether a mesh of n vertices can be drawn only through the vertex cache: larger than a store
// it needs, which is large enough for the cache.
bool FrontEnd::needs_cache(size_t n, const DrawPlan& plan) const {
  return !store_.takes_mesh(n, plan.kind.phong, plan.uv, false) &&
         store_.takes_mesh(n, plan.kind.phong, plan.uv);
}

Status FrontEnd::configure(const FrontEndStorage& s, int width, int height, int strip_height,
                           const FrontEndRoutines* routines) {
  configured_ = false;
  phase_ = Phase::kIdle;
  if (routines == nullptr || width < 1 || height < 1 || width > kMaxViewport ||
      height > kMaxViewport)
    return Status::kInvalidArgument;
  if (strip_height < 1 || strip_height > 32) return Status::kInvalidArgument;
  if (s.draws.size() > 256) return Status::kInvalidArgument;
  // A renderer without a vertex, triangle or draw record could take no draw at all.
  if (s.draws.empty() || s.vertices.empty() || s.triangles.empty()) return Status::kStoreTooSmall;
  if (!edges_.configure(s.triangles, s.triangle_colors, s.buckets, s.strip_inputs, width, height,
                        strip_height))
    return Status::kStoreTooSmall;
  // Strip signatures asked of a renderer that leaves them out (RendererFeatures).
  if (!s.strip_inputs.empty() && routines->sign == nullptr) return Status::kNotLinked;
  store_.configure(s.vertices, s.surfaces, s.tex_vertices, kMaxStoreEntries);
  records_.configure(s.draws, s.lighting_tables, s.pixel_lights);
  active_extra_ = s.active_extra;
  width_ = width;
  height_ = height;
  strip_height_ = strip_height;
  guard_.gx = 8192 / width > 1 ? 8192 / width : 1;
  guard_.gy = 8192 / height > 1 ? 8192 / height : 1;
  routines_ = routines;
  configured_ = true;
  return Status::kOk;
}

Status FrontEnd::begin_frame(const Camera& camera, const LightSet& lights, Rgb8 background) {
  if (!configured_) return Status::kNotConfigured;
  phase_ = Phase::kIdle;  // until this frame is begun: a failed begin abandons the last frame
  if (lights.count > kMaxLights) return Status::kInvalidArgument;
  if (camera.fine_projection != nullptr && !camera.fine_projection->valid())
    return Status::kInvalidArgument;
  camera_ = camera;
  lights_ = lights;
  background_ = background;
  store_.clear();
  records_.begin_frame(&camera_.view, lights_.two_sided);
  overflow_ = false;
  refused_triangles_ = refused_vertices_ = 0;
  // What every strip depends on: the viewport, the background, the camera (per-pixel lighting
  // and environment maps read it) and the lights (per-pixel lighting).
  edges_.begin_frame(edges_.signing() ? routines_->sign->frame(*this) : 0);
  stats_ = FrameStats{};
  stats_.bands = 1;
  stats_.bytes_per_vertex = sizeof(ScreenVertex);
  stats_.bytes_per_binned_triangle = sizeof(BinnedTriangle);
  refused_ = Status::kOk;
  phase_ = Phase::kOpen;
  return Status::kOk;
}

Outcome FrontEnd::bin(uint16_t a, uint16_t b, uint16_t c, uint8_t draw, Rgb8 flat, Rgb8 flat_spec,
                      Cull cull, const int32_t* rows, bool cached) {
  return bin_as<false>(a, b, c, draw, flat, flat_spec, cull, rows, cached);
}

Outcome FrontEnd::bin_lean(uint16_t a, uint16_t b, uint16_t c, uint8_t draw, Rgb8 flat,
                           Rgb8 flat_spec, Cull cull, const int32_t* rows) {
  return bin_as<true>(a, b, c, draw, flat, flat_spec, cull, rows, false);
}

template <bool kLean>
Outcome FrontEnd::bin_as(uint16_t a, uint16_t b, uint16_t c, uint8_t draw, Rgb8 flat,
                         Rgb8 flat_spec, Cull cull, const int32_t* rows, bool cached) {
  const ScreenVertex& v0 = store_.vertex(a);
  const ScreenVertex& v1 = store_.vertex(b);
  const ScreenVertex& v2 = store_.vertex(c);
  int32_t classified[2] = {0, 0};
  if (rows == nullptr) {
    const Outcome result = edges_.classify(v0, v1, v2, cull, classified[0], classified[1]);
    if (result != Outcome::kBinned) return result;
    rows = classified;
  }
  // Locals, not classify()'s outputs: kept in registers.
  int32_t r0 = rows[0], r1 = rows[1];
  if constexpr (kLean) {
    // No band: a full table drops the triangle (the loop below without bands).
    (void)draw;
    (void)r1;
    (void)cached;
    if (edges_.full()) {
      edges_.set_dropped();
      return Outcome::kCapacity;
    }
  } else {
    // Binning a band: another band's triangle is binned there; one from above starts here.
    // (One pass: the band is the viewport, to which classify() clamped the rows already.)
    if (edges_.banding()) [[unlikely]] {
      if (edges_.outside_window(r0, r1)) return Outcome::kBinned;
      edges_.clamp_to_window(r0, r1);
    }
    while (edges_.full()) {
      // The band (the first one: the whole frame, until now) ends higher up, until it is one
      // strip (below the minimum, or without bands: the triangle is dropped, and counted). From
      // now on each draw keeps only the vertices its binned triangles use.
      if (routines_->bands == nullptr) {
        edges_.set_dropped();
        return Outcome::kCapacity;
      }
      edges_.start_banding();
      if (!routines_->bands->shrink(*this)) {
        edges_.set_dropped();
        return Outcome::kCapacity;
      }
      if (r0 > edges_.window_last()) return Outcome::kBinned;
      if (r1 > edges_.window_last()) r1 = edges_.window_last();
    }
    if (edges_.signing()) routines_->sign->triangle(*this, a, b, c, draw, flat, flat_spec, r0, r1);
    // Through the vertex cache: the triangle's vertices are copied out of it on first use.
    if (cached) {
      const auto persist = routines_->cache->persist;
      if (!(store_.*persist)(a) || !(store_.*persist)(b) || !(store_.*persist)(c)) {
        overflow_ = true;
        return Outcome::kVertexCapacity;
      }
    }
  }
  // A triangle from above the band was counted in its own band: not counted again (only once
  // it is added: a dropped one was never counted here).
  edges_.note_carried(rows[0]);
  BinnedTriangle& t = edges_.add(r0);
  store_binned(t.v, a, b, c, v1.y - v0.y, v2.y - v0.y, draw_sorted_);
  if (draw_colors_) edges_.set_colors({flat, flat_spec});
  ++stats_.triangles_binned;
  return Outcome::kBinned;
}

// One triangle of a draw: culled, lit (lit Gouraud: its vertices on first use; flat: its face),
// clipped when it crosses a plane, and binned. This and the two ends below are always inlined
// into draw(): one loop body, whose locals share one stack frame.
template <bool kTwoSided, bool kCache, bool kClip, bool kBandsOrSigns>
void FrontEnd::draw_triangle(MeshDraw& d, const std::array<uint16_t, 3>& tri) {
  const size_t n = d.mesh.positions.size();
  if (tri[0] >= n || tri[1] >= n || tri[2] >= n) {
    ++stats_.rejected_invalid;
    return;
  }
  uint16_t vi[3] = {static_cast<uint16_t>(d.base + tri[0]), static_cast<uint16_t>(d.base + tri[1]),
                    static_cast<uint16_t>(d.base + tri[2])};
  if (kCache && d.cached) {
    // By value: vi stays in registers.
    const std::array<uint16_t, 3> c = (store_.*routines_->cache->corners)(
        d.stage, d.mesh, d.colors, tri, stats_.vertices_transformed, stats_.vertices_wide);
    vi[0] = c[0];
    vi[1] = c[1];
    vi[2] = c[2];
  }
  ScreenVertex* const sv[3] = {&store_.vertex(vi[0]), &store_.vertex(vi[1]), &store_.vertex(vi[2])};
  const uint8_t oc_or = sv[0]->outcode | sv[1]->outcode | sv[2]->outcode;
  const uint8_t oc_and = sv[0]->outcode & sv[1]->outcode & sv[2]->outcode;
  if (oc_or & kClipOutOfRange) {
    ++stats_.rejected_invalid;
    return;
  }
  if (oc_and != 0) {
    ++stats_.clipped_away;
    return;
  }
  if constexpr (!kClip) {
    // A renderer without the clipper (RendererFeatures::clipping): dropped, counted, and the
    // frame's status (render()) kNotLinked unless a draw was refused before.
    if (oc_or != 0) {
      ++stats_.dropped_unclipped;
      if (refused_ == Status::kOk) refused_ = Status::kNotLinked;
      return;
    }
  }
  int32_t rows[2] = {0, 0};
  bool classified = false;
  if (d.plan.lit && d.plan.gouraud) {
    // Vertices are lit on first use by a triangle that is drawn: those only culled, off-screen
    // or covering no pixel centre are never lit. bin() takes the rows classify() found here.
    if (oc_or == 0 && !d.plan.two_sided) {
      const Outcome r = edges_.classify(*sv[0], *sv[1], *sv[2], d.state.cull, rows[0], rows[1]);
      classified = true;
      if (r != Outcome::kBinned) {
        count_outcome(stats_, false, r);
        return;
      }
      // Another band's triangle: binned there, not lit here.
      if (edges_.outside_window(rows[0], rows[1])) {
        count_outcome(stats_, true, Outcome::kBinned);
        return;
      }
    }
    for (int k = 0; k < 3; ++k) {
      if (sv[k]->color_pending) {
        const LitColor lc = d.light_vertex(tri[static_cast<size_t>(k)], false);
        sv[k]->color = lc.primary;
        if (d.colors.split) store_.tex(vi[k]).spec = lc.secondary;
        sv[k]->color_pending = 0;
      }
    }
  }
  // Two-sided lighting: back faces are lit with the negated normal (GL decides per polygon).
  ClipCoord clip[3];
  if (oc_or != 0)
    for (int k = 0; k < 3; ++k)
      clip[k] = d.stage.clip(d.mesh.positions[tri[static_cast<size_t>(k)]]);
  bool back = false;
  if (kTwoSided && d.plan.two_sided)
    back = oc_or == 0 ? back_facing(signed_area2(*sv[0], *sv[1], *sv[2]))
                      : !routines_->front_facing(clip);
  if (back && d.plan.gouraud)
    for (int k = 0; k < 3; ++k)
      d.back_colors[k] = d.light_vertex(tri[static_cast<size_t>(k)], true);
  Rgb8 flat{}, flat_spec{};
  if (d.own_colors != nullptr) d.own_colors(d, tri, *sv[2], back, flat, flat_spec);
  if (oc_or == 0) {
    bin_inside<!kCache && !kBandsOrSigns>(d, vi, sv, back && d.plan.gouraud, flat, flat_spec,
                                          classified ? rows : nullptr, kCache && d.cached);
    return;
  }
  clip_and_bin(d, vi, sv, clip, oc_or, back && d.plan.gouraud, flat, flat_spec);
}

// A triangle inside every plane. A two-sided Gouraud back face gets its own copies of its
// vertices, with the back colours.
template <bool kLeanBin>
void FrontEnd::bin_inside(MeshDraw& d, uint16_t (&vi)[3], ScreenVertex* const (&sv)[3],
                          bool back_copies, Rgb8 flat, Rgb8 flat_spec, const int32_t* rows,
                          bool cached) {
  int32_t classified[2] = {0, 0};  // (read by bin() below: not scoped to the block)
  if (back_copies) {
    // Binning a band: a triangle of another band gets no copies (they would fill the store with
    // vertices no triangle of the band uses). Its tests are bin()'s, done once here.
    if (edges_.banding() && rows == nullptr) [[unlikely]] {
      const Outcome r =
          edges_.classify(*sv[0], *sv[1], *sv[2], d.state.cull, classified[0], classified[1]);
      if (r != Outcome::kBinned) {
        count_outcome(stats_, false, r);
        return;
      }
      rows = classified;
    }
    if (edges_.banding() && edges_.outside_window(rows[0], rows[1])) [[unlikely]] {
      count_outcome(stats_, true, Outcome::kBinned);
      return;
    }
    if (!store_.vertices_fit(3) || (d.plan.uv && !store_.tex_fit(3))) {
      overflow_ = true;
      count_outcome(stats_, false, Outcome::kVertexCapacity);
      return;
    }
    const size_t first = store_.take(3);
    for (int k = 0; k < 3; ++k) {
      const size_t at = first + static_cast<size_t>(k);
      ScreenVertex& nv = store_.vertex(at);
      nv = *sv[k];
      nv.color = d.back_colors[k].primary;
      if (d.plan.uv) {
        store_.tex(at) = store_.tex(vi[k]);
        store_.tex(at).spec = d.back_colors[k].secondary;
      }
      vi[k] = static_cast<uint16_t>(at);
    }
  }
  // Corners in the vertex cache (back-face copies are in the store already).
  Outcome r;
  if constexpr (kLeanBin)
    r = bin_lean(vi[0], vi[1], vi[2], d.draw, flat, flat_spec, d.state.cull, rows);
  else
    r = bin(vi[0], vi[1], vi[2], d.draw, flat, flat_spec, d.state.cull, rows,
            cached && !back_copies);
  count_outcome(stats_, r == Outcome::kBinned, r);
}

// A triangle crossing a plane: clipped in homogeneous space, the polygon's vertices projected
// into the vertex store, binned as a fan. Clip coordinates are recomputed from the d.mesh rather
// than stored per vertex: only triangles that cross a plane pay for it.
void FrontEnd::clip_and_bin(MeshDraw& d, const uint16_t (&vi)[3], ScreenVertex* const (&sv)[3],
                            const ClipCoord (&clip)[3], uint8_t oc_or, bool back_colored, Rgb8 flat,
                            Rgb8 flat_spec) {
  ++stats_.clipped;
  const ClipPolygon poly(clip_.polygon.data(), kMaxClipVertices);
  for (size_t k = 0; k < 3; ++k) {
    poly[k].p = clip[k];
    poly[k].color = back_colored ? d.back_colors[k].primary : sv[k]->color;
    if (d.plan.uv) {
      const TexVertex& tv = store_.tex(vi[k]);
      poly[k].spec = back_colored ? d.back_colors[k].secondary : tv.spec;
      poly[k].u = tv.u;
      poly[k].v = tv.v;
    } else {
      poly[k].spec = Color15{};
      poly[k].u = poly[k].v = 0;
    }
    if (d.plan.kind.phong) poly[k].surface = store_.surface(vi[k]);
    poly[k].corner = static_cast<uint8_t>(k + 1);
    poly[k].outcode = sv[k]->outcode;
  }
  const int m = routines_->clip(poly, ClipPolygon(clip_.scratch.data(), kMaxClipVertices), 3, oc_or,
                                d.stage.guard());
  if (m < 3) {
    ++stats_.clipped_away;
    return;
  }
  if (!store_.mesh_fits(static_cast<size_t>(m), d.plan.kind.phong, d.plan.uv)) {
    overflow_ = true;
    ++stats_.dropped_vertex_capacity;
    return;
  }
  const auto first = static_cast<uint16_t>(store_.count());
  int projected = 0;
  for (size_t k = 0; k < static_cast<size_t>(m); ++k) {
    const size_t at = first + k;
    ScreenVertex& nv = store_.vertex(at);
    // A corner the clipper kept is inside every plane (outcode 0: projected already): the
    // same position as in the triangles around it that need no clipping.
    if (poly[k].corner != 0) {
      nv = *sv[poly[k].corner - 1];
      ++projected;
    } else if (d.stage.project(poly[k].p, nv)) {
      ++projected;
    }
    nv.color = poly[k].color;
    nv.outcode = 0;
    nv.color_pending = 0;
    if (d.plan.kind.phong) store_.surface(at) = poly[k].surface;
    if (d.plan.uv) store_.tex(at) = TexVertex{poly[k].u, poly[k].v, poly[k].spec, 0};
  }
  if (projected != m) {
    ++stats_.clipped_away;
    return;
  }
  // Binning a band: a polygon wholly outside it is not kept (its vertices would fill the store).
  if (edges_.banding() && routines_->bands->outside(*this, first, m, d.state.cull)) [[unlikely]]
    return;
  store_.take(static_cast<size_t>(m));
  bool binned = false;
  Outcome last = Outcome::kClippedAway, dropped = Outcome::kBinned;
  for (int k = 1; k + 1 < m; ++k) {
    const Outcome r =
        bin(first, static_cast<uint16_t>(first + k), static_cast<uint16_t>(first + k + 1), d.draw,
            flat, flat_spec, d.state.cull);
    if (r == Outcome::kBinned)
      binned = true;
    else
      last = r;
    if (r == Outcome::kCapacity || r == Outcome::kVertexCapacity) dropped = r;
  }
  // A clipped triangle binned in part and dropped in part counts as dropped (found by the
  // pipeline fuzzer: render() reported kCapacity with nothing counted).
  if (dropped != Outcome::kBinned)
    count_outcome(stats_, false, dropped);
  else
    count_outcome(stats_, binned, last);
}
Status FrontEnd::draw(const Mesh& mesh, const Mat4& model, const Material& material,
                      const DrawState& state, const FineMat4* fine_model, FineComposeFn compose) {
  if (const Status st = frame_status(); st != Status::kOk) return st;
  if (fine_model != nullptr) {
    if (!fine_model->valid() || compose == nullptr) return refuse(Status::kInvalidArgument);
    fine_compose_ = compose;
  }
  // Refused whole, with nothing added and only the draw counted: arguments that disagree, a
  // state the renderer links no routine for, a store the draw needs that was not given.
  DrawPlan plan;
  if (plan_draw(mesh, state, lights_, plan, routines_->maps) != Status::kOk)
    return refuse(Status::kInvalidArgument);
  const bool triangle_colors = !plan.gouraud && !plan.kind.phong;  // flat: colours per triangle
  // (Phong draws light per pixel: their position is the span set's own dimension.)
  if (!admitted(state, plan.kind) ||
      (triangle_colors && plan.lit && routines_->face_light == nullptr) ||
      (plan.lit && !plan.kind.phong && plan.kind.position && routines_->point_light == nullptr) ||
      ((plan.uv || plan.kind.phong) &&
       (routines_->attributes == nullptr || routines_->maps == nullptr)) ||
      (plan.two_sided && routines_->front_facing == nullptr) ||
      (needs_flat_colors(plan) &&
       (routines_->flat == nullptr || routines_->one_color == nullptr)) ||
      (plan.lit && !routines_->specular && has_specular(material)) ||
      (plan.lit && plan.gouraud && !routines_->world_lighting &&
       !model_space_lighting(mesh, model, plan.kind.position)) ||
      (routines_->cache == nullptr && needs_cache(mesh.positions.size(), plan)))
    return refuse(Status::kNotLinked);
  if (((plan.textured || plan.kind.phong) && routines_->maps->store_missing(*this, plan, state)) ||
      (triangle_colors && !edges_.has_colors()))
    return refuse(Status::kMissingStore);
  const size_t n = mesh.positions.size();
  const auto tri_count = static_cast<uint32_t>(mesh.triangles.size());
  stats_.triangles_in += tri_count;
  // A mesh larger than the stores needs room for the vertex cache (docs/bands.md).
  if (!store_.takes_mesh(n, plan.kind.phong, plan.uv))
    return refuse(Status::kCapacity, tri_count, true);
  // Without a draw record the whole draw is dropped, and counted.
  if (records_.full()) return refuse(Status::kCapacity, tri_count, false);
  const uint8_t draw_index =
      records_.add(state, plan.kind.color_planes, static_cast<uint16_t>(store_.count()));
  DrawRecord& record = records_[draw_index];
  if (plan.textured) routines_->maps->record(record, state);
  record.triangle_colors = triangle_colors;
  if (!triangle_colors && !plan.kind.color_planes && !plan.kind.phong)
    record.color = routines_->one_color(material.diffuse);

  const Vec3 view_dir{camera_.view.m[2][0], camera_.view.m[2][1], camera_.view.m[2][2]};
  PreparedLighting& pl = lighting_;
  if (plan.lit)
    routines_->prepare(lights_, material, view_dir, camera_.eye, pl);
  else
    pl = PreparedLighting{};
  if (plan.kind.phong && routines_->phong(records_, state, pl, record) != Status::kOk) {
    records_.drop_last();
    return refuse(Status::kCapacity, tri_count, false);
  }
  if (edges_.signing())
    routines_->sign->draw(*this, draw_index, plan.kind.phong ? &material : nullptr);
  // Only bands read the draw's arguments again (replay).
  if (routines_->bands != nullptr)
    routines_->bands->record(record.call, mesh, model, material, state, fine_model);
  if (!overflow_)
    run_mesh(draw_index, mesh, model, material, state, plan, pl, fine_model);
  else if (routines_->bands == nullptr)  // no band will bin it: dropped, and counted
    stats_.dropped_vertex_capacity += tri_count;
  return Status::kOk;
}

void FrontEnd::run_mesh(uint8_t index, const Mesh& mesh, const Mat4& model,
                        const Material& material, const DrawState& state, const DrawPlan& plan,
                        const PreparedLighting& pl, const FineMat4* fine_model) {
  records_[index].first_vertex = static_cast<uint16_t>(store_.count());
  one_hue(pl, records_[index].hue);  // (unlit: no diffuse colour, no hue; lanes Gouraud reads it)
  draw_colors_ = records_[index].triangle_colors;
  if constexpr (kBinnedSorted) draw_sorted_ = sorts_for_lanes(records_[index]);
  const size_t n = mesh.positions.size();
  const bool phong = plan.kind.phong, uv = plan.uv;
  // A mesh larger than the free store goes through the vertex cache at the top of the stores.
  const bool cached = !store_.mesh_fits(n, phong, uv);
  if (cached && (routines_->cache == nullptr || !(store_.*routines_->cache->begin)(phong, uv))) {
    overflow_ = true;
    stats_.dropped_vertex_capacity += static_cast<uint32_t>(mesh.triangles.size());
    return;
  }
  // (A fine model: fine_compose_ is set, draw() took it with the model.)
  const VertexStage stage(camera_, model, guard_, width_, height_,
                          mesh.bound != 0 ? mesh.bound : position_bound(mesh.positions.data(), n),
                          mesh.position_fraction_bits(), fine_model, fine_compose_);
  VertexColors colors;
  colors.lit = plan.lit;
  colors.pending = plan.lit && plan.gouraud;
  colors.split = plan.split;
  colors.surfaces = phong;
  colors.need_position = pl.needs_position();
  colors.tangents = phong && state.normal_map != nullptr;
  colors.material = material.diffuse;
  colors.lighting = &pl;
  colors.point = routines_->point_light;
  colors.attributes = routines_->attributes;
  // Lit Gouraud under directional lights and a rigid model: the lights turned into model space.
  if (colors.pending && !colors.need_position &&
      stage.object_lights(pl, object_lights_, routines_->object_lights))
    colors.object = &object_lights_;
  const size_t base = store_.count();
  draw_first_triangle_ = edges_.size();
  uint8_t clip_outcodes = 0;  // the OR of the draw's outcodes (through the cache: unknown)
  if (!cached) {
    store_.take(n);
    stats_.vertices_transformed += static_cast<uint32_t>(n);
    const TransformSummary done = stage.transform(mesh, colors, store_.vertices_at(base),
                                                  phong ? store_.surfaces_at(base) : nullptr,
                                                  uv ? store_.tex_at(base) : nullptr);
    stats_.vertices_wide += done.wide;
    clip_outcodes = done.outcodes;
  }

  MeshDraw d{mesh, state, stage, plan, colors, base, index, cached};
  d.face_light = routines_->face_light;
  d.light = routines_->light;
  if (needs_flat_colors(plan)) d.own_colors = routines_->flat;
  d.clipping = cached || clip_outcodes != 0;
  if (colors.object != nullptr && !colors.object->specular && !colors.split)
    d.diffuse_lights = colors.object;
  triangle_loop(d);
  if (cached) store_.end_cache();
  if (edges_.banding()) routines_->bands->compact(*this, base, phong, uv);
}

// The lane (lane.cpp), but not where the code is built for size: there the general loop takes
// every triangle, the same frame without the lane's code (1.1 KB at -Os on Cortex-M4F) for about
// 95 instructions more per input triangle (the footprint's torus: 3.3 % of its frame).
#if defined(__OPTIMIZE_SIZE__)
constexpr bool kLane = false;
#else
constexpr bool kLane = true;
#endif

// The triangle loop: the lane (lane.cpp) for a draw's common triangles, general_triangles() for
// the others and for every triangle of a draw the lane does not take (two-sided, flat-shaded,
// through the vertex cache, signed). Out of line and small: the lane's frames and the general
// path's are never on the stack together.
void FrontEnd::triangle_loop(MeshDraw& d) {
  const auto count = static_cast<uint32_t>(d.mesh.triangles.size());
  // (The lane stores the vertices sorted: not two-sided Phong's, whose setup reads the winding.)
  if (!kLane || d.cached || d.plan.two_sided || draw_colors_ || edges_.signing() ||
      (kBinnedSorted && records_[d.draw].two_sided)) {
    routines_->triangles(*this, d, 0, count);
    return;
  }
  for (uint32_t t = 0; t < count;) {
    t = lane_triangles(d, t);
    if (t < count) t = routines_->triangles(*this, d, t, t + 1);
  }
}

// Triangles [t, end) through draw_triangle(), inlined here: one stack frame for its locals.
template <bool kTwoSided, bool kCache, bool kClip, bool kBandsOrSigns>
uint32_t FrontEnd::general_triangles(MeshDraw& d, uint32_t t, uint32_t end) {
  for (; t < end; ++t)
    draw_triangle<kTwoSided, kCache, kClip, kBandsOrSigns>(d, d.mesh.triangles[t]);
  return t;
}

template <bool kTwoSided, bool kCache, bool kClip, bool kBandsOrSigns>
uint32_t FrontEndParts::triangles(FrontEnd& fe, MeshDraw& d, uint32_t t, uint32_t end) {
  return fe.general_triangles<kTwoSided, kCache, kClip, kBandsOrSigns>(d, t, end);
}
template uint32_t FrontEndParts::triangles<false, false, false, false>(FrontEnd&, MeshDraw&,
                                                                       uint32_t, uint32_t);
template uint32_t FrontEndParts::triangles<false, false, false, true>(FrontEnd&, MeshDraw&,
                                                                      uint32_t, uint32_t);
template uint32_t FrontEndParts::triangles<false, false, true, false>(FrontEnd&, MeshDraw&,
                                                                      uint32_t, uint32_t);
template uint32_t FrontEndParts::triangles<false, false, true, true>(FrontEnd&, MeshDraw&, uint32_t,
                                                                     uint32_t);
template uint32_t FrontEndParts::triangles<false, true, false, false>(FrontEnd&, MeshDraw&,
                                                                      uint32_t, uint32_t);
template uint32_t FrontEndParts::triangles<false, true, false, true>(FrontEnd&, MeshDraw&, uint32_t,
                                                                     uint32_t);
template uint32_t FrontEndParts::triangles<false, true, true, false>(FrontEnd&, MeshDraw&, uint32_t,
                                                                     uint32_t);
template uint32_t FrontEndParts::triangles<false, true, true, true>(FrontEnd&, MeshDraw&, uint32_t,
                                                                    uint32_t);
template uint32_t FrontEndParts::triangles<true, false, false, false>(FrontEnd&, MeshDraw&,
                                                                      uint32_t, uint32_t);
template uint32_t FrontEndParts::triangles<true, false, false, true>(FrontEnd&, MeshDraw&, uint32_t,
                                                                     uint32_t);
template uint32_t FrontEndParts::triangles<true, false, true, false>(FrontEnd&, MeshDraw&, uint32_t,
                                                                     uint32_t);
template uint32_t FrontEndParts::triangles<true, false, true, true>(FrontEnd&, MeshDraw&, uint32_t,
                                                                    uint32_t);
template uint32_t FrontEndParts::triangles<true, true, false, false>(FrontEnd&, MeshDraw&, uint32_t,
                                                                     uint32_t);
template uint32_t FrontEndParts::triangles<true, true, false, true>(FrontEnd&, MeshDraw&, uint32_t,
                                                                    uint32_t);
template uint32_t FrontEndParts::triangles<true, true, true, false>(FrontEnd&, MeshDraw&, uint32_t,
                                                                    uint32_t);
template uint32_t FrontEndParts::triangles<true, true, true, true>(FrontEnd&, MeshDraw&, uint32_t,
                                                                   uint32_t);

Status FrontEnd::draw_screen(std::span<const ScreenVertex> vertices,
                             std::span<const std::array<uint16_t, 3>> triangles,
                             const DrawState& state, std::span<const TexVertex> tex) {
  if (const Status st = frame_status(); st != Status::kOk) return st;
  const bool uv = state.texture != nullptr;
  if (uv && tex.size() != vertices.size()) return refuse(Status::kInvalidArgument);
  if (!uv) tex = {};
  const bool gouraud = state.shading == Shading::kGouraud;
  if (!admitted(state, {false, gouraud, !lights_.normal_only()}) ||
      (uv && routines_->maps == nullptr))
    return refuse(Status::kNotLinked);
  if ((uv && (!store_.has_tex() || !active_extra_)) || (!gouraud && !edges_.has_colors()))
    return refuse(Status::kMissingStore);
  const auto tri_count = static_cast<uint32_t>(triangles.size());
  stats_.triangles_in += tri_count;
  if (vertices.size() > store_.capacity() || (uv && vertices.size() > store_.tex_capacity()))
    return refuse(Status::kCapacity, tri_count, true);
  if (records_.full()) return refuse(Status::kCapacity, tri_count, false);
  const uint8_t draw_index = records_.add(state, gouraud, static_cast<uint16_t>(store_.count()));
  if (uv) routines_->maps->record(records_[draw_index], state);
  records_[draw_index].triangle_colors = !gouraud;
  replay_screen_ = &FrontEnd::replay_screen;
  if (edges_.signing()) routines_->sign->draw(*this, draw_index, nullptr);
  DrawCall& call = records_[draw_index].call;
  call.mesh = Mesh{};
  call.mesh.triangles = triangles;
  call.screen = vertices;
  call.screen_tex = tex;
  call.model = Mat4{};
  call.fine_model = nullptr;
  call.material.set(Material{});
  call.state.set(state);
  call.is_screen = true;
  if (!overflow_)
    run_screen(draw_index, vertices, tex, triangles, state);
  else if (routines_->bands == nullptr)
    stats_.dropped_vertex_capacity += tri_count;
  return Status::kOk;
}

void FrontEnd::run_screen(uint8_t index, std::span<const ScreenVertex> vertices,
                          std::span<const TexVertex> tex,
                          std::span<const std::array<uint16_t, 3>> triangles,
                          const DrawState& state) {
  records_[index].first_vertex = static_cast<uint16_t>(store_.count());
  draw_colors_ = records_[index].triangle_colors;
  if constexpr (kBinnedSorted) draw_sorted_ = sorts_for_lanes(records_[index]);
  const size_t n = vertices.size();
  const bool uv = !tex.empty();
  if (!store_.mesh_fits(n, false, uv)) {
    overflow_ = true;
    stats_.dropped_vertex_capacity += static_cast<uint32_t>(triangles.size());
    return;
  }
  const size_t base = store_.take(n);
  draw_first_triangle_ = edges_.size();
  const int32_t limit = (kMaxViewport * 3) << kSubpixelBits;  // inside the coordinate budget
  for (size_t i = 0; i < n; ++i) {
    ScreenVertex v = vertices[i];
    if (v.w == 0) v.w = 1u << 16;
    bool ok = v.x > -limit && v.x < limit && v.y > -limit && v.y < limit && v.z <= kDepthMax;
    v.outcode = ok ? 0 : kClipOutOfRange;
    v.color_pending = 0;
    store_.vertex(base + i) = v;
    if (uv) store_.tex(base + i) = tex[i];
  }
  for (const std::array<uint16_t, 3>& tri : triangles) {
    if (tri[0] >= n || tri[1] >= n || tri[2] >= n) {
      ++stats_.rejected_invalid;
      continue;
    }
    const uint16_t vi[3] = {static_cast<uint16_t>(base + tri[0]),
                            static_cast<uint16_t>(base + tri[1]),
                            static_cast<uint16_t>(base + tri[2])};
    if ((store_.vertex(vi[0]).outcode | store_.vertex(vi[1]).outcode |
         store_.vertex(vi[2]).outcode) != 0) {
      ++stats_.rejected_invalid;
      continue;
    }
    const Rgb8 flat = to_rgb8_sat(store_.vertex(vi[2]).color);
    const Rgb8 flat_spec = uv ? to_rgb8_sat(store_.tex(vi[2]).spec) : Rgb8{};
    const Outcome r = bin(vi[0], vi[1], vi[2], index, flat, flat_spec, state.cull);
    count_outcome(stats_, r == Outcome::kBinned, r);
  }
  if (edges_.banding()) routines_->bands->compact(*this, base, false, uv);
}

// A clipped polygon's vertices, projected at [first, first + m) but not yet kept: true when no
// row of it touches the band, its pieces then counted as bin() would count them. Out of line:
// one copy for both triangle loops.
bool FrontEnd::polygon_outside_band(uint16_t first, int m, Cull cull) {
  int32_t ymin = store_.vertex(first).y, ymax = ymin;
  for (int k = 1; k < m; ++k) {
    const int32_t y = store_.vertex(first + static_cast<size_t>(k)).y;
    ymin = y < ymin ? y : ymin;
    ymax = y > ymax ? y : ymax;
  }
  if (!edges_.outside_window(first_row_below(ymin), last_row_at_or_above(ymax))) return false;
  bool binned = false;
  Outcome last = Outcome::kClippedAway;
  for (int k = 1; k + 1 < m; ++k) {
    int32_t r0 = 0, r1 = 0;
    const auto at = static_cast<size_t>(first) + static_cast<size_t>(k);
    const Outcome r = edges_.classify(store_.vertex(first), store_.vertex(at),
                                      store_.vertex(at + 1), cull, r0, r1);
    if (r == Outcome::kBinned)
      binned = true;
    else
      last = r;
  }
  count_outcome(stats_, binned, last);
  return true;
}

void FrontEnd::begin_bands() {
  FrameStats fresh;
  fresh.triangles_in = stats_.triangles_in;
  fresh.dropped_triangle_capacity = refused_triangles_;
  fresh.dropped_vertex_capacity = refused_vertices_;
  fresh.draws_refused_invalid = stats_.draws_refused_invalid;
  fresh.draws_refused_not_linked = stats_.draws_refused_not_linked;
  fresh.draws_refused_missing_store = stats_.draws_refused_missing_store;
  fresh.draws_refused_capacity = stats_.draws_refused_capacity;
  fresh.bytes_per_vertex = stats_.bytes_per_vertex;
  fresh.bytes_per_binned_triangle = stats_.bytes_per_binned_triangle;
  fresh.bytes_per_active_triangle = stats_.bytes_per_active_triangle;
  stats_ = fresh;
}

// One recorded draw run again for the band. Out of line: its locals (the prepared lighting
// above all) are on the stack only while it runs.
void FrontEnd::replay(uint8_t index) {
  const DrawCall& c = records_[index].call;
  const DrawState state = c.state.get();
  if (c.is_screen) {
    replay_screen_(*this, index, state);
    return;
  }
  const Material material = c.material.get();
  DrawPlan plan;
  plan_draw(c.mesh, state, lights_, plan, routines_->maps);  // passed in draw()
  PreparedLighting& pl = lighting_;
  const Vec3 view_dir{camera_.view.m[2][0], camera_.view.m[2][1], camera_.view.m[2][2]};
  if (plan.lit)
    routines_->prepare(lights_, material, view_dir, camera_.eye, pl);
  else
    pl = PreparedLighting{};
  run_mesh(index, c.mesh, c.model, material, state, plan, pl, c.fine_model);
}

Rgb8 FrontEndParts::one_color(Color15 c) {
  return to_rgb8_sat(c);
}

void FrontEndParts::flat_colors(const MeshDraw& d, const std::array<uint16_t, 3>& tri,
                                const ScreenVertex& last, bool back, Rgb8& flat, Rgb8& flat_spec) {
  d.flat_colors(tri, last, back, flat, flat_spec);
}

void FrontEndParts::record_call(DrawCall& call, const Mesh& mesh, const Mat4& model,
                                const Material& material, const DrawState& state,
                                const FineMat4* fine_model) {
  call.mesh = mesh;
  call.screen = {};
  call.model = model;
  call.fine_model = fine_model;
  call.material.set(material);
  call.state.set(state);
  call.is_screen = false;
}

void FrontEnd::replay_screen(FrontEnd& fe, uint8_t index, const DrawState& state) {
  const DrawCall& c = fe.records_[index].call;
  fe.run_screen(index, c.screen, c.screen_tex, c.mesh.triangles, state);
}

void FrontEnd::save_binning_counts() {
  const FrameStats& s = stats_;
  band_before_ = {
      s.culled_backface,  s.culled_zero_area,        s.culled_offscreen,          s.clipped_away,
      s.rejected_invalid, s.dropped_vertex_capacity, s.dropped_triangle_capacity, s.binned_inputs,
      s.clipped,          s.triangles_binned,        s.vertices_transformed};
}

void FrontEnd::restore_binning_counts() {
  const BinningCounts& b = band_before_;
  FrameStats& s = stats_;
  s.culled_backface = b.culled_backface;
  s.culled_zero_area = b.culled_zero_area;
  s.culled_offscreen = b.culled_offscreen;
  s.clipped_away = b.clipped_away;
  s.rejected_invalid = b.rejected_invalid;
  s.dropped_vertex_capacity = b.dropped_vertex_capacity;
  s.dropped_triangle_capacity = b.dropped_triangle_capacity;
  s.binned_inputs = b.binned_inputs;
  s.clipped = b.clipped;
  s.triangles_binned = b.triangles_binned;
  s.vertices_transformed = b.vertices_transformed;
}

Status FrontEnd::bin_band(int s0, int s1, bool keep_partial) {
  save_binning_counts();
  overflow_ = false;
  store_.clear();
  edges_.begin_band(s0, s1);
  for (size_t i = 0; i < records_.count() && (keep_partial || !overflow_); ++i)
    replay(static_cast<uint8_t>(i));
  const bool fit = !overflow_;
  overflow_ = true;  // the frame still needs bands
  stats_.triangles_binned -= edges_.carried();
  if (!fit && !keep_partial) {
    restore_binning_counts();
    ++stats_.band_retries;
    return Status::kCapacity;
  }
  // What becomes of each input triangle is counted in the first band; the pieces binned and
  // the vertices transformed in every band; what was dropped in the bands that dropped it.
  if (s0 != 0) {
    const uint32_t binned = stats_.triangles_binned, transformed = stats_.vertices_transformed;
    const uint32_t wide = stats_.vertices_wide;
    const uint32_t dropped_triangles = stats_.dropped_triangle_capacity;
    const uint32_t dropped_vertices = stats_.dropped_vertex_capacity;
    restore_binning_counts();
    stats_.triangles_binned = binned;
    stats_.vertices_transformed = transformed;
    stats_.vertices_wide = wide;
    stats_.dropped_triangle_capacity = dropped_triangles;
    stats_.dropped_vertex_capacity = dropped_vertices;
  }
  ++stats_.bands;
  return fit ? Status::kOk : Status::kCapacity;
}

bool FrontEndParts::shrink_band(FrontEnd& fe) {
  return fe.shrink_band();
}
void FrontEndParts::compact_vertices(FrontEnd& fe, size_t first_vertex, bool surfaces, bool tex) {
  fe.compact_vertices(first_vertex, surfaces, tex);
}
bool FrontEndParts::polygon_outside_band(FrontEnd& fe, uint16_t first, int m, Cull cull) {
  return fe.polygon_outside_band(first, m, cull);
}

// What every strip depends on: the viewport, the background, the camera (per-pixel lighting
// and environment maps read it) and the lights (per-pixel lighting).
uint32_t FrontEndParts::sign_frame(const FrontEnd& fe) {
  InputHash h;
  h.add(static_cast<uint32_t>(fe.width_) | static_cast<uint32_t>(fe.height_) << 16);
  h.add(static_cast<uint32_t>(fe.strip_height_));
  h.add(fe.background_);
  h.add(fe.camera_);
  h.add(fe.lights_);
  return h.value();
}

void FrontEndParts::sign_draw(FrontEnd& fe, uint8_t draw, const Material* per_pixel_material) {
  fe.records_.sign(draw, per_pixel_material);
}

void FrontEndParts::sign_triangle(FrontEnd& fe, uint16_t a, uint16_t b, uint16_t c, uint8_t draw,
                                  Rgb8 flat, Rgb8 flat_spec, int32_t r0, int32_t r1) {
  const DrawRecord& d = fe.records_[draw];
  VertexStore& store = fe.store_;
  InputHash h(d.inputs);
  h.add(store.vertex(a));
  h.add(store.vertex(b));
  h.add(store.vertex(c));
  if (d.phong) {
    h.add(store.surface(a));
    h.add(store.surface(b));
    h.add(store.surface(c));
  }
  if (d.uv) {
    h.add(store.tex(a));
    h.add(store.tex(b));
    h.add(store.tex(c));
  }
  h.add(flat);
  h.add(flat_spec);
  fe.edges_.sign(r0, r1, h.value());
}

bool FrontEnd::shrink_band() {
  uint32_t evicted = 0;
  if (!edges_.shrink_window(store_.vertices(), draw_first_triangle_, evicted)) return false;
  stats_.triangles_binned -= evicted;
  return true;
}

void FrontEnd::compact_vertices(size_t first_vertex, bool surfaces, bool tex) {
  const std::span<BinnedTriangle> tris = edges_.triangles().subspan(draw_first_triangle_);
  store_.compact(first_vertex, surfaces, tex, [tris](auto&& f) {
    for (BinnedTriangle& t : tris)
      for (uint16_t& v : t.v) f(v);
  });
}

Status FrontEnd::refuse(Status why, uint32_t triangles, bool vertex_store) {
  if (refused_ == Status::kOk) refused_ = why;
  switch (why) {
    case Status::kInvalidArgument:
      ++stats_.draws_refused_invalid;
      break;
    case Status::kNotLinked:
      ++stats_.draws_refused_not_linked;
      break;
    case Status::kMissingStore:
      ++stats_.draws_refused_missing_store;
      break;
    default:  // kCapacity
      ++stats_.draws_refused_capacity;
      (vertex_store ? refused_vertices_ : refused_triangles_) += triangles;
      (vertex_store ? stats_.dropped_vertex_capacity : stats_.dropped_triangle_capacity) +=
          triangles;
      break;
  }
  return why;
}

}  // namespace lr
