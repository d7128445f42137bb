// One footprint image: a complete 320x240 RGB565 application, strips of 8 rows, storage for
// 1,000 triangles, drawing a 1,000-triangle torus (firmware/footprint/scene.hpp) in the shading
// of one configuration (LR_FOOTPRINT_CONFIG, set by firmware/footprint/CMakeLists.txt):
//
//   1 unlit          vertex colours, no lighting
//   2 gouraud        lit per vertex ("gold")
//   3 tex_nearest    lit per vertex, 32x32 RGB565 texture, nearest, repeat, no mipmaps
//   4 tex_bilinear   the same, bilinear
//   5 phong          lit per pixel, exact ("gold"), one directional light, no maps
//   6 gouraud_tex    three draws, a third of the torus each: gouraud, tex_nearest, tex_bilinear
//                    (the renderer holds the three states' routines and nothing else)
//   7 every_feature  five draws, a fifth each: configurations 1 to 5, with a renderer that
//                    holds every span routine the core has (kAllSpans: every family, texel
//                    format, wrap, filter, mip mode, environment and map)
//   8 tex_nearest_shared  tex_nearest without the inlined texel fetch (SpanSet::inline_fetch):
//                    the flash that sharing the span body saves (bench_cortex_m.sh: its cost
//                    per pixel)
//   9 gouraud_diffuse  gouraud with a diffuse material ("gold" without its specular colour, the
//                    kind of draw of the peer scenes): its renderer leaves out specular
//                    (RendererFeatures::specular), the Gouraud family as S1 needs it
//
// Each renderer, Renderer<PF, 8, kSpans>, links only the span routines and texel fetchers of
// the states its configuration draws with (kSpans: the smallest lr::SpanSet holding them,
// core/span/span_state.hpp; e.g. tex_nearest links no bilinear fetcher and no mipmap code), and
// only the mesh arrays its draws read, so scripts/footprint.sh's flash, RAM and stack figures
// are those of a real application of that kind (what the core links for every draw, e.g. its
// texel fetchers, counts too). Static storage only: no heap, no exceptions.
//
// Output (semihosting): the frame's checksum (FNV-1a, as lr_smoke's), the frame statistics and
// the stack high-water mark (stack_probe.hpp), for footprint.sh to check against the static
// bound. Exit status 0 when the frame is complete and nothing was dropped for capacity.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>

#include "firmware/common/ordered_sink.hpp"
#include "firmware/common/report.hpp"
#include "firmware/common/semihost.hpp"
#include "firmware/footprint/scene.hpp"
#include "firmware/footprint/stack_probe.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/material.hpp"

#ifndef LR_FOOTPRINT_CONFIG
#error "LR_FOOTPRINT_CONFIG (1 unlit .. 9) is set by firmware/footprint/CMakeLists.txt"
#endif

namespace {

namespace fp = lr::fw::footprint;
namespace sh = lr::fw::semihost;
using lr::Fixed;

// A draw's shading (configurations 1 to 5), and the configuration of the image.
enum class Part : int { kUnlit = 1, kGouraud, kTexNearest, kTexBilinear, kPhong };
static_assert(LR_FOOTPRINT_CONFIG >= 1 && LR_FOOTPRINT_CONFIG <= 9, "unknown configuration");
constexpr int kConfig = LR_FOOTPRINT_CONFIG;
constexpr int kGouraudTex = 6, kEveryFeature = 7, kTexNearestShared = 8, kGouraudDiffuse = 9;

struct Parts {
  std::array<Part, 5> part{};
  size_t count = 0;
};
constexpr Parts parts_of(int config) {
  if (config == kGouraudTex) return {{Part::kGouraud, Part::kTexNearest, Part::kTexBilinear}, 3};
  if (config == kEveryFeature)
    return {{Part::kUnlit, Part::kGouraud, Part::kTexNearest, Part::kTexBilinear, Part::kPhong}, 5};
  if (config == kTexNearestShared) return {{Part::kTexNearest}, 1};
  if (config == kGouraudDiffuse) return {{Part::kGouraud}, 1};
  return {{static_cast<Part>(config)}, 1};
}
constexpr Parts kParts = parts_of(kConfig);

constexpr bool textured(Part p) {
  return p == Part::kTexNearest || p == Part::kTexBilinear;
}
constexpr bool any_part(bool (*pred)(Part)) {
  for (size_t i = 0; i < kParts.count; ++i)
    if (pred(kParts.part[i])) return true;
  return false;
}
constexpr bool kTextured = any_part(textured);
constexpr bool kPhong = any_part([](Part p) { return p == Part::kPhong; });

constexpr lr::Filter filter_of(Part p) {
  return p == Part::kTexNearest ? lr::Filter::kNearest : lr::Filter::kBilinear;
}

// The span state of a draw (make_state() below), and the set of the renderer: the states of its
// draws with the texture's format and wraps (every routine for every_feature). A draw outside
// the set would be refused (draw() fails).
constexpr lr::SpanState make_span_state(Part p) {
  lr::SpanState s;
  s.depth = true;
  if (textured(p)) {
    s.family = lr::SpanFamily::kTextured;
    s.persp = lr::TexPersp::kExact;
    s.env = lr::TexEnv::kModulate;
    s.mip = lr::MipMode::kNone;
    s.filter = filter_of(p);
  } else if (p == Part::kPhong) {
    s.family = lr::SpanFamily::kPhong;
    s.method = lr::PixelLighting::kExact;
    s.position = false;  // one directional light, infinite viewer
  } else {
    s.family = lr::SpanFamily::kUntextured;
    s.colors = lr::ColorPlanes::kPerspective;  // Gouraud: lit, or the mesh's vertex colours
  }
  return s;
}
constexpr lr::SpanSet make_span_set() {
  if (kConfig == kEveryFeature) return lr::kAllSpans;
  lr::SpanSet set = lr::span_set_of(make_span_state(kParts.part[0]));
  for (size_t i = 1; i < kParts.count; ++i)
    set = set | lr::span_set_of(make_span_state(kParts.part[i]));
  set = set.only(lr::TexelFormat::kRgb565).only_wraps(lr::Wrap::kRepeat, lr::Wrap::kRepeat);
  return kConfig == kTexNearestShared ? set.only_inline_fetch(false) : set;
}
constexpr lr::SpanSet kSpans = make_span_set();

using PF = lr::Rgb565Be;
using Pixel = PF::Storage;
constexpr int kWidth = 320;
constexpr int kHeight = 240;
constexpr int kStripRows = 8;
constexpr size_t kStrips = (kHeight + kStripRows - 1) / kStripRows;
constexpr size_t kStripPixels = size_t{kWidth} * kStripRows;

// ---- Storage for 1,000 triangles -------------------------------------------------------------
// Sized as an application that budgets for "1,000 triangles on screen" would size it:
//  - triangles: the budget, plus 24 for the fans that clipping (near plane, guard band) makes
//    of a triangle crossing a plane (a few triangles of a scene that reaches the screen's edge).
//  - vertices: the vertex store holds every vertex of a draw (transformed before culling) and
//    the polygons clipping makes. A closed, smoothly shaded mesh has about half as many
//    vertices as triangles; seams (texture wrap, hard edges) add some: this torus has 546 for
//    1,000 triangles. 640 = 0.64 per triangle covers that and a few clipped polygons (<= 9
//    vertices each); a flat-shaded mesh with split vertices would need up to 3 per triangle.
//  - active: the triangles crossing one 8-row strip at once, which only a measurement tells:
//    this view peaks at 96 (FrameStats::max_active; the strips through the tube's near and far
//    rims cross the most), 103 from other heights. 128 = the peak + 1/3 for other views. An
//    overflow drops triangles (counted in FrameStats, and fatal here), it corrupts nothing.
//  - Phong only: one SurfaceVertex per vertex-store entry, one PreparedLighting (one material).
//  - Textured only: one TexVertex per vertex-store entry.
//  - The images of several draws (gouraud_tex, every_feature) transform the torus's vertices
//    once per draw: their vertex stores hold 640 per draw.
constexpr size_t kVertices = 640 * kParts.count;
constexpr lr::FrameCapacities kCapacities{.width = kWidth,
                                          .height = kHeight,
                                          .strip_height = kStripRows,
                                          .vertices = kVertices,
                                          .triangles = 1024,
                                          .draws = kParts.count + 1,
                                          .active = 128,
                                          .surfaces = kPhong ? kVertices : 0,
                                          .pixel_lights = kPhong ? 1u : 0u,
                                          .tex_vertices = kTextured ? kVertices : 0,
                                          .active_extra = kTextured || kPhong ? 128u : 0u};

// Constant-initialised, zero-filled in .bss, no constructor at startup.
lr::StaticFrameStorage<kCapacities> g_store;
// Word-aligned: the strip loop fills and clears strips with word stores (memset, memcpy).
alignas(4) std::array<std::array<Pixel, kStripPixels>, 2> g_store_strip_buffers{};

// The front end's features (core/raster/renderer_features.hpp): every_feature all of them, the
// others none but specular where their lit draws' material has a specular colour ("gold",
// "silver"; not unlit, not gouraud_diffuse). The frame fits the stores (no bands, no vertex
// cache), the lights are one-sided, no triangle crosses the near plane or the guard band (no
// clipper) and every strip is rendered: the frame is the same as with every feature.
constexpr lr::RendererFeatures features_of(int config) {
  if (config == kEveryFeature) return lr::kAllFeatures;
  lr::RendererFeatures f = lr::kNoFeatures;
  f.specular = config != kGouraudDiffuse && parts_of(config).part[0] != Part::kUnlit;
  return f;
}
constexpr lr::RendererFeatures kFeatures = features_of(kConfig);
lr::Renderer<PF, kStripRows, kSpans, kFeatures> g_renderer;
// The display: every strip folded into FNV-1a (the smoke test's checksum, so that frames compare
// across cores and with the host), the lease protocol checked (firmware/common/ordered_sink.hpp).
lr::fw::ChecksumConsumer<PF> g_checksum;
lr::fw::OrderedStripSink<PF, lr::fw::ChecksumConsumer<PF>> g_sink(g_store_strip_buffers[0],
                                                                  g_store_strip_buffers[1],
                                                                  g_checksum);

// ---- The draws -------------------------------------------------------------------------------
// Draw i of n covers the torus's triangles [1000 i / n, 1000 (i + 1) / n).
constexpr lr::Mesh make_mesh(Part p, size_t i) {
  lr::Mesh m{};
  m.positions = fp::kPositions;
  const size_t first = fp::kTriangleCount * i / kParts.count;
  const size_t last = fp::kTriangleCount * (i + 1) / kParts.count;
  m.triangles = std::span(fp::kTriangles).subspan(first, last - first);
  if (p != Part::kUnlit) m.normals = fp::kNormals;
  if (p == Part::kUnlit) m.colors = fp::kColors;
  if (textured(p)) m.uvs = fp::kUvs;
  return m;
}
template <size_t... I>
constexpr std::array<lr::Mesh, sizeof...(I)> make_meshes(std::index_sequence<I...>) {
  return {make_mesh(kParts.part[I], I)...};
}
constexpr auto kMeshes = make_meshes(std::make_index_sequence<kParts.count>{});

lr::DrawState make_state(Part p) {
  lr::DrawState s;
  s.lighting = p != Part::kUnlit;
  s.shading = p == Part::kPhong ? lr::Shading::kPhong : lr::Shading::kGouraud;
  s.depth_test = true;
  s.cull = lr::Cull::kBack;
  if (textured(p)) {
    s.texture = &fp::kTexture;
    s.sampler.filter = filter_of(p);
    s.sampler.mip = lr::MipMode::kNone;
    s.sampler.env = lr::TexEnv::kModulate;
  }
  if (p == Part::kPhong) s.pixel_lighting = lr::PixelLighting::kExact;
  return s;
}

constexpr const char* kNames[] = {
    "unlit",       "gouraud",       "tex_nearest",        "tex_bilinear",   "phong",
    "gouraud_tex", "every_feature", "tex_nearest_shared", "gouraud_diffuse"};
constexpr const char* kName = kNames[kConfig - 1];

bool check(lr::Status st, const char* what) {
  return lr::fw::check("footprint", st, what);
}

void report(const char* label, uint32_t value, bool hex = false) {
  sh::write("footprint: ");
  sh::write(label);
  sh::write(" ");
  if (hex)
    sh::write_hex(value);
  else
    sh::write_dec(value);
  sh::write("\n");
}

// The frame's camera, lights, material and model matrix, static: the renderer copies them, and
// on the stack they would add to the deepest path (render() -> ... -> the span routines) whose
// depth the footprint measures.
lr::Camera g_camera;
lr::LightSet g_lights;
lr::Mat4 g_model;
// Untextured and textured lit draws' materials (unlit: unused), from the classic table at
// compile time: the image links the two Materials, not the table and its lookup.
constexpr lr::Material kGold = lr::to_material(*lr::find_material("gold"));
constexpr lr::Material kSilver = lr::to_material(*lr::find_material("silver"));
// gouraud_diffuse's: gold's ambient and diffuse colours, no specular colour.
constexpr lr::Material diffuse_of(lr::Material m) {
  m.specular = {0, 0, 0};
  m.shininess_q8 = 0;
  return m;
}
constexpr lr::Material kGoldDiffuse = diffuse_of(kGold);
constexpr const lr::Material& material_of(Part p) {
  return textured(p) ? kSilver : kConfig == kGouraudDiffuse ? kGoldDiffuse : kGold;
}

// Everything before the draws, out of line: its temporaries (the camera's computation, the
// materials) are off the stack while the frame is drawn and rendered, as an application would
// keep them.
[[gnu::noinline]] bool prepare_frame() {
  if (!check(g_renderer.configure(g_store.storage(), kWidth, kHeight), "configure")) return false;

  // The torus seen from 40 degrees above its plane, filling two thirds of the screen (52,000
  // pixels): every strip but a few at the top and bottom has work.
  lr::Camera& camera = g_camera;
  camera.eye = {Fixed::from_double(0.0), Fixed::from_double(1.8), Fixed::from_double(2.2)};
  const lr::Vec3 target{Fixed::from_double(0.0), Fixed::from_double(-0.1), Fixed::from_double(0.0)};
  const lr::Vec3 up{Fixed::from_double(0.0), Fixed::from_double(1.0), Fixed::from_double(0.0)};
  if (!lr::perspective(Fixed::from_double(45.0), Fixed::ratio(kWidth, kHeight),
                       Fixed::from_double(0.5), Fixed::from_double(20.0), camera.projection) ||
      !lr::look_at(camera.eye, target, up, camera.view)) {
    sh::write("footprint: camera rejected\n");
    return false;
  }

  lr::LightSet& lights = g_lights;
  lights.lights[0].position = {Fixed::from_double(0.4), Fixed::from_double(0.8),
                               Fixed::from_double(0.6)};
  lights.count = 1;
  constexpr uint16_t kAmbient = 6554;  // 0.2 in Q1.15, GL's default global ambient
  lights.global_ambient = {kAmbient, kAmbient, kAmbient};

  g_model = lr::rotate_y(Fixed::from_double(20.0));
  return check(g_renderer.begin_frame(camera, lights, lr::Rgb8{16, 24, 48}), "begin_frame");
}

// The frame's draws, each a call with the static state above.
[[gnu::noinline]] bool draw_frame() {
  for (size_t i = 0; i < kParts.count; ++i) {
    const Part p = kParts.part[i];
    if (!check(g_renderer.draw(kMeshes[i], g_model, material_of(p), make_state(p)), "draw"))
      return false;
  }
  return true;
}

}  // namespace

int main() {
  // The stack below this point is painted before anything else runs, so the high-water mark
  // covers the whole frame and the reports after it.
  uint32_t* const sp_at_main = fp::current_sp();
  fp::paint_stack(sp_at_main);

  sh::write("footprint: ");
  sh::write(kName);
  sh::write(": 320x240 RGB565, strips of 8 rows, torus of 1,000 triangles\n");
  bool ok = prepare_frame() && draw_frame() && check(g_renderer.render(g_sink), "render");
  const lr::FrameStats& st = g_renderer.stats();
  const uint32_t dropped =
      st.dropped_vertex_capacity + st.dropped_triangle_capacity + st.dropped_unclipped;
  report("triangles binned", st.triangles_binned);
  report("max active", st.max_active);
  report("pixels written", st.pixels_written);
  report("dropped (capacity)", dropped);
  if (ok && (dropped != 0 || st.pixels_written == 0 || g_sink.strips() != kStrips)) {
    sh::write("footprint: the frame is empty, incomplete or dropped triangles\n");
    ok = false;
  }
  report("checksum", g_checksum.hash.value, true);
  // The stores' bytes, for scripts/footprint.sh's RAM breakdown, in this order: vertices,
  // triangles, buckets, active, active_index, depth, strip_buffers, draws, surfaces,
  // pixel_lights, tex_vertices, active_extra.
  static constexpr uint32_t kStoreBytes[] = {
      sizeof(g_store.vertices), sizeof(g_store.triangles), sizeof(g_store.buckets),
      sizeof(g_store.active), sizeof(g_store.active_index), sizeof(g_store.depth),
      sizeof(g_store_strip_buffers), sizeof(g_store.draws), sizeof(g_store.surfaces),
      sizeof(g_store.pixel_lights),
      // (an empty std::array is 1 byte: the stores' sizes from their capacities)
      kCapacities.tex_vertices * sizeof(lr::TexVertex),
      kCapacities.active_extra * sizeof(lr::ActiveExtra)};
  sh::write("footprint: stores");
  for (const uint32_t bytes : kStoreBytes) {
    sh::write(" ");
    sh::write_dec(bytes);
  }
  sh::write("\n");

  const uint32_t* const lowest = fp::stack_high_water();
  report("sp at main", static_cast<uint32_t>(reinterpret_cast<uintptr_t>(sp_at_main)), true);
  report("stack region bytes", fp::stack_depth(_sstack));
  if (lowest == _sstack) {
    sh::write("footprint: the stack region was used to its bottom (overflow?)\n");
    ok = false;
  }
  // Bytes below the reset SP (_estack) ever written: Reset_Handler's frame, main's and the
  // deepest call chain of the frame and the reports above.
  report("stack used", fp::stack_depth(lowest));
  sh::write(ok ? "footprint: PASS\n" : "footprint: FAIL\n");
  return ok ? 0 : 1;
}
