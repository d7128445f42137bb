// Host-side mesh in double precision: what the OBJ loader produces and what both the fixed-point
// core (after conversion) and the double reference renderer consume. Host only: uses the heap.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace lr::host {

using Vec2d = std::array<double, 2>;
using Vec3d = std::array<double, 3>;
using Vec4d = std::array<double, 4>;

// A material as read from an MTL file. Colours are linear [0, 1]; shininess is GL's [0, 128].
struct HostMaterial {
  std::string name;
  Vec3d ambient{0.2, 0.2, 0.2};   // Ka
  Vec3d diffuse{0.8, 0.8, 0.8};   // Kd
  Vec3d specular{0.0, 0.0, 0.0};  // Ks
  Vec3d emission{0.0, 0.0, 0.0};  // Ke
  double shininess = 0.0;         // Ns, clamped to GL's range [0, 128]
  double alpha = 1.0;             // d (kept, not used by the core yet)
  std::string map_kd;             // texture path resolved relative to the MTL file; "" = none
};

// An indexed triangle mesh with one record per unique (position, uv, normal) corner of the OBJ.
// Every vertex has a position and a unit normal (smooth normals are made where the OBJ has none).
// Triangles are counter-clockwise when front-facing (OBJ convention = GL convention).
struct HostMesh {
  std::vector<Vec3d> positions;  // model units
  std::vector<Vec3d> normals;    // unit length, one per vertex
  std::vector<Vec3d> colors;  // per vertex linear [0, 1]; empty when the OBJ has no `v x y z r g b`
  std::vector<Vec2d> uvs;     // per vertex; empty when the OBJ has no `vt` in use
  // Per vertex (x, y, z, w): unit tangent along increasing u, orthogonal to the normal, and the
  // handedness w = +-1 (bitangent = w * cross(normal, tangent)); empty until computed from uvs.
  std::vector<Vec4d> tangents;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<int32_t> triangle_material;  // per triangle: index into materials, or -1
  std::vector<HostMaterial> materials;
  std::vector<std::string> material_libraries;  // the MTL files read, as their paths were opened
  std::vector<std::string> warnings;  // "FILE:LINE: what was done" for each input accepted as is
  // For messages: the OBJ's name as given, and per vertex the line of its `v` (0: made here, a
  // subdivision's midpoint; empty: not from a file).
  std::string source;
  std::vector<uint32_t> lines;

  bool has_colors() const { return !colors.empty(); }
  bool has_uvs() const { return !uvs.empty(); }
};

}  // namespace lr::host
