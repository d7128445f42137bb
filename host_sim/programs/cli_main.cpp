// lineraster-sim: renders an OBJ with the fixed-point core to PNG or PPM (or a turntable of
// frames to files or an animated GIF), optionally through a panel (--display). The options:
// sim_options.cpp; where the frames go: frame_output.hpp.
// Any wrong option or bad file: one line on stderr, exit status 2, no output written. Work
// dropped for lack of store space: the image is written, a warning says what, exit status 3.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "lineraster/hal/panel_sink.hpp"
#include "lineraster/host_sim/emulator/emulator_bus.hpp"
#include "lineraster/host_sim/emulator/panel_emulator.hpp"
#include "lineraster/host_sim/formats/image_io.hpp"
#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/programs/frame_output.hpp"
#include "lineraster/host_sim/programs/panel_output.hpp"
#include "lineraster/host_sim/programs/sim_options.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"

namespace {

using lr::host::BusTotals;
using lr::host::RenderResult;
using lr::host::SimOptions;

using ull = unsigned long long;

constexpr int kBadInput = 2;
constexpr int kIncomplete = 3;

int fail(const std::string& msg) {
  std::fprintf(stderr, "lineraster-sim: %s\n", msg.c_str());
  return kBadInput;
}

// The loader's and the scene's warnings, one line each (at most 20, then how many more).
void warn_all(const std::vector<std::string>& warnings) {
  constexpr size_t kShown = 20;
  for (size_t i = 0; i < warnings.size() && i < kShown; ++i)
    std::fprintf(stderr, "lineraster-sim: warning: %s\n", warnings[i].c_str());
  if (warnings.size() > kShown)
    std::fprintf(stderr, "lineraster-sim: warning: %zu more warnings\n", warnings.size() - kShown);
}

// What was dropped over the frames rendered (RenderResult::incomplete).
struct Dropped {
  int frames = 0;
  uint64_t vertex_capacity = 0, triangle_capacity = 0;
  void add(const RenderResult& r) {
    if (!r.incomplete) return;
    ++frames;
    vertex_capacity += r.stats.dropped_vertex_capacity;
    triangle_capacity += r.stats.dropped_triangle_capacity;
  }
};

// A hint when the (last) frame shows nothing of the model: why, from the statistics.
void report_empty(const RenderResult& r, const SimOptions& o) {
  const lr::FrameStats& s = r.stats;
  if (s.pixels_written != 0 || s.triangles_in == 0) return;
  const char* why = "no triangle covers a pixel centre";
  if (s.culled_backface == s.triangles_in)
    why = "every triangle faces away and back faces are culled";
  else if (s.culled_offscreen + s.clipped_away + s.culled_backface >= s.triangles_in)
    why = "the model is outside the view, or too small to cover a pixel centre";
  std::fprintf(stderr, "lineraster-sim: warning: nothing of the model is visible: %s%s\n", why,
               o.scene.fit ? "" : " (--fit puts it in view)");
}

// The one warning line of an incomplete frame; the exit status.
int report_dropped(const Dropped& d, const SimOptions& o) {
  if (d.frames == 0) return 0;
  const auto& s = o.scene.stores;
  std::fprintf(stderr,
               "lineraster-sim: warning: %d frame(s) incomplete for lack of store space: %llu "
               "triangles dropped for the vertex store, %llu for the binned-triangle store "
               "(--stores %zu,%zu,%zu)\n",
               d.frames, static_cast<ull>(d.vertex_capacity), static_cast<ull>(d.triangle_capacity),
               s.vertices, s.triangles, s.active);
  return kIncomplete;
}

// What --frames adds up over the frames sent to a panel.
struct PanelTotals {
  BusTotals bus;
  uint64_t strips_sent = 0, strips_narrowed = 0, strips_skipped = 0;

  void add(const BusTotals& sent, const lr::PanelSinkStats& ss) {
    bus.bytes += sent.bytes;
    bus.pixel_bytes += sent.pixel_bytes;
    bus.commands += sent.commands;
    bus.pixel_transfers += sent.pixel_transfers;
    bus.transactions += sent.transactions;
    strips_sent += ss.strips_sent;
    strips_narrowed += ss.strips_narrowed;
    strips_skipped += ss.strips_skipped;
  }
};

void print_bus(const BusTotals& b) {
  std::printf(
      ",\"bytes\":%llu,\"pixel_bytes\":%llu,\"commands\":%llu,\"pixel_transfers\":%llu,"
      "\"transactions\":%llu",
      static_cast<ull>(b.bytes), static_cast<ull>(b.pixel_bytes), static_cast<ull>(b.commands),
      static_cast<ull>(b.pixel_transfers), static_cast<ull>(b.transactions));
}

// One line of --frames: the frame's counts, what went to the panel (or the strips), the time.
void print_frame(int f, double rotate_y, const RenderResult& r, const BusTotals* sent,
                 const lr::PanelSinkStats* ss, double ms) {
  std::printf("{\"frame\":%d,\"rotate_y\":%g,\"triangles_binned\":%u,\"pixels_written\":%u", f,
              rotate_y, r.stats.triangles_binned, r.stats.pixels_written);
  if (sent) {
    print_bus(*sent);
    std::printf(",\"strips_sent\":%u,\"strips_narrowed\":%u,\"strips_skipped\":%u", ss->strips_sent,
                ss->strips_narrowed, ss->strips_skipped);
  } else {
    std::printf(",\"strips\":%u,\"empty_strips\":%u", r.stats.strips, r.stats.empty_strips);
  }
  std::printf(",\"ms\":%.2f}\n", ms);
}

// The last line of --frames.
void print_totals(int frames, uint64_t pixels, const PanelTotals* panel, double ms) {
  std::printf("{\"frames\":%d,\"pixels_written\":%llu", frames, static_cast<ull>(pixels));
  if (panel) {
    print_bus(panel->bus);
    std::printf(",\"strips_sent\":%llu,\"strips_narrowed\":%llu,\"strips_skipped\":%llu",
                static_cast<ull>(panel->strips_sent), static_cast<ull>(panel->strips_narrowed),
                static_cast<ull>(panel->strips_skipped));
  }
  std::printf(",\"ms\":%.2f}\n", ms);
}

// One frame, or --frames N turning the model about y: each frame rendered, then sent to the
// panel (opened after the first frame rendered: a bad scene leaves it alone), then to the
// outputs that take every frame (--out-pattern, a GIF). `result` is the last frame.
bool render_frames(SimOptions& o, const lr::host::HostMesh& mesh, lr::host::PanelOutput& panel,
                   lr::host::FrameOutputs& outputs, RenderResult& result, Dropped& dropped,
                   std::string& error) {
  const bool to_panel = o.display.kind != lr::host::DisplayKind::kNone;
  const double base_rotation = o.scene.model_rotate_y;
  const int count = o.frames > 0 ? o.frames : 1;
  PanelTotals totals;
  uint64_t pixels_total = 0;
  double ms_total = 0;
  for (int f = 0; f < count; ++f) {
    if (o.frames > 0)
      o.scene.model_rotate_y = std::fmod(base_rotation + 360.0 * f / o.frames, 360.0);
    auto t0 = std::chrono::steady_clock::now();
    if (!lr::host::render_scene(mesh, o.scene, result, error)) return false;
    dropped.add(result);
    BusTotals sent;
    if (to_panel) {
      if (f == 0) {  // the panel's start-up (reset and sleep-out delays) is not the frame's time
        const auto o0 = std::chrono::steady_clock::now();
        if (!panel.open(o.display, o.panel, o.scene.strip_height, error)) return false;
        t0 += std::chrono::steady_clock::now() - o0;
      }
      const BusTotals before = panel.totals();
      // The frame as a panel firmware renders it (SceneOptions::rgb565, set with --display).
      if (!panel.send(result.rgb565, result.image.width, result.image.height, error)) return false;
      sent = panel.totals() - before;
    }
    if (!outputs.add(f, panel.emulator() ? panel.emulator()->image() : result.image, error))
      return false;
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ms_total += ms;
    pixels_total += result.stats.pixels_written;
    if (o.frames == 0) continue;
    if (to_panel) totals.add(sent, panel.sink_stats());
    print_frame(f, o.scene.model_rotate_y, result, to_panel ? &sent : nullptr,
                to_panel ? &panel.sink_stats() : nullptr, ms);
  }
  if (o.frames > 0) print_totals(o.frames, pixels_total, to_panel ? &totals : nullptr, ms_total);
  return true;
}

// What the emulated panel found wrong in the driver's stream (warnings: the image is written).
void report_emulator_warnings(const lr::host::PanelOutput& panel) {
  const lr::host::PanelEmulator* emu = panel.emulator();
  if (!emu) return;
  int shown = 0;
  for (const lr::host::PanelDiagnostic& d : emu->diagnostics()) {
    if (!lr::host::is_error(d.issue) || shown++ >= 10) continue;
    std::fprintf(stderr, "lineraster-sim: warning: panel: %s: %s\n", lr::host::to_string(d.issue),
                 d.text.c_str());
  }
  for (const std::string& m : panel.emulator_bus()->misuse())
    std::fprintf(stderr, "lineraster-sim: warning: bus: %s\n", m.c_str());
}

// Every file the run reads, that no output may be: the OBJ, its MTL files, the textures and maps.
std::vector<std::string> input_files(const SimOptions& o, const lr::host::HostMesh& mesh) {
  std::vector<std::string> in{o.obj};
  in.insert(in.end(), mesh.material_libraries.begin(), mesh.material_libraries.end());
  for (const lr::host::HostMaterial& m : mesh.materials)
    if (!m.map_kd.empty()) in.push_back(m.map_kd);
  for (const std::string* f : {&o.scene.texture, &o.scene.envmap, &o.scene.normalmap})
    if (!f->empty()) in.push_back(*f);
  return in;
}

void print_stats(const SimOptions& o, const RenderResult& result) {
  const lr::FrameStats& s = result.stats;
  std::printf(
      "{\"width\":%d,\"height\":%d,\"strip_height\":%d,\"triangles_in\":%u,\"binned_inputs\":%u,"
      "\"culled_backface\":%u,\"culled_zero_area\":%u,\"culled_offscreen\":%u,\"clipped\":%u,"
      "\"clipped_away\":%u,\"rejected_invalid\":%u,\"dropped_vertex_capacity\":%u,"
      "\"dropped_triangle_capacity\":%u,\"draws_refused_invalid\":%u,"
      "\"draws_refused_not_linked\":%u,\"draws_refused_missing_store\":%u,"
      "\"draws_refused_capacity\":%u,\"triangles_binned\":%u,"
      "\"vertices_transformed\":%u,\"vertices_wide\":%u,\"strips\":%u,\"empty_strips\":%u,"
      "\"strip_passes\":%u,"
      "\"triangles_set_up\":%u,"
      "\"triangles_without_pixels\":%u,\"spans\":%u,"
      "\"pixels_tested\":%u,\"pixels_written\":%u,\"max_active\":%u,\"bytes_sent\":%llu,"
      "\"bytes_per_vertex\":%u,\"bytes_per_binned_triangle\":%u,\"bytes_per_active_triangle\":%u,"
      "\"bytes_per_strip\":%u}\n",
      o.scene.width, o.scene.height, result.strip_height, s.triangles_in, s.binned_inputs,
      s.culled_backface, s.culled_zero_area, s.culled_offscreen, s.clipped, s.clipped_away,
      s.rejected_invalid, s.dropped_vertex_capacity, s.dropped_triangle_capacity,
      s.draws_refused_invalid, s.draws_refused_not_linked, s.draws_refused_missing_store,
      s.draws_refused_capacity, s.triangles_binned, s.vertices_transformed, s.vertices_wide,
      s.strips, s.empty_strips, s.strip_passes, s.triangles_set_up, s.triangles_without_pixels,
      s.spans, s.pixels_tested, s.pixels_written, s.max_active, static_cast<ull>(result.bytes),
      s.bytes_per_vertex, s.bytes_per_binned_triangle, s.bytes_per_active_triangle,
      s.bytes_per_strip);
}

}  // namespace

int main(int argc, char** argv) {
  SimOptions o;
  std::string error;
  if (!lr::host::parse_sim_options(argc, argv, o, error)) return fail(error);
  if (o.help) {
    std::fputs(lr::host::sim_usage(), stdout);
    return 0;
  }
  if (o.version) {
    std::printf("lineraster-sim %s\n", LR_VERSION);
    return 0;
  }
  lr::host::HostMesh mesh;
  if (!lr::host::load_obj(o.obj, mesh, error)) return fail(error);
  // Every output name is checked before anything is rendered or written.
  lr::host::FrameOutputs outputs(o);
  if (!outputs.check(input_files(o, mesh), error)) return fail(error);
  warn_all(mesh.warnings);
  if (o.subdivisions > 0) mesh = lr::host::subdivide(mesh, o.subdivisions);
  lr::host::PanelOutput panel;
  RenderResult result;
  Dropped dropped;
  if (!render_frames(o, mesh, panel, outputs, result, dropped, error)) return fail(error);
  report_emulator_warnings(panel);
  warn_all(result.warnings);
  const lr::host::ImageRgb8 shown =
      panel.emulator() ? panel.emulator()->image() : std::move(result.image);
  if (!outputs.finish(shown, result.depth, error)) return fail(error);
  if (o.stats) print_stats(o, result);
  report_empty(result, o);
  return report_dropped(dropped, o);
}
