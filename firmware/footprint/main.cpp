// One footprint image: a complete 320x240 RGB565 application, strips of 8 rows, storage for
// 1,000 triangles, drawing a 1,000-triangle torus (firmware/footprint/scene.hpp) in the shading
// of one configuration (LR_FOOTPRINT_CONFIG, set by firmware/footprint/CMakeLists.txt):
//
//   1 unlit         vertex colours, no lighting
//   2 gouraud       lit per vertex ("gold")
//   3 tex_nearest   lit per vertex, 32x32 RGB565 texture, nearest, repeat, no mipmaps
//   4 tex_bilinear  the same, bilinear
//   5 phong         lit per pixel, exact ("gold"), one directional light, no maps
//
// Each renderer, Renderer<PF, 8, kSpans>, links only the span routine and the texel fetcher of
// the one state its configuration draws with (kSpans: the smallest lr::SpanSet holding that
// state, core/span/span_state.hpp; e.g. tex_nearest links no bilinear fetcher and no mipmap code),
// and only the mesh arrays its draw reads, so scripts/footprint.sh's flash,
// RAM and stack figures are those of a real application of that kind (what the core links for
// every draw, e.g. its texel fetchers, counts too). Static storage only: no heap, no exceptions.
//
// Output (semihosting): the frame's checksum (FNV-1a, as lr_smoke's), the frame statistics and
// the stack high-water mark (stack_probe.hpp), for footprint.sh to check against the static
// bound. Exit status 0 when the frame is complete and nothing was dropped for capacity.
#include <array>
#include <cstddef>
#include <cstdint>

#include "core/raster/renderer.hpp"
#include "core/scene/camera.hpp"
#include "core/scene/material.hpp"
#include "firmware/common/ordered_sink.hpp"
#include "firmware/common/report.hpp"
#include "firmware/common/semihost.hpp"
#include "firmware/footprint/scene.hpp"
#include "firmware/footprint/stack_probe.hpp"

#ifndef LR_FOOTPRINT_CONFIG
#error "LR_FOOTPRINT_CONFIG (1 unlit .. 5 phong) is set by firmware/footprint/CMakeLists.txt"
#endif

namespace {

namespace fp = lr::fw::footprint;
namespace sh = lr::fw::semihost;
using lr::Fixed;

enum class Config : int { kUnlit = 1, kGouraud, kTexNearest, kTexBilinear, kPhong };
constexpr Config kConfig = static_cast<Config>(LR_FOOTPRINT_CONFIG);
static_assert(LR_FOOTPRINT_CONFIG >= 1 && LR_FOOTPRINT_CONFIG <= 5, "unknown configuration");

constexpr bool kTextured = kConfig == Config::kTexNearest || kConfig == Config::kTexBilinear;
constexpr bool kPhong = kConfig == Config::kPhong;
constexpr bool kLit = kConfig != Config::kUnlit;
constexpr lr::Filter kFilter =
    kConfig == Config::kTexNearest ? lr::Filter::kNearest : lr::Filter::kBilinear;

// The span state of the draw (make_state() below), and the set of the renderer: that state with
// the texture's format and wraps. A draw outside the set would be refused (draw() fails).
constexpr lr::SpanState make_span_state() {
  lr::SpanState s;
  s.depth = true;
  if constexpr (kTextured) {
    s.family = lr::SpanFamily::kTextured;
    s.persp = lr::TexPersp::kExact;
    s.env = lr::TexEnv::kModulate;
    s.mip = lr::MipMode::kNone;
    s.filter = kFilter;
  } else if constexpr (kPhong) {
    s.family = lr::SpanFamily::kPhong;
    s.method = lr::PixelLighting::kExact;
    s.position = false;  // one directional light, infinite viewer
  } else {
    s.family = lr::SpanFamily::kUntextured;
    s.colors = lr::ColorPlanes::kPerspective;  // Gouraud: lit, or the mesh's vertex colours
  }
  return s;
}
constexpr lr::SpanSet kSpans = lr::span_set_of(make_span_state())
                                   .only(lr::TexelFormat::kRgb565)
                                   .only_wraps(lr::Wrap::kRepeat, lr::Wrap::kRepeat);

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
constexpr lr::FrameCapacities kCapacities{.width = kWidth,
                                          .height = kHeight,
                                          .strip_height = kStripRows,
                                          .vertices = 640,
                                          .triangles = 1024,
                                          .draws = 2,
                                          .active = 128,
                                          .surfaces = kPhong ? 640 : 0,
                                          .pixel_lights = kPhong ? 1u : 0u,
                                          .tex_vertices = kTextured ? 640u : 0u,
                                          .active_extra = kTextured || kPhong ? 128u : 0u};

// Constant-initialised, zero-filled in .bss, no constructor at startup.
lr::StaticFrameStorage<kCapacities> g_store;
// Word-aligned: the strip loop fills and clears strips with word stores (memset, memcpy).
alignas(4) std::array<std::array<Pixel, kStripPixels>, 2> g_store_strip_buffers{};

lr::Renderer<PF, kStripRows, kSpans> g_renderer;
// The display: every strip folded into FNV-1a (the smoke test's checksum, so that frames compare
// across cores and with the host), the lease protocol checked (firmware/common/ordered_sink.hpp).
lr::fw::ChecksumConsumer<PF> g_checksum;
lr::fw::OrderedStripSink<PF, lr::fw::ChecksumConsumer<PF>> g_sink(g_store_strip_buffers[0],
                                                                  g_store_strip_buffers[1],
                                                                  g_checksum);

// ---- The draw --------------------------------------------------------------------------------
constexpr lr::Mesh make_mesh() {
  lr::Mesh m{};
  m.positions = fp::kPositions;
  m.triangles = fp::kTriangles;
  if constexpr (kLit) m.normals = fp::kNormals;
  if constexpr (!kLit) m.colors = fp::kColors;
  if constexpr (kTextured) m.uvs = fp::kUvs;
  return m;
}
constexpr lr::Mesh kMesh = make_mesh();

lr::DrawState make_state() {
  lr::DrawState s;
  s.lighting = kLit;
  s.shading = kPhong ? lr::Shading::kPhong : lr::Shading::kGouraud;
  s.depth_test = true;
  s.cull = lr::Cull::kBack;
  if constexpr (kTextured) {
    s.texture = &fp::kTexture;
    s.sampler.filter = kFilter;
    s.sampler.mip = lr::MipMode::kNone;
    s.sampler.env = lr::TexEnv::kModulate;
  }
  if constexpr (kPhong) s.pixel_lighting = lr::PixelLighting::kExact;
  return s;
}

constexpr const char* kName = kConfig == Config::kUnlit         ? "unlit"
                              : kConfig == Config::kGouraud     ? "gouraud"
                              : kConfig == Config::kTexNearest  ? "tex_nearest"
                              : kConfig == Config::kTexBilinear ? "tex_bilinear"
                                                                : "phong";

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
lr::Material g_material;  // GL's default material (unlit: unused)
lr::Mat4 g_model;

bool render_frame() {
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

  lr::Material& material = g_material;
  if constexpr (kLit) {
    const lr::NamedMaterial* gold = lr::find_material(kTextured ? "silver" : "gold");
    if (gold == nullptr) return false;
    material = lr::to_material(*gold);
  }

  if (!check(g_renderer.begin_frame(camera, lights, lr::Rgb8{16, 24, 48}), "begin_frame"))
    return false;
  g_model = lr::rotate_y(Fixed::from_double(20.0));
  if (!check(g_renderer.draw(kMesh, g_model, material, make_state()), "draw")) return false;
  return check(g_renderer.render(g_sink), "render");
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
  bool ok = render_frame();
  const lr::FrameStats& st = g_renderer.stats();
  const uint32_t dropped = st.dropped_vertex_capacity + st.dropped_triangle_capacity;
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
