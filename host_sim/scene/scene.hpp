// Rendering a HostMesh with the fixed-point core on the host: converts the double-precision
// mesh and options to the core's formats (rejecting what they cannot hold), builds the camera,
// lights and materials, and runs the strip renderer into a capture display.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lineraster/core/output/frame_stats.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/core/scene/mesh.hpp"
#include "lineraster/core/texture/texture.hpp"
#include "lineraster/host_sim/formats/host_mesh.hpp"
#include "lineraster/host_sim/formats/image_io.hpp"

namespace lr::host {

struct MaterialOptions {
  Vec3d ambient{0.1, 0.1, 0.1};
  Vec3d diffuse{0.8, 0.8, 0.8};
  Vec3d specular{0.5, 0.5, 0.5};
  Vec3d emission{0.0, 0.0, 0.0};
  double shininess = 32.0;  // GL range [0, 128]
};

// A light as the options describe it (GL's fixed-function light; see core/lighting/lighting.hpp).
// Directional: xyz is the world-space direction from the surface towards the light (any
// non-zero length). Point: xyz is the light's world position, and its terms are scaled by GL's
// attenuation 1 / (constant + linear d + quadratic d^2) (coefficients >= 0, not all 0).
// `color` in [0, 1] is its ambient, diffuse and specular colour (the project's convention).
struct LightOption {
  bool point = false;
  Vec3d xyz{1, 1, 1};
  Vec3d color{1, 1, 1};
  double constant = 1, linear = 0, quadratic = 0;
};

// Everything lineraster-sim's options describe (defaults are the CLI's).
struct SceneOptions {
  int width = 320, height = 240;
  double fovy = 60.0, near = 0.1, far = 100.0;
  Vec3d eye{0, 0, 3}, target{0, 0, 0}, up{0, 1, 0};
  bool fit = false;
  // Positions with the most fraction bits the fitted mesh's largest coordinate allows (in
  // [16, 30]: Mesh::position_frac), else Q16.16. lineraster-asset --fine-positions.
  bool fine_positions = false;
  // The model transform: translate * rotate_y * rotate_x * rotate_z * scale (* the fit), so a
  // vertex is turned about z first, then x, then y (degrees, GL's right-handed rotations): x and
  // z set the model upright (a Z-up model: rotate_x -90), y turns it about the vertical axis
  // (the turntable of --frames). Unity's Euler angles compose in the same order.
  double model_scale = 1.0, model_rotate_y = 0.0, model_rotate_x = 0.0, model_rotate_z = 0.0;
  Vec3d model_translate{0, 0, 0};
  Shading shading = Shading::kGouraud;  // kFlat, kGouraud or kPhong (lit per pixel)
  bool unlit = false;
  std::vector<Vec3d> light_dirs{{1, 1, 1}};  // world space, towards the light; colour white
  std::vector<LightOption> lights;  // when not empty: the lights, and light_dirs is not used
  Vec3d global_ambient{0, 0, 0};
  bool local_viewer = false;
  bool two_sided = false;  // back faces lit with the negated normal (GL_LIGHT_MODEL_TWO_SIDE)
  // Phong shading only: how a pixel is lit (kTable needs directional lights only and no local
  // viewer), the table's size and filter, and the sphere environment map and tangent-space
  // normal map (PNG files; the normal map is loaded as RGB888, the environment map in
  // texture_format; both at level 0). A normal map needs texture coordinates in the mesh; its
  // tangents are the mesh's, or computed (compute_tangents) when the mesh has none.
  PixelLighting pixel_lighting = PixelLighting::kExact;
  LightingTableSpec table{};
  std::string envmap, normalmap;
  MaterialOptions material;
  bool use_mesh_materials =
      true;  // MTL materials of the mesh win unless material options were given
  Vec3d background{0, 0, 0};
  bool depth_test = true;
  Cull cull = Cull::kNone;
  Perspective perspective = Perspective::kExact;
  int strip_height = 8;  // 1, 2, 4, 8, 16 or 32
  // The pixel format rendered in: Rgb888 (host images), or Rgb565Be (what an RGB565 panel is
  // sent, the frame a panel firmware renders: RenderResult::rgb565, the image its decode).
  bool rgb565 = false;
  // Texturing. The texture is `texture` when given, else each material's map_Kd (when the mesh
  // has texture coordinates). Lit draws modulate the texel (specular added after), unlit ones
  // replace the colour by the texel.
  std::string texture;
  TexelFormat texture_format = TexelFormat::kRgb565;
  Filter filter = Filter::kBilinear;
  Wrap wrap = Wrap::kRepeat;
  MipMode mipmap = MipMode::kNone;
  const Texture* texture_object = nullptr;  // for tests and tools: used instead of any file
  // The renderer's store capacities (entries; the core's limits by default).
  struct Stores {
    size_t vertices = 0xFFFF, triangles = 0xFFFE, active = 4096;
  } stores{};
};

struct RenderResult {
  // The frame as 8-bit RGB: rendered so, or with SceneOptions::rgb565 the RGB565 frame decoded
  // by bit replication (as panel controllers expand it).
  ImageRgb8 image;
  std::vector<uint16_t> rgb565;  // SceneOptions::rgb565: the RGB565 values, row by row; else empty
  std::vector<uint16_t> depth;   // 16-bit window depth per pixel, 65535 where nothing was drawn
  FrameStats stats;
  uint32_t strips = 0;
  uint64_t bytes = 0;
  // Work dropped for lack of store space (a draw refused with kCapacity, or render() reporting a
  // strip that did not fit): the image is what fit. The statistics count the triangles.
  bool incomplete = false;
  // The strip height drawn with: the options' unless a strip overflowed the binned store, then
  // halved until none does (or 1).
  int strip_height = 0;
  std::vector<std::string> warnings;  // what the scene's files asked for and was left out
};

// The fit of the model transform the options describe (applied to positions in double):
// translate * rotate_y * rotate_x * rotate_z * scale * fit. Used by the reference renderer's
// tests too.
struct ModelTransform {
  Vec3d fit_center{0, 0, 0};
  double fit_scale = 1.0;
};
ModelTransform model_transform(const HostMesh& mesh, const SceneOptions& options);

// A mesh in the core's formats: one piece with one material and at most 65535 vertices.
struct FixedDraw {
  std::vector<Vec3> positions;
  std::vector<Normal16> normals;
  std::vector<Rgb8> colors;   // empty when the mesh has none
  std::vector<TexCoord> uvs;  // empty when the mesh has none
  std::vector<std::array<uint16_t, 3>> triangles;
  std::vector<Tangent16> tangents;  // empty when the mesh has none; Q1.14, w = +-16384
  Material material;
  int32_t material_index = -1;  // the HostMesh material it came from, -1 for the options' one
  uint8_t position_frac = 16;   // the positions' fraction bits (Mesh::position_frac)
  // With its bound (Mesh::bound), as lineraster-asset writes it: the same frames either way.
  Mesh mesh() const {
    return {positions,    normals, colors, uvs, triangles, tangents, mesh_bound(positions),
            position_frac};
  }
};

// Converts the mesh (with the options' fit applied) to the core's formats, split by material
// and into pieces of at most 65535 vertices. The asset converter uses the same conversion.
bool build_fixed_draws(const HostMesh& mesh, const SceneOptions& options,
                       std::vector<FixedDraw>& draws, std::string& error);

// Renders; on failure returns false with a one-line error (nothing rendered). Phong frames get
// the SurfaceVertex store (as large as the vertex store), one PreparedLighting per distinct
// material and, for PixelLighting::kTable, one split table (2 (size + 1)^2 words) per material.
bool render_scene(const HostMesh& mesh, const SceneOptions& options, RenderResult& out,
                  std::string& error);

// The core's conversions, exposed for tests: false when the value cannot be represented.
bool to_fixed(double v, Fixed& out);
// The most fraction bits in [16, 30] that hold every coordinate of magnitude up to max_abs
// rounded (16 when none does: to_fixed's range).
int position_frac_for(double max_abs);
bool to_texcoord(const Vec2d& uv, TexCoord& out);
Color15 to_color15(const Vec3d& c);
// A unit tangent (x, y, z) in Q1.14 and w = +16384 for w >= 0, else -16384; false when a
// component is not finite.
bool to_tangent16(const Vec4d& t, Tangent16& out);

}  // namespace lr::host
