// Tangents for normal mapping: along increasing u, orthogonal to the normal, handedness so that
// w * cross(normal, tangent) points along increasing v; degenerate input gets a valid frame.
#include "lineraster/host_sim/scene/tangents.hpp"
#include "lineraster/host_sim/scene/vec3d.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "lineraster/host_sim/scene/mesh_prep.hpp"

namespace lr::host {
namespace {

Vec3d xyz(const Vec4d& t) {
  return {t[0], t[1], t[2]};
}

// Every tangent: one per vertex, unit, orthogonal to the normal, w exactly +1 or -1.
void expect_valid_frames(const HostMesh& m) {
  ASSERT_EQ(m.tangents.size(), m.positions.size());
  for (size_t i = 0; i < m.tangents.size(); ++i) {
    const Vec4d& t = m.tangents[i];
    EXPECT_NEAR(length(xyz(t)), 1.0, 1e-12) << "vertex " << i;
    EXPECT_NEAR(dot(xyz(t), m.normals[i]), 0.0, 1e-12) << "vertex " << i;
    EXPECT_TRUE(t[3] == 1.0 || t[3] == -1.0) << "vertex " << i << ": w = " << t[3];
  }
}

void expect_tangent(const Vec4d& t, const Vec4d& want, double tol, size_t i) {
  for (size_t c = 0; c < 4; ++c)
    EXPECT_NEAR(t[c], want[c], tol) << "vertex " << i << " [" << c << "]";
}

TEST(Tangents, GridTangentIsPlusXRightHanded) {
  HostMesh m = make_grid(4, 3);
  m.tangents.clear();
  compute_tangents(m);
  ASSERT_EQ(m.tangents.size(), m.positions.size());
  for (size_t i = 0; i < m.tangents.size(); ++i)
    expect_tangent(m.tangents[i], {1, 0, 0, 1}, 1e-15, i);
}

TEST(Tangents, ProceduralMeshesComeWithTangents) {
  const HostMesh g = make_grid(2, 2);
  ASSERT_EQ(g.tangents.size(), g.positions.size());
  for (size_t i = 0; i < g.tangents.size(); ++i)
    expect_tangent(g.tangents[i], {1, 0, 0, 1}, 1e-15, i);
  expect_valid_frames(make_uv_sphere(8, 16));
  expect_valid_frames(make_torus(1.0, 0.3, 16, 8));
  expect_valid_frames(make_cube());
  expect_valid_frames(make_torus_knot(2, 3, 0.18, 100, 8));
}

TEST(Tangents, MirroredUGivesMinusXAndLeftHandedness) {
  HostMesh m = make_grid(3, 3);
  for (Vec2d& uv : m.uvs) uv[0] = 1.0 - uv[0];
  compute_tangents(m);
  ASSERT_EQ(m.tangents.size(), m.positions.size());
  for (size_t i = 0; i < m.tangents.size(); ++i) {
    expect_tangent(m.tangents[i], {-1, 0, 0, -1}, 1e-15, i);
    // The bitangent still points along increasing v (+y).
    const Vec3d b = cross(m.normals[i], xyz(m.tangents[i]));
    EXPECT_NEAR(m.tangents[i][3] * b[1], 1.0, 1e-15);
  }
}

TEST(Tangents, MirroredVKeepsTheTangentAndFlipsW) {
  HostMesh m = make_grid(3, 2);
  for (Vec2d& uv : m.uvs) uv[1] = 1.0 - uv[1];
  compute_tangents(m);
  ASSERT_EQ(m.tangents.size(), m.positions.size());
  for (size_t i = 0; i < m.tangents.size(); ++i)
    expect_tangent(m.tangents[i], {1, 0, 0, -1}, 1e-15, i);
}

TEST(Tangents, RotatedUvsRotateTheTangent) {
  // u grows with y, v grows with -x: tangent +y, bitangent -x = cross(+z, +y): right-handed.
  HostMesh m = make_grid(2, 2);
  for (size_t i = 0; i < m.uvs.size(); ++i)
    m.uvs[i] = {(m.positions[i][1] + 1) / 2, (1 - m.positions[i][0]) / 2};
  compute_tangents(m);
  ASSERT_EQ(m.tangents.size(), m.positions.size());
  for (size_t i = 0; i < m.tangents.size(); ++i)
    expect_tangent(m.tangents[i], {0, 1, 0, 1}, 1e-15, i);
}

// The angle between a unit vector and the unit vector `want`.
double angle_to(const Vec4d& t, const Vec3d& want) {
  return std::atan2(length(cross(xyz(t), want)), dot(xyz(t), want));
}

TEST(Tangents, SphereFollowsTheLongitude) {
  const int stacks = 16, slices = 32;
  const HostMesh m = make_uv_sphere(stacks, slices);
  expect_valid_frames(m);
  // Off the poles the analytic tangent is the direction of increasing longitude (u),
  // (cos phi, 0, -sin phi), and v grows northwards (+y) = cross(n, t): w = +1. Each triangle's
  // u direction is a horizontal chord of a ring, at phi +- half a slice: the vertex tangent is
  // within half a slice of the analytic one. At the poles (normal +-y) it is horizontal.
  const double half_slice = std::numbers::pi / slices;
  double worst = 0.0;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3d& p = m.positions[i];
    EXPECT_EQ(m.tangents[i][3], 1.0) << "vertex " << i;
    if (std::fabs(p[1]) == 1.0) {
      EXPECT_NEAR(m.tangents[i][1], 0.0, 1e-12) << "vertex " << i;
      continue;
    }
    const double phi = std::atan2(p[0], p[2]);
    worst = std::fmax(worst, angle_to(m.tangents[i], {std::cos(phi), 0.0, -std::sin(phi)}));
  }
  EXPECT_LE(worst, half_slice + 1e-12);
  EXPECT_GT(worst, 0.0);
}

TEST(Tangents, TorusFollowsTheRing) {
  // The analytic tangent (-sin a, cos a, 0) around the z axis; v around the tube = cross(n, t):
  // w = +1. Triangle u directions are chords of the ring circles, within half a ring step.
  for (int rings : {24, 96}) {
    const HostMesh m = make_torus(1.0, 0.3, rings, 12);
    expect_valid_frames(m);
    double worst = 0.0;
    for (size_t i = 0; i < m.positions.size(); ++i) {
      const double a = std::atan2(m.positions[i][1], m.positions[i][0]);
      worst = std::fmax(worst, angle_to(m.tangents[i], {-std::sin(a), std::cos(a), 0.0}));
      EXPECT_EQ(m.tangents[i][3], 1.0) << "vertex " << i;
    }
    EXPECT_LE(worst, std::numbers::pi / rings + 1e-12) << rings;
  }
}

TEST(Tangents, CubeFacesUseTheirUAxis) {
  const HostMesh m = make_cube();
  // make_cube's faces: corners (-,-), (+,-), (+,+), (-,+) in the face's (u, v) axes, u x v = n.
  const Vec3d u_axis[6] = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {-1, 0, 0}};
  ASSERT_EQ(m.tangents.size(), 24u);
  for (size_t i = 0; i < 24; ++i) {
    const Vec3d& u = u_axis[i / 4];
    expect_tangent(m.tangents[i], {u[0], u[1], u[2], 1}, 1e-15, i);
  }
}

TEST(Tangents, TorusKnotTubeIsMirrored) {
  // The knot's v runs around the tube from n to b while u runs along the curve T, and
  // cross(outward normal, T) points against increasing v: the uvs are mirrored, w = -1.
  const HostMesh m = make_torus_knot(2, 3, 0.18, 200, 10);
  expect_valid_frames(m);
  for (size_t i = 0; i < m.tangents.size(); ++i) EXPECT_EQ(m.tangents[i][3], -1.0) << i;
}

TEST(Tangents, NoUvsClearsTheTangents) {
  HostMesh m = make_grid(1, 1);
  ASSERT_FALSE(m.tangents.empty());
  m.uvs.clear();
  compute_tangents(m);
  EXPECT_TRUE(m.tangents.empty());
}

TEST(Tangents, DegenerateUvsGiveAnyOrthogonalUnitVector) {
  HostMesh m = make_uv_sphere(6, 8);
  for (Vec2d& uv : m.uvs) uv = {0.25, 0.75};  // every triangle has zero uv area
  compute_tangents(m);
  expect_valid_frames(m);
  for (const Vec4d& t : m.tangents) EXPECT_EQ(t[3], 1.0);
  // uvs along a line (u = v): zero uv area too.
  HostMesh g = make_grid(2, 2);
  for (Vec2d& uv : g.uvs) uv = {uv[0], uv[0]};
  compute_tangents(g);
  expect_valid_frames(g);
  for (const Vec4d& t : g.tangents) EXPECT_EQ(t[3], 1.0);
}

TEST(Tangents, DegenerateTrianglesContributeNothing) {
  HostMesh m = make_grid(1, 1);  // vertices 0 (-1,-1), 1 (1,-1), 2 (-1,1), 3 (1,1); uv = (x+1)/2
  auto add = [&m](const Vec3d& p, const Vec2d& uv) {
    m.positions.push_back(p);
    m.normals.push_back({0, 0, 1});
    m.uvs.push_back(uv);
  };
  // Vertex 4: its triangle with 0 and 2 has zero uv area (uv 4 = uv 0), and its tangent would
  // be +y if the collapsed uvs were taken as valid.
  add({0.5, -1, 0}, {0, 0});
  m.triangles.push_back({0, 4, 2});
  // Vertex 5: collinear with 0 and 1 (zero area) but with uvs that span an area; without the
  // area check its corner angle of pi at vertex 1 would pull 1's tangent off +x.
  add({3, -1, 0}, {0.5, 0.7});
  m.triangles.push_back({0, 1, 5});
  // Vertex 6: used by no triangle.
  add({5, 5, 5}, {0.5, 0.5});
  m.normals.back() = {0, 1, 0};
  m.triangle_material.assign(m.triangles.size(), -1);
  compute_tangents(m);
  expect_valid_frames(m);
  for (size_t i = 0; i < 4; ++i) expect_tangent(m.tangents[i], {1, 0, 0, 1}, 1e-15, i);
  for (size_t i = 4; i < 7; ++i) EXPECT_EQ(m.tangents[i][3], 1.0) << i;
}

TEST(Tangents, AngleWeightingIgnoresHowAFlatRegionIsSplit) {
  // A fan of triangles around a centre vertex in the plane z = 0 with uv = (x, y) / 2 + 0.5 but
  // a skewed uv on one side, so the triangles disagree: the result must not change when one
  // triangle is split in two (the split triangles' angles add up to the original's).
  auto fan = [](bool split) {
    HostMesh m;
    const double k = std::numbers::pi / 2;
    m.positions.push_back({0, 0, 0});
    for (int i = 0; i < 4; ++i) m.positions.push_back({std::cos(k * i), std::sin(k * i), 0});
    for (const Vec3d& p : m.positions) {
      m.normals.push_back({0, 0, 1});
      m.uvs.push_back({p[0] / 2 + 0.5 + (p[1] > 0.5 ? 0.3 : 0.0), p[1] / 2 + 0.5});
    }
    m.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}};
    if (split) {  // split (0, 4, 1) at the middle of its edge 4-1, on the same plane and uv line
      m.positions.push_back({0.5, -0.5, 0});
      m.normals.push_back({0, 0, 1});
      m.uvs.push_back({(m.uvs[4][0] + m.uvs[1][0]) / 2, (m.uvs[4][1] + m.uvs[1][1]) / 2});
      m.triangles.back() = {0, 4, 5};
      m.triangles.push_back({0, 5, 1});
    }
    m.triangle_material.assign(m.triangles.size(), -1);
    compute_tangents(m);
    return m.tangents[0];
  };
  const Vec4d a = fan(false), b = fan(true);
  for (size_t c = 0; c < 4; ++c) EXPECT_NEAR(a[c], b[c], 1e-15) << c;
  EXPECT_GT(a[0], 0.9);  // still mostly along +x
}

}  // namespace
}  // namespace lr::host
