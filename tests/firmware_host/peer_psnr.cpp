// The peer scenes' quality: each frame of firmware/peer (the same scene definitions, flash arrays
// and model matrices as lr_peer) rendered by the core on the host in RGB888 strips of 8 (the
// core's arithmetic, before the display's RGB565 rounding, as tests/bench/quality_bench does),
// and by the double-precision reference (tests/reference) from the double-precision meshes
// (the same OBJ files, fitted and subdivided by the same host_sim functions as lineraster-asset)
// with the 8-bit baboon (the RGB565 texture's rounding counts as error), and again with the
// RGB565 texels the core samples (the renderer's own error). Prints one line per scene: covered
// pixels of each, coverage mismatches, and over the pixels both cover the PSNR, the % of pixels
// within one level in every channel, the largest channel error (tests/support/scene_compare.hpp
// measures them); and lr_peer's RGB565 frame against the reference's colours rounded to RGB565
// (the % of pixels on the rounded level in every channel, the pixels with a channel more than
// one step from it). scripts/peer_bench.sh puts the PSNR in its tables. A figure, not a test: it
// never fails on the error's size.
//
// usage: lr_peer_psnr [SOURCE_DIR]   (default: the source tree it was built from)
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "firmware/peer/assets.hpp"
#include "firmware/peer/scenes.hpp"
#include "lineraster/core/raster/frame_storage.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"
#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "tests/reference/ref_math.hpp"
#include "tests/reference/ref_renderer.hpp"
#include "tests/reference/ref_texture_core.hpp"
#include "tests/support/scene_compare.hpp"

namespace {

namespace peer = lr::fw::peer;
constexpr int K = 8;

[[noreturn]] void die(const std::string& what) {
  std::fprintf(stderr, "lr_peer_psnr: %s\n", what.c_str());
  std::exit(2);
}

// The stores of firmware/peer/main.cpp (all scenes fit the subdivided bunny's).
constexpr lr::FrameCapacities kCapacities{
    .width = peer::kWidth,
    .height = peer::kHeight,
    .strip_height = K,
    .vertices = peer_bunnyx_asset::meshes[0].positions.size() + 32,
    .triangles = peer_bunnyx_asset::meshes[0].triangles.size() + 32,
    .draws = 2,
    .active = 2048,
    .tex_vertices = peer_bunnyx_asset::meshes[0].positions.size() + 32,
    .active_extra = 2048};

// The core's frame of a case, as lr_peer draws it, in PF (RGB888; RGB565 for the step check).
template <class PF = lr::Rgb888>
void render_core(const peer::PeerCase& c, lr::host::RenderResult& out) {
  auto store = std::make_unique<lr::StaticFrameStorage<kCapacities>>();
  auto renderer = std::make_unique<lr::Renderer<PF, K>>();
  if (renderer->configure(store->storage(), peer::kWidth, peer::kHeight) != lr::Status::kOk)
    die("configure failed");
  lr::Camera camera;
  if (!peer::make_camera(c, camera)) die("projection rejected");
  const lr::Mat4 model = peer::model(c);
  lr::DrawState state = c.state;
  state.texture = peer::texture(c.geometry);
  lr::Status s = renderer->begin_frame(camera, c.lights, peer::kBackground);
  for (const lr::Mesh& m : peer::meshes(c.geometry))
    if (s == lr::Status::kOk) s = renderer->draw(m, model, c.material, state);
  lr::host::CaptureDisplay<PF> display(size_t{peer::kWidth} * K);
  lr::host::DepthCapture depth;
  depth.resize(peer::kWidth, peer::kHeight);
  if (s == lr::Status::kOk) s = renderer->render(display, &depth);
  if (s != lr::Status::kOk) die(std::string(c.name) + ": " + lr::to_string(s));
  out.image = display.image();
  out.depth = depth.depth();
  out.stats = renderer->stats();
}

// The double-precision mesh of a geometry, as lineraster-asset makes the fixed-point one
// (firmware/peer/assets.cmake): loaded, subdivided, then fitted to its box.
lr::host::HostMesh host_mesh(const std::string& dir, peer::Geometry g) {
  const bool bunny = g == peer::Geometry::kBunny || g == peer::Geometry::kBunnyX;
  const std::string file = bunny                        ? "bunny.obj"
                           : g == peer::Geometry::kCube ? "cube.obj"
                                                        : "ground.obj";
  lr::host::HostMesh mesh;
  std::string error;
  if (!lr::host::load_obj(dir + file, mesh, error)) die(error);
  if (g == peer::Geometry::kBunnyX) mesh = lr::host::subdivide(mesh, 2);
  if (bunny) lr::host::apply_fit(mesh, lr::host::fit_box_transform(mesh));
  return mesh;
}

lr::ref::RefParams ref_params(const peer::PeerScene& s) {
  lr::ref::RefParams p;
  p.width = peer::kWidth;
  p.height = peer::kHeight;
  p.model = lr::ref::mul(
      lr::ref::translate({0, 0, s.translate_z}),
      lr::ref::mul(lr::ref::rotate_x(s.rotate_x_deg), lr::ref::rotate_y(s.rotate_y_deg)));
  p.projection =
      lr::ref::perspective(peer::kFovyDeg, double(peer::kWidth) / peer::kHeight, s.near, s.far);
  p.background = {peer::kBackground.r / 255.0, peer::kBackground.g / 255.0,
                  peer::kBackground.b / 255.0};
  p.cull_back = true;
  p.shading = lr::ref::RefShading::Gouraud;
  p.unlit = !s.lit;
  if (s.lit) {
    const auto& c = peer::kMaterialColor;
    p.lights.push_back(lr::ref::RefLight{
        {peer::kLightTowards[0], peer::kLightTowards[1], peer::kLightTowards[2]}, {1, 1, 1}});
    p.material = {{peer::kAmbient * c[0], peer::kAmbient * c[1], peer::kAmbient * c[2]},
                  {peer::kDiffuse * c[0], peer::kDiffuse * c[1], peer::kDiffuse * c[2]},
                  {0, 0, 0},
                  {0, 0, 0},
                  0};
  }
  return p;
}

// The RGB565 frame (lr_peer's) against the reference's colours rounded to RGB565, over the
// pixels both cover: how many have every channel on the rounded level, and how many have a
// channel more than one step from it. The capture expands 565 by bit replication, so the top
// bits of its bytes are the stored levels.
struct StepCheck {
  size_t both = 0, exact = 0, over1 = 0;
};
StepCheck rgb565_steps(const lr::host::RenderResult& core, const lr::ref::RefFrame& ref) {
  StepCheck out;
  for (int y = 0; y < ref.height; ++y) {
    for (int x = 0; x < ref.width; ++x) {
      const size_t i = ref.index(x, y);
      if (core.depth[i] == 0xFFFF || ref.owner[i] < 0) continue;
      ++out.both;
      const double c[3] = {ref.color[i][0], ref.color[i][1], ref.color[i][2]};
      const int levels[3] = {31, 63, 31}, shifts[3] = {3, 2, 3};
      bool exact = true, over = false;
      for (int k = 0; k < 3; ++k) {
        const double v = c[k] < 0 ? 0 : c[k] > 1 ? 1 : c[k];
        const int want = static_cast<int>(v * levels[k] + 0.5);
        const int got = core.image.rgb[3 * i + static_cast<size_t>(k)] >> shifts[k];
        exact = exact && got == want;
        over = over || got > want + 1 || got < want - 1;
      }
      out.exact += exact ? 1 : 0;
      out.over1 += over ? 1 : 0;
    }
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string root = argc > 1 ? argv[1] : LR_SOURCE_DIR;
  const std::string dir = root + "/tests/data/peer/";
  lr::host::HostTexture baboon;
  std::string error;
  if (!lr::host::load_texture(dir + "baboon.png", lr::TexelFormat::kRgb888, false, baboon, error))
    die(error);
  const lr::ref::RefTexture truth = lr::ref::from_core(baboon.texture);
  const lr::ref::RefTexture stored = lr::ref::from_core(*peer::texture(peer::Geometry::kCube));
  std::printf(
      "lr_peer_psnr: core RGB888 (strips of 8) against the double reference (8-bit "
      "texture); error over the pixels both cover\n");
  for (size_t i = 0; i < peer::kScenes.size(); ++i) {
    const peer::PeerScene& s = peer::kScenes[i];
    const peer::PeerCase& c = peer::kCases[i];
    lr::test::Comparison cmp;
    render_core(c, cmp.core);
    const lr::host::HostMesh mesh = host_mesh(dir, s.geometry);
    lr::ref::RefParams rp = ref_params(s);
    if (!s.lit) {
      rp.texture = &truth;
      lr::ref::set_sampler(rp, c.state.sampler);
    }
    lr::ref::render(mesh, rp, cmp.reference);
    lr::test::measure(true, cmp);
    // The same against the reference sampling the texels the core samples (RGB565): the
    // renderer's own error, without the texture format's.
    lr::test::Comparison same = cmp;
    if (!s.lit) {
      same = {};
      same.core = cmp.core;
      rp.texture = &stored;
      lr::ref::render(mesh, rp, same.reference);
      lr::test::measure(true, same);
    }
    // lr_peer's RGB565 frame against the same reference (the colours it rounds to RGB565).
    lr::host::RenderResult core565;
    render_core<lr::Rgb565Be>(c, core565);
    const StepCheck steps = rgb565_steps(core565, s.lit ? cmp.reference : same.reference);
    size_t covered = 0, ref_covered = 0;
    for (uint16_t d : cmp.core.depth) covered += d != 0xFFFF;
    for (int32_t o : cmp.reference.owner) ref_covered += o >= 0;
    std::printf(
        "lr_peer_psnr: case %s covered %zu ref_covered %zu coverage_diff %zu written %u psnr %.2f "
        "within1 %.2f max_error %d psnr_same_texels %.2f within1_same_texels %.2f "
        "rgb565_both %zu rgb565_exact %.2f rgb565_over1 %zu\n",
        s.name, covered, ref_covered, cmp.coverage_diff, cmp.core.stats.pixels_written, cmp.psnr,
        100.0 * cmp.fraction_within1(), cmp.max_error, same.psnr, 100.0 * same.fraction_within1(),
        steps.both, steps.both ? 100.0 * double(steps.exact) / double(steps.both) : 0.0,
        steps.over1);
  }
  return 0;
}
