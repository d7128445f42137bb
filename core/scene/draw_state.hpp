// How a mesh is drawn: shading, lighting, depth test, culling, interpolation and textures
// (DrawState, what the caller gives draw()), and the two resolved modes the renderer's records
// carry from it (ColorPlanes, TexPersp).
#pragma once

#include <cstdint>

#include "lineraster/core/texture/texture.hpp"

namespace lr {

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

// The colour planes of an untextured triangle: none (one colour: flat shading, or an unlit mesh
// without vertex colours), perspective-correct, or screen-linear. The front end resolves a
// draw's from its Shading and Perspective; triangle setup may give a perspective-correct draw's
// triangle affine planes where the two agree (ActiveTriangle::colors).
enum class ColorPlanes : uint8_t { kNone, kPerspective, kAffine };

// How a textured span interpolates: exactly per pixel, exactly every span_len pixels (the
// kSpan8/16/32 modes of Perspective), or affine.
enum class TexPersp : uint8_t { kExact, kSpan, kAffine };

}  // namespace lr
