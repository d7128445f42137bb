// The README's demo scene on a panel: the 4,000-triangle torus knot (tests/host/data/
// torus_knot.obj, fitted, compiled in as constexpr arrays that lineraster-asset generates at
// build time) in the classic "gold" material, Gouraud-shaded, depth-tested, lit and viewed as
// lineraster-sim does by default, turning about y by kDegreesPerFrame each frame. Frame f is
// the frame of
//   lineraster-sim --obj tests/host/data/torus_knot.obj --fit --material gold
//     --width W --height H --model-rotate-y (3 f mod 360)
// pixel for pixel (the unit test compares them), in RGB565 for the panel.
//
// The core keeps no frame: the renderer hands strips of kStripRows rows to the sink. Its stores
// are sized for the mesh here, on the heap (this is a Linux program; the core itself allocates
// nothing).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "lineraster/core/output/frame_stats.hpp"
#include "lineraster/core/raster/renderer.hpp"

namespace lr::app {

class DemoScene {
 public:
  static constexpr int kStripRows = 8;
  static constexpr int kDegreesPerFrame = 3;  // 120 frames per turn
  // Gouraud spans only (the scene has no texture and no Phong draw): less code on the board.
  using SceneRenderer = Renderer<Rgb565Be, kStripRows, kUntexturedSpans>;

  DemoScene();
  ~DemoScene();
  DemoScene(const DemoScene&) = delete;
  DemoScene& operator=(const DemoScene&) = delete;

  // Sizes the stores for a width x height viewport. False and a one-line error when the core
  // refuses it.
  bool configure(int width, int height, std::string& error);
  // Renders frame `index` into the sink (begin_frame ... end_frame). kCapacity if the mesh did
  // not fit the stores (they are sized so that it does); otherwise the sink's status.
  Status render(uint32_t index, StripSink<Rgb565Be>& sink);
  // The model's rotation about y for frame `index`, in whole degrees [0, 360).
  static int degrees(uint32_t index) { return static_cast<int>(index % 120u) * kDegreesPerFrame; }
  const FrameStats& stats() const { return renderer_->stats(); }
  // Triangles in the compiled-in mesh.
  static size_t triangle_count();

 private:
  int width_ = 0, height_ = 0;
  std::unique_ptr<BasicFrameStorage<std::vector>> store_;
  std::unique_ptr<SceneRenderer> renderer_;
};

}  // namespace lr::app
