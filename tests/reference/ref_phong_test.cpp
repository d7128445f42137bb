// Tests of the reference renderer's per-pixel lighting: point lights with GL attenuation,
// separate light colours, Phong shading, two-sided lighting, sphere environment maps, normal
// maps and the normal interpolation methods (Linear, Slerp, SphereAnalytic).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tests/reference/ref_renderer.hpp"

namespace lr::ref {
namespace {

using host::HostMesh;
using Tri = std::array<uint32_t, 3>;

HostMesh make_mesh(const std::vector<Vec3d>& positions, const std::vector<Tri>& tris,
                   Vec3d normal = {0, 0, 1}) {
  HostMesh m;
  m.positions = positions;
  m.normals.assign(positions.size(), normal);
  m.triangles = tris;
  return m;
}

// 33 x 33 pixels, 60 degrees, looking at the origin: pixel (16, 16)'s centre sees the origin.
RefParams camera_params(Vec3d eye, int size = 33) {
  RefParams p;
  p.width = p.height = size;
  p.view = look_at(eye, {0, 0, 0}, {0, 1, 0});
  p.projection = perspective(60, 1, 1, 100);
  return p;
}

double angle_between(const Vec3d& a, const Vec3d& b) {
  return std::atan2(length(cross(a, b)), dot(a, b));
}

void expect_near3(const Vec3d& a, const Vec3d& b, double tol) {
  for (size_t c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], tol) << "component " << c;
}

RefTexture constant_texture(Vec3d c, int size = 2) {
  RefLevel l;
  l.width = l.height = size;
  l.texels.assign(static_cast<size_t>(size * size), c);
  return RefTexture{{l}};
}

// The world point on the plane z = 0 seen through pixel (i, j)'s centre.
Vec3d unproject_to_z0(const RefParams& p, int i, int j) {
  Mat4d inv;
  EXPECT_TRUE(invert(mul(p.projection, p.view), inv));
  const double xn = 2.0 * (i + 0.5) / p.width - 1.0, yn = 1.0 - 2.0 * (j + 0.5) / p.height;
  auto point = [&](double zn) {
    const Vec4d h = transform(inv, Vec4d{xn, yn, zn, 1.0});
    return Vec3d{h[0] / h[3], h[1] / h[3], h[2] / h[3]};
  };
  const Vec3d a = point(-1.0), b = point(1.0);
  const double s = a[2] / (a[2] - b[2]);
  return add(a, muls(sub(b, a), s));
}

// ---------------------------------------------------------------------------------------------
// Point lights and light colours

TEST(PointLight, AttenuationAtAKnownDistanceGivesTheGlColour) {
  // Light at (3, 0, 4), lit point the origin: d = 5, L = (0.6, 0, 0.8).
  // Attenuation 1 / (0.5 + 0.1 * 5 + 0.02 * 25) = 2/3. Infinite viewer V = (0, 0, 1):
  // H = normalize(0.6, 0, 1.8), (N.H)^2 = 3.24 / 3.6 = 0.9, (N.H)^8 = 0.6561.
  RefParams p = camera_params({0, 0, 5});
  RefLight l;
  l.kind = RefLightKind::Point;
  l.position = {3, 0, 4};
  l.direction = {0, 0, -1};  // ignored by point lights
  l.constant = 0.5;
  l.linear = 0.1;
  l.quadratic = 0.02;
  l.separate_colors = true;
  l.ambient = {0.2, 0.4, 0.6};
  l.diffuse = {1.0, 0.5, 0.25};
  l.specular = {0.5, 0.5, 1.0};
  l.color = {9, 9, 9};  // ignored with separate colours
  p.lights = {l};
  p.global_ambient = {0.1, 0.1, 0.1};
  p.material.ambient = {0.1, 0.2, 0.3};
  p.material.diffuse = {0.8, 0.6, 0.4};
  p.material.specular = {0.5, 0.25, 0.2};
  p.material.emission = {0.01, 0.02, 0.03};
  p.material.shininess = 8;
  const double att = 2.0 / 3.0, ndl = 0.8, spec = 0.6561;
  Vec3d expect{}, primary{}, secondary{};
  for (size_t c = 0; c < 3; ++c) {
    primary[c] =
        p.material.emission[c] + 0.1 * p.material.ambient[c] +
        att * (l.ambient[c] * p.material.ambient[c] + ndl * l.diffuse[c] * p.material.diffuse[c]);
    secondary[c] = att * spec * l.specular[c] * p.material.specular[c];
    expect[c] = primary[c] + secondary[c];
  }
  EXPECT_NEAR(expect[0], 0.01 + 0.01 + att * (0.02 + 0.8 * 0.8) + att * 0.6561 * 0.25, 1e-15);

  const Vec3d got = light_point(p, {0, 0, 1}, {0, 0, 0});
  expect_near3(got, expect, 1e-14);
  const RefLitColor sep = light_point_separate(p, {0, 0, 1}, {0, 0, 0});
  expect_near3(sep.primary, primary, 1e-14);
  expect_near3(sep.secondary, secondary, 1e-14);

  // A point twice as far along the same ray from the light: d = 10, attenuation 1/3.5.
  // (3,0,4) - 2 * (3,0,4) = (-3, 0, -4); with N = L: N.L = 1, N.H = cos(angle(L, V) / 2).
  const Vec3d far_point{-3, 0, -4};
  const Vec3d n = normalize(Vec3d{3, 0, 4});
  const Vec3d h = normalize(add(n, Vec3d{0, 0, 1}));
  const double far_att = 1.0 / (0.5 + 1.0 + 2.0);
  const Vec3d far = light_point(p, n, far_point);
  for (size_t c = 0; c < 3; ++c)
    EXPECT_NEAR(
        far[c],
        p.material.emission[c] + 0.1 * p.material.ambient[c] +
            far_att * (l.ambient[c] * p.material.ambient[c] + l.diffuse[c] * p.material.diffuse[c] +
                       std::pow(dot(n, h), 8) * l.specular[c] * p.material.specular[c]),
        1e-14);

  // Rendered with Phong: pixel (16, 16) is the origin (normal (0, 0, 1) everywhere).
  const HostMesh mesh = make_mesh({{-4, -4, 0}, {4, -4, 0}, {0, 4, 0}}, {{0, 1, 2}});
  p.shading = RefShading::Phong;
  RefFrame f;
  render(mesh, p, f);
  const size_t c = f.index(16, 16);
  ASSERT_EQ(f.owner[c], 0);
  expect_near3(f.color[c], expect, 1e-6);
  expect_near3(f.normal[c], {0, 0, 1}, 1e-12);
}

TEST(PointLight, DirectionalLightsIgnoreTheAttenuationCoefficients) {
  RefParams p = camera_params({0, 0, 5});
  RefLight l{{1, 2, 2}, {1.0, 0.5, 0.25}};
  const Vec3d before = light_point(p, normalize({0.2, 0.1, 1}), {1, 2, 3});
  p.lights = {l};
  const Vec3d plain = light_point(p, normalize({0.2, 0.1, 1}), {1, 2, 3});
  l.constant = 4;
  l.linear = 3;
  l.quadratic = 2;
  l.position = {100, 0, 0};
  p.lights = {l};
  EXPECT_EQ(light_point(p, normalize({0.2, 0.1, 1}), {1, 2, 3}), plain);
  EXPECT_NE(plain, before);
}

TEST(PointLight, SeparateColoursEqualToColorReproduceTheSingleColourLight) {
  RefParams p = camera_params({1, 2, 5});
  p.local_viewer = true;
  p.material.shininess = 20;
  RefLight a{{1, 2, 2}, {1.0, 0.5, 0.25}};
  RefLight b = a;
  b.separate_colors = true;
  b.ambient = b.diffuse = b.specular = a.color;
  b.color = {0, 0, 0};
  const Vec3d n = normalize({0.3, 0.2, 1});
  p.lights = {a};
  const RefLitColor ra = light_point_separate(p, n, {0.5, 0.5, 0});
  p.lights = {b};
  const RefLitColor rb = light_point_separate(p, n, {0.5, 0.5, 0});
  EXPECT_EQ(ra.primary, rb.primary);
  EXPECT_EQ(ra.secondary, rb.secondary);
  EXPECT_GT(ra.secondary[0], 0.01);

  // Only the ambient colour: the ambient term alone, whatever N.L.
  RefLight amb;
  amb.separate_colors = true;
  amb.ambient = {0.5, 0.5, 0.5};
  amb.diffuse = amb.specular = {0, 0, 0};
  p.lights = {amb};
  expect_near3(light_point(p, n, {0, 0, 0}), cmul({0.5, 0.5, 0.5}, p.material.ambient), 1e-15);
}

TEST(PointLight, InverseSquareAttenuation) {
  // Point light 1 above vertex 0 of a plane, attenuation 1 / d^2.
  const HostMesh mesh = make_mesh({{-2, -2, 0}, {2, -2, 0}, {0, 2, 0}}, {{0, 1, 2}});
  RefParams p = camera_params({0, 0, 5});
  RefLight l;
  l.kind = RefLightKind::Point;
  l.position = {-2, -2, 1};
  l.quadratic = 1;
  l.constant = 0;
  p.lights = {l};
  p.material.specular = {0, 0, 0};
  const Vec3d c0 = light_point(p, {0, 0, 1}, {-2, -2, 0});
  const Vec3d c1 = light_point(p, {0, 0, 1}, {2, -2, 0});
  // d = 1 at vertex 0: N.L = 1, attenuation 1: 0.1 + 0.8.
  EXPECT_NEAR(c0[0], 0.9, 1e-15);
  // d = sqrt(17) at vertex 1: N.L = 1/sqrt(17), attenuation 1/17.
  EXPECT_NEAR(c1[0], (0.1 + 0.8 / std::sqrt(17.0)) / 17.0, 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Phong shading

// A large triangle whose vertex normals lean outwards, away from a point light just above its
// centre, while the interpolated normal in the middle points straight at it.
HostMesh leaning_triangle() {
  HostMesh m;
  for (int k = 0; k < 3; ++k) {
    const double a = (90.0 + 120.0 * k) * kPi / 180.0;
    m.positions.push_back({3 * std::cos(a), 3 * std::sin(a), 0});
    m.normals.push_back(normalize({std::cos(a), std::sin(a), 0.1}));
  }
  m.triangles = {{0, 1, 2}};
  return m;
}

TEST(Phong, HighlightInsideATriangleWhoseVerticesFaceAway) {
  const HostMesh mesh = leaning_triangle();
  RefParams p = camera_params({0, 0, 5});
  RefLight l;
  l.kind = RefLightKind::Point;
  l.position = {0, 0, 1};
  l.color = {1, 1, 1};
  p.lights = {l};
  p.material.ambient = {0.1, 0.1, 0.1};
  p.material.diffuse = {0.5, 0.5, 0.5};
  p.material.specular = {0.3, 0.3, 0.3};
  p.material.shininess = 32;
  // Every vertex faces away from the light: N.L < 0.
  for (size_t v = 0; v < 3; ++v)
    EXPECT_LT(dot(mesh.normals[v], sub(l.position, mesh.positions[v])), 0.0);

  RefFrame gouraud, phong;
  p.shading = RefShading::Gouraud;
  render(mesh, p, gouraud);
  p.shading = RefShading::Phong;
  render(mesh, p, phong);
  const size_t c = phong.index(16, 16);
  ASSERT_EQ(phong.owner[c], 0);
  ASSERT_EQ(gouraud.owner[c], 0);
  // Gouraud: the ambient term everywhere.
  for (size_t i = 0; i < gouraud.owner.size(); ++i) {
    if (gouraud.owner[i] == 0) {
      EXPECT_NEAR(gouraud.color[i][0], 0.1, 1e-12);
    }
  }
  // Phong: N = L = H = (0, 0, 1) at the centre: ambient + diffuse + specular = 0.9.
  EXPECT_NEAR(phong.color[c][0], 0.9, 1e-4);
  expect_near3(phong.normal[c], {0, 0, 1}, 1e-3);
  EXPECT_EQ(gouraud.normal[c], (Vec3d{0, 0, 0}));  // RefFrame::normal: Phong fragments only
  // The highlight falls off away from the centre.
  EXPECT_LT(phong.color[phong.index(16, 8)][0], 0.5);
  EXPECT_NEAR(phong.color[phong.index(16, 24)][0], 0.1, 1e-12);  // beyond the light's horizon
}

TEST(Phong, PositionsArePerspectiveCorrectEvenWhenClipped) {
  // A huge ground plane crossing the near plane, lit by a point light near the camera: every
  // pixel's colour is the lighting at the world point its ray hits.
  const HostMesh mesh = make_mesh({{-100, -100, 0}, {100, -100, 0}, {100, 100, 0}, {-100, 100, 0}},
                                  {{0, 1, 2}, {0, 2, 3}});
  RefParams p;
  p.width = 48;
  p.height = 32;
  p.view = look_at({0, -3, 1}, {0, 5, 0}, {0, 0, 1});
  p.projection = perspective(70, 1.5, 0.5, 50);
  RefLight l;
  l.kind = RefLightKind::Point;
  l.position = {1, 0, 0.5};
  l.linear = 0.5;
  p.lights = {l};
  p.material.shininess = 10;
  p.local_viewer = true;
  p.shading = RefShading::Phong;
  RefFrame f;
  render(mesh, p, f);
  int checked = 0;
  for (int j = 0; j < p.height; ++j)
    for (int i = 0; i < p.width; ++i) {
      const size_t px = f.index(i, j);
      if (f.owner[px] < 0) continue;
      const Vec3d w = unproject_to_z0(p, i, j);
      const Vec3d expect = light_point(p, {0, 0, 1}, w);
      for (size_t ch = 0; ch < 3; ++ch)
        ASSERT_NEAR(f.color[px][ch], expect[ch], 2e-3) << i << "," << j;
      ++checked;
    }
  EXPECT_GT(checked, 600);
  // The near plane cut the plane: the bottom rows see the ground right below the camera.
  EXPECT_GE(f.owner[f.index(24, 31)], 0);
}

TEST(Phong, EqualNormalsAndDirectionalLightsMatchGouraud) {
  HostMesh mesh =
      make_mesh({{-2, -2, 0.5}, {2, -2, -0.5}, {0, 2, 0}}, {{0, 1, 2}}, normalize({0.2, -0.1, 1}));
  RefParams p = camera_params({1, -1, 4});
  p.lights = {RefLight{{1, 2, 2}, {1.0, 0.8, 0.6}}, RefLight{{-1, 0, 1}, {0.2, 0.3, 0.4}}};
  p.material.shininess = 12;
  p.global_ambient = {0.05, 0.05, 0.05};
  RefFrame g, ph;
  render(mesh, p, g);
  p.shading = RefShading::Phong;
  render(mesh, p, ph);
  int n = 0;
  for (size_t i = 0; i < g.owner.size(); ++i) {
    ASSERT_EQ(g.owner[i], ph.owner[i]);
    if (g.owner[i] < 0) continue;
    ++n;
    expect_near3(ph.color[i], g.color[i], 1e-12);
  }
  EXPECT_GT(n, 100);

  // Textured: texel * primary + secondary, like Gouraud's.
  const RefTexture tex = constant_texture({0.5, 0.75, 1.0});
  p.texture = &tex;
  p.shading = RefShading::Gouraud;
  render(mesh, p, g);
  p.shading = RefShading::Phong;
  render(mesh, p, ph);
  for (size_t i = 0; i < g.owner.size(); ++i)
    if (g.owner[i] >= 0) {
      expect_near3(ph.color[i], g.color[i], 1e-12);
      EXPECT_EQ(ph.lod[i], g.lod[i]);
    }
}

TEST(Phong, UnlitPhongShadesLikeUnlitGouraud) {
  HostMesh mesh = make_mesh({{-2, -2, 0}, {2, -2, 0}, {0, 2, 0}}, {{0, 1, 2}});
  mesh.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  RefParams p = camera_params({0, 0, 5});
  p.unlit = true;
  RefFrame g, ph;
  render(mesh, p, g);
  p.shading = RefShading::Phong;
  render(mesh, p, ph);
  EXPECT_EQ(g.color, ph.color);
  const size_t c = ph.index(16, 16);
  expect_near3(ph.normal[c], {0, 0, 1}, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Two-sided lighting

TEST(TwoSided, BackFacesAreLitWithTheNegatedNormal) {
  // Clockwise as seen from the camera: a back face whose normal points away from the viewer
  // (and from the light, which is on the viewer's side).
  const HostMesh back = make_mesh({{-2, -2, 0}, {0, 2, 0}, {2, -2, 0}}, {{0, 1, 2}}, {0, 0, -1});
  const HostMesh front = make_mesh({{-2, -2, 0}, {2, -2, 0}, {0, 2, 0}}, {{0, 1, 2}}, {0, 0, 1});
  RefParams p = camera_params({0, 0, 5});
  p.lights = {RefLight{{0, 0, 1}, {1, 1, 1}}};
  p.material.ambient = {0.1, 0.1, 0.1};
  p.material.diffuse = {0.5, 0.5, 0.5};
  p.material.specular = {0.25, 0.25, 0.25};
  // Global ambient 0; lit straight on: La Ka + Ld Kd + Ls Ks = 0.1 + 0.5 + 0.25 = 0.85.
  const RefTexture normal_flat = constant_texture({0.5, 0.5, 1.0});
  for (RefShading s : {RefShading::Flat, RefShading::Gouraud, RefShading::Phong}) {
    for (bool use_map : {false, true}) {
      if (use_map && s != RefShading::Phong) continue;
      SCOPED_TRACE(static_cast<int>(s) * 10 + use_map);
      p.shading = s;
      p.normal_map = use_map ? &normal_flat : nullptr;
      HostMesh b = back;
      if (use_map) {
        b.uvs.assign(3, {0.5, 0.5});
        b.tangents.assign(3, {1, 0, 0, 1});
      }
      RefFrame f;
      p.two_sided = false;
      render(b, p, f);
      const size_t c = f.index(16, 16);
      ASSERT_EQ(f.owner[c], 0);
      EXPECT_NEAR(f.color[c][0], 0.1, 1e-12);  // ambient only
      p.two_sided = true;
      render(b, p, f);
      EXPECT_NEAR(f.color[c][0], 0.85, 1e-12);  // N = (0, 0, 1): everything
      if (s == RefShading::Phong) expect_near3(f.normal[c], {0, 0, 1}, 1e-12);

      // Front faces: unchanged by two_sided, bit for bit.
      RefFrame f1, f2;
      p.two_sided = false;
      render(front, p, f1);
      p.two_sided = true;
      render(front, p, f2);
      EXPECT_EQ(f1.color, f2.color);
      EXPECT_NEAR(f1.color[c][0], 0.85, 1e-12);
    }
  }
  p.normal_map = nullptr;

  // Textured Gouraud keeps the separate specular on back faces too.
  const RefTexture tex = constant_texture({0.5, 0.5, 0.5});
  HostMesh b = back;
  b.uvs.assign(3, {0.5, 0.5});
  p.texture = &tex;
  p.shading = RefShading::Gouraud;
  p.two_sided = true;
  RefFrame f;
  render(b, p, f);
  EXPECT_NEAR(f.color[f.index(16, 16)][0], 0.5 * 0.6 + 0.25, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Sphere environment map

// A map of `size` x `size` texels: black except the 2 x 2 centre texels, which are c.
RefTexture centre_spot_map(Vec3d c, int size = 4) {
  RefLevel l;
  l.width = l.height = size;
  l.texels.assign(static_cast<size_t>(size * size), Vec3d{0, 0, 0});
  for (int j = size / 2 - 1; j <= size / 2; ++j)
    for (int i = size / 2 - 1; i <= size / 2; ++i) l.texels[static_cast<size_t>(j * size + i)] = c;
  return RefTexture{{l}};
}

// 1 x 64 texels whose value is the texel centre's v: bilinear lookups return v itself.
RefTexture vertical_ramp_map() {
  RefLevel l;
  l.width = 1;
  l.height = 64;
  for (int j = 0; j < 64; ++j) {
    const double v = (j + 0.5) / 64.0;
    l.texels.push_back({v, v, v});
  }
  return RefTexture{{l}};
}

RefParams emissive_phong(Vec3d eye) {
  RefParams p = camera_params(eye);
  p.shading = RefShading::Phong;
  p.material.emission = {1, 1, 1};  // primary = 1, secondary = 0: the colour is the env texel
  p.material.ambient = p.material.diffuse = p.material.specular = {0, 0, 0};
  return p;
}

TEST(EnvMap, ReflectionStraightBackAtTheViewerHitsTheMapCentre) {
  // N = V = (0, 0, 1): r = (0, 0, 1), m = 4, (s, t) = (0.5, 0.5).
  const HostMesh mesh = make_mesh({{-4, -4, 0}, {4, -4, 0}, {0, 4, 0}}, {{0, 1, 2}});
  const RefTexture env = centre_spot_map({0.9, 0.6, 0.3}, 16);
  RefParams p = emissive_phong({0, 0, 5});
  p.envmap = &env;
  RefFrame f;
  render(mesh, p, f);
  int n = 0;
  for (size_t i = 0; i < f.owner.size(); ++i)
    if (f.owner[i] == 0) {
      ++n;
      expect_near3(f.color[i], {0.9, 0.6, 0.3}, 1e-12);  // infinite viewer: the same everywhere
    }
  EXPECT_GT(n, 300);

  // Local viewer: only the pixel straight below the eye reflects back along the view axis.
  p.local_viewer = true;
  render(mesh, p, f);
  expect_near3(f.color[f.index(16, 16)], {0.9, 0.6, 0.3}, 1e-6);
  EXPECT_LT(f.color[f.index(2, 16)][0], 0.5);

  // With a base texture and lighting: clamp(texel * env * primary + secondary).
  const RefTexture base = constant_texture({0.5, 1.0, 1.0});
  HostMesh tm = mesh;
  tm.uvs.assign(3, {0.5, 0.5});
  p.local_viewer = false;
  p.texture = &base;
  p.lights = {RefLight{{0, 0, 1}, {1, 1, 1}}};
  p.material.emission = {0, 0, 0};
  p.material.ambient = {0.1, 0.1, 0.1};
  p.material.diffuse = {0.5, 0.5, 0.5};
  p.material.specular = {0.2, 0.2, 0.2};
  render(tm, p, f);
  const Vec3d prim{0.6, 0.6, 0.6}, sec{0.2, 0.2, 0.2};
  const Vec3d expect = add(cmul(cmul({0.5, 1.0, 1.0}, {0.9, 0.6, 0.3}), prim), sec);
  expect_near3(f.color[f.index(16, 16)], expect, 1e-12);
}

TEST(EnvMap, TiltedNormalReflectsToTheAnalyticSphereMapCoordinate) {
  // N = (0, sin 30, cos 30), V = (0, 0, 1): r = (0, sin 60, cos 60), m = 4 cos 30,
  // t = sin 30 / 2 + 0.5 = 0.75; s = 0.5.
  const RefTexture env = vertical_ramp_map();
  const double th = 30.0 * kPi / 180.0;
  const HostMesh mesh =
      make_mesh({{-4, -4, 0}, {4, -4, 0}, {0, 4, 0}}, {{0, 1, 2}}, {0, std::sin(th), std::cos(th)});
  RefParams p = emissive_phong({0, 0, 5});
  p.envmap = &env;
  RefFrame f;
  render(mesh, p, f);
  EXPECT_NEAR(f.color[f.index(16, 16)][0], 0.75, 1e-12);

  // The same in a rotated view: the reflection is taken to eye space by the view matrix, so
  // rotating the camera and the mesh together changes nothing.
  p.view = mul(look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0}), rotate_z(-90));
  p.model = rotate_z(90);
  render(mesh, p, f);
  EXPECT_NEAR(f.color[f.index(16, 16)][0], 0.75, 1e-12);

  // N perpendicular to V: r = -V, m = 0: the map's centre (0.5, 0.5).
  const HostMesh side = make_mesh({{-4, -4, 0}, {4, -4, 0}, {0, 4, 0}}, {{0, 1, 2}}, {0, 1, 0});
  p.view = look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  p.model = identity();
  render(side, p, f);
  EXPECT_NEAR(f.color[f.index(16, 16)][0], 0.5, 1e-12);
}

TEST(EnvMap, IgnoredOutsideLitPhong) {
  const HostMesh mesh = make_mesh({{-4, -4, 0}, {4, -4, 0}, {0, 4, 0}}, {{0, 1, 2}});
  const RefTexture env = centre_spot_map({0.5, 0.5, 0.5});
  RefParams p = emissive_phong({0, 0, 5});
  p.shading = RefShading::Gouraud;
  RefFrame a, b;
  render(mesh, p, a);
  p.envmap = &env;
  render(mesh, p, b);
  EXPECT_EQ(a.color, b.color);
}

// ---------------------------------------------------------------------------------------------
// Normal maps

// A curved patch (normals differ per vertex) with uvs and tangents.
HostMesh curved_patch() {
  HostMesh m;
  m.positions = {{-2, -2, 0}, {2, -2, 0.3}, {2, 2, 0}, {-2, 2, -0.3}};
  m.normals = {normalize({-0.3, -0.3, 1}), normalize({0.4, -0.2, 1}), normalize({0.3, 0.3, 1}),
               normalize({-0.2, 0.4, 1})};
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  m.tangents = {{1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TEST(NormalMap, FlatMapEqualsPlainPhong) {
  const HostMesh mesh = curved_patch();
  const RefTexture nmap = constant_texture({0.5, 0.5, 1.0});  // tn = (0, 0, 1): N' = N
  RefParams p = camera_params({0.5, -1, 5});
  p.lights = {RefLight{{1, 1, 2}, {1, 1, 1}}};
  p.material.shininess = 40;
  p.shading = RefShading::Phong;
  RefFrame plain, mapped;
  render(mesh, p, plain);
  p.normal_map = &nmap;
  render(mesh, p, mapped);
  int n = 0;
  for (size_t i = 0; i < plain.owner.size(); ++i) {
    ASSERT_EQ(plain.owner[i], mapped.owner[i]);
    if (plain.owner[i] < 0) continue;
    ++n;
    expect_near3(mapped.color[i], plain.color[i], 1e-12);
    expect_near3(mapped.normal[i], plain.normal[i], 1e-12);
  }
  EXPECT_GT(n, 400);
}

TEST(NormalMap, TangentBitangentAndHandedness) {
  HostMesh mesh = make_mesh({{-4, -4, 0}, {4, -4, 0}, {0, 4, 0}}, {{0, 1, 2}});
  mesh.uvs = {{0, 0}, {1, 0}, {0.5, 1}};
  mesh.tangents.assign(3, {2, 0, 0, 1});  // normalized by the renderer
  RefParams p = camera_params({0, 0, 5});
  p.shading = RefShading::Phong;
  p.lights = {RefLight{{1, 0, 0}, {1, 1, 1}}};
  p.material.ambient = {0, 0, 0};
  p.material.specular = {0, 0, 0};
  p.material.diffuse = {1, 1, 1};
  const size_t c = static_cast<size_t>(16 * 33 + 16);
  RefFrame f;

  const RefTexture along_t = constant_texture({1.0, 0.5, 0.5});  // tn = (1, 0, 0): N' = T
  p.normal_map = &along_t;
  render(mesh, p, f);
  expect_near3(f.normal[c], {1, 0, 0}, 1e-12);
  EXPECT_NEAR(f.color[c][0], 1.0, 1e-12);  // N'.L = 1

  const RefTexture along_b = constant_texture({0.5, 1.0, 0.5});  // tn = (0, 1, 0): N' = B
  p.normal_map = &along_b;
  render(mesh, p, f);
  expect_near3(f.normal[c], {0, 1, 0}, 1e-12);  // B = cross((0,0,1), (1,0,0))
  EXPECT_NEAR(f.color[c][0], 0.0, 1e-12);
  // Handedness -1 (taken from the triangle's first vertex): B flips.
  mesh.tangents[0][3] = -1;
  render(mesh, p, f);
  expect_near3(f.normal[c], {0, -1, 0}, 1e-12);
  mesh.tangents[0][3] = 1;
  mesh.tangents[1][3] = -1;  // other vertices' handedness is not consulted
  render(mesh, p, f);
  expect_near3(f.normal[c], {0, 1, 0}, 1e-12);
  mesh.tangents[1][3] = 1;

  // Tangents follow the model matrix: rotated 90 degrees about z, T = (0, 1, 0), and
  // B = cross(N, T) = (-1, 0, 0).
  p.model = rotate_z(90);
  render(mesh, p, f);
  expect_near3(f.normal[c], {-1, 0, 0}, 1e-12);

  // A diagonal map value: tn = (0.6, 0, 0.8), N' = 0.6 T + 0.8 N.
  p.model = identity();
  const RefTexture tilted = constant_texture({0.8, 0.5, 0.9});
  p.normal_map = &tilted;
  render(mesh, p, f);
  expect_near3(f.normal[c], normalize({0.6, 0, 0.8}), 1e-12);
  EXPECT_NEAR(f.color[c][0], 0.6, 1e-12);

  // A tangent that is not orthogonal to N is made so (Gram-Schmidt) before use.
  mesh.tangents.assign(3, {1, 0, 1, 1});
  p.normal_map = &along_t;
  render(mesh, p, f);
  expect_near3(f.normal[c], {1, 0, 0}, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Normal interpolation methods

TEST(NormalInterp, SlerpEqualsLinearWhereAllNormalsAreEqual) {
  const HostMesh mesh =
      make_mesh({{-2, -2, 0.5}, {2, -2, -0.5}, {0, 2, 0}}, {{0, 1, 2}}, normalize({0.3, -0.2, 1}));
  RefParams p = camera_params({1, -1, 4});
  p.lights = {RefLight{{1, 2, 2}, {1, 1, 1}}};
  p.local_viewer = true;
  p.shading = RefShading::Phong;
  RefFrame lin, sl;
  render(mesh, p, lin);
  p.normal_interp = RefNormalInterp::Slerp;
  render(mesh, p, sl);
  int n = 0;
  for (size_t i = 0; i < lin.owner.size(); ++i)
    if (lin.owner[i] >= 0) {
      ++n;
      expect_near3(sl.normal[i], lin.normal[i], 1e-12);
      expect_near3(sl.color[i], lin.color[i], 1e-12);
    }
  EXPECT_GT(n, 100);
}

TEST(NormalInterp, SlerpTurnsTheNormalAtAConstantRatePerPixelAlongARow) {
  // Orthographic (identity matrices): vertex normals (0,0,1) on the left edge and (1,0,0) at
  // the right vertex; every pixel normal lies in the xz plane at angle phi from (0,0,1), and
  // along a row phi grows linearly with x with Slerp (not with Linear).
  HostMesh mesh;
  mesh.positions = {{-0.9, -0.9, 0}, {0.9, -0.9, 0}, {-0.9, 0.9, 0}};
  mesh.normals = {{0, 0, 1}, {1, 0, 0}, {0, 0, 1}};
  mesh.triangles = {{0, 1, 2}};
  RefParams p;
  p.width = p.height = 64;
  p.shading = RefShading::Phong;
  p.lights = {RefLight{{0, 0, 1}, {1, 1, 1}}};
  for (RefNormalInterp mode : {RefNormalInterp::Slerp, RefNormalInterp::Linear}) {
    p.normal_interp = mode;
    RefFrame f;
    render(mesh, p, f);
    double worst_second_diff = 0;
    for (int j = 10; j < 54; ++j) {
      std::vector<double> phi;
      for (int i = 0; i < 64; ++i) {
        const size_t px = f.index(i, j);
        if (f.owner[px] < 0) continue;
        const Vec3d& n = f.normal[px];
        EXPECT_NEAR(n[1], 0.0, 1e-12);
        EXPECT_NEAR(length(n), 1.0, 1e-12);
        phi.push_back(std::atan2(n[0], n[2]));
      }
      for (size_t k = 2; k < phi.size(); ++k)
        worst_second_diff =
            std::max(worst_second_diff, std::fabs(phi[k] - 2 * phi[k - 1] + phi[k - 2]));
    }
    if (mode == RefNormalInterp::Slerp)
      EXPECT_LT(worst_second_diff, 1e-12);
    else
      EXPECT_GT(worst_second_diff, 1e-4);
  }
}

TEST(NormalInterp, SphereAnalyticGivesTheExactSphereNormal) {
  // Orthographic view of a triangle inscribed in the unit sphere: the pixel at NDC (x, y) sees
  // the plane point (x, y, z(x, y)), whose exact sphere normal is its normalized position.
  // SphereAnalytic ignores the mesh normals (here all (0, 0, 1)). Linear with vertex normals =
  // positions is exact too (perspective-correct interpolation of the normals is the
  // interpolation of the positions); Slerp, in screen space, is not.
  HostMesh mesh;
  mesh.positions = {normalize({-0.6, -0.5, 0.6}), normalize({0.7, -0.4, 0.5}),
                    normalize({0.0, 0.7, 0.7})};
  mesh.normals.assign(3, {0, 0, 1});
  mesh.triangles = {{0, 1, 2}};
  HostMesh sphere_normals = mesh;
  sphere_normals.normals = mesh.positions;
  const Vec3d& a = mesh.positions[0];
  const Vec3d plane_n = cross(sub(mesh.positions[1], a), sub(mesh.positions[2], a));
  RefParams p;
  p.width = p.height = 64;
  p.shading = RefShading::Phong;
  p.lights = {RefLight{{0, 0, 1}, {1, 1, 1}}};
  RefFrame exact, lin, sl;
  for (double rot : {0.0, 30.0}) {
    p.model = rotate_z(rot);
    p.normal_interp = RefNormalInterp::SphereAnalytic;
    render(mesh, p, exact);
    p.normal_interp = RefNormalInterp::Linear;
    render(sphere_normals, p, lin);
    p.normal_interp = RefNormalInterp::Slerp;
    render(sphere_normals, p, sl);
    double worst_exact = 0, worst_lin = 0, worst_slerp = 0;
    int n = 0;
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i) {
        const size_t px = exact.index(i, j);
        if (exact.owner[px] < 0) continue;
        ++n;
        // World NDC point back to model space (rotation about z only), then onto the plane.
        const Vec3d wp{2.0 * (i + 0.5) / 64 - 1.0, 1.0 - 2.0 * (j + 0.5) / 64, 0};
        Vec3d mp = transform_point(rotate_z(-rot), wp);
        mp[2] = a[2] - (plane_n[0] * (mp[0] - a[0]) + plane_n[1] * (mp[1] - a[1])) / plane_n[2];
        const Vec3d expect = transform_dir(p.model, normalize(mp));
        worst_exact = std::max(worst_exact, angle_between(exact.normal[px], expect));
        worst_lin = std::max(worst_lin, angle_between(lin.normal[px], exact.normal[px]));
        worst_slerp = std::max(worst_slerp, angle_between(sl.normal[px], expect));
      }
    EXPECT_GT(n, 300);
    EXPECT_LT(worst_exact, 1e-3);  // vertex snapping to 1/256 pixel only
    EXPECT_LT(worst_lin, 1e-12);
    EXPECT_GT(worst_slerp, 10 * worst_exact);
  }
}

TEST(RefFrameNormal, ZeroWhereNoPhongFragmentWasWritten) {
  const HostMesh mesh = make_mesh({{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}, {{0, 1, 2}});
  RefParams p = camera_params({0, 0, 5});
  p.shading = RefShading::Phong;
  RefFrame f;
  render(mesh, p, f);
  ASSERT_EQ(f.normal.size(), f.owner.size());
  int drawn = 0;
  for (size_t i = 0; i < f.owner.size(); ++i) {
    if (f.owner[i] < 0) {
      EXPECT_EQ(f.normal[i], (Vec3d{0, 0, 0}));
    } else {
      ++drawn;
      expect_near3(f.normal[i], {0, 0, 1}, 1e-12);
    }
  }
  EXPECT_GT(drawn, 20);
}

}  // namespace
}  // namespace lr::ref
