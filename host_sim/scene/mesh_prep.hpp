// Mesh preparation for the host simulator: bounds, the --fit transform, procedural meshes for tests
// and demos, and writing a mesh back as OBJ text. Host only (uses the heap).
//
// Procedural meshes follow the conventions of host_mesh.hpp and docs/conventions.md:
// counter-clockwise triangles seen from outside, unit per-vertex normals pointing outwards (the
// analytic normals of the surface), uvs in [0, 1] with v = 1 at the top of the image, and tangents
// from compute_tangents (tangents.hpp) for normal mapping. Vertices are duplicated along
// texture seams (and at the poles of the sphere, one per slice); the duplicates have bit-identical
// positions, so the closed meshes are watertight when vertices are welded by position.
// Counts are clamped to a valid range: at least the minimum stated, at most 2048.
#pragma once

#include <string>

#include "lineraster/host_sim/formats/host_mesh.hpp"

namespace lr::host {

struct Bounds {
  Vec3d min, max;
};
// Axis-aligned bounds of the positions; {0,0,0}-{0,0,0} for a mesh without vertices.
Bounds bounds(const HostMesh& mesh);

// --fit: centre the mesh on its bounding-box centre and scale so its farthest vertex from that
// centre is at distance 1: p' = (p - center) * scale. A mesh without extent gets scale 1.
struct FitTransform {
  Vec3d center;
  double scale;
};
FitTransform fit_transform(const HostMesh& mesh);
// --fit-box: centre the mesh on its bounding-box centre and scale uniformly so that its largest
// half extent is 1, i.e. the box's longest side spans [-1, 1] and the mesh lies in [-1, 1]^3.
// A mesh without extent gets scale 1.
FitTransform fit_box_transform(const HostMesh& mesh);
// Applies p' = (p - center) * scale to every position (normals are unchanged: uniform scale).
void apply_fit(HostMesh& mesh, const FitTransform& fit);

// Sphere of radius 1 around the origin, poles on the y axis (north = +y, v = 1); u grows with the
// longitude, u = 0 at +z. stacks >= 2 (latitude bands), slices >= 3.
HostMesh make_uv_sphere(int stacks, int slices);
// Torus around the z axis: tube centre circle of radius `major` in the plane z = 0, tube radius
// `minor`. rings >= 3 (around z), sides >= 3 (around the tube). Returns an empty mesh unless
// 0 < minor and 0 < major (both finite).
HostMesh make_torus(double major, double minor, int rings, int sides);
// Cube [-1,1]^3: 24 vertices (4 per face, per-face normals), 12 triangles, uvs 0..1 on each face.
HostMesh make_cube();
// Plane z = 0 over [-1,1]^2 split into nx * ny cells (2 triangles each), normal +z,
// uv = ((x + 1) / 2, (y + 1) / 2). nx, ny >= 1.
HostMesh make_grid(int nx, int ny);
// (p, q) torus knot tube: the curve ((2 + cos(q t)) cos(p t), (2 + cos(q t)) sin(p t), -sin(q t)) /
// 3 (so it lies within radius 1 of the origin), swept by a circle of radius `tube` (same units).
// segments >= 3 along the curve, sides >= 3 around the tube. Empty mesh unless 0 < tube (finite)
// and p, q are in 1..16.
HostMesh make_torus_knot(int p, int q, double tube, int segments, int sides);

// Midpoint subdivision, `levels` times (0: unchanged): each triangle (a, b, c) becomes four,
// (a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca), with the orientation of the original and
// its material. A midpoint is made once per edge (an unordered pair of vertex indices) and shared
// by the two triangles of that edge, so T triangles with E distinct edges over V vertices become
// 4T triangles over V + E vertices, and a closed mesh stays closed (midpoints of seam
// duplicates are computed from bit-identical positions in the same order: bit-identical too).
// At a midpoint: position, uv and colour are the averages of the edge's ends, the normal is
// their sum normalised (the first end's normal if the sum vanishes). Tangents, when the mesh has
// them, are recomputed (compute_tangents). The fit transform (bounds) does not change: midpoints
// lie within the bounding box.
HostMesh subdivide(const HostMesh& mesh, int levels);

// Sets colors[i] = 0.5 + 0.5 * normal[i] (a visible, smooth vertex colour for demos and tests).
void set_colors_from_normals(HostMesh& mesh);

// Writes the mesh back as OBJ text: a comment line, `v x y z [r g b]`, `vt` (if uvs), `vn`, and
// `f v/vt/vn` (or `f v//vn`), all numbers in their shortest exact (round-trip) form. Materials are
// not written (no MTL).
std::string to_obj_text(const HostMesh& mesh);

}  // namespace lr::host
