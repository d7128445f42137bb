// Triangulating an OBJ face: the triangles of a polygon as the file means it.
//
// A convex face is fanned from its first corner (the triangles every loader makes). Any other
// face is ear-clipped in its plane (the plane of Newell's normal, so a slightly non-planar face
// is triangulated as seen along its mean normal): no triangle leaves the polygon and together
// they cover it once, concave corners and keyholes (an outer loop joined to an inner one by a
// doubled edge) included. A face without area (all corners on a line) is fanned, and so is a
// concave face of more than kMaxEarClippedCorners corners (ear clipping takes time quadratic in
// the corners: such a face is reported, not clipped).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "lineraster/host_sim/formats/host_mesh.hpp"

namespace lr::host {

inline constexpr size_t kMaxEarClippedCorners = 4096;

// Appends the triangles of the polygon `corners` (in order, at least 3) to `out`, as indices into
// `corners`, wound as the polygon is. False when a concave face was fanned all the same (more
// than kMaxEarClippedCorners corners): its triangles may leave it.
bool triangulate_polygon(std::span<const Vec3d> corners, std::vector<std::array<uint32_t, 3>>& out);

}  // namespace lr::host
