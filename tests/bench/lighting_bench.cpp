// Lighting benchmark: cost and error of each shading mode on two 320x240
// scenes:
//   sphere  tests/support/scenes.hpp's phong_sphere(): a 40 x 60 UV sphere, two coloured
//           directional lights, shininess 64 (nothing saturates);
//   knot    the 4,000-triangle torus knot, gold, one light (the demo scene; a closed mesh).
// Modes: flat, gouraud, phong exact, phong table {16, 32, 64, 128, 256} x {nearest, bilinear}.
// Per (scene, mode):
//   lit pixels (pixels the frame wrote), RAM of the mode's own stores (surface vertices,
//   prepared lighting, the table), and the error of the core's frame against the double
//   reference of the SAME shading (flat, Gouraud or Phong: the arithmetic's error) and against
//   the double reference's Phong (how far the mode is from per-pixel lighting): max and mean
//   absolute channel error (0..255) and PSNR over the pixels both cover.
// SLERP: the reference alone renders the sphere and the knot with spherical interpolation of
//   normals (along edges, then along spans: the scanline method) and with renormalised linear
//   interpolation (Phong's): it prints their difference (PSNR, max) and the largest angle
//   between the two normals of a pixel. That is what SLERP would buy; the core does not offer
//   it (see the note in README's per-pixel lighting section).
//
// Modes:
//   --table FILE.csv     one CSV row per (scene, mode), and the SLERP lines on stdout
//   --list               the configurations, one per line, as --once arguments
//   --once SCENE MODE    one frame through lighting_bench_frame() only, for valgrind
//                        --tool=callgrind --toggle-collect='*lighting_bench_frame*'
// Benchmarks print figures; they never pass or fail on time.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "tests/bench/bench_common.hpp"
#include "tests/bench/null_sink.hpp"
#include "tests/support/scene_compare.hpp"
#include "tests/support/scenes.hpp"

namespace {

using namespace lr;
using bench::die;
using bench::Prepared;

constexpr int kWidth = 320, kHeight = 240, kStrip = 8;

enum class Scene { kSphere, kKnot };
const char* scene_name(Scene s) {
  return s == Scene::kSphere ? "sphere" : "knot";
}

struct Mode {
  const char* name;
  Shading shading;
  PixelLighting lighting;
  uint16_t table;
  bool bilinear;
};
const Mode kModesList[] = {
    {"flat", Shading::kFlat, PixelLighting::kExact, 0, false},
    {"gouraud", Shading::kGouraud, PixelLighting::kExact, 0, false},
    {"phong-exact", Shading::kPhong, PixelLighting::kExact, 0, false},
    {"phong-table16-nearest", Shading::kPhong, PixelLighting::kTable, 16, false},
    {"phong-table16-bilinear", Shading::kPhong, PixelLighting::kTable, 16, true},
    {"phong-table32-nearest", Shading::kPhong, PixelLighting::kTable, 32, false},
    {"phong-table32-bilinear", Shading::kPhong, PixelLighting::kTable, 32, true},
    {"phong-table64-nearest", Shading::kPhong, PixelLighting::kTable, 64, false},
    {"phong-table64-bilinear", Shading::kPhong, PixelLighting::kTable, 64, true},
    {"phong-table128-nearest", Shading::kPhong, PixelLighting::kTable, 128, false},
    {"phong-table128-bilinear", Shading::kPhong, PixelLighting::kTable, 128, true},
    {"phong-table256-nearest", Shading::kPhong, PixelLighting::kTable, 256, false},
    {"phong-table256-bilinear", Shading::kPhong, PixelLighting::kTable, 256, true},
};

const host::HostMesh& scene_mesh(Scene s) {
  static const host::HostMesh sphere = host::make_uv_sphere(40, 60);
  static const host::HostMesh knot = host::make_torus_knot(2, 3, 0.12, 200, 10);
  return s == Scene::kSphere ? sphere : knot;
}

host::SceneOptions options(Scene s, const Mode& m) {
  host::SceneOptions o = s == Scene::kSphere ? test::phong_sphere() : test::gold_options();
  o.shading = m.shading;
  o.pixel_lighting = m.lighting;
  if (m.table != 0) o.table = {m.table, m.bilinear};
  o.strip_height = kStrip;
  return o;
}

struct Frame {
  std::vector<ScreenVertex> vertices = std::vector<ScreenVertex>(16384);
  std::vector<BinnedTriangle> triangles = std::vector<BinnedTriangle>(16384);
  std::vector<TriangleColors> colors = std::vector<TriangleColors>(16384);
  std::vector<DrawRecord> draws = std::vector<DrawRecord>(16);
  std::vector<uint16_t> buckets = std::vector<uint16_t>((kHeight + kStrip - 1) / kStrip);
  std::vector<ActiveTriangle> active = std::vector<ActiveTriangle>(4096);
  std::vector<uint16_t> index = std::vector<uint16_t>(8192);
  std::vector<uint16_t> depth = std::vector<uint16_t>(kWidth * kStrip);
  std::vector<SurfaceVertex> surfaces = std::vector<SurfaceVertex>(16384);
  std::vector<uint32_t> tables = std::vector<uint32_t>(lighting_table_words(256, false));
  std::vector<PreparedLighting> pixel_lights = std::vector<PreparedLighting>(2);
  std::vector<TexVertex> tex = std::vector<TexVertex>(16384);
  std::vector<ActiveExtra> extra = std::vector<ActiveExtra>(4096);
  Renderer<Rgb565Be, kStrip> renderer;
  Frame() {
    FrameStorage s{vertices, triangles, draws,    buckets, active,
                   index,    depth,     surfaces, tables,  pixel_lights};
    s.tex_vertices = tex;
    s.active_extra = extra;
    s.triangle_colors = colors;
    if (renderer.configure(s, kWidth, kHeight) != Status::kOk)
      die("lighting_bench", "configure failed");
  }
};

// The measured work of one frame: begin_frame, the draws (vertex stage, lighting tables,
// setup, binning) and render (every strip, into the sink).
__attribute__((noinline)) Status lighting_bench_frame(Frame& f, const Prepared& p,
                                                      StripSink<Rgb565Be>& sink) {
  Status s = f.renderer.begin_frame(p.camera, p.lights, p.background);
  if (s != Status::kOk) return s;
  for (const host::FixedDraw& d : p.draws) {
    s = f.renderer.draw(d.mesh(), p.model, d.material, p.state);
    if (s != Status::kOk) return s;
  }
  return f.renderer.render(sink);
}

bool parse_scene(const char* s, Scene& out) {
  for (Scene c : {Scene::kSphere, Scene::kKnot})
    if (std::strcmp(s, scene_name(c)) == 0) {
      out = c;
      return true;
    }
  return false;
}
const Mode* parse_mode(const char* s) {
  for (const Mode& m : kModesList)
    if (std::strcmp(s, m.name) == 0) return &m;
  return nullptr;
}

// Error of a core frame against a reference frame over the pixels both cover.
struct Error {
  int max = 0;
  double mean = 0, psnr = 99;
};
Error error_against(const host::RenderResult& core, const ref::RefFrame& r) {
  Error e;
  double sum = 0, sq = 0;
  size_t n = 0;
  for (size_t p = 0; p < core.depth.size(); ++p) {
    if (core.depth[p] == 0xFFFF || r.owner[p] < 0) continue;
    ++n;
    for (size_t k = 0; k < 3; ++k) {
      const int d = std::abs(int(core.image.rgb[3 * p + k]) - int(r.rgb8[3 * p + k]));
      e.max = std::max(e.max, d);
      sum += d;
      sq += double(d) * d;
    }
  }
  if (n > 0) {
    e.mean = sum / (3.0 * double(n));
    const double mse = sq / (3.0 * double(n));
    e.psnr = mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : 99.0;
  }
  return e;
}

const ref::RefFrame& phong_reference(Scene s) {
  static ref::RefFrame frames[2];
  static bool done[2] = {false, false};
  const auto i = static_cast<size_t>(s);
  if (!done[i]) {
    host::SceneOptions o = options(s, kModesList[2]);
    ref::RefParams rp = test::ref_params(scene_mesh(s), o);
    ref::render(scene_mesh(s), rp, frames[i]);
    done[i] = true;
  }
  return frames[i];
}

void slerp_report(Scene s) {
  host::SceneOptions o = options(s, kModesList[2]);
  ref::RefParams rp = test::ref_params(scene_mesh(s), o);
  ref::RefFrame lin, sl;
  ref::render(scene_mesh(s), rp, lin);
  rp.normal_interp = ref::RefNormalInterp::Slerp;
  ref::render(scene_mesh(s), rp, sl);
  double sq = 0, worst_angle = 0;
  int worst = 0;
  size_t n = 0, differ = 0;
  for (size_t p = 0; p < lin.owner.size(); ++p) {
    if (lin.owner[p] < 0 || sl.owner[p] < 0) continue;
    ++n;
    bool d = false;
    for (size_t k = 0; k < 3; ++k) {
      const int e = std::abs(int(lin.rgb8[3 * p + k]) - int(sl.rgb8[3 * p + k]));
      worst = std::max(worst, e);
      sq += double(e) * e;
      d = d || e != 0;
    }
    differ += d;
    const ref::Vec3d& a = lin.normal[p];
    const ref::Vec3d& b = sl.normal[p];
    const double c = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    worst_angle = std::max(worst_angle, std::acos(std::min(1.0, std::max(-1.0, c))));
  }
  const double mse = n ? sq / (3.0 * double(n)) : 0;
  std::printf(
      "slerp vs renormalised linear (double reference, %s): pixels %zu, differing %zu, max %d "
      "levels, PSNR %.1f dB, largest angle between the normals %.4f degrees\n",
      scene_name(s), n, differ, worst, mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : 99.0,
      worst_angle * 180 / M_PI);
}

int table_mode(const char* path) {
  std::FILE* f = std::fopen(path, "w");
  if (!f) die("lighting_bench", std::string("cannot write ") + path);
  std::fprintf(f,
               "scene,mode,lit_pixels,mode_ram_bytes,max_err_same,mean_err_same,psnr_same,"
               "max_err_phong,mean_err_phong,psnr_phong\n");
  for (Scene s : {Scene::kSphere, Scene::kKnot}) {
    for (const Mode& m : kModesList) {
      host::SceneOptions o = options(s, m);
      test::Comparison c;
      std::string err;
      if (!test::compare_scene(scene_mesh(s), o, c, err)) die("lighting_bench", err);
      const Error ph = error_against(c.core, phong_reference(s));
      size_t ram = 0;
      if (m.shading == Shading::kPhong) {
        ram = c.core.stats.vertices_transformed * sizeof(SurfaceVertex) + sizeof(PreparedLighting);
        if (m.table != 0) ram += lighting_table_words(m.table, false) * sizeof(uint32_t);
      }
      std::fprintf(f, "%s,%s,%u,%zu,%d,%.4f,%.2f,%d,%.4f,%.2f\n", scene_name(s), m.name,
                   c.core.stats.pixels_written, ram, c.max_error, c.mean_error, c.psnr, ph.max,
                   ph.mean, ph.psnr);
    }
    slerp_report(s);
  }
  std::fclose(f);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "--table") == 0) return table_mode(argv[2]);
  if (argc == 2 && std::strcmp(argv[1], "--list") == 0) {
    for (Scene s : {Scene::kSphere, Scene::kKnot})
      for (const Mode& m : kModesList) std::printf("%s %s\n", scene_name(s), m.name);
    return 0;
  }
  if (argc == 4 && std::strcmp(argv[1], "--once") == 0) {
    Scene s;
    const Mode* m = parse_mode(argv[3]);
    if (!parse_scene(argv[2], s) || m == nullptr) die("lighting_bench", "unknown scene or mode");
    const Prepared p = bench::prepare(scene_mesh(s), options(s, *m), "lighting_bench");
    auto f = std::make_unique<Frame>();
    bench::NullSink<Rgb565Be> sink(kWidth * kStrip);
    const Status st = lighting_bench_frame(*f, p, sink);
    if (st != Status::kOk) die("lighting_bench", std::string("frame: ") + to_string(st));
    std::printf("lit_pixels %u\n", f->renderer.stats().pixels_written);
    return 0;
  }
  std::fprintf(stderr, "usage: lr_lighting_bench --table FILE.csv | --list | --once SCENE MODE\n");
  return 2;
}
