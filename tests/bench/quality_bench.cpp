// Quality benchmark: time, instructions, RAM and error against the double
// reference for every quality setting the core offers, on five 320x240 scenes:
//   knot     the 4,000-triangle torus knot, gold (the demo scene), one light;
//   sphere   a 40 x 60 UV sphere, four lights, shininess 96, a global ambient;
//   clipped  an unlit ground plane with vertex colours, cut by the near plane (guard band);
//   cube     the textured, lit cube of texture_bench (64x64 texture with its mip chain);
//   ground   the textured ground plane to the horizon of texture_bench (unlit, far plane 400).
// Settings varied per scene (the ones that matter to it):
//   untextured (knot, sphere, clipped): shading {flat, gouraud} x perspective {exact, span8,
//     span16, span32, affine} x strip height {1, 8, 32};
//   textured (cube, ground): filter {nearest, bilinear} x perspective x mip {none, nearest,
//     linear} x texture format {rgb565, rgb888}, Gouraud, strips of 8.
// The timed frame: RGB565 (big-endian) strips into a null sink, prepared fixed-point data (no
// conversion inside), through the noinline quality_bench_frame() (begin_frame + draws + render).
//
// Error: the same prepared frame rendered into RGB888 strips (the core's arithmetic, before the
// display's RGB565 rounding that every setting shares) against tests/reference's double
// renderer. The reference always samples the 8-bit source texture and its 8-bit mip chain (the
// RGB888 texture), so the texture format's quantization counts as error. Over the pixels both
// cover: max and mean absolute channel error (0..255), PSNR (99 when identical), % of pixels
// whose worst channel is off by more than 1 / 4 / 16 levels. coverage_mismatch: pixels covered by
// one renderer only. depth_order_errors: pixels both cover where the core shows another surface
// than the reference: the core's 16-bit depth lies outside [min - 16, max + 16] of the
// reference's depths (x 65535) over the 3x3 pixels around it that the reference covers. A surface
// seen through its own interpolation error stays within that range (16 units is far more than
// rounding); an occlusion boundary moved by up to one pixel (vertices snapped differently) is
// not counted, only a wrong front surface inside a region is.
// RAM (bytes): transformed vertices x bytes_per_vertex + binned triangles x bytes_per_binned +
// peak active triangles x bytes_per_active + two colour strips (double buffering) + one depth
// strip + the edge table's buckets + draw records. texture_bytes: the texels the setting reads
// (level 0, or the whole mip chain with mipmaps), flash or RAM.
//
// Modes:
//   --table FILE.csv                   one CSV row per configuration (median of 21 timed frames)
//   --check RECORD.csv                 the errors only (no timing): every configuration's PSNR
//                                      (as the table rounds it) against the record
//                                      (docs/measurements/quality_bench_psnr.csv); exit status 1
//                                      when one is more than 0.5 dB worse or the record and the
//                                      configurations differ (the CTest test
//                                      QualityBench.NoRowWorseThanRecorded)
//   --check RECORD.csv --raise         the same, then (when it passes) writes each better row's
//                                      new PSNR into the record: rows only move up
//   --list                             the configurations, one per line, as --once arguments
//   --once SCENE SHADING PERSP STRIP FILTER MIP FORMAT
//                                      one frame through quality_bench_frame() only, for
//                                      valgrind --tool=callgrind
//                                      --toggle-collect='*quality_bench_frame*'
//                                      (FILTER, MIP, FORMAT "-" for untextured scenes)
// Benchmarks print figures; they never pass or fail on time (--check fails on accuracy only).
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
#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "tests/bench/bench_common.hpp"
#include "tests/bench/null_sink.hpp"
#include "tests/bench/quality_configs.hpp"
#include "tests/support/scene_compare.hpp"
#include "tests/support/scenes.hpp"

namespace {

using namespace lr;

constexpr int kWidth = 320, kHeight = 240;
constexpr int kTimedRuns = 21;
constexpr int kDepthSlack = 16;  // 16-bit depth units, see depth_order_errors above

using bench::kFilters;
using bench::kMips;
using bench::kModes;
using bench::name;
using bench::NullSink;
using bench::parse;
using bench::Prepared;

[[noreturn]] void die(const std::string& what) {
  bench::die("quality_bench", what);
}

using quality::all_configs;
using quality::Config;
using quality::kFormats;
using quality::kScenes;
using quality::kShadings;
using quality::kStrips;
using quality::name;
using quality::prepare;
using quality::scene_mesh;
using quality::scene_options;
using quality::SceneId;
using quality::texture;
using quality::texture_bytes;
using quality::textured;

template <class PF, int K>
struct Frame {
  BasicFrameStorage<std::vector> store{FrameCapacities{.width = kWidth,
                                                       .height = kHeight,
                                                       .strip_height = K,
                                                       .vertices = 8192,
                                                       .triangles = 8192,
                                                       .draws = 16,
                                                       .active = 4096,
                                                       .tex_vertices = 8192,
                                                       .active_extra = 4096,
                                                       .triangle_colors = 8192}};
  Renderer<PF, K> renderer;
  Frame() {
    if (renderer.configure(store.storage(), kWidth, kHeight) != Status::kOk)
      die("configure failed");
  }
};

// The measured work of one frame: begin_frame, the draws (vertex stage, setup, binning) and
// render (every strip, into the sink). Nothing else is inside.
template <class PF, int K>
__attribute__((noinline)) Status quality_bench_frame(Frame<PF, K>& f, const Prepared& p,
                                                     StripSink<PF>& sink,
                                                     DepthSink* depth = nullptr) {
  Status s = f.renderer.begin_frame(p.camera, p.lights, p.background);
  if (s != Status::kOk) return s;
  for (const host::FixedDraw& d : p.draws) {
    s = f.renderer.draw(d.mesh(), p.model, d.material, p.state);
    if (s != Status::kOk) return s;
  }
  return f.renderer.render(sink, depth);
}

// ---------------------------------------------------------------------------------------------
// Measurements

struct Row {
  uint32_t pixels = 0, triangles_binned = 0;
  double host_ns = 0;
  uint64_t ram_bytes = 0, texture_bytes = 0;
  size_t both = 0, coverage_mismatch = 0, depth_order_errors = 0;
  size_t over1 = 0, over4 = 0, over16 = 0;
  int max_error = 0;
  double mean_error = 0, psnr = 0;
};

// The reference frame depends only on the scene, shading and texture sampling (not on the
// perspective mode, strip height or texture format): rendered once per key.
const ref::RefFrame& reference(const Config& c, const host::SceneOptions& o) {
  static std::map<std::string, ref::RefFrame> cache;
  const bool t = textured(c.scene);
  const std::string key = std::string(name(c.scene)) + name(c.shading) +
                          (t ? std::string(name(c.filter)) + name(c.mip) : std::string());
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  const host::HostMesh& mesh = scene_mesh(c.scene);
  ref::RefParams rp = test::ref_params(mesh, o);
  ref::RefTexture rt;
  if (t) {
    rt = ref::from_core(texture(TexelFormat::kRgb888).texture);  // the 8-bit truth
    rp.texture = &rt;
    Sampler smp;
    smp.filter = o.filter;
    smp.wrap_s = smp.wrap_t = o.wrap;
    smp.mip = o.mipmap;
    smp.env = o.unlit ? TexEnv::kReplace : TexEnv::kModulate;
    ref::set_sampler(rp, smp);
  }
  ref::RefFrame f;
  ref::render(mesh, rp, f);
  return cache.emplace(key, std::move(f)).first->second;
}

void compare(const host::ImageRgb8& img, const std::vector<uint16_t>& depth, const ref::RefFrame& r,
             Row& row) {
  double sum = 0, sq = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const size_t p = r.index(x, y);
      const bool core_cov = depth[p] != 0xFFFF, ref_cov = r.owner[p] >= 0;
      if (core_cov != ref_cov) {
        ++row.coverage_mismatch;
        continue;
      }
      if (!core_cov) continue;
      ++row.both;
      int worst = 0;
      for (size_t k = 0; k < 3; ++k) {
        const int e = std::abs(int(img.rgb[3 * p + k]) - int(r.rgb8[3 * p + k]));
        worst = std::max(worst, e);
        sum += e;
        sq += double(e) * e;
      }
      row.max_error = std::max(row.max_error, worst);
      row.over1 += worst > 1;
      row.over4 += worst > 4;
      row.over16 += worst > 16;
      double lo = 1e30, hi = -1e30;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= kWidth || ny >= kHeight) continue;
          const size_t q = r.index(nx, ny);
          if (r.owner[q] < 0) continue;
          lo = std::min(lo, r.depth[q] * 65535.0);
          hi = std::max(hi, r.depth[q] * 65535.0);
        }
      row.depth_order_errors += depth[p] < lo - kDepthSlack || depth[p] > hi + kDepthSlack;
    }
  if (row.both) {
    row.mean_error = sum / (3.0 * double(row.both));
    const double mse = sq / (3.0 * double(row.both));
    row.psnr = mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : 99.0;
  }
}

// timed_runs: frames timed (0: none); errors: whether to measure the error against the reference.
template <int K>
Row measure_k(const Config& c, int timed_runs, bool errors) {
  const host::SceneOptions o = scene_options(c);
  const host::HostMesh& mesh = scene_mesh(c.scene);
  const Prepared p = prepare(mesh, o);
  Row row;

  // Timed: RGB565 strips into the null sink.
  auto f = std::make_unique<Frame<Rgb565Be, K>>();
  NullSink<Rgb565Be> sink(size_t(kWidth) * K);
  if (quality_bench_frame(*f, p, sink) != Status::kOk) die("render failed: " + c.key(' '));
  if (timed_runs > 0) {
    std::vector<double> ns;
    for (int run = 0; run < timed_runs; ++run) {
      const auto t0 = std::chrono::steady_clock::now();
      const Status st = quality_bench_frame(*f, p, sink);
      const auto t1 = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(st);
      ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
    }
    std::nth_element(ns.begin(), ns.begin() + timed_runs / 2, ns.end());
    row.host_ns = ns[size_t(timed_runs / 2)];
  }
  if (!errors) return row;
  const FrameStats& st = f->renderer.stats();
  row.pixels = st.pixels_written;
  row.triangles_binned = st.triangles_binned;
  row.ram_bytes = uint64_t(st.vertices_transformed) * st.bytes_per_vertex +
                  uint64_t(st.triangles_binned) * st.bytes_per_binned_triangle +
                  uint64_t(st.max_active) * st.bytes_per_active_triangle + st.bytes_per_strip +
                  uint64_t(kWidth) * K * sizeof(Rgb565Be::Storage) +
                  f->store.buckets.size() * sizeof(uint16_t) + p.draws.size() * sizeof(DrawRecord);
  if (o.texture_object) row.texture_bytes = texture_bytes(*o.texture_object, o.mipmap);

  // Error: the same prepared frame in RGB888 with its depth, against the reference.
  auto f888 = std::make_unique<Frame<Rgb888, K>>();
  host::CaptureDisplay<Rgb888> cap(size_t(kWidth) * K);
  host::DepthCapture depth;
  depth.resize(kWidth, kHeight);
  if (quality_bench_frame(*f888, p, cap, &depth) != Status::kOk) die("render failed");
  const host::ImageRgb8 img = cap.image();
  if (f888->renderer.stats().pixels_written != row.pixels)
    die("RGB565 and RGB888 frames differ in pixels: " + c.key(' '));

  // The prepared frame must be host::render_scene's (which the reference comparisons use).
  host::RenderResult rs;
  std::string err;
  if (!host::render_scene(mesh, o, rs, err)) die(err);
  if (rs.image.rgb != img.rgb || rs.depth != depth.depth())
    std::fprintf(stderr, "quality_bench: %s: the prepared frame differs from render_scene's\n",
                 c.key(' ').c_str());

  compare(img, depth.depth(), reference(c, o), row);
  return row;
}

Row measure(const Config& c, int timed_runs, bool errors = true) {
  switch (c.strip) {
    case 1:
      return measure_k<1>(c, timed_runs, errors);
    case 8:
      return measure_k<8>(c, timed_runs, errors);
    case 32:
      return measure_k<32>(c, timed_runs, errors);
  }
  die("strip height must be 1, 8 or 32");
}

int run_table(const char* path) {
  std::FILE* out = std::fopen(path, "w");
  if (!out) die(std::string(path) + ": cannot open for writing");
  std::fprintf(out,
               "scene,shading,perspective,strip,filter,mip,format,pixels,triangles_binned,"
               "host_ns_per_frame,ram_bytes,texture_bytes,max_err,mean_err,psnr_db,pct_off_gt1,"
               "pct_off_gt4,pct_off_gt16,coverage_mismatch,depth_order_errors\n");
  for (const Config& c : all_configs()) {
    const Row r = measure(c, kTimedRuns);
    const double both = r.both ? double(r.both) : 1.0;
    std::fprintf(out, "%s,%u,%u,%.0f,%llu,%llu,%d,%.4f,%.2f,%.3f,%.3f,%.3f,%zu,%zu\n",
                 c.key(',').c_str(), r.pixels, r.triangles_binned, r.host_ns,
                 static_cast<unsigned long long>(r.ram_bytes),
                 static_cast<unsigned long long>(r.texture_bytes), r.max_error, r.mean_error,
                 r.psnr, 100.0 * double(r.over1) / both, 100.0 * double(r.over4) / both,
                 100.0 * double(r.over16) / both, r.coverage_mismatch, r.depth_order_errors);
    std::fflush(out);
  }
  std::fclose(out);
  return 0;
}

int run_once(int argc, char** argv) {
  Config c;
  bool ok = argc == 9 && parse(argv[2], kScenes, c.scene) && parse(argv[3], kShadings, c.shading) &&
            parse(argv[4], kModes, c.perspective);
  if (ok) {
    c.strip = std::atoi(argv[5]);
    ok = std::find(std::begin(kStrips), std::end(kStrips), c.strip) != std::end(kStrips);
  }
  if (ok && textured(c.scene))
    ok = parse(argv[6], kFilters, c.filter) && parse(argv[7], kMips, c.mip) &&
         parse(argv[8], kFormats, c.format);
  if (!ok) {
    std::fprintf(stderr,
                 "usage: lr_quality_bench --once knot|sphere|clipped|cube|ground flat|gouraud "
                 "exact|span8|span16|span32|affine 1|8|32 nearest|bilinear|- none|nearest|linear|- "
                 "rgb565|rgb888|-\n");
    return 2;
  }
  measure(c, 0, false);
  return 0;
}

// The record: "key,psnr_db" per configuration (key: scene .. format joined by ','), lines
// starting with '#' and the header skipped. False with the reason when unreadable.
bool read_record(const char* path, std::map<std::string, double>& out, std::string& error) {
  std::FILE* in = std::fopen(path, "r");
  if (!in) {
    error = std::string(path) + ": cannot open";
    return false;
  }
  char line[256];
  int n = 0;
  bool ok = true;
  while (ok && std::fgets(line, sizeof line, in)) {
    ++n;
    std::string l(line);
    while (!l.empty() && (l.back() == '\n' || l.back() == '\r')) l.pop_back();
    if (l.empty() || l[0] == '#' || l.rfind("scene,", 0) == 0) continue;
    const size_t comma = l.rfind(',');
    char* end = nullptr;
    const double psnr = comma == std::string::npos ? 0 : std::strtod(l.c_str() + comma + 1, &end);
    ok = comma != std::string::npos && end != l.c_str() + comma + 1 && *end == '\0' &&
         out.emplace(l.substr(0, comma), psnr).second;
    if (!ok) error = std::string(path) + ":" + std::to_string(n) + ": not a new KEY,PSNR: " + l;
  }
  std::fclose(in);
  return ok;
}

// Every configuration's PSNR against the record: a configuration more than kCheckMargin dB worse
// than recorded, or one the record lacks (or a record row no configuration has), fails.
constexpr double kCheckMargin = 0.5;  // dB, issue 36: "within 0.5 dB of today's or better"

// raise: rewrite the record with each row's better value (a row never goes down), keeping its
// comment lines; only when no row is worse, missing or unknown.
int run_check(const char* path, bool raise) {
  std::map<std::string, double> record;
  std::string error;
  if (!read_record(path, record, error)) die(error);
  std::vector<std::pair<std::string, double>> raised;  // every configuration, in order
  int worse = 0, better = 0, missing = 0, checked = 0;
  double lowest = 1e9;
  for (const Config& c : all_configs()) {
    const std::string key = c.key(',');
    const auto it = record.find(key);
    const Row r = measure(c, 0);
    const double psnr = std::round(r.psnr * 100.0) / 100.0;  // as the table shows it
    if (it == record.end()) {
      std::printf("quality_check: %s: %.2f dB, not in the record\n", key.c_str(), psnr);
      ++missing;
      continue;
    }
    ++checked;
    raised.emplace_back(key, std::max(psnr, it->second));
    const double delta = psnr - it->second;
    lowest = std::min(lowest, delta);
    if (delta < -kCheckMargin) {
      std::printf("quality_check: WORSE %s: %.2f dB, recorded %.2f dB (%+.2f)\n", key.c_str(), psnr,
                  it->second, delta);
      ++worse;
    } else if (delta > 0.005) {
      ++better;
      std::printf("quality_check: better %s: %.2f dB, recorded %.2f dB (%+.2f)\n", key.c_str(),
                  psnr, it->second, delta);
    }
    record.erase(it);
  }
  for (const auto& [key, psnr] : record)
    std::printf("quality_check: %s: recorded (%.2f dB) but not a configuration\n", key.c_str(),
                psnr);
  std::printf(
      "quality_check: %d configurations against %s: %d more than %.1f dB worse, %d better "
      "(record them), %d missing, %zu unknown; largest loss %.2f dB\n",
      checked, path, worse, kCheckMargin, better, missing, record.size(),
      lowest < 0 ? -lowest : 0.0);
  const bool pass = worse == 0 && missing == 0 && record.empty() && checked > 0;
  std::printf("quality_check: %s\n", pass ? "PASS" : "FAIL");
  if (pass && raise && better > 0) {
    std::vector<std::string> comments;
    std::FILE* in = std::fopen(path, "r");
    char line[256];
    while (in && std::fgets(line, sizeof line, in))
      if (line[0] == '#') comments.emplace_back(line);
    if (in) std::fclose(in);
    std::FILE* out = std::fopen(path, "w");
    if (!out) die(std::string(path) + ": cannot write");
    for (const std::string& c : comments) std::fputs(c.c_str(), out);
    std::fputs("scene,shading,perspective,strip,filter,mip,format,psnr_db\n", out);
    for (const auto& [key, psnr] : raised) std::fprintf(out, "%s,%.2f\n", key.c_str(), psnr);
    std::fclose(out);
    std::printf("quality_check: raised %d rows of %s\n", better, path);
  }
  return pass ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "--once") == 0) return run_once(argc, argv);
  if (argc == 2 && std::strcmp(argv[1], "--list") == 0) {
    for (const Config& c : all_configs()) std::printf("%s\n", c.key(' ').c_str());
    return 0;
  }
  if (argc == 3 && std::strcmp(argv[1], "--table") == 0) return run_table(argv[2]);
  if (argc == 3 && std::strcmp(argv[1], "--check") == 0) return run_check(argv[2], false);
  if (argc == 4 && std::strcmp(argv[1], "--check") == 0 && std::strcmp(argv[3], "--raise") == 0)
    return run_check(argv[2], true);
  std::fprintf(stderr,
               "usage: lr_quality_bench --table FILE.csv | --check RECORD.csv [--raise] | --list | "
               "--once (see --list)\n");
  return 2;
}
