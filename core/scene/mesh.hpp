// The geometry the caller hands to the renderer: an indexed triangle mesh (in flash or RAM).
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "lineraster/core/math/vec.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/texture/texture.hpp"

namespace lr {

// An indexed triangle mesh. Positions in model units, fixed point of position_frac fraction bits
// (Q16.16 by default; up to Q1.30 for meshes within [-2, 2): finer snapping,
// docs/numerics.md#fine-transforms); normals unit Q1.14 (needed for Gouraud and Phong lighting;
// flat lighting uses face normals); colours optional (unlit shading); tangents (one per position)
// only for normal mapping. Triangles are counter-clockwise when front-facing; indices <
// positions.size().
struct Mesh {
  std::span<const Vec3> positions;
  std::span<const Normal16> normals;  // empty, or one per position
  std::span<const Rgb8> colors;       // empty, or one per position
  std::span<const TexCoord> uvs;      // empty, or one per position (textured draws)
  std::span<const std::array<uint16_t, 3>> triangles;
  std::span<const Tangent16> tangents{};  // empty, or one per position (normal-mapped draws)
  // Optional: the largest |coordinate| of the positions (Q16.16 raw; mesh_bound() gives it), or
  // 0: the renderer finds a bound itself, a pass over the positions per draw. lineraster-asset
  // writes it. A bound below a coordinate draws the mesh wrongly (never outside the coordinate
  // budget); one above it costs precision, not correctness.
  uint32_t bound = 0;
  // The fraction bits of the positions (and of bound): 0 (the default, so that a default Mesh
  // is zero bytes and a static store holding one stays in .bss) or 16 for Q16.16, else up to
  // kMaxPositionFrac: a coordinate is raw / 2^position_fraction_bits() model units (so
  // |coordinate| < 2^(31 - bits)). lineraster-asset --fine-positions writes the finest the
  // mesh's bound allows. A draw refuses others (kInvalidArgument). The vertex stage folds it
  // into the draw's per-draw factors (no work per vertex); the lighting reads the positions
  // rounded to Q16.16.
  uint8_t position_frac = 0;
  constexpr int position_fraction_bits() const { return position_frac == 0 ? 16 : position_frac; }
  constexpr bool valid_position_frac() const {
    return position_frac == 0 ||
           (position_frac >= kMinPositionFrac && position_frac <= kMaxPositionFrac);
  }
  static constexpr int kMinPositionFrac = 16, kMaxPositionFrac = 30;
};

// Mesh::bound of these positions (raw: in units of 2^-position_frac).
constexpr uint32_t mesh_bound(std::span<const Vec3> positions) {
  uint32_t b = 0;
  for (const Vec3& p : positions)
    for (const int32_t c : {p.x.raw, p.y.raw, p.z.raw}) {
      const uint32_t m = c < 0 ? 0u - static_cast<uint32_t>(c) : static_cast<uint32_t>(c);
      if (m > b) b = m;
    }
  return b;
}

}  // namespace lr
