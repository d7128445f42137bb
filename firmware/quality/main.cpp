// The quality benchmark's frames on the target: every configuration of lr_quality_bench
// (tests/bench/quality_configs.hpp) rendered at 320x240 in RGB565 strips, once into a checksum
// sink (compared with the host's frame, generated with the scenes by lr_quality_scenes) and once
// into a sink that does no per-pixel work between two calls of lr_bench_marker(), so that the
// instruction-counting plugin counts exactly the frame (scripts/quality_bench.sh: the
// benchmark's instruction axis).
#include <cstddef>
#include <cstdint>
#include <span>

#include "firmware/common/ordered_sink.hpp"
#include "firmware/common/report.hpp"
#include "firmware/common/semihost.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "quality_cases.hpp"

extern "C" {
[[gnu::noinline, gnu::used]] void lr_bench_marker() {
  __asm__ volatile("" ::: "memory");
}
}

namespace {

namespace sh = lr::fw::semihost;
namespace gen = lr::fw::quality_gen;
using PF = lr::Rgb565Be;
using Pixel = PF::Storage;

constexpr int kWidth = 320, kHeight = 240, kMaxStrip = 32;
constexpr int kScenes = 5;

consteval size_t most(size_t (*count)(const lr::Mesh&)) {
  size_t n = 0;
  for (int s = 0; s < kScenes; ++s) {
    size_t k = 0;
    for (const lr::Mesh& m : gen::meshes(s)) k += count(m);
    n = k > n ? k : n;
  }
  return n;
}
// Clipping makes a few vertices and triangles more (the clipped scene): room for them.
constexpr size_t kVertices =
    most([](const lr::Mesh& m) -> size_t { return m.positions.size(); }) + 512;
constexpr size_t kTriangles =
    most([](const lr::Mesh& m) -> size_t { return m.triangles.size(); }) + 512;
static_assert(kVertices <= lr::kMaxStoreEntries && kTriangles <= lr::kMaxStoreEntries);
// The host benchmark's active store (tests/bench/quality_bench.cpp): its free list is part of
// each frame's work, so the counted frames use the same size.
constexpr size_t kActive = 4096;

constexpr lr::FrameCapacities kCapacities{.width = kWidth,
                                          .height = kHeight,
                                          .strip_height = 1,
                                          .vertices = kVertices,
                                          .triangles = kTriangles,
                                          .draws = 16,
                                          .active = kActive,
                                          .tex_vertices = kVertices,
                                          .active_extra = kActive,
                                          .triangle_colors = kTriangles};
// Sized for strips of 1 (the most edge-table buckets); the depth strip for the tallest strips.
lr::StaticFrameStorage<kCapacities> g_store;
alignas(4) std::array<uint16_t, size_t{kWidth} * kMaxStrip> g_depth{};
alignas(4) std::array<std::array<Pixel, size_t{kWidth} * kMaxStrip>, 2> g_strips{};

lr::Renderer<PF, 1> g_r1;
lr::Renderer<PF, 8> g_r8;
lr::Renderer<PF, 32> g_r32;

lr::fw::ChecksumConsumer<PF> g_checksum;

template <int K>
[[gnu::noinline]] lr::Status render_frame(lr::Renderer<PF, K>& r, const gen::QualitySetup& s,
                                          std::span<const lr::Mesh> meshes,
                                          std::span<const lr::Material> materials,
                                          lr::StripSink<PF>& sink) {
  lr::Status st = r.begin_frame(s.camera, s.lights, s.background);
  for (size_t d = 0; d < meshes.size() && st == lr::Status::kOk; ++d)
    st = r.draw(meshes[d], s.model, materials[d], s.state);
  return st == lr::Status::kOk ? r.render(sink) : st;
}

template <int K>
bool run(lr::Renderer<PF, K>& r, const gen::QualityCase& c) {
  lr::FrameStorage storage = g_store.storage();
  storage.depth = g_depth;
  if (!lr::fw::check("lr_quality", r.configure(storage, kWidth, kHeight), "configure"))
    return false;
  gen::QualitySetup s;
  gen::setup(c.scene, s);
  s.state.shading = c.shading;
  s.state.perspective = c.perspective;
  if (c.textured) {
    s.state.texture = gen::texture(c.format);
    s.state.sampler.filter = c.filter;
    s.state.sampler.mip = c.mip;
  }
  const auto meshes = gen::meshes(c.scene);
  const auto materials = gen::materials(c.scene);
  const std::span<Pixel> a(g_strips[0].data(), size_t{kWidth} * K),
      b(g_strips[1].data(), size_t{kWidth} * K);
  lr::fw::OrderedStripSink<PF, lr::fw::ChecksumConsumer<PF>> sink(a, b, g_checksum);
  g_checksum.enabled = true;
  if (!lr::fw::check("lr_quality", render_frame(r, s, meshes, materials, sink), c.key))
    return false;
  const uint32_t sum = g_checksum.hash.value;
  const uint32_t pixels = r.stats().pixels_written;
  g_checksum.enabled = false;
  lr_bench_marker();
  const lr::Status st = render_frame(r, s, meshes, materials, sink);
  lr_bench_marker();
  if (!lr::fw::check("lr_quality", st, c.key)) return false;
  sh::write("lr_quality: case ");
  sh::write(c.key);
  sh::write(" checksum ");
  sh::write_hex(sum);
  sh::write(" pixels ");
  sh::write_dec(pixels);
  const bool same = sum == c.checksum && pixels == c.pixels;
  sh::write(same ? " host-equal\n" : " DIFFERS from the host's frame\n");
  return same;
}

}  // namespace

int main() {
  sh::write("lr_quality: 320x240 RGB565, the quality benchmark's configurations\n");
  bool ok = true;
  for (const gen::QualityCase& c : gen::kCases) {
    switch (c.strip) {
      case 1:
        ok = run(g_r1, c) && ok;
        break;
      case 8:
        ok = run(g_r8, c) && ok;
        break;
      default:
        ok = run(g_r32, c) && ok;
        break;
    }
  }
  sh::write(ok ? "lr_quality: PASS\n" : "lr_quality: FAIL\n");
  return ok ? 0 : 1;
}
