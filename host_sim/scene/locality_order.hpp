// A mesh reordered so that triangles near each other in space are near each other in the index
// list: what the renderer's vertex cache needs when a mesh is larger than the vertex store
// (docs/bands.md). Host only (uses the heap).
#pragma once

#include "lineraster/host_sim/formats/host_mesh.hpp"

namespace lr::host {

// Sorts the triangles by the Morton code (Z-order) of their centroids, 10 bits per axis over the
// mesh's bounding box, keeping the file's order among equal codes (a stable sort), and then
// numbers the vertices in the order the sorted triangles first use them (vertices no triangle
// uses follow, in their old order). Every vertex attribute and each triangle's material move
// with it; each triangle keeps its corners in the same cyclic order, so its winding is kept.
//
// The mesh is the same surface: only the order in which triangles are drawn changes, which can
// change a pixel only where two triangles reach it at exactly the same depth. A triangle with an
// index out of range keeps its indices and sorts last.
void sort_for_locality(HostMesh& mesh);

}  // namespace lr::host
