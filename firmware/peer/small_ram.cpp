// The peer scenes S1 and S1x, and lr_bench's 64,000-triangle knot, in small RAM: the stores hold
// a fraction of the mesh, so the frame is drawn in bands (docs/bands.md); it must still be the
// one-pass frame lr_peer (or lr_bench) draws, pixel for pixel. LR_SMALL_RAM_CASE picks the case
// of small_ram_cases.hpp: 0, S1 in the micro:bit's 16 KB (lr_peer_bunny_16k); 1, S1x in 64 KB
// (lr_peer_bunnyx_64k); 2, knot64k_gouraud in 64 KB (lr_peer_knot64k_64k); 3, S1 in 64 KB in
// one pass (lr_peer_bunny_64k: stores for the whole frame, no band).
//
// The frame goes twice through the renderer:
//   1. into a PPM file on the host (semihosting), while every RGB565 pixel is folded into the
//      FNV-1a checksum lr_peer (lr_bench) prints for the scene (the same bytes: big-endian RGB565,
//      rows top to bottom): scripts/small_ram.sh compares the checksum with lr_peer_host's line and
//      the file with the one this program's host build writes;
//   2. into a sink that does no per-pixel work, between two calls of lr_bench_marker(), for the
//      instruction count (scripts/icount.sh), in lr_bench's line format.
// It fails when a store drops work, when render() reports a capacity error, or when a strip is
// missing: a frame drawn in bands is complete or the run says why.
#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/bench/knot_view.hpp"
#include "firmware/common/bench_case.hpp"
#include "firmware/common/ordered_sink.hpp"
#include "firmware/common/ppm_file.hpp"
#include "firmware/common/report.hpp"
#include "firmware/common/semihost.hpp"
#include "firmware/peer/scenes.hpp"
#include "firmware/peer/small_ram_cases.hpp"
#include "lineraster/core/raster/renderer.hpp"
#if LR_SMALL_RAM_CASE == 2
#include "knot64k_local_asset.hpp"  // lineraster-asset --fit --subdivide 2 --locality
namespace asset = ::knot64k_local_asset;
constexpr const lr::fw::peer::small::SmallRamCase& kSmall = lr::fw::peer::small::kKnot64k64k;
#elif LR_SMALL_RAM_CASE == 3
#include "peer_bunny_local_asset.hpp"  // lineraster-asset --obj bunny.obj --fit-box --locality
namespace asset = ::peer_bunny_local_asset;
constexpr const lr::fw::peer::small::SmallRamCase& kSmall = lr::fw::peer::small::kBunny64k;
#elif LR_SMALL_RAM_CASE == 1
#include "peer_bunnyx_local_asset.hpp"  // lineraster-asset --fit-box --subdivide 2 --locality
namespace asset = ::peer_bunnyx_local_asset;
constexpr const lr::fw::peer::small::SmallRamCase& kSmall = lr::fw::peer::small::kBunnyx64k;
#else
#include "peer_bunny_local_asset.hpp"  // lineraster-asset --obj bunny.obj --fit-box --locality
namespace asset = ::peer_bunny_local_asset;
constexpr const lr::fw::peer::small::SmallRamCase& kSmall = lr::fw::peer::small::kBunny16k;
#endif

namespace {

namespace sh = lr::fw::semihost;
namespace peer = lr::fw::peer;
using PF = lr::Rgb565Be;
using Pixel = PF::Storage;

constexpr int kStripRows = kSmall.strip_rows;
constexpr size_t kStripPixels = size_t{peer::kWidth} * kStripRows;

constexpr lr::FrameCapacities kCapacities{.width = peer::kWidth,
                                          .height = peer::kHeight,
                                          .strip_height = kStripRows,
                                          .vertices = kSmall.vertices,
                                          .triangles = kSmall.triangles,
                                          .draws = 1,
                                          .active = kSmall.active};
lr::StaticFrameStorage<kCapacities> g_store;
// Word-aligned: the strip loop fills and clears strips with word stores (memset, memcpy).
alignas(4) std::array<std::array<Pixel, kStripPixels>, 2> g_strips{};

// Every case is lit Gouraud with perspective-exact colours and a depth test: the renderer links
// those span routines only.
constexpr lr::SpanSet kSpans =
    lr::kUntexturedSpans.only_depth(true).only(lr::ColorPlanes::kPerspective);
lr::Renderer<PF, kStripRows, kSpans> g_renderer;

// What the frame draws besides its mesh: a peer scene's, or lr_bench's knot64k_gouraud's.
struct Scene {
  const char* name;
  lr::LightSet lights;
  lr::DrawState state;
  lr::Rgb8 background;
};
constexpr bool kKnot = kSmall.scene == peer::small::kKnotScene;
consteval Scene make_scene() {
  if constexpr (kKnot) {
    return {"knot64k_gouraud", lr::fw::demo::sim_default_lights(), lr::fw::bench::knot64k_state(),
            lr::Rgb8{0, 0, 0}};
  } else {
    const peer::PeerCase& c = peer::kCases[kSmall.scene];
    return {c.name, c.lights, c.state, peer::kBackground};
  }
}
constexpr Scene kScene = make_scene();
lr::Material g_material;  // the scene's (prepare())
static_assert(kScene.state.lighting && kScene.state.texture == nullptr);
static_assert(asset::meshes.size() == 1);

// The PPM file (in QEMU's working directory) and lr_peer's checksum of the same strips.
struct PpmAndChecksum {
  lr::fw::PpmFile<PF> file{kSmall.ppm};
  lr::fw::ChecksumConsumer<PF> sum;
  bool to_file = true;
  lr::Status begin(uint16_t w, uint16_t h) {
    sum.begin(w, h);
    return to_file ? file.begin(w, h) : lr::Status::kOk;
  }
  lr::Status strip(const lr::StripRect& r, std::span<const Pixel> pixels) {
    sum.strip(r, pixels);
    return to_file ? file.strip(r, pixels) : lr::Status::kOk;
  }
  lr::Status end() { return to_file ? file.end() : lr::Status::kOk; }
};
PpmAndChecksum g_out;
lr::fw::OrderedStripSink<PF, PpmAndChecksum> g_sink(g_strips[0], g_strips[1], g_out);

bool check(lr::Status st, const char* what) {
  return lr::fw::check(kSmall.name, st, what);
}

// The model matrix (a Q16.16 one as to_fine gives it: frac 16, drawn as the Mat4 it holds) and,
// for a fine scene (PeerCase::fine), its projection, which g_camera points to.
lr::FineMat4 g_model{};
// (The knot's build never reads the projection.)
[[maybe_unused]] lr::FineMat4 g_fine_projection{};
bool g_fine = false;  // draw g_model as a FineMat4

// The draw; out of line, so that the Q16.16 model's copy is off the stack while the frame renders.
[[gnu::noinline]] lr::Status draw_mesh() {
  if (g_fine) return g_renderer.draw(asset::meshes[0], g_model, g_material, kScene.state);
  return g_renderer.draw(asset::meshes[0], lr::to_mat4(g_model), g_material, kScene.state);
}

// The measured work: one whole frame.
[[gnu::noinline]] lr::Status render_frame(const lr::Camera& camera) {
  lr::Status s = g_renderer.begin_frame(camera, kScene.lights, kScene.background);
  if (s == lr::Status::kOk) s = draw_mesh();
  return s == lr::Status::kOk ? g_renderer.render(g_sink) : s;
}

[[gnu::noinline]] void write_stats(const lr::FrameStats& st) {
  sh::write(kSmall.name);
  sh::write(":");
  const lr::fw::NamedCount counts[] = {
      {"pixels_written", st.pixels_written},
      {"vertices", st.vertices_transformed},
      {"triangles_in", st.triangles_in},
      {"binned", st.triangles_binned},
      {"bands", st.bands},
      {"band_retries", st.band_retries},
      {"strip_passes", st.strip_passes},
      {"max_active", st.max_active},
      {"dropped_vertices", st.dropped_vertex_capacity},
      {"dropped_triangles", st.dropped_triangle_capacity},
      {"vertex_store", static_cast<uint32_t>(kSmall.vertices)},
      {"triangle_store", static_cast<uint32_t>(kSmall.triangles)},
      {"active_store", static_cast<uint32_t>(kSmall.active)},
      {"ram_budget", kSmall.ram_budget},
      {"strip_rows", static_cast<uint32_t>(kStripRows)},
      {"store_bytes", static_cast<uint32_t>(sizeof(g_store))},
      {"strip_bytes", static_cast<uint32_t>(sizeof(g_strips))},
      {"renderer_bytes", static_cast<uint32_t>(sizeof(g_renderer))}};
  lr::fw::write_counts(counts);
  sh::write("\n");
}

bool complete(const lr::FrameStats& st) {
  const uint32_t dropped = st.dropped_vertex_capacity + st.dropped_triangle_capacity;
  if (dropped == 0 && st.pixels_written > 0 && g_sink.strips() == peer::kHeight / kStripRows)
    return true;
  sh::write(kSmall.name);
  sh::write(": the frame is incomplete (capacity, or strips missing)\n");
  return false;
}

// A one-pass case must not need bands or strips in passes: its stores hold the whole frame.
bool in_one_pass(const lr::FrameStats& st) {
  if (!kSmall.one_pass || (st.bands == 1 && st.band_retries == 0 && st.strip_passes == 0))
    return true;
  sh::write(kSmall.name);
  sh::write(": the frame needed bands or strips in passes: not one pass\n");
  return false;
}

// The camera and the model matrix, static: on the stack they would add to the deepest path, whose
// bound is part of the RAM budget.
lr::Camera g_camera;

// The stores, the camera and the model matrix; out of line, so that its temporaries are off the
// stack while the frame renders.
[[gnu::noinline]] bool prepare() {
  if (!check(g_renderer.configure(g_store.storage(), peer::kWidth, peer::kHeight), "configure"))
    return false;
  bool camera_ok = false;
  if constexpr (kKnot) {
    // lr_bench's camera, model matrix and material of the case (firmware/bench/cases.hpp).
    camera_ok =
        lr::fw::demo::make_camera(lr::fw::bench::kKnotView, peer::kWidth, peer::kHeight, g_camera);
    g_model = lr::to_fine(lr::rotate_y(lr::Fixed::from_int(0)));
    const lr::NamedMaterial* gold = lr::find_material("gold");
    if (gold == nullptr) return false;
    g_material = lr::to_material(*gold);
  } else {
    const peer::PeerCase& c = peer::kCases[kSmall.scene];
    camera_ok = peer::make_camera(c, g_camera, g_fine_projection);
    g_fine = c.fine;
    g_model = c.fine ? peer::fine_model(c) : lr::to_fine(peer::model(c));
    g_material = c.material;
  }
  if (!camera_ok) {
    sh::write(kSmall.name);
    sh::write(": camera rejected\n");
    return false;
  }
  return true;
}

bool run() {
  if (!prepare()) return false;
  const lr::Camera& camera = g_camera;
  const lr::Status first = render_frame(camera);
  const uint32_t sum = g_out.sum.hash.value;
  // The first frame's statistics, read in the renderer (no copy: 144 B of RAM) before the
  // second frame begins.
  const lr::FrameStats& st = g_renderer.stats();
  write_stats(st);
  if (!check(first, "render (to the file)") || !complete(st) || !in_one_pass(st)) return false;

  g_out.to_file = false;
  g_out.sum.enabled = false;
  lr_bench_marker();
  const lr::Status s = render_frame(camera);
  lr_bench_marker();
  if (!check(s, "render (counted)") || !complete(g_renderer.stats())) return false;

  sh::write("lr_bench: case ");
  sh::write(kSmall.case_name);
  sh::write(" checksum ");
  sh::write_hex(sum);
  sh::write("\n");
  return true;
}

}  // namespace

int main() {
  sh::write(kSmall.name);
  sh::write(": ");
  sh::write(kScene.name);
  sh::write(", 320x240 RGB565 in strips of ");
  sh::write_dec(static_cast<uint32_t>(kStripRows));
  sh::write(" row(s), banded stores\n");
  const bool ok = run();
  sh::write(kSmall.name);
  sh::write(ok ? ": PASS\n" : ": FAIL\n");
  return ok ? 0 : 1;
}
