// What per-pixel (Phong) lighting needs of a vertex besides its ScreenVertex: the world-space
// normal, position and tangent. Kept in a store of its own (FrameStorage::surfaces, indexed like
// the vertex store) so that draws without per-pixel lighting pay no RAM for it. 32 bytes.
#pragma once

#include <cstdint>

#include "lineraster/core/math/vec.hpp"

namespace lr {

struct SurfaceVertex {
  Unit30 normal{};  // world space, unit (Q1.30); negated for back faces of two-sided draws
  Vec3 position{};  // world space, Q16.16 (point lights, local viewer)
  int16_t tangent[3] = {0, 0, 0};  // world space, unit Q1.14 (normal maps)
  int16_t handedness = 0;          // +-16384: bitangent = handedness * cross(normal, tangent)
};
static_assert(sizeof(SurfaceVertex) == 32);

}  // namespace lr
