// Host time per frame of the demo scene (the 4,000-triangle torus knot, gold, Gouraud, 320x240,
// strips of 8 rows, RGB565) and RAM figures. `--frame-once` renders one frame through
// render_frame() only, for instruction counting under callgrind (--toggle-collect=render_frame).
// Benchmarks print figures; they do not pass or fail on time.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/formats/obj_loader.hpp"
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
  // Strip signatures kept, used only after configure(true) (enable_skipping).
  BasicFrameStorage<std::vector> store{FrameCapacities{.width = 320,
                                                       .height = 240,
                                                       .strip_height = K,
                                                       .vertices = 4096,
                                                       .triangles = 8192,
                                                       .draws = 4,
                                                       .active = 4096,
                                                       .strip_skipping = true}};
  Renderer<PF, K> renderer;
  NullSink<PF> sink{320 * K};
  Frame() { configure(false); }
  void configure(bool skip) {
    FrameStorage s = store.storage();
    if (!skip) s.strip_inputs = {};
    renderer.configure(s, 320, 240);
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

// Skipping unchanged strips: the knot stands still while a small cube (12 triangles,
// about 20 x 20 pixels) circles in front of it, one step per frame. With strip signatures only
// the strips the cube left or entered are rendered; without, every strip of every frame.
struct MovingCube {
  std::array<Vec3, 8> positions;
  std::array<Normal16, 8> normals;
  std::array<std::array<uint16_t, 3>, 12> triangles = {{{0, 2, 1},
                                                        {1, 2, 3},
                                                        {4, 5, 6},
                                                        {5, 7, 6},
                                                        {0, 1, 4},
                                                        {1, 5, 4},
                                                        {2, 6, 3},
                                                        {3, 6, 7},
                                                        {0, 4, 2},
                                                        {2, 4, 6},
                                                        {1, 3, 5},
                                                        {3, 7, 5}}};
  MovingCube() {
    for (int i = 0; i < 8; ++i) {
      const int x = i & 1 ? 1 : -1, y = i & 2 ? 1 : -1, z = i & 4 ? 1 : -1;
      positions[size_t(i)] = {Fixed::from_int(x), Fixed::from_int(y), Fixed::from_int(z)};
      normals[size_t(i)] = {int16_t(x * 9459), int16_t(y * 9459), int16_t(z * 9459)};
    }
  }
  Mesh mesh() const { return {positions, normals, {}, {}, triangles}; }
};

// The knot and the cube at step `step` of its circle, rendered.
Status moving_frame(Frame<Rgb565Be, 8>& f, const Scene& scene, const MovingCube& cube, int step) {
  f.renderer.begin_frame(scene.camera, scene.lights, Rgb8{0, 0, 0});
  DrawState st;
  Status r = f.renderer.draw(scene.mesh(), Mat4::identity(), scene.material, st);
  if (r != Status::kOk) return r;
  // A circle of radius 0.8 in front of the knot, 5 degrees per frame.
  const Fixed a = Fixed::from_int(5 * (step % 72));
  const Mat4 model = rotate_z(a) *
                     translate({Fixed::from_double(0.8), Fixed{}, Fixed::from_int(1)}) *
                     scale(Fixed::from_double(0.06));
  r = f.renderer.draw(cube.mesh(), model, scene.material, st);
  if (r != Status::kOk) return r;
  return f.renderer.render(f.sink);
}
// The frame callgrind counts (--moving-once).
__attribute__((noinline)) Status counted_moving_frame(Frame<Rgb565Be, 8>& f, const Scene& scene,
                                                      const MovingCube& cube, int step) {
  return moving_frame(f, scene, cube, step);
}

void enable_skipping(Frame<Rgb565Be, 8>& f) {
  f.configure(true);
  f.sink.set_retain(true);
}

template <bool kSkip>
void BM_MovingCubeOverKnot(benchmark::State& state) {
  static const Scene scene = load_scene();
  static const MovingCube cube;
  auto f = std::make_unique<Frame<Rgb565Be, 8>>();
  if (kSkip) enable_skipping(*f);
  int step = 0;
  uint64_t frames = 0, skipped = 0, set_up = 0, tested = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(moving_frame(*f, scene, cube, step++));
    const FrameStats& fs = f->renderer.stats();
    ++frames;
    skipped += fs.strips_skipped;
    set_up += fs.triangles_set_up;
    tested += fs.pixels_tested;
  }
  state.counters["strips_skipped_per_frame"] = double(skipped) / double(frames);
  state.counters["triangles_set_up_per_frame"] = double(set_up) / double(frames);
  state.counters["pixels_tested_per_frame"] = double(tested) / double(frames);
}
BENCHMARK(BM_MovingCubeOverKnot<false>)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MovingCubeOverKnot<true>)->Unit(benchmark::kMicrosecond);

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
  if (argc > 2 && std::strcmp(argv[1], "--moving-once") == 0) {
    // Ten frames of the moving cube, then the counted eleventh (skip: with strip signatures;
    // signed: with strip signatures, the first frame counted, when nothing can be left out, so
    // that the signatures' own cost shows against "full").
    const bool first = std::strcmp(argv[2], "signed") == 0;
    const bool skip = first || std::strcmp(argv[2], "skip") == 0;
    Scene scene = load_scene();
    MovingCube cube;
    auto f = std::make_unique<Frame<Rgb565Be, 8>>();
    if (skip) enable_skipping(*f);
    Status s = Status::kOk;
    for (int i = 0; i < (first ? 0 : 10) && s == Status::kOk; ++i)
      s = moving_frame(*f, scene, cube, i);
    if (s == Status::kOk) s = counted_moving_frame(*f, scene, cube, 10);
    const FrameStats& st = f->renderer.stats();
    std::printf("status=%s strips_skipped=%u triangles_set_up=%u pixels_tested=%u\n", to_string(s),
                st.strips_skipped, st.triangles_set_up, st.pixels_tested);
    return s == Status::kOk ? 0 : 1;
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
