// Smoke test of the core on the target: one 320x240 frame of a lit, Gouraud-shaded, depth-tested
// octahedron in the "gold" material, rendered in strips of K rows into a sink that folds every
// pixel into a checksum. All storage is static (no heap, no frame buffer: two strip buffers of
// 320 x K RGB565 pixels and one strip of depth).
//
// K and the store capacities depend on the board's RAM (LR_BOARD_RAM_SIZE, which
// firmware/boards.cmake defines for every firmware image): K = 8 with room to spare where there
// is plenty, K = 2 and stores sized for this scene on the micro:bit's 16 KB. The frame, and so the
// checksum, is the same for every K: the renderer's output does not depend on the strip height
// (scripts/ci_cross.sh checks every board's checksum against the host build's). LR_SMOKE_STRIP_ROWS
// overrides K (e.g. to check that claim on the host).
//
// The checksum is FNV-1a (32 bit) over the frame's bytes in wire order: each pixel as RGB565
// big-endian (high byte first), rows top to bottom. It depends only on integer arithmetic, so
// the same scene rendered by the host build gives the same value.
//
// Result: the volatile globals g_smoke_checksum and g_smoke_result (1 = pass, 2 = fail) for a
// debugger; with semihosting (QEMU: -semihosting) a report on the console and the exit status.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "firmware/common/ordered_sink.hpp"
#include "firmware/common/report.hpp"
#include "firmware/common/semihost.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/material.hpp"

extern "C" {
volatile uint32_t g_smoke_checksum = 0;
volatile uint32_t g_smoke_result = 0;  // 0 running, 1 pass, 2 fail
#ifdef LR_BOARD_RAM_SIZE
uint32_t lr_stack_used_bytes();  // firmware/common/startup.cpp (firmware builds only)
#endif
}

namespace {

using lr::Fixed;
using PF = lr::Rgb565Be;
using Pixel = PF::Storage;

constexpr int kWidth = 320;
constexpr int kHeight = 240;

// Board-dependent sizes. The small profile (16 KB of RAM, of which the stack takes 4 KB) holds
// this scene with little to spare: 6 vertices and 8 triangles (nothing is clipped: the
// octahedron lies well inside the near plane), at most 7 triangles active at once ("max active"
// in the report); docs/measurements/footprint.md has the RAM they take.
#if defined(LR_BOARD_RAM_SIZE) && LR_BOARD_RAM_SIZE < 64 * 1024
constexpr bool kSmallRam = true;
#else
constexpr bool kSmallRam = false;
#endif
#ifdef LR_SMOKE_STRIP_ROWS
constexpr int kStripRows = LR_SMOKE_STRIP_ROWS;
#else
constexpr int kStripRows = kSmallRam ? 2 : 8;
#endif
constexpr size_t kStrips = (kHeight + kStripRows - 1) / kStripRows;
constexpr size_t kStripPixels = size_t{kWidth} * kStripRows;

// ---- The mesh, in flash --------------------------------------------------------------------
// A regular octahedron of radius 1.2 with smooth normals (each vertex's normal is its own
// direction), so Gouraud shading interpolates real gradients across every face.
constexpr Fixed kR = Fixed::from_double(1.2);
constexpr Fixed k0 = Fixed::from_double(0.0);
constexpr int16_t kN1 = 1 << lr::Normal16::kFracBits;  // 1.0 in Q1.14

constexpr std::array<lr::Vec3, 6> kPositions = {{
    {kR, k0, k0},   // 0: +X
    {-kR, k0, k0},  // 1: -X
    {k0, kR, k0},   // 2: +Y
    {k0, -kR, k0},  // 3: -Y
    {k0, k0, kR},   // 4: +Z
    {k0, k0, -kR},  // 5: -Z
}};
constexpr std::array<lr::Normal16, 6> kNormals = {{
    {kN1, 0, 0},
    {-kN1, 0, 0},
    {0, kN1, 0},
    {0, -kN1, 0},
    {0, 0, kN1},
    {0, 0, -kN1},
}};
// One triangle per octant, counter-clockwise seen from outside.
constexpr std::array<std::array<uint16_t, 3>, 8> kTriangles = {{
    {0, 2, 4},
    {1, 4, 2},
    {0, 4, 3},
    {1, 3, 4},
    {0, 5, 2},
    {1, 2, 5},
    {0, 3, 5},
    {1, 5, 3},
}};

// Every face's normal (counter-clockwise winding) points away from the centre.
consteval bool outward_winding() {
  for (const auto& t : kTriangles) {
    const lr::Vec3 a = kPositions[t[0]], b = kPositions[t[1]], c = kPositions[t[2]];
    if (lr::dot_q30(lr::cross(b - a, c - a), a + b + c) <= 0) return false;
  }
  return true;
}
static_assert(outward_winding(), "octahedron triangles must be counter-clockwise from outside");

constexpr lr::Mesh kOctahedron{kPositions, kNormals, {}, {}, kTriangles};

// ---- Frame storage (RAM, static) -------------------------------------------------------------
// Capacities: 6 vertices and 8 triangles per draw, plus what clipping makes (nothing here).
constexpr size_t kMaxVertices = kSmallRam ? 8 : 64;
constexpr size_t kMaxTriangles = kSmallRam ? 8 : 64;
constexpr size_t kMaxActive = kSmallRam ? 8 : 32;

// Constant-initialised: the zero-filled stores go to .bss and need no constructor at startup.
constexpr lr::FrameCapacities kCapacities{.width = kWidth,
                                          .height = kHeight,
                                          .strip_height = kStripRows,
                                          .vertices = kMaxVertices,
                                          .triangles = kMaxTriangles,
                                          .draws = kSmallRam ? 1u : 4u,  // one draw in this scene
                                          .active = kMaxActive};
lr::StaticFrameStorage<kCapacities> g_store;
// Word-aligned: the strip loop fills and clears strips with word stores (memset, memcpy).
alignas(4) std::array<std::array<Pixel, kStripPixels>, 2> g_strip_buffers{};

// Gouraud only: no textured or Phong span routines linked (lr::SpanSet, core/span/span_state.hpp).
lr::Renderer<PF, kStripRows, lr::kUntexturedSpans> g_renderer;

// ---- The display: two strip buffers, every pixel folded into FNV-1a --------------------------
// Stands in for a panel backend: the lease protocol is checked on every strip and a strip is
// "sent" by hashing it inside submit(), so a buffer is free again as soon as it is submitted.
lr::fw::ChecksumConsumer<PF> g_checksum;
lr::fw::OrderedStripSink<PF, lr::fw::ChecksumConsumer<PF>> g_sink(g_strip_buffers[0],
                                                                  g_strip_buffers[1], g_checksum);

namespace sh = lr::fw::semihost;

bool check(lr::Status st, const char* what) {
  return lr::fw::check("lr_smoke", st, what);
}
using lr::fw::report;

bool render_frame() {
  if (!check(g_renderer.configure(g_store.storage(), kWidth, kHeight), "configure")) return false;

  lr::Camera camera;
  camera.eye = {Fixed::from_double(1.6), Fixed::from_double(1.4), Fixed::from_double(3.6)};
  const lr::Vec3 target{k0, k0, k0};
  const lr::Vec3 up{k0, Fixed::from_double(1.0), k0};
  if (!lr::perspective(Fixed::from_double(45.0), Fixed::ratio(kWidth, kHeight),
                       Fixed::from_double(0.5), Fixed::from_double(20.0), camera.projection) ||
      !lr::look_at(camera.eye, target, up, camera.view)) {
    sh::write("lr_smoke: camera rejected\n");
    return false;
  }

  // One white directional light (GL's light 0 colours: no ambient, diffuse and specular 1),
  // GL's default global ambient of 0.2.
  lr::LightSet lights;
  lights.lights[0].position = {Fixed::from_double(0.4), Fixed::from_double(0.8),
                               Fixed::from_double(0.6)};
  lights.count = 1;
  constexpr uint16_t kAmbient = 6554;  // 0.2 in Q1.15
  lights.global_ambient = {kAmbient, kAmbient, kAmbient};

  const lr::NamedMaterial* gold = lr::find_material("gold");
  if (gold == nullptr) {
    sh::write("lr_smoke: material \"gold\" not found\n");
    return false;
  }
  const lr::Material material = lr::to_material(*gold);

  if (!check(g_renderer.begin_frame(camera, lights, lr::Rgb8{16, 24, 48}), "begin_frame"))
    return false;

  lr::DrawState state;
  state.shading = lr::Shading::kGouraud;
  state.lighting = true;
  state.depth_test = true;
  state.cull = lr::Cull::kNone;  // back faces are drawn too: the depth test must hide them
  const lr::Mat4 model =
      lr::rotate_y(Fixed::from_double(25.0)) * lr::rotate_x(Fixed::from_double(-15.0));
  if (!check(g_renderer.draw(kOctahedron, model, material, state), "draw")) return false;

  return check(g_renderer.render(g_sink), "render");
}

}  // namespace

int main() {
  sh::write("lr_smoke: 320x240 RGB565BE, strips of ");
  sh::write_dec(static_cast<uint32_t>(kStripRows));
  sh::write(" rows, gold octahedron (Gouraud, depth test)\n");
  bool ok = render_frame();
  const lr::FrameStats& st = g_renderer.stats();
  const uint32_t sum = g_checksum.hash.value;
  g_smoke_checksum = sum;

  report("triangles in:", st.triangles_in);
  report("triangles binned:", st.triangles_binned);
  report("strips:", g_sink.strips());
  report("empty strips:", st.empty_strips);
  report("pixels tested:", st.pixels_tested);
  report("pixels written:", st.pixels_written);
  report("max active:", st.max_active);
  report("dropped (capacity):", st.dropped_vertex_capacity + st.dropped_triangle_capacity);
#ifdef LR_BOARD_RAM_SIZE
  report("stack used (bytes):", lr_stack_used_bytes());
#endif

  if (ok && (st.triangles_binned == 0 || st.pixels_written == 0 ||
             g_sink.strips() != static_cast<uint32_t>(kStrips))) {
    sh::write("lr_smoke: the frame is empty or incomplete\n");
    ok = false;
  }
  // A store too small for the scene drops triangles: the frame would be wrong, say why.
  if (st.dropped_vertex_capacity + st.dropped_triangle_capacity != 0) {
    sh::write("lr_smoke: a store is too small for the scene (dropped, capacity)\n");
    ok = false;
  }
  sh::write("lr_smoke: checksum (FNV-1a of the RGB565BE frame) ");
  sh::write_hex(sum);
  sh::write("\n");
#ifdef LR_SMOKE_EXPECTED_CHECKSUM
  if (sum != static_cast<uint32_t>(LR_SMOKE_EXPECTED_CHECKSUM)) {
    sh::write("lr_smoke: expected ");
    sh::write_hex(static_cast<uint32_t>(LR_SMOKE_EXPECTED_CHECKSUM));
    sh::write("\n");
    ok = false;
  }
#endif
  sh::write(ok ? "lr_smoke: PASS\n" : "lr_smoke: FAIL\n");
  g_smoke_result = ok ? 1u : 2u;
  return ok ? 0 : 1;
}
