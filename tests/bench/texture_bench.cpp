// Texture benchmark: filter x perspective mode x mip mode on two 320x240
// scenes rendered with the core (RGB565 big-endian strips of 8 rows into a null sink):
//   cube    a perspective-correct textured cube (6 faces, uv 0..1 each, 64x64 RGB565 texture
//           with its mip chain), rotated so three faces show, lit by one light (modulate);
//   ground  the ground plane to the horizon: two triangles (y = 0, half-size 200, 200 repeats
//           of the texture), eye about 1 unit above it, far plane 400, unlit (replace).
// Per configuration: host time per frame, pixels written, and the error against the double
// reference over the pixels both cover (max and mean absolute channel error, PSNR), measured
// once per configuration with test::compare_scene, outside any timing.
//
// Modes:
//   (no mode)                          Google Benchmark, one entry per configuration
//   --table FILE.csv                   one CSV row per configuration (median of 15 timed runs)
//   --once SCENE FILTER PERSP MIP      one frame through texture_bench_frame() only, for
//                                      valgrind --tool=callgrind
//                                      --toggle-collect='*texture_bench_frame*' (FILTER "none": the
//                                      same scene untextured, a baseline)
//   --png SCENE FILTER PERSP MIP FILE  writes that configuration's core frame (RGB888) as PNG
// Benchmarks print figures; they never pass or fail on time.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "tests/bench/bench_common.hpp"
#include "tests/bench/null_sink.hpp"
#include "tests/support/scene_compare.hpp"
#include "tests/support/scenes.hpp"

namespace {

using namespace lr;

constexpr int kWidth = 320, kHeight = 240, kStrip = 8;

using bench::kFilters;
using bench::kMips;
using bench::kModes;
using bench::name;
using bench::NullSink;
using bench::parse;
using bench::Prepared;

[[noreturn]] void die(const std::string& what) {
  bench::die("texture_bench", what);
}

// ---------------------------------------------------------------------------------------------
// Configurations

enum class SceneId { kCube, kGround };
const char* name(SceneId s) {
  return s == SceneId::kCube ? "cube" : "ground";
}
const SceneId kScenes[] = {SceneId::kCube, SceneId::kGround};

struct Config {
  SceneId scene = SceneId::kCube;
  Filter filter = Filter::kBilinear;
  Perspective perspective = Perspective::kExact;
  MipMode mip = MipMode::kNone;
  bool textured = true;  // false: the same scene without texture (--once baseline only)
};

// ---------------------------------------------------------------------------------------------
// Scenes

const host::HostTexture& texture() {
  static const host::HostTexture tex = [] {
    host::HostTexture t;
    std::string err;
    if (!host::texture_from_image(test::checker64(), TexelFormat::kRgb565, true, t, err)) die(err);
    return t;
  }();
  return tex;
}

host::HostMesh scene_mesh(SceneId s) {
  return s == SceneId::kCube ? host::make_cube() : test::ground_plane(200, 200);
}

host::SceneOptions scene_options(const Config& c) {
  // The cube: the top face and two side faces show (about 40,000 pixels); one light, default
  // material: the texel modulates ambient + diffuse, specular is added after it. The ground:
  // eye about 1 unit above the plane, looking level.
  host::SceneOptions o = c.scene == SceneId::kCube ? test::cube_view() : test::level_ground_view();
  o.width = kWidth;
  o.height = kHeight;
  o.strip_height = kStrip;
  o.texture_object = c.textured ? &texture().texture : nullptr;
  o.filter = c.filter;
  o.wrap = Wrap::kRepeat;
  o.mipmap = c.mip;
  o.perspective = c.perspective;
  return o;
}

Prepared prepare(const host::HostMesh& mesh, const host::SceneOptions& o) {
  return bench::prepare(mesh, o, "texture_bench");
}

template <class PF>
struct Frame {
  std::vector<ScreenVertex> vertices = std::vector<ScreenVertex>(1024);
  std::vector<BinnedTriangle> triangles = std::vector<BinnedTriangle>(2048);
  std::vector<TriangleColors> colors = std::vector<TriangleColors>(2048);
  std::vector<DrawRecord> draws = std::vector<DrawRecord>(8);
  std::vector<uint16_t> buckets = std::vector<uint16_t>((kHeight + kStrip - 1) / kStrip);
  std::vector<ActiveTriangle> active = std::vector<ActiveTriangle>(256);
  std::vector<uint16_t> index = std::vector<uint16_t>(512);
  std::vector<uint16_t> depth = std::vector<uint16_t>(kWidth * kStrip);
  std::vector<TexVertex> tex = std::vector<TexVertex>(1024);
  std::vector<ActiveExtra> extra = std::vector<ActiveExtra>(256);
  Renderer<PF, kStrip> renderer;
  Frame() {
    FrameStorage s{vertices, triangles, draws, buckets, active, index, depth};
    s.tex_vertices = tex;
    s.active_extra = extra;
    s.triangle_colors = colors;
    if (renderer.configure(s, kWidth, kHeight) != Status::kOk) die("configure failed");
  }
};

// The measured work of one frame: begin_frame, the draws (vertex stage, setup, binning) and
// render (every strip, into the sink). Nothing else is inside.
template <class PF>
__attribute__((noinline)) Status texture_bench_frame(Frame<PF>& f, const Prepared& p,
                                                     StripSink<PF>& sink) {
  Status s = f.renderer.begin_frame(p.camera, p.lights, p.background);
  if (s != Status::kOk) return s;
  for (const host::FixedDraw& d : p.draws) {
    s = f.renderer.draw(d.mesh(), p.model, d.material, p.state);
    if (s != Status::kOk) return s;
  }
  return f.renderer.render(sink);
}

// ---------------------------------------------------------------------------------------------
// Measurements

struct Errors {
  uint32_t pixels = 0;  // pixels written by the RGB565 frame that is timed
  int max_error = 0;
  double mean_error = 0, psnr = 0;
};

// Error against the double reference (compare_scene renders through host::render_scene) over
// the pixels both cover, and a check that the prepared scene is that same frame.
Errors measure_errors(const Config& cfg, const Prepared& p) {
  test::Comparison c;
  std::string err;
  if (!test::compare_scene(scene_mesh(cfg.scene), scene_options(cfg), c, err)) die(err);
  auto f = std::make_unique<Frame<Rgb888>>();
  host::CaptureDisplay<Rgb888> cap(size_t(kWidth) * kStrip);
  if (texture_bench_frame(*f, p, cap) != Status::kOk) die("render failed");
  const host::ImageRgb8 img = cap.image();
  size_t mismatch = img.rgb.size() == c.core.image.rgb.size() ? 0 : img.rgb.size() / 3;
  for (size_t i = 0; mismatch == 0 && i < img.rgb.size(); i += 3)
    mismatch += img.rgb[i] != c.core.image.rgb[i] || img.rgb[i + 1] != c.core.image.rgb[i + 1] ||
                img.rgb[i + 2] != c.core.image.rgb[i + 2];
  auto f565 = std::make_unique<Frame<Rgb565Be>>();
  NullSink<Rgb565Be> sink(size_t(kWidth) * kStrip);
  if (texture_bench_frame(*f565, p, sink) != Status::kOk) die("render failed");
  Errors e;
  e.pixels = f565->renderer.stats().pixels_written;
  e.max_error = c.max_error;
  e.mean_error = c.mean_error;
  e.psnr = c.psnr;
  if (mismatch != 0 || e.pixels != c.core.stats.pixels_written)
    std::fprintf(stderr,
                 "texture_bench: %s %s %s %s: the prepared frame differs from compare_scene's "
                 "(%zu pixels differ, %u vs %u written)\n",
                 name(cfg.scene), name(cfg.filter), name(cfg.perspective), name(cfg.mip), mismatch,
                 e.pixels, c.core.stats.pixels_written);
  if (c.coverage_diff != 0)
    std::fprintf(stderr, "texture_bench: %s %s %s %s: %zu pixels covered by one renderer only\n",
                 name(cfg.scene), name(cfg.filter), name(cfg.perspective), name(cfg.mip),
                 c.coverage_diff);
  return e;
}

void BM_Texture(benchmark::State& state, Config cfg) {
  const Prepared p = prepare(scene_mesh(cfg.scene), scene_options(cfg));
  // Google Benchmark calls this function several times per entry: measure the errors once.
  static std::map<std::string, Errors> measured;
  const std::string key =
      std::string(name(cfg.scene)) + name(cfg.filter) + name(cfg.perspective) + name(cfg.mip);
  if (!measured.count(key)) measured[key] = measure_errors(cfg, p);
  const Errors& e = measured[key];
  auto f = std::make_unique<Frame<Rgb565Be>>();
  NullSink<Rgb565Be> sink(size_t(kWidth) * kStrip);
  for (auto _ : state) benchmark::DoNotOptimize(texture_bench_frame(*f, p, sink));
  state.counters["pixels_written"] = f->renderer.stats().pixels_written;
  state.counters["max_err"] = e.max_error;
  state.counters["mean_err"] = e.mean_error;
  state.counters["psnr_db"] = e.psnr;
}

int run_table(const char* path) {
  std::FILE* out = std::fopen(path, "w");
  if (!out) die(std::string(path) + ": cannot open for writing");
  std::fprintf(out,
               "scene,filter,perspective,mip,pixels_written,host_ns_per_frame,max_err,mean_err,"
               "psnr_db\n");
  for (SceneId s : kScenes)
    for (Filter fi : kFilters)
      for (Perspective pm : kModes)
        for (MipMode m : kMips) {
          const Config cfg{s, fi, pm, m, true};
          const Prepared p = prepare(scene_mesh(s), scene_options(cfg));
          const Errors e = measure_errors(cfg, p);
          auto f = std::make_unique<Frame<Rgb565Be>>();
          NullSink<Rgb565Be> sink(size_t(kWidth) * kStrip);
          texture_bench_frame(*f, p, sink);  // warm-up
          std::vector<double> ns;
          for (int run = 0; run < 15; ++run) {
            const auto t0 = std::chrono::steady_clock::now();
            const Status st = texture_bench_frame(*f, p, sink);
            const auto t1 = std::chrono::steady_clock::now();
            benchmark::DoNotOptimize(st);
            ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
          }
          std::nth_element(ns.begin(), ns.begin() + 7, ns.end());
          std::fprintf(out, "%s,%s,%s,%s,%u,%.0f,%d,%.4f,%.2f\n", name(s), name(fi), name(pm),
                       name(m), e.pixels, ns[7], e.max_error, e.mean_error, e.psnr);
          std::fflush(out);
        }
  std::fclose(out);
  return 0;
}

int run_once(int argc, char** argv) {
  const bool png = std::strcmp(argv[1], "--png") == 0;
  Config cfg;
  bool ok = argc == (png ? 7 : 6) && parse(argv[2], kScenes, cfg.scene) &&
            parse(argv[4], kModes, cfg.perspective) && parse(argv[5], kMips, cfg.mip);
  if (ok && std::strcmp(argv[3], "none") == 0)
    cfg.textured = false;
  else
    ok = ok && parse(argv[3], kFilters, cfg.filter);
  if (!ok) {
    std::fprintf(stderr,
                 "usage: lr_texture_bench --once cube|ground nearest|bilinear|none "
                 "exact|span8|span16|span32|affine none|nearest|linear\n"
                 "       lr_texture_bench --png (same arguments) FILE.png\n");
    return 2;
  }
  if (png) {
    host::RenderResult r;
    std::string err;
    if (!host::render_scene(scene_mesh(cfg.scene), scene_options(cfg), r, err) ||
        !host::write_png(argv[6], r.image, err))
      die(err);
    std::printf("pixels_written=%u\n", r.stats.pixels_written);
    return 0;
  }
  const Prepared p = prepare(scene_mesh(cfg.scene), scene_options(cfg));
  auto f = std::make_unique<Frame<Rgb565Be>>();
  NullSink<Rgb565Be> sink(size_t(kWidth) * kStrip);
  const Status s = texture_bench_frame(*f, p, sink);
  const FrameStats& st = f->renderer.stats();
  std::printf("status=%s triangles_in=%u binned=%u pixels_written=%u strips=%u\n", to_string(s),
              st.triangles_in, st.triangles_binned, st.pixels_written, st.strips);
  return s == Status::kOk ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && (std::strcmp(argv[1], "--once") == 0 || std::strcmp(argv[1], "--png") == 0))
    return run_once(argc, argv);
  if (argc > 1 && std::strcmp(argv[1], "--table") == 0) {
    if (argc != 3) {
      std::fprintf(stderr, "usage: lr_texture_bench --table FILE.csv\n");
      return 2;
    }
    return run_table(argv[2]);
  }
  for (SceneId s : kScenes)
    for (Filter fi : kFilters)
      for (Perspective pm : kModes)
        for (MipMode m : kMips) {
          const std::string n = std::string("BM_Texture/") + name(s) + "/" + name(fi) + "/" +
                                name(pm) + "/mip_" + name(m);
          benchmark::RegisterBenchmark(n.c_str(), BM_Texture, Config{s, fi, pm, m, true})
              ->Unit(benchmark::kMicrosecond);
        }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
