// What the caller hands to the renderer: meshes (in flash or RAM), the camera and the draw state.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "core/output/color.hpp"
#include "core/math/mat4.hpp"
#include "core/texture/texture.hpp"
#include "core/math/vec.hpp"

namespace lr {

// An indexed triangle mesh. Positions in model units (Q16.16); normals unit Q1.14 (needed for
// Gouraud and Phong lighting; flat lighting uses face normals); colours optional (unlit
// shading); tangents (one per position) only for normal mapping.
// Triangles are counter-clockwise when front-facing; indices < positions.size().
struct Mesh {
  std::span<const Vec3> positions;
  std::span<const Normal16> normals;  // empty, or one per position
  std::span<const Rgb8> colors;       // empty, or one per position
  std::span<const TexCoord> uvs;      // empty, or one per position (textured draws)
  std::span<const std::array<uint16_t, 3>> triangles;
  std::span<const Tangent16> tangents{};  // empty, or one per position (normal-mapped draws)
};

enum class Shading : uint8_t {
  kFlat,     // one colour per triangle: lit with the face normal, or the last vertex's colour
  kGouraud,  // lit per vertex, colours interpolated perspective-correctly
  kPhong,    // normals interpolated perspective-correctly, lit per pixel (see PixelLighting);
             // always exact perspective (DrawState::perspective does not apply)
};

// How Phong shading lights a pixel.
enum class PixelLighting : uint8_t {
  // The lighting model evaluated per pixel: the interpolated normal renormalised with the
  // inverse-square-root table, Blinn specular from the power table. Any lights.
  kExact,
  // The lit colour looked up in a table over normal directions (octahedral parameterisation),
  // filled per frame and material: directional lights and the infinite viewer only.
  kTable,
};

// The normal-indexed lighting table of a PixelLighting::kTable draw: (size + 1)^2 samples.
struct LightingTableSpec {
  uint16_t size = 32;    // 8..256 cells per side
  bool bilinear = true;  // blend the 4 nearest samples (false: the nearest one)
};

enum class Cull : uint8_t { kNone, kBack, kFront };

// How attributes (texture coordinates, Gouraud colours) are interpolated: a quality setting.
// The span modes apply to textured draws; untextured Gouraud colours are exact in them (their
// per-pixel reciprocal is a 17-bit one, cheaper than a textured span's setup).
enum class Perspective : uint8_t {
  kExact,   // a/w and 1/w linear in screen space, one reciprocal per pixel (default)
  kSpan8,   // exact every 8 pixels (and at the end of the span), linear in between
  kSpan16,  // ... every 16 pixels
  kSpan32,  // ... every 32 pixels
  kAffine,  // a linear in screen space
};

struct DrawState {
  Shading shading = Shading::kGouraud;
  bool lighting = true;    // false: unlit (vertex colours if the mesh has them, else Kd)
  bool depth_test = true;  // LESS against the strip's depth buffer, and write
  Cull cull = Cull::kNone;
  Perspective perspective = Perspective::kExact;
  // Texturing: the texture (nullptr: none; it must outlive render()) and how it is sampled.
  // The mesh needs texture coordinates (uvs); draw() checks the texture with validate().
  const Texture* texture = nullptr;
  Sampler sampler{};
  // Phong shading only.
  PixelLighting pixel_lighting = PixelLighting::kExact;
  LightingTableSpec table{};
  // Sphere environment map (GL_SPHERE_MAP from the per-pixel reflected vector, bilinear, clamp
  // to edge, level 0): it modulates the lit primary colour (after the texture, if any) like a
  // second GL texture unit with GL_MODULATE; specular is added after it.
  const Texture* envmap = nullptr;
  // Tangent-space normal map (RGB = (n + 1) / 2, sampled at the mesh's uvs with the sampler's
  // filter and wraps, level 0): needs uvs and tangents.
  const Texture* normal_map = nullptr;
};

// The camera of a frame: view and projection matrices (OpenGL meaning), and the eye position
// in world space (for the local viewer).
struct Camera {
  Mat4 view = Mat4::identity();
  Mat4 projection = Mat4::identity();
  Vec3 eye{};
};

}  // namespace lr
