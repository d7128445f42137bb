#include "firmware/linux/demo_scene.hpp"

#include <algorithm>

#include "demo_knot.hpp"  // generated at build time: lineraster-asset --obj torus_knot.obj --fit
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/material.hpp"

namespace lr::app {
namespace {

static_assert(demo_knot::draw_count == 1, "the demo mesh is one draw");

// lineraster-sim's defaults (host_sim/scene/scene.hpp SceneOptions): --fovy 60 --near 0.1 --far 100
// --eye 0,0,3 --target 0,0,0 --up 0,1,0, background black. Fixed::from_double rounds v * 65536
// to nearest at compile time as the CLI's to_fixed does at run time.
constexpr Fixed kFovy = Fixed::from_double(60.0);
constexpr Fixed kNear = Fixed::from_double(0.1);
constexpr Fixed kFar = Fixed::from_double(100.0);
constexpr Vec3 kEye{Fixed::from_int(0), Fixed::from_int(0), Fixed::from_int(3)};
constexpr Vec3 kTarget{};
constexpr Vec3 kUp{Fixed::from_int(0), Fixed::from_int(1), Fixed::from_int(0)};
constexpr Rgb8 kBackground{0, 0, 0};

// The CLI's default light: white, directional, towards (1, 1, 1), which it normalises in double
// before converting: each component 1 / sqrt(3).
constexpr Fixed kInvSqrt3 = Fixed::from_double(0.57735026918962576);

LightSet default_lights() {
  LightSet s;
  s.lights[0] = Light::directional({kInvSqrt3, kInvSqrt3, kInvSqrt3},
                                   Color15{Color15::kOne, Color15::kOne, Color15::kOne});
  s.count = 1;
  return s;  // no global ambient, infinite viewer, one-sided: the CLI's defaults
}

// Headroom over the mesh's own counts for the vertices and triangles near/far clipping makes
// (the knot stays inside the frustum, so none in practice).
constexpr size_t kClipHeadroom = 256;
// Triangles on one strip at once (FrameStats::max_active says how many a view needs).
constexpr size_t kActive = 1024;

}  // namespace

DemoScene::DemoScene() = default;
DemoScene::~DemoScene() = default;

size_t DemoScene::triangle_count() {
  return demo_knot::meshes[0].triangles.size();
}

bool DemoScene::configure(int width, int height, std::string& error) {
  const Mesh& mesh = demo_knot::meshes[0];
  FrameCapacities caps;
  caps.width = std::max(width, 0);
  caps.height = std::max(height, 0);
  caps.strip_height = kStripRows;
  caps.vertices = mesh.positions.size() + kClipHeadroom;
  caps.triangles = mesh.triangles.size() + kClipHeadroom;
  caps.draws = 1;
  caps.active = kActive;
  store_ = std::make_unique<BasicFrameStorage<std::vector>>(caps);
  renderer_ = std::make_unique<SceneRenderer>();
  if (renderer_->configure(store_->storage(), width, height) != Status::kOk) {
    error = "viewport " + std::to_string(width) + "x" + std::to_string(height) +
            " refused by the renderer (1.." + std::to_string(kMaxViewport) + " each way)";
    return false;
  }
  width_ = width;
  height_ = height;
  return true;
}

Status DemoScene::render(uint32_t index, StripSink<Rgb565Be>& sink) {
  if (!renderer_ || width_ == 0) return Status::kInvalidArgument;
  Camera camera;
  camera.eye = kEye;
  if (!perspective(kFovy, Fixed::ratio(width_, height_), kNear, kFar, camera.projection) ||
      !look_at(kEye, kTarget, kUp, camera.view))
    return Status::kInvalidArgument;
  if (const Status st = renderer_->begin_frame(camera, default_lights(), kBackground);
      st != Status::kOk)
    return st;

  const NamedMaterial* gold = find_material("gold");
  if (gold == nullptr) return Status::kInvalidArgument;
  DrawState state;  // Gouraud, lit, depth test, no culling: the CLI's defaults
  const Mat4 model = rotate_y(Fixed::from_int(degrees(index)));
  if (const Status st = renderer_->draw(demo_knot::meshes[0], model, to_material(*gold), state);
      st != Status::kOk)
    return st;
  return renderer_->render(sink);
}

}  // namespace lr::app
