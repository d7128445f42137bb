// What the front end's triangle loop reads of one draw (front_end.cpp, lane.cpp): its plan (what
// draw() decided from its state, mesh and lights) and its context. Internal to core/binning.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "lineraster/core/binning/draw_record.hpp"
#include "lineraster/core/binning/front_end.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/scene/mesh.hpp"
#include "lineraster/core/vertex/vertex_stage.hpp"

namespace lr {

// What draw() decides about a draw from its state, its mesh and the lights.
struct DrawPlan {
  DrawKind kind;
  bool lit = false;
  bool gouraud = false;  // per-vertex colours: lit Gouraud, or unlit and interpolated
  bool textured = false;
  bool uv = false;         // the vertices have TexVertex entries (DrawRecord::uv)
  bool split = false;      // textured, lit, modulated: primary and specular colours apart
  bool two_sided = false;  // Gouraud and flat: back faces lit with the negated normal
};

// A colour clamped to [0, 1] in bytes.
inline Rgb8 to_rgb8_sat(Color15 c) {
  auto b = [](uint16_t v) { return to_byte(clamp_c15(v)); };
  return {b(c.r), b(c.g), b(c.b)};
}

// What draw()'s triangle loop reads of its draw.
struct MeshDraw {
  const Mesh& mesh;
  const DrawState& state;
  const VertexStage& stage;
  // Copies of the draw's plan and colours, not references to them.
  const DrawPlan plan;
  const VertexColors colors;
  const size_t base;  // the mesh's first vertex store entry
  const uint8_t draw;
  const bool cached;     // the mesh goes through the vertex cache (FrontEnd::cache_corners)
  bool clipping = true;  // a vertex may be outside a plane (else no triangle needs the clipper)
  // Flat shading's face lighting (FrontEnd::configure): never nullptr for a lit flat draw.
  FaceLightFn face_light = nullptr;
  // The colours of its triangles without colour planes (FrontEndRoutines::flat): set only for a
  // flat-shaded or one-coloured draw, else nullptr (its triangles' colours are planes).
  void (*own_colors)(const MeshDraw&, const std::array<uint16_t, 3>&, const ScreenVertex&, bool,
                     Rgb8&, Rgb8&) = nullptr;
  // A lit vertex's colours (FrontEndRoutines::light): never nullptr.
  LightFn light = nullptr;
  LitColor light_vertex(size_t i, bool back) const { return light(stage, mesh, colors, i, back); }
  // Lit Gouraud under diffuse directional lights in model space, one colour: the lights
  // (light_corners()'s inline case), else nullptr.
  const ObjectLights* diffuse_lights = nullptr;
  // Back faces' colours (two-sided Gouraud): written before use on each back face; one set per
  // draw, because a value-initialised local per triangle cost a 120-byte memset each.
  LitColor back_colors[3] = {};

  // The colours of a triangle without colour planes: flat shading (lit by its face normal, or
  // the last vertex's colour), or an unlit mesh's one colour.
  [[gnu::always_inline]] void flat_colors(const std::array<uint16_t, 3>& tri,
                                          const ScreenVertex& last, bool back, Rgb8& flat,
                                          Rgb8& flat_spec) const {
    if (!plan.gouraud && !plan.kind.phong) {
      if (plan.lit) {
        const LitColor lc = (stage.*face_light)(
            colors, mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]], back);
        flat = to_rgb8_sat(lc.primary);
        if (plan.split) flat_spec = to_rgb8_sat(lc.secondary);
      } else {
        flat = to_rgb8_sat(last.color);  // GL's provoking vertex: the last one
      }
    } else if (!plan.kind.color_planes && !plan.kind.phong) {
      flat = to_rgb8_sat(colors.material);
    }
  }
};

}  // namespace lr
