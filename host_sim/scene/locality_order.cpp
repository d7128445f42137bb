#include "lineraster/host_sim/scene/locality_order.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

namespace lr::host {
namespace {

constexpr uint32_t kBitsPerAxis = 10;
constexpr uint32_t kCells = 1u << kBitsPerAxis;
constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();

// The cell of v along one axis of [lo, hi]: 0 .. kCells - 1 (an empty extent maps to 0).
uint32_t cell(double v, double lo, double hi) {
  if (!(hi > lo)) return 0;
  const double t = (v - lo) / (hi - lo) * kCells;
  if (!(t > 0)) return 0;
  return t >= kCells - 1 ? kCells - 1 : static_cast<uint32_t>(t);
}

// The three cells' bits interleaved, x lowest.
uint32_t morton(const std::array<uint32_t, 3>& c) {
  uint32_t code = 0;
  for (uint32_t b = 0; b < kBitsPerAxis; ++b)
    for (uint32_t axis = 0; axis < 3; ++axis) code |= ((c[axis] >> b) & 1u) << (3 * b + axis);
  return code;
}

template <class T>
void permute(std::vector<T>& values, const std::vector<uint32_t>& new_to_old) {
  if (values.size() != new_to_old.size()) return;  // an attribute the mesh does not have
  std::vector<T> out(values.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = values[new_to_old[i]];
  values = std::move(out);
}

}  // namespace

void sort_for_locality(HostMesh& mesh) {
  const size_t nv = mesh.positions.size();
  if (nv == 0 || mesh.triangles.empty()) return;
  Vec3d lo = mesh.positions[0], hi = mesh.positions[0];
  for (const Vec3d& p : mesh.positions) {
    for (size_t axis = 0; axis < 3; ++axis) {
      lo[axis] = std::min(lo[axis], p[axis]);
      hi[axis] = std::max(hi[axis], p[axis]);
    }
  }
  const size_t nt = mesh.triangles.size();
  std::vector<uint64_t> key(nt);
  for (size_t t = 0; t < nt; ++t) {
    const auto& tri = mesh.triangles[t];
    if (tri[0] >= nv || tri[1] >= nv || tri[2] >= nv) {
      key[t] = uint64_t{1} << 32;  // after every valid code
      continue;
    }
    std::array<uint32_t, 3> cells{};
    for (size_t axis = 0; axis < 3; ++axis) {
      const double centroid = (mesh.positions[tri[0]][axis] + mesh.positions[tri[1]][axis] +
                               mesh.positions[tri[2]][axis]) /
                              3;
      cells[axis] = cell(centroid, lo[axis], hi[axis]);
    }
    key[t] = morton(cells);
  }
  std::vector<uint32_t> order(nt);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t x, uint32_t y) { return key[x] < key[y]; });

  std::vector<std::array<uint32_t, 3>> triangles(nt);
  for (size_t t = 0; t < nt; ++t) triangles[t] = mesh.triangles[order[t]];
  if (mesh.triangle_material.size() == nt) {
    std::vector<int32_t> material(nt);
    for (size_t t = 0; t < nt; ++t) material[t] = mesh.triangle_material[order[t]];
    mesh.triangle_material = std::move(material);
  }

  // Vertices by first use.
  std::vector<uint32_t> old_to_new(nv, kUnused), new_to_old;
  new_to_old.reserve(nv);
  for (const auto& tri : triangles) {
    for (uint32_t v : tri) {
      if (v < nv && old_to_new[v] == kUnused) {
        old_to_new[v] = static_cast<uint32_t>(new_to_old.size());
        new_to_old.push_back(v);
      }
    }
  }
  for (uint32_t v = 0; v < nv; ++v) {
    if (old_to_new[v] == kUnused) {
      old_to_new[v] = static_cast<uint32_t>(new_to_old.size());
      new_to_old.push_back(v);
    }
  }
  for (auto& tri : triangles)
    for (uint32_t& v : tri)
      if (v < nv) v = old_to_new[v];
  mesh.triangles = std::move(triangles);
  permute(mesh.positions, new_to_old);
  permute(mesh.normals, new_to_old);
  permute(mesh.colors, new_to_old);
  permute(mesh.uvs, new_to_old);
  permute(mesh.tangents, new_to_old);
  permute(mesh.lines, new_to_old);
}

}  // namespace lr::host
