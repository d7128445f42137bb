// The peer scenes of firmware/peer on the host, three ways: the core's frame as lr_peer draws it
// (the same scene definitions, flash arrays and model matrices; strips of 8; any pixel format),
// the double-precision reference's (tests/reference) and Mesa's (OSMesa, tests/glcheck) from the
// double-precision meshes (the same OBJ files, fitted and subdivided by the same host_sim
// functions as lineraster-asset), and the figures that compare them (peer_figures.hpp). Shared
// by lr_peer_psnr (the benchmark's columns) and peer_accuracy_test (the bounds of issue 36).
#pragma once

#include <memory>
#include <string>

#include "firmware/peer/assets.hpp"
#include "firmware/peer/scenes.hpp"
#include "lineraster/core/raster/frame_storage.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"
#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/reference/ref_math.hpp"
#include "tests/reference/ref_renderer.hpp"

namespace lr::test::peer {

namespace fwp = lr::fw::peer;
inline constexpr int kStripRows = 8;

// The stores of firmware/peer/main.cpp (every scene fits the subdivided bunny's).
inline constexpr FrameCapacities kCapacities{
    .width = fwp::kWidth,
    .height = fwp::kHeight,
    .strip_height = kStripRows,
    .vertices = peer_bunnyx_asset::meshes[0].positions.size() + 32,
    .triangles = peer_bunnyx_asset::meshes[0].triangles.size() + 32,
    .draws = 2,
    .active = 2048,
    .tex_vertices = peer_bunnyx_asset::meshes[0].positions.size() + 32,
    .active_extra = 2048};

// The core's frame of a case as lr_peer draws it, in pixel format PF (the image decoded to 8 bits
// as PF::decode does: bit replication for RGB565), with its depth and statistics. False with a
// one-line error when a call fails.
template <class PF>
bool render_core(const fwp::PeerCase& c, host::RenderResult& out, std::string& error) {
  auto store = std::make_unique<StaticFrameStorage<kCapacities>>();
  auto renderer = std::make_unique<Renderer<PF, kStripRows>>();
  if (renderer->configure(store->storage(), fwp::kWidth, fwp::kHeight) != Status::kOk) {
    error = "configure failed";
    return false;
  }
  Camera camera;
  FineMat4 fine_projection{};
  if (!fwp::make_camera(c, camera, fine_projection)) {
    error = "projection rejected";
    return false;
  }
  const Mat4 model = fwp::model(c);
  const FineMat4 fine_model = c.fine ? fwp::fine_model(c) : FineMat4{};
  DrawState state = c.state;
  state.texture = fwp::texture(c.geometry);
  Status s = renderer->begin_frame(camera, c.lights, fwp::kBackground);
  for (const Mesh& m : fwp::meshes(c.geometry))
    if (s == Status::kOk)
      s = c.fine ? renderer->draw(m, fine_model, c.material, state)
                 : renderer->draw(m, model, c.material, state);
  host::CaptureDisplay<PF> display(size_t{fwp::kWidth} * kStripRows);
  host::DepthCapture depth;
  depth.resize(fwp::kWidth, fwp::kHeight);
  if (s == Status::kOk) s = renderer->render(display, &depth);
  if (s != Status::kOk) {
    error = std::string(c.name) + ": " + to_string(s);
    return false;
  }
  out.image = display.image();
  out.depth = depth.depth();
  out.stats = renderer->stats();
  return true;
}

// The double-precision mesh of a geometry, as lineraster-asset makes the fixed-point one
// (firmware/peer/assets.cmake): loaded from dir (tests/data/peer/), subdivided, then fitted to
// its box.
inline bool host_mesh(const std::string& dir, fwp::Geometry g, host::HostMesh& mesh,
                      std::string& error) {
  const bool bunny = g == fwp::Geometry::kBunny || g == fwp::Geometry::kBunnyX;
  const std::string file = bunny                       ? "bunny.obj"
                           : g == fwp::Geometry::kCube ? "cube.obj"
                                                       : "ground.obj";
  if (!host::load_obj(dir + file, mesh, error)) return false;
  if (g == fwp::Geometry::kBunnyX) mesh = host::subdivide(mesh, 2);
  if (bunny) host::apply_fit(mesh, host::fit_box_transform(mesh));
  return true;
}

// The reference's parameters of a scene (no texture: the caller chooses which texels it samples).
inline ref::RefParams ref_params(const fwp::PeerScene& s) {
  ref::RefParams p;
  p.width = fwp::kWidth;
  p.height = fwp::kHeight;
  p.model = ref::mul(ref::translate({0, 0, s.translate_z}),
                     ref::mul(ref::rotate_x(s.rotate_x_deg), ref::rotate_y(s.rotate_y_deg)));
  p.projection = ref::perspective(fwp::kFovyDeg, double(fwp::kWidth) / fwp::kHeight, s.near, s.far);
  p.background = {fwp::kBackground.r / 255.0, fwp::kBackground.g / 255.0,
                  fwp::kBackground.b / 255.0};
  p.cull_back = true;
  p.shading = ref::RefShading::Gouraud;
  p.unlit = !s.lit;
  if (s.lit) {
    const auto& c = fwp::kMaterialColor;
    p.lights.push_back(ref::RefLight{
        {fwp::kLightTowards[0], fwp::kLightTowards[1], fwp::kLightTowards[2]}, {1, 1, 1}});
    p.material = {{fwp::kAmbient * c[0], fwp::kAmbient * c[1], fwp::kAmbient * c[2]},
                  {fwp::kDiffuse * c[0], fwp::kDiffuse * c[1], fwp::kDiffuse * c[2]},
                  {0, 0, 0},
                  {0, 0, 0},
                  0};
  }
  return p;
}

// The options the Mesa renderer (tests/glcheck/osmesa_scene.hpp) takes besides ref_params(s): the
// frame, the state and material of the scene; textured scenes sample the core's RGB565 texels
// (the texture the firmware holds), GL_REPLACE, GL_REPEAT, no mipmaps.
inline host::SceneOptions gl_options(const fwp::PeerScene& s, const fwp::PeerCase& c) {
  const ref::RefParams p = ref_params(s);
  host::SceneOptions o;
  o.width = fwp::kWidth;
  o.height = fwp::kHeight;
  o.background = p.background;
  o.cull = Cull::kBack;
  o.shading = Shading::kGouraud;
  o.unlit = !s.lit;
  o.global_ambient = {0, 0, 0};
  o.material = {p.material.ambient, p.material.diffuse, p.material.specular, p.material.emission,
                p.material.shininess};
  o.texture_object = fwp::texture(s.geometry);
  o.filter = c.state.sampler.filter;
  o.wrap = Wrap::kRepeat;
  o.mipmap = MipMode::kNone;
  return o;
}

}  // namespace lr::test::peer
