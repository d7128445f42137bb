// The draw record: one per draw() call, what the strip loop and the span routines need of the
// draw's state (which routine, its textures and lighting). Written by the front end when a draw
// is added; the strip loop fills in the texel fetchers when it renders.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/lighting/lighting_table.hpp"
#include "lineraster/core/lighting/one_hue.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/core/scene/mesh.hpp"
#include "lineraster/core/texture/texel_fetch.hpp"
#include "lineraster/core/texture/texture.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"

namespace lr {

// A copy of a trivially copyable T kept as bytes, whose default is all zeros whatever T's
// defaults are: a static store of records holding one stays in .bss.
template <class T>
class ZeroStored {
 public:
  void set(const T& v) { bytes_ = std::bit_cast<std::array<std::byte, sizeof(T)>>(v); }
  T get() const { return std::bit_cast<T>(bytes_); }

 private:
  std::array<std::byte, sizeof(T)> bytes_{};
};

// What re-runs a draw when the frame is binned again band by band (FrontEnd::bin_band): the
// arguments of draw() or draw_screen(). The caller's arrays are referred to, not copied.
struct DrawCall {
  Mesh mesh{};                              // draw(); draw_screen(): its triangles only
  std::span<const ScreenVertex> screen{};   // draw_screen()'s vertices
  std::span<const TexVertex> screen_tex{};  // and their texture coordinates
  Mat4 model{};
  const FineMat4* fine_model = nullptr;  // draw()'s fine model (the caller keeps it until render)
  ZeroStored<Material> material{};
  ZeroStored<DrawState> state{};
  bool is_screen = false;  // draw_screen()
};

// Every default is zero bytes (false, nullptr, the enums' first value), so that a static store
// of records stays in .bss; the front end sets every field a draw uses.
struct DrawRecord {
  ColorPlanes colors = ColorPlanes::kNone;  // untextured draws
  OneHue hue{};        // lit colours that are one hue (set for every draw; lanes Gouraud reads it)
  bool depth = false;  // the depth test (DrawState::depth_test)
  bool flat = false;
  // The draw's first vertex in the vertex store: its binned triangles refer to vertices from
  // here up to the next draw's first (the strip loop finds a triangle's draw by its first
  // vertex). Set when the draw is binned, in every band.
  uint16_t first_vertex = 0;
  // Flat shading: each binned triangle has its colours in FrameStorage::triangle_colors;
  // otherwise a draw without colour planes has one colour, `color`.
  bool triangle_colors = false;
  Rgb8 color{};
  const Texture* texture = nullptr;  // textured draws
  bool uv = false;  // the vertices have TexVertex entries (textured, or Phong with a normal map)
  // The texel fetchers (fetch, env_fetch, nmap_fetch) are chosen by the strip loop when it
  // renders (StripLoop::resolve_fetchers), from the texture's format, the filter and the wraps,
  // in the tables of its SpanSet: firmware links only the fetchers of the states its set admits.
  FetchFn fetch = nullptr;
  Filter filter = Filter::kNearest;  // the sampler's, for the texture and the normal map
  TexPersp persp = TexPersp::kExact;
  uint8_t span_len = 0;  // kSpan: 8, 16 or 32
  TexEnv env = TexEnv::kModulate;
  MipMode mip = MipMode::kNone;
  Wrap wrap_s = Wrap::kRepeat, wrap_t = Wrap::kRepeat;  // the sampler's, as filter
  // Phong (per-pixel lighting) draws.
  bool phong = false;
  PixelLighting method = PixelLighting::kExact;
  bool two_sided = false;  // back faces get the negated normal
  bool position = false;   // planes of the world position (point lights, local viewer)
  bool table_bilinear = false;
  const PreparedLighting* lighting = nullptr;  // exact mode; the viewer for environment maps
  LightingTable table{};                       // table mode
  const Texture* envmap = nullptr;
  FetchFn env_fetch = nullptr;
  const Texture* normal_map = nullptr;
  FetchFn nmap_fetch = nullptr;
  // The frame's view matrix (the front end's camera, one per frame; environment maps: world to
  // eye directions).
  const Mat4* view = nullptr;
  DrawCall call{};  // not in the signature: the call's results are (the binned triangles)
  // Signature of everything above that decides pixels (core/binning/strip_inputs.hpp), with the
  // material of per-pixel lighting; set once per draw when strip skipping is on.
  uint32_t inputs = 0;
};

// Whether binning stores the draw's triangles sorted by y where kBinnedSorted
// (binned_triangle.hpp): every draw whose triangles setup's hand-made lanes block may take
// (untextured, with colour planes, not Phong: the strip loop's lanes draws are among them). The
// others keep the rotation, which their setup sorts with one compare (and two-sided Phong reads for
// the winding).
constexpr bool sorts_for_lanes(const DrawRecord& r) {
  return r.colors != ColorPlanes::kNone && r.texture == nullptr && !r.phong;
}

// The colour planes of an untextured draw (its record and its span state agree through this).
constexpr ColorPlanes color_planes_of(const DrawState& state, bool has_color_planes) {
  if (state.shading == Shading::kFlat || !has_color_planes) return ColorPlanes::kNone;
  return state.perspective == Perspective::kAffine ? ColorPlanes::kAffine
                                                   : ColorPlanes::kPerspective;
}

// The textured span mode of a Perspective (the span length aside).
constexpr TexPersp tex_persp_of(Perspective p) {
  return p == Perspective::kExact    ? TexPersp::kExact
         : p == Perspective::kAffine ? TexPersp::kAffine
                                     : TexPersp::kSpan;
}

// What selects a draw's span routine besides its DrawState, as the front end decides it from
// the mesh and the lights.
struct DrawKind {
  bool phong = false;         // lit per pixel
  bool color_planes = false;  // untextured, not flat: colour planes (else one colour)
  bool position = false;      // the lighting needs the surface position (point lights, local
                              // viewer): Phong's exact method interpolates it
};

// Whether the renderer links a routine for a draw and its textures (core/span/admission.hpp).
// The front end refuses a draw it does not admit; nullptr admits every draw.
using AdmitFn = bool (*)(const DrawState& state, const DrawKind& kind);

class DrawRecords;
struct PreparedLighting;
// The per-pixel lighting part of a Phong draw's record (DrawRecords::phong_record): a renderer
// without Phong spans passes nullptr and links none of it (lighting tables included); the front
// end then refuses Phong draws.
using PhongRecordFn = Status (*)(DrawRecords& records, const DrawState& state,
                                 const PreparedLighting& pl, DrawRecord& r);

}  // namespace lr
