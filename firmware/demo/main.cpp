// The demo firmware: one frame of a scene whose mesh and texture were converted to flash arrays
// at build time (lineraster-asset), rendered strip by strip through the HAL's StripSink into a
// PPM file on the host (semihosting: QEMU -semihosting, or a debugger). scripts/ci_firmware.sh
// renders the same scene with lineraster-sim on the PC and compares the two files byte for byte.
// With LR_DEMO_PANEL (the Cortex-M7 build) the strips take a panel firmware's path instead:
// RGB565 in DMA strip buffers, a PanelSink and a bus that cleans the data cache before each
// transfer (firmware/demo/output.hpp); the file is then what the panel would show.
//
// The scene is chosen at compile time: LR_DEMO_SCENE names its header and LR_DEMO_SCENE_NS its
// namespace (knot_scene.hpp, knot: the README's demo; cube_scene.hpp, cube: a textured cube that
// fits a 16 KB-RAM Cortex-M0+), LR_DEMO_OUTPUT
// the file QEMU writes, relative to its working directory. All storage is static and sized from
// the scene: no heap, no frame buffer (two strips of RGB888 and one strip of depth).
#include <cstddef>
#include <cstdint>

#include "firmware/common/report.hpp"
#include "firmware/common/semihost.hpp"
#include "firmware/demo/output.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include LR_DEMO_SCENE

namespace {

namespace scene = lr::fw::demo::LR_DEMO_SCENE_NS;
namespace sh = lr::fw::semihost;
constexpr int kWidth = scene::kWidth, kHeight = scene::kHeight, kStripRows = scene::kStripRows;
constexpr size_t kStrips = (kHeight + kStripRows - 1) / kStripRows;
constexpr size_t kStripPixels = size_t{kWidth} * kStripRows;

consteval size_t total_vertices() {
  size_t n = 0;
  for (const lr::Mesh& m : scene::asset::meshes) n += m.positions.size();
  return n;
}
consteval size_t total_triangles() {
  size_t n = 0;
  for (const lr::Mesh& m : scene::asset::meshes) n += m.triangles.size();
  return n;
}
// Clipping at the near plane adds a few vertices and triangles per clipped triangle (the scene's
// kClipMargin); the stores report (FrameStats::dropped_*) rather than overflow.
constexpr size_t kVertexCapacity = total_vertices() + scene::kClipMargin;
constexpr size_t kTriangleCapacity = total_triangles() + scene::kClipMargin;
constexpr size_t kActive = scene::kActiveCapacity;
consteval bool any_textured() {
  for (bool t : scene::asset::textured)
    if (t) return true;
  return false;
}
static_assert(kVertexCapacity <= 0xFFFF && kTriangleCapacity <= 0xFFFE, "uint16 indices");

// Constant-initialised: the stores go to .bss and cost no startup code.
constexpr lr::FrameCapacities kCapacities{.width = kWidth,
                                          .height = kHeight,
                                          .strip_height = kStripRows,
                                          .vertices = kVertexCapacity,
                                          .triangles = kTriangleCapacity,
                                          .draws = scene::asset::draw_count,
                                          .active = kActive,
                                          .tex_vertices = any_textured() ? kVertexCapacity : 0,
                                          .active_extra = any_textured() ? kActive : 0};
lr::StaticFrameStorage<kCapacities> g_store;
#ifndef LR_DEMO_OUTPUT
#define LR_DEMO_OUTPUT "lr_demo.ppm"
#endif
#if LR_DEMO_PANEL
lr::fw::demo::PanelOutput<kStripPixels> g_out(LR_DEMO_OUTPUT);
static_assert(kHeight % kStripRows == 0, "the DMA check counts whole strips");
#else
lr::fw::demo::FileOutput<kStripPixels> g_out(LR_DEMO_OUTPUT);
#endif
using PF = decltype(g_out)::PF;

// Only the span routines of the scene's draw states are linked (scene::kSpans, an lr::SpanSet:
// core/span/span_state.hpp); a draw outside them would be refused.
lr::Renderer<PF, kStripRows, scene::kSpans> g_renderer;

bool check(lr::Status st, const char* what) {
  return lr::fw::check("lr_demo", st, what);
}
using lr::fw::report;

bool render_frame() {
  if (!check(g_renderer.configure(g_store.storage(), kWidth, kHeight), "configure")) return false;
  lr::Camera camera;
  if (!lr::fw::demo::make_camera(scene::kView, kWidth, kHeight, camera)) {
    sh::write("lr_demo: camera rejected\n");
    return false;
  }
  if (!check(g_renderer.begin_frame(camera, scene::kLights, scene::kBackground), "begin_frame"))
    return false;
  const lr::Mat4 model = lr::Mat4::identity();  // the asset is already fitted (--fit)
  for (size_t d = 0; d < scene::asset::draw_count; ++d) {
    if (!check(g_renderer.draw(scene::asset::meshes[d], model, scene::material(d), scene::state(d)),
               "draw"))
      return false;
  }
  if (!check(g_out.begin(), "panel start")) return false;
  const bool rendered = check(g_renderer.render(g_out.sink()), "render");
  return check(g_out.end(), "frame end") && rendered;
}

}  // namespace

int main() {
  g_out.start_core();
  sh::write("lr_demo: scene ");
  sh::write(scene::kName);
  sh::write(LR_DEMO_PANEL ? ", 320x240 RGB565 to an ST7789 (DMA strips) in strips of "
                          : ", 320x240 RGB888 in strips of ");
  sh::write_dec(static_cast<uint32_t>(kStripRows));
  sh::write(" rows -> " LR_DEMO_OUTPUT "\n");
  bool ok = render_frame();
  const lr::FrameStats& st = g_renderer.stats();
  report("triangles in:", st.triangles_in);
  report("triangles binned:", st.triangles_binned);
  report("strips:", g_out.strips());
  report("pixels written:", st.pixels_written);
  report("max active:", st.max_active);
  const uint32_t dropped = st.dropped_vertex_capacity + st.dropped_triangle_capacity;
  report("dropped (capacity):", dropped);
  if (ok &&
      (dropped != 0 || st.pixels_written == 0 || g_out.strips() != static_cast<uint32_t>(kStrips) ||
       g_out.pixel_bytes() != 3u * kWidth * kHeight)) {
    sh::write("lr_demo: the frame is incomplete (capacity, or strips missing)\n");
    ok = false;
  }
  sh::write("lr_demo: checksum (FNV-1a of the RGB888 pixels) ");
  sh::write_hex(g_out.checksum());
  sh::write("\n");
  if (!g_out.check(static_cast<uint32_t>(kStripPixels * sizeof(PF::Storage)))) {
    sh::write("lr_demo: a transfer was not cleaned first, or not exactly\n");
    ok = false;
  }
  if (g_out.kSimOptions[0] != '\0') {
    sh::write("lr_demo: sim options: ");
    sh::write(g_out.kSimOptions);
    sh::write("\n");
  }
  sh::write(ok ? "lr_demo: PASS\n" : "lr_demo: FAIL\n");
  return ok ? 0 : 1;
}
