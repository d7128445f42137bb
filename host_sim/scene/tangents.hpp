// Per-vertex tangent frames for normal mapping, computed from a mesh's positions and texture
// coordinates. Host only (uses the heap).
#pragma once

#include "lineraster/host_sim/formats/host_mesh.hpp"

namespace lr::host {

// Fills mesh.tangents with one (x, y, z, w) per vertex, as host_mesh.hpp defines them: (x, y, z)
// the unit tangent along increasing u, orthogonal to the vertex normal; w = +1 or -1 so that
// w * cross(normal, tangent) points along increasing v (w = -1 where the uvs are mirrored).
//
// Lengyel's method: each triangle's direction of increasing u (and of increasing v) in its plane
// is solved from its edges and uv differences, normalised, and added to each of its corners
// weighted by the corner's angle (so that the result does not depend on how a surface is split
// into triangles); each vertex's sum is then made orthogonal to the vertex normal (Gram-Schmidt)
// and normalised, and w is the sign of the summed v direction along cross(normal, tangent).
// Triangles whose uvs are degenerate (zero uv area) or whose positions are (zero area) add
// nothing. A vertex left without a usable tangent (no contributing triangle, or a sum parallel
// to its normal) gets a unit vector orthogonal to its normal and w = +1.
//
// Without uvs (mesh.uvs empty) mesh.tangents is cleared (empty). Triangles with an index out of
// range are skipped. A vertex without a normal entry uses (0, 0, 1).
void compute_tangents(HostMesh& mesh);

}  // namespace lr::host
