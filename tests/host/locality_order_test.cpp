// The locality order (lineraster-asset --locality): the same triangles with the same windings and
// attributes, in Z-order of their centroids, vertices numbered by first use.
#include "lineraster/host_sim/scene/locality_order.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "lineraster/host_sim/scene/mesh_prep.hpp"

namespace lr::host {
namespace {

// A triangle as its corner positions, starting at its smallest corner (the same triangle with
// the same winding compares equal however its corners were numbered).
using Corners = std::array<Vec3d, 3>;
Corners corners(const HostMesh& m, const std::array<uint32_t, 3>& t) {
  Corners c{m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]};
  std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
  return c;
}

// The grid's triangles in a scattered order (a fixed permutation: every 7th, modulo the count),
// each vertex with its own normal (not unit length: only moved, never used).
HostMesh scattered_grid() {
  HostMesh g = make_grid(16, 16);
  for (size_t v = 0; v < g.normals.size(); ++v) g.normals[v] = {static_cast<double>(v), 0, 1};
  HostMesh m = g;
  const size_t n = g.triangles.size();
  for (size_t i = 0; i < n; ++i) {
    m.triangles[i] = g.triangles[(i * 7) % n];
    m.triangle_material[i] = static_cast<int32_t>((i * 7) % n % 3);
  }
  return m;
}

// Corner lookups whose vertex was last used more than `window` distinct vertices ago (what a
// vertex cache of that size misses, first uses apart).
size_t far_reuses(const HostMesh& m, size_t window) {
  std::vector<uint32_t> recent;
  size_t far = 0;
  for (const auto& t : m.triangles) {
    for (uint32_t v : t) {
      const auto it = std::find(recent.begin(), recent.end(), v);
      if (it != recent.end()) {
        far += static_cast<size_t>(recent.end() - it) > window;
        recent.erase(it);
      }
      recent.push_back(v);
    }
  }
  return far;
}

TEST(LocalityOrder, KeepsEveryTriangleWindingAndAttribute) {
  const HostMesh before = scattered_grid();
  HostMesh after = before;
  sort_for_locality(after);
  ASSERT_EQ(after.positions.size(), before.positions.size());
  ASSERT_EQ(after.normals.size(), before.normals.size());
  ASSERT_EQ(after.uvs.size(), before.uvs.size());
  ASSERT_EQ(after.triangles.size(), before.triangles.size());
  ASSERT_EQ(after.triangle_material.size(), before.triangle_material.size());
  // Each old triangle, with its material, appears once.
  std::vector<std::pair<Corners, int32_t>> a, b;
  for (size_t t = 0; t < before.triangles.size(); ++t) {
    b.emplace_back(corners(before, before.triangles[t]), before.triangle_material[t]);
    a.emplace_back(corners(after, after.triangles[t]), after.triangle_material[t]);
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  // A vertex keeps its normal and uv (the grid's positions are distinct: position -> vertex).
  for (size_t v = 0; v < after.positions.size(); ++v) {
    const auto it = std::find(before.positions.begin(), before.positions.end(), after.positions[v]);
    ASSERT_NE(it, before.positions.end());
    const size_t old = static_cast<size_t>(it - before.positions.begin());
    EXPECT_EQ(after.normals[v], before.normals[old]);
    EXPECT_EQ(after.uvs[v], before.uvs[old]);
  }
}

TEST(LocalityOrder, NumbersVerticesByFirstUseAndNeighboursComeTogether) {
  HostMesh m = scattered_grid();
  const size_t far_before = far_reuses(m, 32);
  sort_for_locality(m);
  uint32_t next = 0;
  for (const auto& t : m.triangles) {
    for (uint32_t v : t) {
      ASSERT_LE(v, next);
      if (v == next) ++next;
    }
  }
  EXPECT_EQ(next, m.positions.size());  // the grid uses every vertex
  // Z-order: the scattered order reuses almost nothing within 32 vertices, the sorted one
  // almost everything.
  const size_t far_after = far_reuses(m, 32);
  EXPECT_GT(far_before, 1000u);
  EXPECT_LT(far_after, far_before / 10);
}

TEST(LocalityOrder, UnusedVerticesFollowAndBadTrianglesSortLast) {
  HostMesh m;
  m.positions = {{9, 9, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {5, 5, 0}};
  m.normals.assign(5, {0, 0, 1});
  m.triangles = {{1, 7, 2}, {3, 1, 2}};  // the first has an index out of range
  m.triangle_material = {0, 1};
  sort_for_locality(m);
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));  // {3, 1, 2} renumbered
  EXPECT_EQ(m.triangle_material[0], 1);
  // The bad triangle: its valid indices renumbered, the bad one kept.
  EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{1, 7, 2}));
  EXPECT_EQ(m.triangle_material[1], 0);
  // Used vertices first (old 3, 1, 2), then the unused ones in their old order (0, 4).
  const std::vector<Vec3d> want{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {9, 9, 0}, {5, 5, 0}};
  EXPECT_EQ(m.positions, want);
}

}  // namespace
}  // namespace lr::host
