// Renders a host scene with Mesa's software OpenGL (OSMesa, offscreen, fixed-function GL 1.x)
// with the state docs/conventions.md describes: the same double matrices as the reference
// (tests/support/scene_compare.hpp), directional lights whose ambient, diffuse and specular
// colours are white, the options' material, GL_DITHER off, depth test LESS, GL_NORMALIZE, CCW
// front faces. Textures are uploaded texel for texel as the core holds them (host::texel_rgb8),
// bottom row first (GL's order). Tests only: an independent implementation to check the
// conventions against.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lineraster/host_sim/formats/host_mesh.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/reference/ref_renderer.hpp"

namespace lr::glcheck {

struct GlFrame {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;      // 3 bytes per pixel, row 0 = top (glReadPixels rows flipped)
  std::vector<uint8_t> covered;  // 1 where a fragment was written (window depth < 1)
  std::string renderer;          // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
};

// Renders mesh as `o` describes (o.material for every triangle, like the reference; lit
// untextured: GL_SINGLE_COLOR, which equals the separate sum for non-negative terms; lit
// textured: GL_MODULATE + GL_SEPARATE_SPECULAR_COLOR; unlit textured: GL_REPLACE; unlit: vertex
// colours, else the material's diffuse colour). Returns false with a one-line error when
// OSMesa fails.
bool render_gl(const host::HostMesh& mesh, const host::SceneOptions& o, GlFrame& out,
               std::string& error);

// The same with the matrices and light directions of `p` instead of those `o` describes (for
// scenes whose model transform the options cannot say, such as the peer scenes' rotations about
// x); everything else still comes from `o`.
bool render_gl(const host::HostMesh& mesh, const host::SceneOptions& o, const ref::RefParams& p,
               GlFrame& out, std::string& error);

}  // namespace lr::glcheck
