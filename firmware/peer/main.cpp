// lr_peer: the six peer scenes of scenes.hpp, each rendered twice at 320x240 in RGB565 strips of 8
// (big-endian, as on the SPI wire) with the renderer's default settings:
//   1. into a sink that folds every pixel into an FNV-1a checksum, with a depth sink that counts
//      the covered pixels: the frame, printed so that the host build of this file
//      (tests/firmware_host: lr_peer_host) can be compared with it line by line;
//   2. into a sink that does no per-pixel work, between two calls of lr_bench_marker(): the
//      counting QEMU plugin (scripts/icount.sh, scripts/icount_profile.py, scripts/peer_bench.sh)
//      counts the whole frame, begin_frame, the draw and render.
// A case fails when it drops work or when its covered pixels differ from Mesa's count by more
// than a few (scenes.hpp): a frame that is not the scene's definition.
// Each case's line is in lr_bench's format ("lr_bench: case NAME ..." after the case's two
// markers), the protocol scripts/icount_profile.py reads, followed by the frame statistics by
// name. Nothing between the markers calls semihosting or takes an exception.
//
// Two images of this file (firmware/peer/CMakeLists.txt):
//   lr_peer        one renderer with every span routine linked (kAllSpans, the default);
//   lr_peer_spans  (LR_PEER_SCENE_SPANS) one renderer per case, each restricted to the span set
//                  of its case's draw state (scenes.hpp: scene_spans), as an application that
//                  draws only that scene links it. Its frames must equal lr_peer's.
#include <array>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <utility>

#include "firmware/common/bench_case.hpp"
#include "firmware/common/ordered_sink.hpp"
#include "firmware/common/report.hpp"
#include "firmware/common/semihost.hpp"
#include "firmware/peer/assets.hpp"
#include "firmware/peer/scenes.hpp"
#include "lineraster/core/output/depth_sink.hpp"
#include "lineraster/core/raster/renderer.hpp"

namespace {

namespace sh = lr::fw::semihost;
namespace peer = lr::fw::peer;
using PF = lr::Rgb565Be;
using Pixel = PF::Storage;

constexpr int kStripRows = 8;
constexpr size_t kStripPixels = size_t{peer::kWidth} * kStripRows;

// The subdivided bunny sets the vertex and triangle stores (every vertex transformed, every
// triangle binned); the near plane clips only the ground plane's two triangles.
constexpr size_t kVertexCapacity = peer_bunnyx_asset::meshes[0].positions.size() + 32;
constexpr size_t kTriangleCapacity = peer_bunnyx_asset::meshes[0].triangles.size() + 32;
static_assert(peer_bunnyx_asset::meshes.size() == 1);
static_assert(kVertexCapacity <= lr::kMaxStoreEntries && kTriangleCapacity < lr::kMaxStoreEntries);
// Active triangles: the subdivided bunny gets the whole store, the other scenes its first
// kActiveSmall entries (render() makes a free list of the whole active store each frame, so its
// size is part of every frame's count).
constexpr size_t kActive = 2048;
constexpr size_t kActiveSmall = 512;

constexpr lr::FrameCapacities kCapacities{.width = peer::kWidth,
                                          .height = peer::kHeight,
                                          .strip_height = kStripRows,
                                          .vertices = kVertexCapacity,
                                          .triangles = kTriangleCapacity,
                                          .draws = 2,
                                          .active = kActive,
                                          .tex_vertices = kVertexCapacity,
                                          .active_extra = kActive};
lr::StaticFrameStorage<kCapacities> g_store;
// Word-aligned: the strip loop fills and clears strips with word stores (memset, memcpy).
alignas(4) std::array<std::array<Pixel, kStripPixels>, 2> g_strips{};

#ifdef LR_PEER_SCENE_SPANS
template <size_t I>
using CaseRenderer = lr::Renderer<PF, kStripRows, peer::scene_spans(peer::kCases[I])>;
template <class Indices>
struct CaseRenderers;
template <size_t... I>
struct CaseRenderers<std::index_sequence<I...>> {
  using type = std::tuple<CaseRenderer<I>...>;
};
CaseRenderers<std::make_index_sequence<peer::kCases.size()>>::type g_renderers;
// The renderer of case I.
template <size_t I>
auto& renderer() {
  return std::get<I>(g_renderers);
}
#else
lr::Renderer<PF, kStripRows> g_renderer;
template <size_t>
auto& renderer() {
  return g_renderer;
}
#endif

lr::fw::ChecksumConsumer<PF> g_checksum;
lr::fw::OrderedStripSink<PF, lr::fw::ChecksumConsumer<PF>> g_sink(g_strips[0], g_strips[1],
                                                                  g_checksum);

// Counts the pixels some triangle covered: those whose depth is no longer the cleared value.
class CoveredPixels final : public lr::DepthSink {
 public:
  void on_depth(const lr::StripRect&, std::span<const uint16_t> depth) override {
    for (uint16_t d : depth) count += d != 0xFFFFu;
  }
  uint32_t count = 0;
};

bool check(lr::Status st, const char* what) {
  return lr::fw::check("lr_peer", st, what);
}

struct Prepared {
  lr::Camera camera;
  lr::Mat4 model;
  lr::FineMat4 fine_model;       // fine scenes (PeerCase::fine)
  lr::FineMat4 fine_projection;  // their camera's (camera.fine_projection points to it)
  lr::DrawState state;
  std::span<const lr::Mesh> meshes;
};

template <class R>
bool prepare(R& renderer, const peer::PeerCase& c, Prepared& p) {
  const size_t active = c.geometry == peer::Geometry::kBunnyX ? kActive : kActiveSmall;
  lr::FrameStorage storage = g_store.storage();
  storage.active = storage.active.first(active);
  storage.active_index = storage.active_index.first(2 * active);
  if (!check(renderer.configure(storage, peer::kWidth, peer::kHeight), "configure")) return false;
  if (!peer::make_camera(c, p.camera, p.fine_projection)) {
    sh::write("lr_peer: projection rejected\n");
    return false;
  }
  p.model = peer::model(c);
  p.fine_model = c.fine ? peer::fine_model(c) : lr::FineMat4{};
  p.state = c.state;
  p.state.texture = peer::texture(c.geometry);
  p.meshes = peer::meshes(c.geometry);
  return true;
}

// The measured work: one whole frame.
template <class R>
[[gnu::noinline]] lr::Status render_frame(R& renderer, const peer::PeerCase& c, const Prepared& p,
                                          lr::DepthSink* depth) {
  lr::Status s = renderer.begin_frame(p.camera, c.lights, peer::kBackground);
  for (size_t d = 0; d < p.meshes.size() && s == lr::Status::kOk; ++d)
    s = c.fine ? renderer.draw(p.meshes[d], p.fine_model, c.material, p.state)
               : renderer.draw(p.meshes[d], p.model, c.material, p.state);
  return s == lr::Status::kOk ? renderer.render(g_sink, depth) : s;
}

template <size_t I>
bool run_case() {
  const peer::PeerCase& c = peer::kCases[I];
  auto& r = renderer<I>();
  Prepared p;
  if (!prepare(r, c, p)) return false;
  CoveredPixels covered;
  g_checksum.enabled = true;
  if (!check(render_frame(r, c, p, &covered), c.name)) return false;
  const uint32_t sum = g_checksum.hash.value;
  const lr::FrameStats st = r.stats();
  const uint32_t dropped = st.dropped_vertex_capacity + st.dropped_triangle_capacity;

  g_checksum.enabled = false;
  lr_bench_marker();
  const lr::Status s = render_frame(r, c, p, nullptr);
  lr_bench_marker();
  if (!check(s, c.name)) return false;

  sh::write("lr_bench: case ");
  sh::write(c.name);
  sh::write(" checksum ");
  sh::write_hex(sum);
  const lr::fw::NamedCount counts[] = {{"covered", covered.count},
                                       {"pixels_written", st.pixels_written},
                                       {"pixels_tested", st.pixels_tested},
                                       {"vertices", st.vertices_transformed},
                                       {"triangles_in", st.triangles_in},
                                       {"culled_back", st.culled_backface},
                                       {"culled_zero", st.culled_zero_area},
                                       {"culled_off", st.culled_offscreen},
                                       {"clipped_away", st.clipped_away},
                                       {"binned", st.triangles_binned},
                                       {"set_up", st.triangles_set_up},
                                       {"wide", st.triangles_wide},
                                       {"no_pixels", st.triangles_without_pixels},
                                       {"spans", st.spans},
                                       {"rows", st.rows_walked},
                                       {"max_active", st.max_active},
                                       {"dropped", dropped}};
  lr::fw::write_counts(counts);
  sh::write("\n");
  const uint32_t off = covered.count > c.mesa_covered ? covered.count - c.mesa_covered
                                                      : c.mesa_covered - covered.count;
  if (off > peer::kCoverageSlack) {
    sh::write("lr_peer: ");
    sh::write(c.name);
    sh::write(" covers a different frame than Mesa's (");
    sh::write_dec(c.mesa_covered);
    sh::write(" pixels)\n");
  }
  return dropped == 0 && st.pixels_written > 0 && off <= peer::kCoverageSlack;
}

template <size_t... I>
bool run_cases(std::index_sequence<I...>) {
  bool ok = true;
  ((ok = run_case<I>() && ok), ...);
  return ok;
}

}  // namespace

int main() {
#ifdef LR_PEER_SCENE_SPANS
  sh::write(
      "lr_peer: the peer scenes, 320x240 RGB565, strips of 8 rows, each case's span set linked\n");
#else
  sh::write("lr_peer: the peer scenes, 320x240 RGB565, strips of 8 rows, every span routine\n");
#endif
  const bool ok = run_cases(std::make_index_sequence<peer::kCases.size()>());
  sh::write(ok ? "lr_peer: PASS\n" : "lr_peer: FAIL\n");
  return ok ? 0 : 1;
}
