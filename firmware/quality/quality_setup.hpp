// What lr_quality_scenes generates for the quality image (tests/bench/quality_scenes_main.cpp):
// a scene's frame parameters and one benchmark configuration.
#pragma once

#include <cstdint>

#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/scene/mesh.hpp"
#include "lineraster/core/texture/texture.hpp"

namespace lr::fw::quality_gen {

// A scene's camera, lights, background, model matrix and the draw-state fields every
// configuration of it shares.
struct QualitySetup {
  Camera camera;
  LightSet lights;
  Rgb8 background{};
  Mat4 model = Mat4::identity();
  DrawState state;
};

// One configuration: its key (the quality benchmark's columns), scene index, strip height, the
// settings it varies, and the host's RGB565 frame checksum (firmware/common/ordered_sink.hpp)
// and pixels written.
struct QualityCase {
  const char* key;
  uint8_t scene;
  uint8_t strip;
  Shading shading;
  Perspective perspective;
  Filter filter;
  MipMode mip;
  uint8_t format;  // 0: RGB565 texture, 1: RGB888
  bool textured;
  uint32_t checksum;
  uint32_t pixels;
};

}  // namespace lr::fw::quality_gen
