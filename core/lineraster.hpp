// The core's umbrella header: everything a program needs to render a frame (renderer, storage,
// camera, meshes, materials, lights, textures, the strip sink it implements, the frame-buffer
// sink). Including the parts one by one compiles faster; this is for a first program and for
// examples.
#pragma once

#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/output/frame_buffer_sink.hpp"
#include "lineraster/core/output/frame_stats.hpp"
#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/output/status.hpp"
#include "lineraster/core/output/strip_sink.hpp"
#include "lineraster/core/raster/frame_storage.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/core/scene/mesh.hpp"
#include "lineraster/core/texture/mipmap.hpp"
#include "lineraster/core/texture/texture.hpp"
