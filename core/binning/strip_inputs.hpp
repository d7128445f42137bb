// Strip input signatures: a 32-bit hash per strip of everything that decides its pixels, so that
// a renderer can leave out a strip whose inputs are those of the previous frame (the display
// still holds its pixels) without rendering it at all.
//
// A strip's signature starts from the frame's (viewport, background, camera, lights) and takes
// in, in submission order, every binned triangle whose rows touch the strip: its three screen
// vertices (position, depth, w, texture coordinates, colours), Phong surface data, flat colours
// and its draw record's signature (routine state, sampler, texture descriptors, material of
// per-pixel lighting). So a triangle that moves, appears, disappears or changes colour or state
// changes the signature of every strip it touched in either frame. Memory: two uint32 per strip
// (this frame's and the last rendered one's), O(height / K).
//
// What it cannot see: texel or lighting-table memory rewritten in place between frames (call
// Renderer::invalidate_strips() then), and an active list too small for the frame (a frame that
// drops triangles for lack of active slots renders every strip of the next frame).
//
// Mixing: mix_word (FNV-1a, then h ^= h >> 13) per 32-bit word. Both steps are bijections of
// h for a given v, and the first of v for a given h: inputs that differ in one word always give
// different signatures; any larger difference goes unnoticed with a probability of about 2^-32
// per strip (the same order as the display path's pixel signatures, hal/strip_signature.hpp).
#pragma once

#include <cstdint>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/hash.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/math/vec.hpp"
#include "lineraster/core/output/color.hpp"

namespace lr {

struct ScreenVertex;
struct SurfaceVertex;
struct TexVertex;
struct Texture;
struct Material;
struct LightSet;
struct Camera;
struct DrawRecord;

// An order-dependent 32-bit hash of a sequence of words (see above). Same value on every CPU.
class InputHash {
 public:
  constexpr explicit InputHash(uint32_t seed = kFnv1a32Offset) : h_(seed) {}
  constexpr void add(uint32_t v) { h_ = mix_word(h_, v); }
  constexpr void add(int32_t v) { add(static_cast<uint32_t>(v)); }
  constexpr void add(bool v) { add(uint32_t{v}); }
  constexpr void add(Fixed f) { add(f.raw); }
  constexpr void add(Color15 c) {
    add(uint32_t{c.r} | uint32_t{c.g} << 16);
    add(uint32_t{c.b});
  }
  constexpr void add(Rgb8 c) { add(uint32_t{c.r} | uint32_t{c.g} << 8 | uint32_t{c.b} << 16); }
  constexpr void add(const Vec3& v) {
    add(v.x);
    add(v.y);
    add(v.z);
  }
  constexpr void add(const Mat4& m) {
    for (const auto& row : m.m)
      for (Fixed f : row) add(f);
  }
  // An address: which object, not its contents (textures are identified by their descriptor).
  void add(const void* p);
  void add(const ScreenVertex& v);
  void add(const SurfaceVertex& s);
  void add(const TexVertex& t);
  void add(const Texture& t);
  void add(const Material& m);
  void add(const LightSet& s);
  void add(const Camera& c);
  void add(const DrawRecord& d);
  constexpr uint32_t value() const { return h_; }

 private:
  uint32_t h_;
};

}  // namespace lr
