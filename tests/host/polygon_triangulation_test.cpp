// OBJ faces triangulated as the file means them: checked by coverage against the polygon itself
// (every sample point inside the polygon in exactly one triangle, every point outside in none),
// by area and by winding, on concave, keyhole, star, tilted and clockwise polygons.
#include "lineraster/host_sim/formats/polygon_triangulation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "lineraster/host_sim/formats/obj_loader.hpp"

namespace lr::host {
namespace {

using Tri = std::array<uint32_t, 3>;
using Poly2 = std::vector<std::array<double, 2>>;

double cross2(const std::array<double, 2>& a, const std::array<double, 2>& b,
              const std::array<double, 2>& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

double signed_area(const Poly2& p) {
  double s = 0;
  for (size_t i = 0; i < p.size(); ++i) s += cross2({0, 0}, p[i], p[(i + 1) % p.size()]);
  return s / 2;
}

// Even-odd rule (a keyhole's doubled edge cancels itself).
bool inside_polygon(const Poly2& p, double x, double y) {
  bool in = false;
  for (size_t i = 0, j = p.size() - 1; i < p.size(); j = i++) {
    if ((p[i][1] > y) != (p[j][1] > y) &&
        x < (p[j][0] - p[i][0]) * (y - p[i][1]) / (p[j][1] - p[i][1]) + p[i][0])
      in = !in;
  }
  return in;
}

bool inside_triangle(const Poly2& p, const Tri& t, double x, double y) {
  const std::array<double, 2> q{x, y};
  const double a = cross2(p[t[0]], p[t[1]], q), b = cross2(p[t[1]], p[t[2]], q),
               c = cross2(p[t[2]], p[t[0]], q);
  return (a > 0 && b > 0 && c > 0) || (a < 0 && b < 0 && c < 0);
}

// Triangulates `p` (in the plane z = 0 unless `lift` maps it elsewhere) and checks the result.
void expect_exact_cover(const Poly2& p, const std::string& what,
                        Vec3d (*lift)(double, double) = nullptr) {
  std::vector<Vec3d> corners;
  for (const auto& q : p) corners.push_back(lift ? lift(q[0], q[1]) : Vec3d{q[0], q[1], 0});
  std::vector<Tri> tris;
  triangulate_polygon(corners, tris);
  ASSERT_EQ(tris.size(), p.size() - 2) << what;
  const double area = signed_area(p);
  double sum = 0;
  for (const Tri& t : tris) {
    for (uint32_t k : t) ASSERT_LT(k, p.size()) << what;
    const double a = cross2(p[t[0]], p[t[1]], p[t[2]]) / 2;
    EXPECT_GE(a * area, 0) << what << ": a triangle wound against the polygon";
    sum += a;
  }
  EXPECT_NEAR(sum, area, 1e-9 * std::fabs(area)) << what;
  double lo_x = p[0][0], hi_x = lo_x, lo_y = p[0][1], hi_y = lo_y;
  for (const auto& q : p) {
    lo_x = std::min(lo_x, q[0]), hi_x = std::max(hi_x, q[0]);
    lo_y = std::min(lo_y, q[1]), hi_y = std::max(hi_y, q[1]);
  }
  int checked = 0;
  for (int i = 0; i < 97; ++i) {
    for (int j = 0; j < 89; ++j) {
      // Offsets by irrational fractions keep the samples off the polygons' edges.
      const double x = lo_x + (hi_x - lo_x) * (i + 0.5 + 0.0123 * std::sqrt(2.0)) / 97;
      const double y = lo_y + (hi_y - lo_y) * (j + 0.5 + 0.0117 * std::sqrt(3.0)) / 89;
      int hits = 0;
      for (const Tri& t : tris) hits += inside_triangle(p, t, x, y) ? 1 : 0;
      EXPECT_EQ(hits, inside_polygon(p, x, y) ? 1 : 0) << what << " at " << x << ", " << y;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 97 * 89);
}

Poly2 circle(double r, int n, double a0, bool ccw) {
  Poly2 p;
  for (int k = 0; k < n; ++k) {
    const double a = a0 + (ccw ? 1 : -1) * 2 * M_PI * k / n;
    p.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return p;
}

TEST(PolygonTriangulation, ConvexFacesAreFannedFromTheirFirstCorner) {
  const Poly2 hex = circle(1, 6, 0.1, true);
  std::vector<Vec3d> c;
  for (const auto& q : hex) c.push_back({q[0], q[1], 0});
  std::vector<Tri> tris;
  triangulate_polygon(c, tris);
  EXPECT_EQ(tris, (std::vector<Tri>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}}));
  expect_exact_cover(hex, "hexagon");
}

TEST(PolygonTriangulation, ConcaveFacesCoverThemselvesExactly) {
  expect_exact_cover({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}, "L");
  // The L from another corner: a fan from its first corner leaves the polygon.
  expect_exact_cover({{2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}}, "L from (2, 0)");
  expect_exact_cover({{0, 0},
                      {5, 0},
                      {5, 3},
                      {4, 3},
                      {4, 1},
                      {3, 1},
                      {3, 3},
                      {2, 3},
                      {2, 1},
                      {1, 1},
                      {1, 3},
                      {0, 3}},
                     "comb");
  Poly2 star;
  for (int k = 0; k < 10; ++k) {
    const double a = 2 * M_PI * k / 10, r = k % 2 ? 0.4 : 1.0;
    star.push_back({r * std::cos(a), r * std::sin(a)});
  }
  expect_exact_cover(star, "star");
  Poly2 clockwise = star;
  std::reverse(clockwise.begin(), clockwise.end());
  expect_exact_cover(clockwise, "clockwise star");
}

// A thin ring written as one face: the outer loop, a doubled edge to the inner loop, the inner
// loop the other way round. A fan fills the hole (the disc of the user's report).
TEST(PolygonTriangulation, AKeyholeRingKeepsItsHole) {
  const Poly2 outer = circle(2, 24, 0, true), inner = circle(1.8, 24, 0, false);
  Poly2 ring = outer;
  ring.push_back(outer[0]);
  ring.insert(ring.end(), inner.begin(), inner.end());
  ring.push_back(inner[0]);
  expect_exact_cover(ring, "ring");
}

TEST(PolygonTriangulation, ATiltedSlightlyNonPlanarFaceIsTriangulatedInItsPlane) {
  // The comb in the plane x + y + z = 1, each corner off it by up to 1 % of its size.
  expect_exact_cover({{0, 0},
                      {5, 0},
                      {5, 3},
                      {4, 3},
                      {4, 1},
                      {3, 1},
                      {3, 3},
                      {2, 3},
                      {2, 1},
                      {1, 1},
                      {1, 3},
                      {0, 3}},
                     "tilted comb", [](double u, double v) {
                       const double off = 0.05 * std::sin(7 * u + 3 * v);
                       return Vec3d{u, v, 1 - u - v + off};
                     });
}

TEST(PolygonTriangulation, TheObjLoaderTriangulatesConcaveFacesSo) {
  // The L from (2, 0): a fan would wind one triangle backwards and cover 4 square units.
  HostMesh m;
  std::string error;
  ASSERT_TRUE(parse_obj("v 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 0\nf 1 2 3 4 5 6\n",
                        "t.obj", "", m, error))
      << error;
  ASSERT_EQ(m.triangles.size(), 4u);
  double area = 0;
  for (const auto& t : m.triangles) {
    const Vec3d &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    const double z = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    EXPECT_GT(z, 0);  // counter-clockwise, as the face
    area += std::fabs(z) / 2;
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
}

// A comb of `teeth` teeth: 2 + 4 teeth corners, concave.
std::string comb_obj(int teeth) {
  // Appended piece by piece: GCC 12 (armhf, -O2) warns falsely (-Wrestrict) on
  // "literal" + std::to_string(...) here.
  std::string obj;
  char line[64];
  std::snprintf(line, sizeof line, "v 0 0 0\nv %d 0 0\n", 2 * teeth);
  obj += line;
  for (int k = 0; k < teeth; ++k) {
    const int x = 2 * teeth - 2 * k;
    for (const auto& [u, v] : {std::pair{x, 3}, {x - 1, 3}, {x - 1, 1}, {x - 2, 1}}) {
      std::snprintf(line, sizeof line, "v %d %d 0\n", u, v);
      obj += line;
    }
  }
  obj += "f";
  for (int i = 1; i <= 2 + 4 * teeth; ++i) {
    std::snprintf(line, sizeof line, " %d", i);
    obj += line;
  }
  obj += "\n";
  return obj;
}

// Ear clipping is quadratic: up to kMaxEarClippedCorners a concave face is clipped (its area
// is exact), beyond it fanned with a warning.
TEST(PolygonTriangulation, ConcaveFacesBeyondTheLimitAreFannedWithAWarning) {
  const auto area = [](const HostMesh& m) {
    double a = 0;
    for (const auto& t : m.triangles) {
      const Vec3d &p = m.positions[t[0]], &q = m.positions[t[1]], &r = m.positions[t[2]];
      a += std::fabs((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])) / 2;
    }
    return a;
  };
  HostMesh m;
  std::string error;
  const int below = (static_cast<int>(kMaxEarClippedCorners) - 2) / 4;  // 1023 teeth
  ASSERT_TRUE(parse_obj(comb_obj(below), "c.obj", "", m, error)) << error;
  EXPECT_TRUE(m.warnings.empty());
  EXPECT_NEAR(area(m), 2.0 * below + 2.0 * below, 1e-6);  // the base, and 2 x 1 per tooth
  ASSERT_TRUE(parse_obj(comb_obj(below + 1), "c.obj", "", m, error)) << error;
  EXPECT_EQ(m.warnings, std::vector<std::string>{
                            "c.obj:" + std::to_string(4 * below + 7) + ": a concave face of " +
                            std::to_string(4 * below + 6) +
                            " corners: fanned from its first corner (ear clipping stops at 4096 "
                            "corners), its triangles may leave it"});
}

// A circle of 100,000 corners written with 7 decimals (rounding bends corners either way) is
// convex: fanned, no warning.
TEST(PolygonTriangulation, AHugeRoundedCircleIsFanned) {
  constexpr int kCorners = 100000;
  std::string obj, f = "f";
  char line[64];
  for (int k = 0; k < kCorners; ++k) {
    const double a = 2 * M_PI * k / kCorners;
    std::snprintf(line, sizeof line, "v %.7f %.7f 0\n", std::cos(a), std::sin(a));
    obj += line;
    std::snprintf(line, sizeof line, " %d", k + 1);
    f += line;
  }
  HostMesh m;
  std::string error;
  ASSERT_TRUE(parse_obj(obj + f + "\n", "disc.obj", "", m, error)) << error;
  EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
  ASSERT_EQ(m.triangles.size(), static_cast<size_t>(kCorners - 2));
  EXPECT_EQ(m.triangles[0][0], m.triangles.back()[0]);  // all from the first corner
}

}  // namespace
}  // namespace lr::host
