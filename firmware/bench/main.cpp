// The Cortex-M benchmark: every case of cases.hpp rendered twice at 320x240 in RGB565 strips of 8.
//   1. into a sink that folds every pixel into an FNV-1a checksum: the frame, printed so that the
//      host build of this file (tests/firmware_host: lr_bench_host) can be compared line by line;
//   2. into a sink that does no per-pixel work (a DMA-driven panel costs the CPU nothing per
//      pixel), between two calls of lr_bench_marker(): the instruction-counting QEMU plugin
//      (tools/qemu_icount, scripts/bench_cortex_m.sh) prints its count each time the marker is
//      entered, so the difference is the frame's instruction count: begin_frame, the draws
//      (vertex transform, lighting, clipping, setup, binning) and render (every strip).
// Nothing between the two markers calls semihosting or takes an exception (either would end a
// translation block early and make the plugin's block counts inexact).
#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/bench/cases.hpp"
#include "firmware/common/ordered_sink.hpp"
#include "firmware/common/report.hpp"
#include "firmware/common/semihost.hpp"
#include "lineraster/core/raster/renderer.hpp"

extern "C" {
// The marker: entered right before and right after each measured frame. Its body is one
// instruction (bx lr); noinline + used keep it a real call with a symbol the runner can find.
[[gnu::noinline, gnu::used]] void lr_bench_marker() {
  __asm__ volatile("" ::: "memory");
}
}

namespace {

namespace sh = lr::fw::semihost;
namespace bench = lr::fw::bench;
using PF = lr::Rgb565Be;
using Pixel = PF::Storage;

constexpr int kWidth = 320, kHeight = 240, kStripRows = 8;
constexpr size_t kStripPixels = size_t{kWidth} * kStripRows;

consteval size_t vertices(std::span<const lr::Mesh> meshes) {
  size_t n = 0;
  for (const lr::Mesh& m : meshes) n += m.positions.size();
  return n;
}
consteval size_t max_of(size_t a, size_t b) {
  return a > b ? a : b;
}
consteval size_t triangles(std::span<const lr::Mesh> meshes) {
  size_t n = 0;
  for (const lr::Mesh& m : meshes) n += m.triangles.size();
  return n;
}
// The near plane clips only the ground plane (two triangles): a little room suffices.
// The subdivided knot (32,841 vertices, 64,000 triangles) sets the vertex and triangle stores;
// it is drawn Gouraud-shaded only, so the Phong surfaces are sized for the other meshes.
constexpr size_t kVertexCapacity =
    max_of(
        vertices(bench_knot64k_asset::meshes),
        max_of(vertices(bench_knot_asset::meshes),
               max_of(vertices(bench_cube_asset::meshes), vertices(bench_ground_asset::meshes)))) +
    32;
constexpr size_t kSurfaceCapacity =
    max_of(vertices(bench_knot_asset::meshes),
           max_of(vertices(bench_cube_asset::meshes), vertices(bench_ground_asset::meshes))) +
    32;
constexpr size_t kTriangleCapacity = triangles(bench_knot64k_asset::meshes) + 32;
static_assert(kVertexCapacity <= lr::kMaxStoreEntries && kTriangleCapacity < lr::kMaxStoreEntries);
// The knot: 565 at most at 2.4 units, 958 at 12 units; its subdivided twin: 4,468.
// Every other case gets the first kActiveSmall entries: render() makes a free list of the whole
// active store each frame (a few instructions per entry), so the store's size is part of the
// frame's count.
constexpr size_t kActive = 5000;
constexpr size_t kActiveSmall = 1024;
constexpr uint16_t kTableSize = 32;

// Phong draws: one lighting table and one prepared lighting per material (the cube has two).
constexpr lr::FrameCapacities kCapacities{
    .width = kWidth,
    .height = kHeight,
    .strip_height = kStripRows,
    .vertices = kVertexCapacity,
    .triangles = kTriangleCapacity,
    .draws = 4,
    .active = kActive,
    .surfaces = kSurfaceCapacity,
    .lighting_table_words = 2 * lr::lighting_table_words(kTableSize, false),
    .pixel_lights = 2,
    .tex_vertices = kVertexCapacity,
    .active_extra = kActive,
    .triangle_colors = kTriangleCapacity};
lr::StaticFrameStorage<kCapacities> g_store;
// Word-aligned: the strip loop fills and clears strips with word stores (memset, memcpy).
alignas(4) std::array<std::array<Pixel, kStripPixels>, 2> g_strips{};

lr::Renderer<PF, kStripRows> g_renderer;
// The cases with BenchCase::shared_fetch: a renderer without the inlined texel fetch
// (SpanSet::inline_fetch), for the textured states of the cube and the ground.
constexpr lr::SpanSet kSharedFetchSpans = lr::kTexturedOnly.only(lr::TexPersp::kExact)
                                              .only(lr::MipMode::kNone)
                                              .only(lr::TexelFormat::kRgb565)
                                              .only_inline_fetch(false);
lr::Renderer<PF, kStripRows, kSharedFetchSpans> g_shared_renderer;

// Two buffers lent in turn; each strip is hashed (the checked frame) or only handed back (the
// measured one).
lr::fw::ChecksumConsumer<PF> g_checksum;
lr::fw::OrderedStripSink<PF, lr::fw::ChecksumConsumer<PF>> g_sink(g_strips[0], g_strips[1],
                                                                  g_checksum);

bool check(lr::Status st, const char* what) {
  return lr::fw::check("lr_bench", st, what);
}

// Everything the measured region needs, prepared before it.
struct Prepared {
  lr::Camera camera;
  std::array<lr::Mat4, 4> models;
  std::array<lr::Material, 4> materials;
  lr::DrawState state;
  std::span<const lr::Mesh> meshes;
};

template <class R>
bool prepare(R& renderer, const bench::BenchCase& c, Prepared& p) {
  const size_t active = c.active_store != 0                ? c.active_store
                        : c.mesh == bench::Mesh3::kKnot64k ? kActive
                                                           : kActiveSmall;
  lr::FrameStorage storage = g_store.storage();
  storage.active = storage.active.first(active);
  storage.active_index = storage.active_index.first(2 * active);
  if (c.triangle_store != 0) storage.triangles = storage.triangles.first(c.triangle_store);
  if (c.vertex_store != 0) storage.vertices = storage.vertices.first(c.vertex_store);
  if (!check(renderer.configure(storage, kWidth, kHeight), "configure")) return false;
  if (!lr::fw::demo::make_camera(c.view, kWidth, kHeight, p.camera)) {
    sh::write("lr_bench: camera rejected\n");
    return false;
  }
  p.meshes = bench::meshes(c.mesh);
  if (p.meshes.size() > p.materials.size()) return false;
  for (size_t d = 0; d < p.meshes.size(); ++d) {
    p.materials[d] = bench::material(c, d);
    p.models[d] = bench::model(c, d);
  }
  p.state = c.state;
  p.state.texture = bench::texture(c);
  return true;
}

// The measured work: one whole frame.
template <class R>
[[gnu::noinline]] lr::Status render_frame(R& renderer, const bench::BenchCase& c,
                                          const Prepared& p) {
  lr::Status s = renderer.begin_frame(p.camera, c.lights, lr::Rgb8{0, 0, 0});
  for (size_t d = 0; d < p.meshes.size() && s == lr::Status::kOk; ++d)
    s = renderer.draw(p.meshes[d], p.models[d], p.materials[d], p.state);
  return s == lr::Status::kOk ? renderer.render(g_sink) : s;
}

template <class R>
bool run_case(R& renderer, const bench::BenchCase& c) {
  Prepared p;
  if (!prepare(renderer, c, p)) return false;
  g_checksum.enabled = true;
  if (!check(render_frame(renderer, c, p), c.name)) return false;
  const uint32_t sum = g_checksum.hash.value;
  const lr::FrameStats st = renderer.stats();
  const uint32_t dropped = st.dropped_vertex_capacity + st.dropped_triangle_capacity;

  g_checksum.enabled = false;
  lr_bench_marker();
  const lr::Status s = render_frame(renderer, c, p);
  lr_bench_marker();
  if (!check(s, c.name)) return false;

  // One line per case, after its two markers: the runner pairs them in order.
  sh::write("lr_bench: case ");
  sh::write(c.name);
  sh::write(" checksum ");
  sh::write_hex(sum);
  sh::write(" pixels ");
  sh::write_dec(st.pixels_written);
  sh::write(" triangles ");
  sh::write_dec(st.triangles_in);
  sh::write(" binned ");
  sh::write_dec(st.triangles_binned);
  sh::write(" dropped ");
  sh::write_dec(dropped);
  // What the early outs did (scripts/bench_cortex_m.sh reads these by name).
  const struct {
    const char* name;
    uint32_t value;
  } counts[] = {{"tested", st.pixels_tested},         {"culled_back", st.culled_backface},
                {"culled_zero", st.culled_zero_area}, {"culled_off", st.culled_offscreen},
                {"clipped_away", st.clipped_away},    {"strips", st.strips},
                {"empty_strips", st.empty_strips},    {"vertices", st.vertices_transformed},
                {"max_active", st.max_active},        {"bands", st.bands},
                {"band_retries", st.band_retries},    {"strip_passes", st.strip_passes}};
  for (const auto& n : counts) {
    sh::write(" ");
    sh::write(n.name);
    sh::write(" ");
    sh::write_dec(n.value);
  }
  sh::write("\n");
  return dropped == 0 && (st.pixels_written > 0) == bench::draws_pixels(c);
}

}  // namespace

int main() {
  sh::write("lr_bench: 320x240 RGB565, strips of 8 rows\n");
  bool ok = true;
  for (const bench::BenchCase& c : bench::kCases)
    ok = (c.shared_fetch ? run_case(g_shared_renderer, c) : run_case(g_renderer, c)) && ok;
  sh::write(ok ? "lr_bench: PASS\n" : "lr_bench: FAIL\n");
  return ok ? 0 : 1;
}
