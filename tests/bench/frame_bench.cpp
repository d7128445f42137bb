// Host time per frame of the demo scene (the 4,000-triangle torus knot, gold, Gouraud, 320x240,
// strips of 8 rows, RGB565) and RAM figures. `--frame-once` renders one frame through
// render_frame() only, for instruction counting under callgrind (--toggle-collect=render_frame).
// Benchmarks print figures; they do not pass or fail on time.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "core/camera.hpp"
#include "core/renderer.hpp"
#include "host_sim/obj_loader.hpp"
#include "tests/bench/null_sink.hpp"

namespace {

using namespace lr;

using bench::NullSink;

struct Scene {
  std::vector<Vec3> positions;
  std::vector<Normal16> normals;
  std::vector<std::array<uint16_t, 3>> triangles;
  Camera camera;
  LightSet lights;
  Material material;
  Mesh mesh() const { return {positions, normals, {}, {}, triangles}; }
};

Scene load_scene() {
  Scene s;
  host::HostMesh m;
  std::string err;
  if (!host::load_obj(std::string(LR_SOURCE_DIR) + "/tests/host/data/torus_knot.obj", m, err)) {
    std::fprintf(stderr, "%s\n", err.c_str());
    std::exit(2);
  }
  // The mesh spans about [-1.4, 1.4]: used as is (the CLI's --fit would scale it to radius 1).
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const auto& p = m.positions[i];
    const auto& n = m.normals[i];
    s.positions.push_back({Fixed::from_raw(int32_t(p[0] * 65536 / 1.4)),
                           Fixed::from_raw(int32_t(p[1] * 65536 / 1.4)),
                           Fixed::from_raw(int32_t(p[2] * 65536 / 1.4))});
    s.normals.push_back({int16_t(n[0] * 16384), int16_t(n[1] * 16384), int16_t(n[2] * 16384)});
  }
  for (const auto& t : m.triangles)
    s.triangles.push_back({uint16_t(t[0]), uint16_t(t[1]), uint16_t(t[2])});
  perspective(Fixed::from_int(60), Fixed::ratio(320, 240), Fixed::from_double(0.1),
              Fixed::from_int(100), s.camera.projection);
  s.camera.eye = {Fixed{}, Fixed{}, Fixed::from_int(3)};
  look_at(s.camera.eye, {}, {Fixed{}, Fixed::from_int(1), Fixed{}}, s.camera.view);
  s.lights.count = 1;
  s.lights.lights[0] =
      Light::directional({Fixed::from_int(1), Fixed::from_int(1), Fixed::from_int(1)},
                                 {Color15::kOne, Color15::kOne, Color15::kOne});
  s.material = to_material(*find_material("gold"));
  return s;
}

template <class PF, int K>
struct Frame {
  std::vector<ScreenVertex> vertices = std::vector<ScreenVertex>(4096);
  std::vector<BinnedTriangle> triangles = std::vector<BinnedTriangle>(8192);
  std::vector<DrawRecord> draws = std::vector<DrawRecord>(4);
  std::vector<uint16_t> buckets = std::vector<uint16_t>((240 + K - 1) / K);
  std::vector<ActiveTriangle> active = std::vector<ActiveTriangle>(4096);
  std::vector<uint16_t> index = std::vector<uint16_t>(8192);
  std::vector<uint16_t> depth = std::vector<uint16_t>(320 * K);
  Renderer<PF, K> renderer;
  NullSink<PF> sink{320 * K};
  Frame() {
    renderer.configure({vertices, triangles, draws, buckets, active, index, depth}, 320, 240);
  }
};

template <class PF, int K>
__attribute__((noinline)) Status render_frame(Frame<PF, K>& f, const Scene& s) {
  f.renderer.begin_frame(s.camera, s.lights, Rgb8{0, 0, 0});
  DrawState st;
  Status r = f.renderer.draw(s.mesh(), Mat4::identity(), s.material, st);
  if (r != Status::kOk) return r;
  return f.renderer.render(f.sink);
}

template <class PF, int K>
void BM_TorusKnotGouraud(benchmark::State& state) {
  static const Scene scene = load_scene();
  auto f = std::make_unique<Frame<PF, K>>();
  for (auto _ : state) benchmark::DoNotOptimize(render_frame(*f, scene));
  const FrameStats& st = f->renderer.stats();
  state.counters["triangles_binned"] = st.triangles_binned;
  state.counters["pixels_written"] = st.pixels_written;
  state.counters["B_per_vertex"] = st.bytes_per_vertex;
  state.counters["B_per_binned_tri"] = st.bytes_per_binned_triangle;
  state.counters["B_per_active_tri"] = st.bytes_per_active_triangle;
  state.counters["B_per_strip"] = st.bytes_per_strip;
  state.counters["max_active"] = st.max_active;
}
BENCHMARK(BM_TorusKnotGouraud<Rgb565Be, 1>)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TorusKnotGouraud<Rgb565Be, 8>)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TorusKnotGouraud<Rgb565Be, 32>)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TorusKnotGouraud<Rgb888, 8>)->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "--frame-once") == 0) {
    Scene scene = load_scene();
    auto f = std::make_unique<Frame<Rgb565Be, 8>>();
    Status s = render_frame(*f, scene);
    const FrameStats& st = f->renderer.stats();
    std::printf("status=%s triangles_in=%u binned=%u pixels_written=%u strips=%u max_active=%u\n",
                to_string(s), st.triangles_in, st.triangles_binned, st.pixels_written, st.strips,
                st.max_active);
    return s == Status::kOk ? 0 : 1;
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
