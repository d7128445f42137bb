// Mesh preparation: procedural meshes are closed, consistently oriented and face outwards; bounds,
// the --fit transform and the OBJ writer do what they say.
#include "lineraster/host_sim/scene/mesh_prep.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/scene/vec3d.hpp"

namespace lr::host {
namespace {

Vec3d face_normal(const HostMesh& m, const std::array<uint32_t, 3>& t) {
  return cross(sub(m.positions[t[1]], m.positions[t[0]]),
               sub(m.positions[t[2]], m.positions[t[0]]));
}

// Basic consistency every mesh must have.
void expect_well_formed(const HostMesh& m) {
  ASSERT_EQ(m.normals.size(), m.positions.size());
  ASSERT_EQ(m.triangle_material.size(), m.triangles.size());
  if (m.has_uvs()) {
    ASSERT_EQ(m.uvs.size(), m.positions.size());
  }
  if (m.has_colors()) {
    ASSERT_EQ(m.colors.size(), m.positions.size());
  }
  for (const auto& t : m.triangles) {
    for (uint32_t v : t) ASSERT_LT(v, m.positions.size());
  }
  for (const Vec3d& n : m.normals) ASSERT_NEAR(length(n), 1.0, 1e-12);
  for (const Vec2d& uv : m.uvs) {
    ASSERT_GE(uv[0], 0.0);
    ASSERT_LE(uv[0], 1.0);
    ASSERT_GE(uv[1], 0.0);
    ASSERT_LE(uv[1], 1.0);
  }
}

// Watertight and consistently oriented: after welding vertices with identical positions, every
// directed edge (a, b) occurs exactly once and its reverse (b, a) exactly once; no triangle is
// degenerate.
void expect_closed_and_consistent(const HostMesh& m) {
  std::map<Vec3d, uint32_t> weld;
  std::vector<uint32_t> id(m.positions.size());
  for (size_t i = 0; i < m.positions.size(); ++i) {
    id[i] = weld.emplace(m.positions[i], static_cast<uint32_t>(weld.size())).first->second;
  }
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  for (const auto& t : m.triangles) {
    const uint32_t a = id[t[0]], b = id[t[1]], c = id[t[2]];
    ASSERT_TRUE(a != b && b != c && a != c) << "degenerate triangle after welding";
    ++edges[{a, b}];
    ++edges[{b, c}];
    ++edges[{c, a}];
  }
  for (const auto& [e, count] : edges) {
    ASSERT_EQ(count, 1) << "edge " << e.first << "-" << e.second << " used twice the same way";
    const auto rev = edges.find({e.second, e.first});
    ASSERT_NE(rev, edges.end()) << "edge " << e.first << "-" << e.second << " is a border";
    ASSERT_EQ(rev->second, 1);
  }
}

// Each triangle's geometric normal agrees with its vertices' normals (CCW = front = outside).
void expect_faces_agree_with_normals(const HostMesh& m) {
  for (const auto& t : m.triangles) {
    const Vec3d fn = face_normal(m, t);
    for (uint32_t v : t) ASSERT_GT(dot(fn, m.normals[v]), 0.0);
  }
}

TEST(MeshPrep, UvSphereIsClosedOrientedAndOutward) {
  const HostMesh m = make_uv_sphere(12, 24);
  expect_well_formed(m);
  EXPECT_EQ(m.triangles.size(), 2u * 24u * 11u);
  EXPECT_TRUE(m.has_uvs());
  EXPECT_FALSE(m.has_colors());
  expect_closed_and_consistent(m);
  expect_faces_agree_with_normals(m);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_NEAR(length(m.positions[i]), 1.0, 1e-15);
    EXPECT_GT(dot(m.normals[i], m.positions[i]), 0.0);  // outward from the centre
  }
  for (const auto& t : m.triangles) {
    const Vec3d centroid{(m.positions[t[0]][0] + m.positions[t[1]][0] + m.positions[t[2]][0]) / 3,
                         (m.positions[t[0]][1] + m.positions[t[1]][1] + m.positions[t[2]][1]) / 3,
                         (m.positions[t[0]][2] + m.positions[t[1]][2] + m.positions[t[2]][2]) / 3};
    EXPECT_GT(dot(face_normal(m, t), centroid), 0.0);
  }
  // North pole on +y at v = 1.
  EXPECT_EQ(m.positions[0], (Vec3d{0, 1, 0}));
  EXPECT_EQ(m.uvs[0][1], 1.0);
}

TEST(MeshPrep, SmallestSphereIsStillClosed) {
  const HostMesh m = make_uv_sphere(0, -5);  // clamped to 2 stacks, 3 slices
  expect_well_formed(m);
  EXPECT_EQ(m.triangles.size(), 6u);
  expect_closed_and_consistent(m);
  expect_faces_agree_with_normals(m);
}

TEST(MeshPrep, TorusIsClosedOrientedAndOutward) {
  const double major = 1.0, minor = 0.3;
  const HostMesh m = make_torus(major, minor, 32, 12);
  expect_well_formed(m);
  EXPECT_EQ(m.triangles.size(), 2u * 32u * 12u);
  expect_closed_and_consistent(m);
  expect_faces_agree_with_normals(m);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3d& p = m.positions[i];
    const double r = std::hypot(p[0], p[1]);
    const Vec3d tube_centre{p[0] / r * major, p[1] / r * major, 0.0};
    EXPECT_NEAR(length(sub(p, tube_centre)), minor, 1e-12);
    EXPECT_GT(dot(m.normals[i], sub(p, tube_centre)), 0.0);
  }
  const Bounds b = bounds(m);
  EXPECT_NEAR(b.max[0], 1.3, 1e-12);
  EXPECT_NEAR(b.max[2], 0.3, 1e-12);
  EXPECT_NEAR(b.min[2], -0.3, 1e-12);
}

TEST(MeshPrep, TorusWithInvalidRadiiIsEmpty) {
  EXPECT_TRUE(make_torus(1.0, 0.0, 8, 8).triangles.empty());
  EXPECT_TRUE(make_torus(-1.0, 0.2, 8, 8).triangles.empty());
  EXPECT_TRUE(make_torus(std::nan(""), 0.2, 8, 8).positions.empty());
}

TEST(MeshPrep, TorusKnotIsClosedOrientedAndOutward) {
  const HostMesh m = make_torus_knot(2, 3, 0.18, 200, 10);
  expect_well_formed(m);
  EXPECT_EQ(m.triangles.size(), 4000u);
  expect_closed_and_consistent(m);
  expect_faces_agree_with_normals(m);
  for (const Vec3d& p : m.positions) EXPECT_LE(length(p), 1.0 + 0.18 + 1e-12);
}

TEST(MeshPrep, CubeHas24VerticesWithPerFaceNormalsAndUvs) {
  const HostMesh m = make_cube();
  expect_well_formed(m);
  EXPECT_EQ(m.positions.size(), 24u);
  EXPECT_EQ(m.triangles.size(), 12u);
  expect_closed_and_consistent(m);
  for (const auto& t : m.triangles) {
    const Vec3d fn = face_normal(m, t);
    const Vec3d unit{fn[0] / length(fn), fn[1] / length(fn), fn[2] / length(fn)};
    for (uint32_t v : t) EXPECT_EQ(m.normals[v], unit);  // flat, exactly axis-aligned
    EXPECT_EQ(length(fn), 4.0);                          // each triangle is half of a 2 x 2 face
  }
  for (size_t i = 0; i < 24; ++i) {
    for (double c : m.positions[i]) EXPECT_TRUE(c == 1.0 || c == -1.0);
    for (double c : m.uvs[i]) EXPECT_TRUE(c == 0.0 || c == 1.0);
    EXPECT_EQ(dot(m.normals[i], m.positions[i]), 1.0);  // outward
  }
  const Bounds b = bounds(m);
  EXPECT_EQ(b.min, (Vec3d{-1, -1, -1}));
  EXPECT_EQ(b.max, (Vec3d{1, 1, 1}));
}

TEST(MeshPrep, GridIsAFlatCcwPlane) {
  const HostMesh m = make_grid(4, 3);
  expect_well_formed(m);
  EXPECT_EQ(m.positions.size(), 5u * 4u);
  EXPECT_EQ(m.triangles.size(), 2u * 4u * 3u);
  double area = 0.0;
  for (const auto& t : m.triangles) {
    const Vec3d fn = face_normal(m, t);
    EXPECT_GT(fn[2], 0.0);
    area += fn[2] / 2.0;
  }
  EXPECT_NEAR(area, 4.0, 1e-12);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_EQ(m.positions[i][2], 0.0);
    EXPECT_EQ(m.normals[i], (Vec3d{0, 0, 1}));
    EXPECT_EQ(m.uvs[i][0], (m.positions[i][0] + 1.0) / 2.0);
    EXPECT_EQ(m.uvs[i][1], (m.positions[i][1] + 1.0) / 2.0);
  }
}

TEST(MeshPrep, BoundsAndFit) {
  HostMesh m = make_cube();
  for (Vec3d& p : m.positions) p = {p[0] * 3 + 5, p[1] * 3 - 2, p[2] * 3 + 1};
  const Bounds b = bounds(m);
  EXPECT_EQ(b.min, (Vec3d{2, -5, -2}));
  EXPECT_EQ(b.max, (Vec3d{8, 1, 4}));
  const FitTransform fit = fit_transform(m);
  EXPECT_EQ(fit.center, (Vec3d{5, -2, 1}));
  EXPECT_NEAR(fit.scale, 1.0 / (3.0 * std::sqrt(3.0)), 1e-15);
  apply_fit(m, fit);
  double far = 0.0;
  for (const Vec3d& p : m.positions) far = std::max(far, length(p));
  EXPECT_NEAR(far, 1.0, 1e-15);
}

TEST(MeshPrep, FitUsesTheBoxCentreNotTheCentroid) {
  HostMesh m;
  m.positions = {{0, 0, 0}, {0.1, 0, 0}, {0.2, 0, 0}, {4, 0, 0}};
  const FitTransform fit = fit_transform(m);
  EXPECT_EQ(fit.center, (Vec3d{2, 0, 0}));
  EXPECT_EQ(fit.scale, 0.5);
}

TEST(MeshPrep, FitBoxScalesByTheLargestHalfExtent) {
  // Box [2, 8] x [-5, -3] x [0, 1]: centre (5, -4, 0.5), half extents 3, 1, 0.5.
  HostMesh m;
  m.positions = {{2, -5, 0}, {8, -3, 1}, {4, -4, 0.5}};
  const FitTransform fit = fit_box_transform(m);
  EXPECT_EQ(fit.center, (Vec3d{5, -4, 0.5}));
  EXPECT_EQ(fit.scale, 1.0 / 3.0);
  apply_fit(m, fit);
  EXPECT_EQ(bounds(m).min, (Vec3d{-1, -1.0 / 3.0, -0.5 / 3.0}));
  EXPECT_EQ(bounds(m).max, (Vec3d{1, 1.0 / 3.0, 0.5 / 3.0}));
  // Not --fit's farthest vertex: the cube's corners end at (+-1, +-1, +-1).
  HostMesh c = make_cube();
  EXPECT_EQ(fit_box_transform(c).scale, 1.0);
  EXPECT_LT(fit_transform(c).scale, 0.6);
  HostMesh point;
  point.positions = {{3, 4, 5}};
  EXPECT_EQ(fit_box_transform(point).scale, 1.0);
  HostMesh huge;
  huge.positions = {{-1e308, 0, 0}, {1e308, 1, 1}};
  EXPECT_EQ(fit_box_transform(huge).scale, 1e-308);
}

TEST(MeshPrep, FitOfDegenerateAndExtremeMeshes) {
  HostMesh empty;
  EXPECT_EQ(fit_transform(empty).scale, 1.0);
  EXPECT_EQ(bounds(empty).min, (Vec3d{0, 0, 0}));
  HostMesh point;
  point.positions = {{3, 4, 5}, {3, 4, 5}};
  const FitTransform p = fit_transform(point);
  EXPECT_EQ(p.center, (Vec3d{3, 4, 5}));
  EXPECT_EQ(p.scale, 1.0);
  HostMesh huge;
  huge.positions = {{-1e308, 0, 0}, {1e308, 1e308, -1e308}};
  const FitTransform h = fit_transform(huge);
  EXPECT_TRUE(std::isfinite(h.center[0]) && std::isfinite(h.scale));
  EXPECT_GT(h.scale, 0.0);
  EXPECT_NEAR(h.scale * 1e308 * std::sqrt(1.0 + 0.25 + 0.25), 1.0, 1e-12);
}

// Distinct edges (unordered index pairs) of a mesh.
size_t edge_count(const HostMesh& m) {
  std::set<std::pair<uint32_t, uint32_t>> edges;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = t[static_cast<size_t>(k)], b = t[static_cast<size_t>((k + 1) % 3)];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return edges.size();
}

TEST(MeshPrep, SubdivideSplitsEachTriangleInFourAndSharesMidpoints) {
  // The demo knot's shape (with uv seams): T -> 4T, V -> V + E at each level, closed throughout.
  HostMesh m = make_torus_knot(2, 3, 0.18, 40, 6);
  for (int level = 1; level <= 2; ++level) {
    const HostMesh s = subdivide(m, 1);
    EXPECT_EQ(s.triangles.size(), 4 * m.triangles.size()) << "level " << level;
    EXPECT_EQ(s.positions.size(), m.positions.size() + edge_count(m)) << "level " << level;
    EXPECT_EQ(s.tangents.size(), s.positions.size());
    expect_well_formed(s);
    expect_closed_and_consistent(s);
    expect_faces_agree_with_normals(s);
    m = s;
  }
  EXPECT_EQ(subdivide(make_torus_knot(2, 3, 0.18, 40, 6), 2).triangles.size(), m.triangles.size());
  EXPECT_EQ(subdivide(m, 0).triangles, m.triangles);
}

TEST(MeshPrep, SubdivideInterpolatesAtMidpoints) {
  HostMesh m;
  m.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  m.normals = {{0, 0, 1}, {1, 0, 0}, {0, 0, 1}};
  m.uvs = {{0, 0}, {1, 0.5}, {0, 1}};
  m.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 1, 2}};
  m.triangle_material = {3};
  const HostMesh s = subdivide(m, 1);
  ASSERT_EQ(s.positions.size(), 6u);
  ASSERT_EQ(s.triangles.size(), 4u);
  // The corner triangles keep the original corners, in the original order, and the material.
  EXPECT_EQ(s.triangles[0][0], 0u);
  EXPECT_EQ(s.triangles[1][1], 1u);
  EXPECT_EQ(s.triangles[2][2], 2u);
  for (int32_t mat : s.triangle_material) EXPECT_EQ(mat, 3);
  // Midpoint of edge 0-1: vertex 3 (made first).
  const uint32_t ab = s.triangles[0][1];
  EXPECT_EQ(s.positions[ab], (Vec3d{1, 0, 0}));
  EXPECT_NEAR(s.normals[ab][0], std::sqrt(0.5), 1e-15);
  EXPECT_EQ(s.normals[ab][1], 0.0);
  EXPECT_NEAR(s.normals[ab][2], std::sqrt(0.5), 1e-15);
  EXPECT_EQ(s.uvs[ab], (Vec2d{0.5, 0.25}));
  EXPECT_EQ(s.colors[ab], (Vec3d{0.5, 0.5, 0}));
  // Same orientation: every child faces +z like the parent.
  for (const auto& t : s.triangles) EXPECT_GT(face_normal(s, t)[2], 0.0);
  // The fit does not change (midpoints lie inside the bounds).
  const FitTransform f0 = fit_transform(m), f1 = fit_transform(s);
  EXPECT_EQ(f0.center, f1.center);
  EXPECT_EQ(f0.scale, f1.scale);
}

TEST(MeshPrep, ObjTextRoundTripsExactly) {
  HostMesh m = make_torus(1.0, 0.25, 16, 8);
  set_colors_from_normals(m);
  const std::string text = to_obj_text(m);
  EXPECT_EQ(text.rfind("# ", 0), 0u);
  HostMesh back;
  std::string error;
  ASSERT_TRUE(parse_obj(text, "round.obj", "", back, error)) << error;
  ASSERT_EQ(back.triangles.size(), m.triangles.size());
  ASSERT_EQ(back.positions.size(), m.positions.size());
  ASSERT_TRUE(back.has_colors());
  ASSERT_TRUE(back.has_uvs());
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[t][k], b = back.triangles[t][k];
      EXPECT_EQ(back.positions[b], m.positions[a]);  // shortest round-trip numbers: exact
      EXPECT_EQ(back.uvs[b], m.uvs[a]);
      EXPECT_EQ(back.colors[b], m.colors[a]);
      for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(back.normals[b][c], m.normals[a][c], 1e-15);
    }
  }
}

TEST(MeshPrep, ObjTextWithoutUvsUsesDoubleSlash) {
  HostMesh m = make_grid(1, 1);
  m.uvs.clear();
  const std::string text = to_obj_text(m);
  EXPECT_NE(text.find("\nf 1//1 2//2 4//4\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("vt "), std::string::npos);
}

}  // namespace
}  // namespace lr::host
