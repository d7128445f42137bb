// OBJ/MTL loader: every index form, fanning, unification, colours, materials, smooth normals, and
// the exact "FILE:LINE: ..." errors for malformed input (which must leave the output untouched).
#include "lineraster/host_sim/formats/obj_loader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "tests/support/tmp_dir.hpp"

#include <sys/stat.h>
#include <unistd.h>

namespace lr::host {
namespace {

const std::string kSourceDir = LR_SOURCE_DIR;

using test::TmpDir;

HostMesh parse_ok(const std::string& text, const std::string& base_dir = "") {
  HostMesh m;
  std::string error;
  EXPECT_TRUE(parse_obj(text, "t.obj", base_dir, m, error)) << error;
  EXPECT_EQ(m.normals.size(), m.positions.size());
  EXPECT_EQ(m.triangle_material.size(), m.triangles.size());
  return m;
}

// A mesh with recognisable content, to check that failures leave `out` untouched.
HostMesh sentinel() {
  HostMesh m;
  m.positions = {{7.0, 7.0, 7.0}};
  m.normals = {{0.0, 0.0, 1.0}};
  m.triangles = {{0, 0, 0}};
  m.triangle_material = {-1};
  return m;
}

void expect_sentinel(const HostMesh& m) {
  ASSERT_EQ(m.positions.size(), 1u);
  EXPECT_EQ(m.positions[0], (Vec3d{7.0, 7.0, 7.0}));
  EXPECT_EQ(m.triangles.size(), 1u);
  EXPECT_TRUE(m.colors.empty());
  EXPECT_TRUE(m.uvs.empty());
  EXPECT_TRUE(m.materials.empty());
}

// Parses `text` expecting failure with exactly `expected` as the error.
void expect_error(const std::string& text, const std::string& expected,
                  const std::string& base_dir = "") {
  HostMesh m = sentinel();
  std::string error;
  EXPECT_FALSE(parse_obj(text, "t.obj", base_dir, m, error));
  EXPECT_EQ(error, expected);
  expect_sentinel(m);
}

void expect_near3(const Vec3d& a, const Vec3d& b, double tol = 1e-12) {
  EXPECT_NEAR(a[0], b[0], tol);
  EXPECT_NEAR(a[1], b[1], tol);
  EXPECT_NEAR(a[2], b[2], tol);
}

const char* kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

// ---------------------------------------------------------------------------------------------
// Index forms

TEST(ObjLoader, FaceWithPositionsOnly) {
  const HostMesh m = parse_ok(std::string(kTri) + "f 1 2 3\n");
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.positions[1], (Vec3d{1, 0, 0}));
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangle_material[0], -1);
  EXPECT_FALSE(m.has_uvs());
  EXPECT_FALSE(m.has_colors());
  for (const Vec3d& n : m.normals) EXPECT_EQ(n, (Vec3d{0, 0, 1}));  // smooth normal of a CCW face
}

TEST(ObjLoader, FaceWithPositionsAndUvs) {
  const HostMesh m =
      parse_ok(std::string(kTri) + "vt 0.25 0.5\nvt 1 0\nvt 0 1 0.7\nf 1/3 2/2 3/1\n");
  ASSERT_EQ(m.uvs.size(), 3u);
  EXPECT_EQ(m.uvs[0], (Vec2d{0, 1}));
  EXPECT_EQ(m.uvs[1], (Vec2d{1, 0}));
  EXPECT_EQ(m.uvs[2], (Vec2d{0.25, 0.5}));
  EXPECT_EQ(m.normals[2], (Vec3d{0, 0, 1}));
}

TEST(ObjLoader, FaceWithPositionsAndNormals) {
  const HostMesh m = parse_ok(std::string(kTri) + "vn 0 0 2\nvn 3 4 0\nf 1//2 2//1 3//2\n");
  EXPECT_FALSE(m.has_uvs());
  ASSERT_EQ(m.normals.size(), 3u);
  expect_near3(m.normals[0], {0.6, 0.8, 0.0}, 1e-15);  // normalized
  EXPECT_EQ(m.normals[1], (Vec3d{0, 0, 1}));
  expect_near3(m.normals[2], {0.6, 0.8, 0.0}, 1e-15);
}

TEST(ObjLoader, FaceWithAllThreeIndices) {
  const HostMesh m =
      parse_ok(std::string(kTri) + "vt 0 0\nvt 1 0\nvt 0 1\nvn 1 0 0\nf 1/1/1 2/2/1 3/3/1\n");
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.uvs[1], (Vec2d{1, 0}));
  for (const Vec3d& n : m.normals) EXPECT_EQ(n, (Vec3d{1, 0, 0}));
}

TEST(ObjLoader, MixedCornerFormsGiveZeroUvAndSmoothNormalWhereMissing) {
  const HostMesh m = parse_ok(std::string(kTri) + "vt 0.5 0.5\nvn 0 1 0\nf 1/1 2 3//1\n");
  ASSERT_EQ(m.uvs.size(), 3u);
  EXPECT_EQ(m.uvs[0], (Vec2d{0.5, 0.5}));
  EXPECT_EQ(m.uvs[1], (Vec2d{0, 0}));
  EXPECT_EQ(m.uvs[2], (Vec2d{0, 0}));
  EXPECT_EQ(m.normals[0], (Vec3d{0, 0, 1}));
  EXPECT_EQ(m.normals[1], (Vec3d{0, 0, 1}));
  EXPECT_EQ(m.normals[2], (Vec3d{0, 1, 0}));
}

TEST(ObjLoader, NegativeIndicesAreRelativeToElementsDefinedSoFar) {
  const HostMesh m = parse_ok(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.1 0.2\nvn 0 0 1\n"
      "f -3/-1/-1 -2/-1/-1 -1/-1/-1\n"
      "v 5 5 5\nvt 0.3 0.4\n"
      "f -4/-2 -2/-1 -1/-1\n");
  ASSERT_EQ(m.triangles.size(), 2u);
  const auto& t1 = m.triangles[1];
  EXPECT_EQ(m.positions[t1[0]], (Vec3d{0, 0, 0}));
  EXPECT_EQ(m.positions[t1[1]], (Vec3d{0, 1, 0}));
  EXPECT_EQ(m.positions[t1[2]], (Vec3d{5, 5, 5}));
  EXPECT_EQ(m.uvs[t1[0]], (Vec2d{0.1, 0.2}));
  EXPECT_EQ(m.uvs[t1[1]], (Vec2d{0.3, 0.4}));
  EXPECT_EQ(m.positions[m.triangles[0][2]], (Vec3d{0, 1, 0}));
}

TEST(ObjLoader, QuadIsFannedFromItsFirstCorner) {
  const HostMesh m = parse_ok("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{0, 2, 3}));
}

TEST(ObjLoader, PentagonIsFannedAndVerticesNumberedInOrderOfFirstUse) {
  const HostMesh m = parse_ok(
      "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\n"
      "f 5 4 3 2 1\n");
  ASSERT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(m.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(m.triangles[2], (std::array<uint32_t, 3>{0, 3, 4}));
  EXPECT_EQ(m.positions[0], (Vec3d{0, 1, 0}));                       // OBJ position 5
  EXPECT_EQ(m.positions[4], (Vec3d{0, 0, 0}));                       // OBJ position 1
  for (const Vec3d& n : m.normals) EXPECT_EQ(n, (Vec3d{0, 0, -1}));  // clockwise seen from +z
}

TEST(ObjLoader, UnifiesIdenticalCornersOnly) {
  // Two triangles sharing an edge with identical (v, vt, vn): 4 vertices. A third face reuses
  // position 1 with another uv: one more vertex.
  const HostMesh m = parse_ok(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\n"
      "f 1/1/1 2/1/1 3/1/1\nf 1/1/1 3/1/1 4/1/1\nf 1/2/1 3/1/1 4/1/1\n");
  EXPECT_EQ(m.positions.size(), 5u);
  EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(m.triangles[2], (std::array<uint32_t, 3>{4, 2, 3}));
  EXPECT_EQ(m.uvs[4], (Vec2d{1, 1}));
  EXPECT_EQ(m.positions[4], (Vec3d{0, 0, 0}));
}

TEST(ObjLoader, CubeWithPerFaceUvsAndNormalsHas24Vertices) {
  HostMesh m;
  std::string error;
  ASSERT_TRUE(load_obj(kSourceDir + "/tests/host/data/cube.obj", m, error)) << error;
  EXPECT_EQ(m.positions.size(), 24u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.uvs.size(), 24u);
  // Counter-clockwise seen from outside: each triangle's cross product agrees with its vn.
  for (const auto& t : m.triangles) {
    const Vec3d& a = m.positions[t[0]];
    const Vec3d& b = m.positions[t[1]];
    const Vec3d& c = m.positions[t[2]];
    const Vec3d e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const Vec3d e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const Vec3d n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                  e1[0] * e2[1] - e1[1] * e2[0]};
    for (uint32_t v : t) {
      EXPECT_GT(n[0] * m.normals[v][0] + n[1] * m.normals[v][1] + n[2] * m.normals[v][2], 0.0);
    }
  }
}

TEST(ObjLoader, DegenerateFacesAreKept) {
  const HostMesh m = parse_ok("v 0 0 0\nv 1 0 0\nf 1 1 2\n");
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0], (std::array<uint32_t, 3>{0, 0, 1}));
  EXPECT_EQ(m.normals[0], (Vec3d{0, 0, 1}));  // zero area sum -> (0, 0, 1)
}

// ---------------------------------------------------------------------------------------------
// Vertex data

TEST(ObjLoader, VertexColoursAreCopiedPerUnifiedVertex) {
  const HostMesh m = parse_ok(
      "v 0 0 0 1 0 0\nv 1 0 0 0 0.5 0\nv 0 1 0 0 0 0.25\nv 1 1 0 1.5 -1 1\nvt 0 0\nvt 1 1\n"
      "f 1 2 3\nf 2/1 4 3/2\n");
  ASSERT_TRUE(m.has_colors());
  ASSERT_EQ(m.colors.size(), m.positions.size());
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3d& p = m.positions[i];
    const Vec3d& c = m.colors[i];
    if (p == Vec3d{0, 0, 0}) {
      EXPECT_EQ(c, (Vec3d{1, 0, 0}));
    }
    if (p == Vec3d{1, 0, 0}) {
      EXPECT_EQ(c, (Vec3d{0, 0.5, 0}));
    }
    if (p == Vec3d{0, 1, 0}) {
      EXPECT_EQ(c, (Vec3d{0, 0, 0.25}));
    }
    if (p == Vec3d{1, 1, 0}) {
      EXPECT_EQ(c, (Vec3d{1, 0, 1}));  // clamped to [0, 1]
    }
  }
  EXPECT_EQ(m.positions.size(), 6u);
}

TEST(ObjLoader, HomogeneousWIsIgnored) {
  const HostMesh m = parse_ok("v 1 2 3 0.5\nv 2 2 3 1\nv 1 3 3 2\nf 1 2 3\n");
  EXPECT_EQ(m.positions[0], (Vec3d{1, 2, 3}));
  EXPECT_EQ(m.positions[2], (Vec3d{1, 3, 3}));
}

TEST(ObjLoader, NumberForms) {
  const HostMesh m = parse_ok("v +1.5 -2e-3 .25\nv 1E2 0. -0\nv 1e-400 7 0\nf 1 2 3\n");
  EXPECT_EQ(m.positions[0], (Vec3d{1.5, -0.002, 0.25}));
  EXPECT_EQ(m.positions[1], (Vec3d{100, 0, 0}));
  EXPECT_EQ(m.positions[2], (Vec3d{0, 7, 0}));  // underflow reads as 0
}

TEST(ObjLoader, TextFormatting) {
  // BOM, CRLF, comments (whole-line and trailing), blank lines, tabs, continuation lines, and
  // statements that are ignored.
  const HostMesh m = parse_ok(
      "\xEF\xBB\xBF# header\r\n"
      "\r\n"
      "o thing\r\n"
      "g group1 group2\r\n"
      "s 1\r\n"
      "v\t0 0 0 # origin\r\n"
      "v 1 \\\r\n"
      "  0 0\r\n"
      "v 0 1 0\r\n"
      "vp 0.5 0.5\r\n"
      "l 1 2\r\n"
      "p 1\r\n"
      "cstype bezier\r\n"
      "s off\r\n"
      "f 1 2 \\\n"
      "3\n"
      "f 1 2 3");  // no final newline
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.positions[1], (Vec3d{1, 0, 0}));
  EXPECT_EQ(m.positions.size(), 3u);
}

// ---------------------------------------------------------------------------------------------
// Smooth normals

TEST(ObjLoader, SmoothNormalsOfACubeWithoutNormalsPointAlongTheDiagonals) {
  // Unit cube [-1,1]^3 with 6 CCW outward quads. Fanning gives each corner one or two triangles of
  // a face, but a face counts with its whole area: every corner normal is (+-1,+-1,+-1)/sqrt(3).
  const HostMesh m = parse_ok(
      "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
      "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  ASSERT_EQ(m.positions.size(), 8u);
  const double s = 1.0 / std::sqrt(3.0);
  for (size_t i = 0; i < 8; ++i) {
    const Vec3d& p = m.positions[i];
    expect_near3(m.normals[i], {p[0] * s, p[1] * s, p[2] * s}, 1e-15);
  }
}

TEST(ObjLoader, SmoothNormalsAreAreaWeighted) {
  // Origin shared by a big triangle in z = 0 (area 2, normal +z) and a small one in x = 0
  // (area 0.5, normal +x): sum = (1, 0, 4) (cross products), so n = (1, 0, 4) / sqrt(17)
  // (an unweighted average would give (1, 0, 1) / sqrt(2)).
  const HostMesh m = parse_ok(
      "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 1 0\nv 0 0 1\n"
      "f 1 2 3\nf 1 4 5\n");
  ASSERT_EQ(m.positions.size(), 5u);
  const double r = 1.0 / std::sqrt(17.0);
  expect_near3(m.normals[0], {r, 0.0, 4.0 * r}, 1e-15);
  EXPECT_EQ(m.normals[1], (Vec3d{0, 0, 1}));
  EXPECT_EQ(m.normals[3], (Vec3d{1, 0, 0}));
}

TEST(ObjLoader, SmoothNormalsAreSharedAcrossUvSeams) {
  // Same position used with two different uvs: two vertices, one smooth normal.
  const HostMesh m = parse_ok(
      "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 1\n"
      "f 1/1 2/1 3/1\nf 1/2 4/2 5/2\n");
  ASSERT_EQ(m.positions.size(), 6u);
  const double r = 1.0 / std::sqrt(17.0);
  expect_near3(m.normals[0], {r, 0.0, 4.0 * r}, 1e-15);
  expect_near3(m.normals[3], {r, 0.0, 4.0 * r}, 1e-15);
}

TEST(ObjLoader, SmoothNormalsSurviveHugeCoordinates) {
  const HostMesh m = parse_ok("v 0 0 0\nv 1e300 0 0\nv 0 1e300 0\nf 1 2 3\n");
  for (const Vec3d& n : m.normals) EXPECT_EQ(n, (Vec3d{0, 0, 1}));
}

// ---------------------------------------------------------------------------------------------
// Materials

TEST(ObjLoader, MtllibAndUsemtlReadValuesAndResolveTexturePaths) {
  TmpDir dir("lr_obj_test");
  dir.write("sub/a.mtl",
            "# two materials\n"
            "newmtl red\n"
            "Ka 0.1 0.2 0.3\n"
            "Kd 1 0 0\n"
            "Ks 0.5\n"
            "Ke 0 0.25 0\n"
            "Ns 500\n"
            "d 0.75\n"
            "illum 2\n"
            "map_Kd -s 1 1 1 -o 0.5 -clamp on ../tex/wood grain.png\n"
            "\n"
            "NEWMTL shiny one\n"
            "kd 0 1 0\n"
            "Ns 32\n"
            "Tr 0.25\n");
  dir.write("b.mtl", "newmtl blue\nKd 0 0 1\nNs -3\nmap_Kd tex\\blue.png\n");
  const std::string obj =
      "mtllib sub/a.mtl b.mtl\n"
      "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "f 1 2 3\n"
      "usemtl shiny one\n"
      "f 1 2 3\n"
      "usemtl blue\n"
      "f 1 2 3 1\n"
      "usemtl red\n"
      "f 1 2 3\n";
  const HostMesh m = parse_ok(obj, dir.path());
  ASSERT_EQ(m.materials.size(), 3u);
  const HostMaterial& red = m.materials[0];
  EXPECT_EQ(red.name, "red");
  EXPECT_EQ(red.ambient, (Vec3d{0.1, 0.2, 0.3}));
  EXPECT_EQ(red.diffuse, (Vec3d{1, 0, 0}));
  EXPECT_EQ(red.specular, (Vec3d{0.5, 0.5, 0.5}));
  EXPECT_EQ(red.emission, (Vec3d{0, 0.25, 0}));
  EXPECT_EQ(red.shininess, 128.0);  // clamped
  EXPECT_EQ(red.alpha, 0.75);
  EXPECT_EQ(red.map_kd, dir.path() + "/sub/../tex/wood grain.png");
  const HostMaterial& shiny = m.materials[1];
  EXPECT_EQ(shiny.name, "shiny one");
  EXPECT_EQ(shiny.diffuse, (Vec3d{0, 1, 0}));
  EXPECT_EQ(shiny.ambient, (Vec3d{0.2, 0.2, 0.2}));  // default
  EXPECT_EQ(shiny.shininess, 32.0);
  EXPECT_EQ(shiny.alpha, 0.75);  // 1 - Tr
  EXPECT_EQ(shiny.map_kd, "");
  const HostMaterial& blue = m.materials[2];
  EXPECT_EQ(blue.shininess, 0.0);  // clamped
  EXPECT_EQ(blue.map_kd, dir.path() + "/tex/blue.png");
  EXPECT_EQ(m.triangle_material, (std::vector<int32_t>{-1, 1, 2, 2, 0}));
}

TEST(ObjLoader, LoadObjResolvesMtllibNextToTheObj) {
  HostMesh m;
  std::string error;
  ASSERT_TRUE(load_obj(kSourceDir + "/tests/host/data/cube.obj", m, error)) << error;
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[0].name, "cube_red");
  EXPECT_EQ(m.materials[0].ambient, (Vec3d{0.2, 0.05, 0.05}));
  EXPECT_EQ(m.materials[0].diffuse, (Vec3d{0.8, 0.1, 0.1}));
  EXPECT_EQ(m.materials[0].specular, (Vec3d{0.5, 0.5, 0.5}));
  EXPECT_EQ(m.materials[0].shininess, 32.0);
  EXPECT_EQ(m.materials[1].name, "cube_white");
  EXPECT_EQ(m.materials[1].shininess, 96.0);
  EXPECT_EQ(m.materials[1].map_kd, kSourceDir + "/tests/host/data/checker.png");
  EXPECT_EQ(m.triangle_material, (std::vector<int32_t>{0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1}));
}

TEST(ObjLoader, LaterMaterialDefinitionReplacesEarlierOne) {
  std::vector<HostMaterial> mats;
  std::string error;
  ASSERT_TRUE(
      parse_mtl("newmtl a\nKd 1 0 0\nnewmtl b\nnewmtl a\nKd 0 1 0\n", "m.mtl", "", mats, error));
  ASSERT_EQ(mats.size(), 3u);  // parse_mtl keeps the file as written ...
  TmpDir dir("lr_obj_test");
  dir.write("m.mtl", "newmtl a\nKd 1 0 0\nnewmtl b\n");
  dir.write("n.mtl", "newmtl a\nKd 0 1 0\n");
  const HostMesh m = parse_ok("mtllib m.mtl n.mtl\nv 0 0 0\nusemtl a\nf 1 1 1\n", dir.path());
  ASSERT_EQ(m.materials.size(), 2u);  // ... the loader merges by name, last definition wins
  EXPECT_EQ(m.materials[0].diffuse, (Vec3d{0, 1, 0}));
  EXPECT_EQ(m.triangle_material[0], 0);
}

// ---------------------------------------------------------------------------------------------
// Errors: exact messages, `out` untouched

TEST(ObjLoaderErrors, BadNumber) {
  expect_error("v 0 0 0\nv 1 x 0\n", "t.obj:2: bad number 'x'");
  expect_error("v 0 0 0\nv 1 2 3abc\n", "t.obj:2: bad number '3abc'");
  expect_error("v 0 0 0\nvt 0.5 -\n", "t.obj:2: bad number '-'");
  expect_error("vn 0 0 1,0\n", "t.obj:1: bad number '1,0'");
  expect_error("v 0x1p3 0 0\n", "t.obj:1: bad number '0x1p3'");
  expect_error("v ++1 0 0\n", "t.obj:1: bad number '++1'");
}

TEST(ObjLoaderErrors, TooFewNumbers) {
  expect_error("# c\nv 1 2\n",
               "t.obj:2: too few numbers in v: expected 3, 4 (x y z w) or 6 (x y z r g b), got 2");
  expect_error("v 1 2 3 4 5\n",
               "t.obj:1: wrong number of numbers in v: expected 3, 4 (x y z w) or 6 (x y z r g "
               "b), got 5");
  expect_error("vt 1\n", "t.obj:1: too few numbers in vt: expected 2 or 3, got 1");
  expect_error("vn 1 2\n", "t.obj:1: too few numbers in vn: expected 3, got 2");
}

TEST(ObjLoaderErrors, IndexZero) {
  expect_error(std::string(kTri) + "f 0 1 2\n",
               "t.obj:4: position index 0 is invalid (OBJ indices start at 1)");
  expect_error(std::string(kTri) + "vt 0 0\nf 1/0 2/1 3/1\n",
               "t.obj:5: texture coordinate index 0 is invalid (OBJ indices start at 1)");
}

TEST(ObjLoaderErrors, IndexOutOfRange) {
  expect_error(std::string(kTri) + "f 1 2 4\n",
               "t.obj:4: position index 4 out of range (3 defined)");
  expect_error(std::string(kTri) + "vn 0 0 1\nf 1//1 2//2 3//1\n",
               "t.obj:5: normal index 2 out of range (1 defined)");
  expect_error(std::string(kTri) + "f 1/1 2/1 3/1\n",
               "t.obj:4: texture coordinate index 1 out of range (0 defined)");
  expect_error(std::string(kTri) + "f 1 2 99999999999999999999999\n",
               "t.obj:4: position index '99999999999999999999999' out of range (3 defined)");
  // Forward references are out of range too (indices refer to what is defined so far).
  expect_error("v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n",
               "t.obj:3: position index 3 out of range (2 defined)");
}

TEST(ObjLoaderErrors, NegativeIndexOutOfRange) {
  expect_error(std::string(kTri) + "f -4 1 2\n",
               "t.obj:4: position index -4 out of range (3 defined)");
  expect_error(std::string(kTri) + "f 1 2 -9223372036854775808\n",
               "t.obj:4: position index -9223372036854775808 out of range (3 defined)");
}

TEST(ObjLoaderErrors, BadFaceVertex) {
  expect_error(std::string(kTri) + "f 1/1/1/1 2 3\n", "t.obj:4: bad face vertex '1/1/1/1'");
  expect_error(std::string(kTri) + "f /1 2 3\n", "t.obj:4: bad face vertex '/1'");
  expect_error(std::string(kTri) + "f 1 2 a\n", "t.obj:4: bad position index 'a'");
}

TEST(ObjLoaderErrors, FaceWithTwoVertices) {
  expect_error(std::string(kTri) + "f 1 2\n", "t.obj:4: face needs at least 3 vertices, got 2");
  expect_error(std::string(kTri) + "f\n", "t.obj:4: face needs at least 3 vertices, got 0");
}

// Accepted as other loaders accept them, each with one warning line "FILE:LINE: what was done".
TEST(ObjLoaderTolerance, UsemtlWithoutALibraryOrAnUnknownNameGetsTheDefaultMaterial) {
  const HostMesh a = parse_ok(std::string(kTri) + "usemtl nope\nf 1 2 3\n");
  ASSERT_EQ(a.triangle_material.size(), 1u);
  EXPECT_EQ(a.triangle_material[0], -1);
  EXPECT_EQ(a.warnings, std::vector<std::string>{
                            "t.obj:4: usemtl 'nope' without a material library: the default "
                            "material is used"});
  TmpDir dir("lr_obj_test");
  dir.write("m.mtl", "newmtl red\nKd 1 0 0\n");
  const HostMesh b =
      parse_ok("mtllib m.mtl\n" + std::string(kTri) + "usemtl red\nf 1 2 3\nusemtl blue\nf 1 2 3\n",
               dir.path());
  ASSERT_EQ(b.triangle_material.size(), 2u);
  EXPECT_EQ(b.triangle_material[0], 0);
  EXPECT_EQ(b.triangle_material[1], -1);  // after the unknown name: the default again
  EXPECT_EQ(b.warnings, std::vector<std::string>{
                            "t.obj:7: unknown material 'blue': the default material is used"});
  // A material without a name (Blender writes them) is selected by a usemtl without a name.
  dir.write("e.mtl", "newmtl\nKd 0 1 0\n");
  const HostMesh c =
      parse_ok("mtllib e.mtl\n" + std::string(kTri) + "usemtl\nf 1 2 3\n", dir.path());
  ASSERT_EQ(c.materials.size(), 1u);
  EXPECT_EQ(c.materials[0].name, "");
  EXPECT_EQ(c.materials[0].diffuse, (Vec3d{0, 1, 0}));
  EXPECT_EQ(c.triangle_material[0], 0);
  EXPECT_EQ(c.warnings,
            std::vector<std::string>{dir.path() + "/e.mtl:1: newmtl without a name: the material "
                                                  "is named ''"});
}

TEST(ObjLoaderErrors, MissingMaterialLibrary) {
  TmpDir dir("lr_obj_test");
  expect_error(std::string(kTri) + "mtllib missing.mtl\nf 1 2 3\n",
               "t.obj:4: cannot open material library '" + dir.path() +
                   "/missing.mtl': No such file or directory",
               dir.path());
}

TEST(ObjLoaderErrors, ErrorInsideMaterialLibraryNamesTheMtlFile) {
  TmpDir dir("lr_obj_test");
  dir.write("bad.mtl", "newmtl a\n\nKd 1 zero 0\n");
  dir.write("early.mtl", "Kd 1 1 1\n");
  dir.write("count.mtl", "newmtl a\nKs 1 1\n");
  expect_error("mtllib bad.mtl\n", dir.path() + "/bad.mtl:3: bad number 'zero'", dir.path());
  expect_error("mtllib early.mtl\n", dir.path() + "/early.mtl:1: 'Kd' before any newmtl",
               dir.path());
  expect_error("mtllib count.mtl\n",
               dir.path() + "/count.mtl:2: Ks: expected 1 or 3 numbers, got 2", dir.path());
}

TEST(ObjLoaderErrors, InconsistentColours) {
  expect_error("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0\n",
               "t.obj:3: inconsistent vertex colours: this vertex has no r g b, earlier ones have");
  expect_error("v 0 0 0\nv 1 0 0 0 1 0\n",
               "t.obj:2: inconsistent vertex colours: this vertex has r g b, earlier ones have "
               "none");
}

TEST(ObjLoaderErrors, NotFiniteOrTooLarge) {
  expect_error("v nan 0 0\n", "t.obj:1: number is not finite 'nan'");
  expect_error("v 0 -inf 0\n", "t.obj:1: number is not finite '-inf'");
  expect_error("vt 0 Infinity\n", "t.obj:1: number is not finite 'Infinity'");
  expect_error("v 0 0 1e999\n", "t.obj:1: number out of range '1e999'");
  expect_error("v 0 0 0\nv 0 0 0 0 0 NaN\n", "t.obj:2: number is not finite 'NaN'");
}

// Statements the loader does not draw: o, g, s and vp silently, any other with one warning per
// keyword (its first line).
TEST(ObjLoaderTolerance, UnknownStatementsAreIgnoredWithOneWarningPerKeyword) {
  const HostMesh m = parse_ok("o a\ng b\ns 1\nvp 0.5\ncstype bspline\n" + std::string(kTri) +
                              "l 1 2\nl 2 3\nf 1 2 3\ncstype rat bspline\n");
  EXPECT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.warnings,
            (std::vector<std::string>{"t.obj:5: 'cstype' statements are not drawn: ignored",
                                      "t.obj:9: 'l' statements are not drawn: ignored"}));
}

// A zero-length vn: its corners get the smooth normal of their faces, the others keep theirs.
TEST(ObjLoaderTolerance, AZeroLengthNormalIsReplacedByTheFacesNormal) {
  const HostMesh m = parse_ok(std::string(kTri) + "vn 0 0 0\nvn 1 0 0\nf 1//1 2//1 3//2\n");
  ASSERT_EQ(m.normals.size(), 3u);
  expect_near3(m.normals[0], {0, 0, 1});  // the face's normal (counter-clockwise in xy)
  expect_near3(m.normals[1], {0, 0, 1});
  expect_near3(m.normals[2], {1, 0, 0});
  EXPECT_EQ(m.warnings, std::vector<std::string>{
                            "t.obj:4: vn has zero length: its corners get the faces' normal"});
}

TEST(ObjLoaderErrors, NoFaces) {
  expect_error("", "t.obj:1: no faces");
  expect_error(std::string(kTri), "t.obj:3: no faces");
  expect_error("# only a comment\n\n", "t.obj:2: no faces");
}

TEST(ObjLoaderErrors, MissingFile) {
  HostMesh m = sentinel();
  std::string error;
  EXPECT_FALSE(load_obj("/nonexistent-dir/none.obj", m, error));
  EXPECT_EQ(error, "/nonexistent-dir/none.obj: cannot open: No such file or directory");
  expect_sentinel(m);
  TmpDir dir("lr_obj_test");
  EXPECT_FALSE(load_obj(dir.path(), m, error));  // a directory
  EXPECT_EQ(error, dir.path() + ": cannot open: Is a directory");
  expect_sentinel(m);
}

// Refused before reading: a device (an endless /dev/zero read 1 GB before) and a file above the
// 1 GiB limit (a sparse one: its size is checked, nothing is read); an MTL file the same way.
// A pipe is still read.
TEST(ObjLoaderErrors, DevicesAndFilesAboveTheLimitAreRefusedBeforeReading) {
  HostMesh m = sentinel();
  std::string error;
  EXPECT_FALSE(load_obj("/dev/zero", m, error));
  EXPECT_EQ(error, "/dev/zero: cannot open: a device, not a file");
  expect_sentinel(m);
  TmpDir dir("lr_obj_test");
  const std::string big = dir.write("big.obj", "");
  ASSERT_EQ(truncate(big.c_str(), (off_t{1} << 30) + 1), 0);
  EXPECT_FALSE(load_obj(big, m, error));
  EXPECT_EQ(error, big + ": cannot open: larger than the 1 GiB limit");
  expect_sentinel(m);
  const std::string obj =
      dir.write("m.obj", "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_FALSE(load_obj(obj, m, error));
  EXPECT_EQ(error, obj + ":1: cannot open material library '/dev/zero': a device, not a file");
  expect_sentinel(m);
  const std::string fifo = dir.file("pipe.obj");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string cmd = "printf 'v 0 0 0\\nv 1 0 0\\nv 0 1 0\\nf 1 2 3\\n' > " + fifo + " &";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  ASSERT_TRUE(load_obj(fifo, m, error)) << error;
  EXPECT_EQ(m.triangles.size(), 1u);
}

TEST(ObjLoaderErrors, LoadObjNamesTheFileAsGiven) {
  TmpDir dir("lr_obj_test");
  const std::string path = dir.write("x.obj", "v 0 0 0\n\nf 1 1 1 \\\n  1 0\n");
  HostMesh m = sentinel();
  std::string error;
  EXPECT_FALSE(load_obj(path, m, error));
  EXPECT_EQ(error, path + ":3: position index 0 is invalid (OBJ indices start at 1)");
  expect_sentinel(m);
}

TEST(ObjLoaderErrors, VeryLongLinesGiveShortMessages) {
  std::string junk(1 << 20, 'z');
  expect_error("v 1 2 " + junk + "\n", "t.obj:1: bad number '" + std::string(40, 'z') + "...'");
  std::string ctrl = "v 1 2 \x01\x02\x7f\n";
  expect_error(ctrl, "t.obj:1: bad number '\?\?\?'");
  // A face with 300000 corners is fine (fanned into 299998 triangles).
  std::string big = std::string(kTri) + "f";
  for (int i = 0; i < 100000; ++i) big += " 1 2 3";
  big += "\n";
  const HostMesh m = parse_ok(big);
  EXPECT_EQ(m.triangles.size(), 299998u);
  EXPECT_EQ(m.positions.size(), 3u);
}

// Mutated variants of a valid file must either load or fail with a "t.obj:LINE: " error; never
// crash (this test is meant to run under ASan + UBSan too).
TEST(ObjLoaderErrors, RandomMutationsNeverCrash) {
  const std::string base =
      "mtllib none.mtl\nv 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 0 1 1 1\n"
      "vt 0 0\nvt 1 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/1/1 4//1\nf -1 -2 -3\n";
  const std::string alphabet = "0123456789-+./ \n\\#eEvnftx\r\t";
  std::mt19937 rng(12345);
  int loaded = 0;
  for (int iter = 0; iter < 3000; ++iter) {
    std::string s = base.substr(16);  // without mtllib, so that some variants load
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const size_t pos = rng() % (s.size() + 1);
      const char c = alphabet[rng() % alphabet.size()];
      switch (rng() % 3) {
        case 0:
          s.insert(pos, 1, c);
          break;
        case 1:
          if (pos < s.size()) s.erase(pos, 1);
          break;
        default:
          if (pos < s.size()) s[pos] = c;
          break;
      }
    }
    HostMesh m;
    std::string error;
    if (parse_obj(s, "t.obj", "/nonexistent-dir", m, error)) {
      ++loaded;
      ASSERT_EQ(m.normals.size(), m.positions.size());
      for (const auto& t : m.triangles) {
        for (uint32_t v : t) ASSERT_LT(v, m.positions.size());
      }
      for (const Vec3d& n : m.normals) {
        ASSERT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-12);
      }
    } else {
      ASSERT_EQ(error.rfind("t.obj:", 0), 0u) << error;
      ASSERT_EQ(error.find('\n'), std::string::npos);
    }
  }
  EXPECT_GT(loaded, 100);
}

// ---------------------------------------------------------------------------------------------
// The project's demo meshes

TEST(ObjLoaderData, DemoMeshesLoad) {
  HostMesh knot, sphere;
  std::string error;
  ASSERT_TRUE(load_obj(kSourceDir + "/tests/host/data/torus_knot.obj", knot, error)) << error;
  EXPECT_EQ(knot.triangles.size(), 4000u);
  EXPECT_EQ(knot.positions.size(), 201u * 11u);
  EXPECT_TRUE(knot.has_uvs());
  ASSERT_TRUE(load_obj(kSourceDir + "/tests/host/data/color_sphere.obj", sphere, error)) << error;
  ASSERT_TRUE(sphere.has_colors());
  EXPECT_EQ(sphere.triangles.size(), 2u * 8u * 5u);
  for (size_t i = 0; i < sphere.positions.size(); ++i) {
    for (size_t c = 0; c < 3; ++c) {
      EXPECT_NEAR(sphere.colors[i][c], 0.5 + 0.5 * sphere.normals[i][c], 2e-6);
    }
  }
}

}  // namespace
}  // namespace lr::host
