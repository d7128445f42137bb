// Scene builders shared by the tests and benchmarks: the ground plane (textured or with vertex
// colours), the procedural test textures and the camera options of the scenes that recur.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "lineraster/host_sim/formats/host_mesh.hpp"
#include "lineraster/host_sim/formats/image_io.hpp"
#include "lineraster/host_sim/scene/scene.hpp"

namespace lr::test {

// The ground plane y = 0: 2 x half units square, two triangles, normals up, the texture repeated
// `repeats` times over it (u along +x, v along -z).
inline host::HostMesh ground_plane(double half, double repeats) {
  host::HostMesh m;
  m.positions = {{-half, 0, -half}, {half, 0, -half}, {half, 0, half}, {-half, 0, half}};
  m.normals.assign(4, {0, 1, 0});
  m.uvs = {{0, repeats}, {repeats, repeats}, {repeats, 0}, {0, 0}};
  m.triangles = {{0, 3, 2}, {0, 2, 1}};
  m.triangle_material = {-1, -1};
  return m;
}

// The same square without texture coordinates, colours varying over its corners (the ground
// plane cut by the near plane: tests/core/clipping_test.cpp).
inline host::HostMesh coloured_ground(double half) {
  host::HostMesh m;
  m.positions = {{-half, 0, -half}, {half, 0, -half}, {half, 0, half}, {-half, 0, half}};
  m.normals.assign(4, {0, 1, 0});
  m.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}};
  m.triangles = {{0, 3, 2}, {0, 2, 1}};
  m.triangle_material = {-1, -1};
  return m;
}

// The ground plane to the horizon seen from about 1 unit above it, looking slightly down, far
// plane 400, unlit. Heights chosen so that no pixel row lands exactly on a texel row boundary (a
// tie that either neighbour may win).
inline host::SceneOptions ground_view() {
  host::SceneOptions o;
  o.eye = {0.0173, 1.0131, 0.0219};
  o.target = {0.0173, 0.7431, -5};
  o.far = 400;
  o.unlit = true;
  return o;
}

// The benchmarks' ground view: the same eye looking level, so the plane fills the lower half of
// the screen up to the horizon. Odd offsets keep pixel centres off texel boundaries.
inline host::SceneOptions level_ground_view() {
  host::SceneOptions o;
  o.eye = {0.0173, 1.0131, 0.0219};
  o.target = {0.0173, 1.0131, -5};
  o.far = 400;
  o.unlit = true;
  return o;
}

// The benchmarks' textured cube: seen from above and in front, turned by 35 degrees about y (the
// top face and two side faces show), back faces culled, one light.
inline host::SceneOptions cube_view() {
  host::SceneOptions o;
  o.eye = {0, 1.5, 2.3};
  o.target = {0, 0, 0};
  o.model_rotate_y = 35;
  o.cull = Cull::kBack;
  o.light_dirs = {{-0.3, 1.0, 0.8}};
  return o;
}

// The UV sphere's lighting: four lights, shininess 96, a bluish global ambient (size left to the
// caller).
inline host::SceneOptions sphere_four_lights() {
  host::SceneOptions o;
  o.light_dirs = {{1, 1, 1}, {-1, 0.5, 0.2}, {0, -1, 1}, {0.3, 0.2, 1}};
  o.material.shininess = 96;
  o.global_ambient = {0.05, 0.05, 0.1};
  o.eye = {0.5, 0.8, 3.2};
  return o;
}

// A lower bound on the pixels the unit sphere covers seen from the eye of sphere_four_lights()
// and phong_sphere() (|eye| = 3.34) in a 240-pixel-high frame: its outline is a circle of
// angular radius asin(1 / 3.34) = 17.4 degrees, 120 tan(17.4) / tan(30) = 65 pixels in radius
// (pi 65^2 > 13200); the outline of a UV sphere of 24 x 32 or more facets lies just inside it.
inline constexpr size_t kUnitSpherePixels = 13000;

// The per-pixel lighting sphere (Phong shading; make_uv_sphere(40, 60)), lit so that nothing
// saturates: a key light, a bluish fill light from the other side, a small global ambient, an
// orange material with a sharp highlight (shininess 64).
inline host::SceneOptions phong_sphere() {
  host::SceneOptions o;
  o.shading = Shading::kPhong;
  o.lights = {{false, {1, 1, 1}, {0.6, 0.6, 0.6}, 1, 0, 0},
              {false, {-1, 0.3, 0.5}, {0.2, 0.25, 0.4}, 1, 0, 0}};
  o.global_ambient = {0.05, 0.05, 0.05};
  o.material.ambient = {0.2, 0.2, 0.2};
  o.material.diffuse = {0.7, 0.5, 0.3};
  o.material.specular = {0.6, 0.6, 0.6};
  o.material.shininess = 64;
  o.eye = {0.5, 0.8, 3.2};
  return o;
}

// A w x h image of distinct colours per texel (row 0 = top of the image file).
inline host::ImageRgb8 pattern(int w, int h) {
  host::ImageRgb8 img;
  img.width = w;
  img.height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      img.rgb.push_back(static_cast<uint8_t>(40 + 200 * x / std::max(1, w - 1)));
      img.rgb.push_back(static_cast<uint8_t>(40 + 200 * y / std::max(1, h - 1)));
      img.rgb.push_back(static_cast<uint8_t>((x * 7 + y * 13) % 2 ? 220 : 30));
    }
  return img;
}

// The benchmarks' texture: 64 x 64, 8 x 8-texel checker cells in two colour ramps, a one-texel
// dark grid line on every cell border and a diagonal stripe: edges for nearest/bilinear, fine
// detail for the mipmaps.
inline host::ImageRgb8 checker64() {
  host::ImageRgb8 img;
  img.width = img.height = 64;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool odd = ((x / 8) + (y / 8)) % 2 != 0;
      int r = odd ? 230 - 2 * y : 40 + 3 * x;
      int g = odd ? 200 - x : 60 + 2 * y;
      int b = odd ? 60 : 220 - 2 * x;
      if (x % 8 == 0 || y % 8 == 0) r = g = b = 20;
      if ((x + y) % 16 == 3) r = g = b = 250;
      img.rgb.push_back(static_cast<uint8_t>(r));
      img.rgb.push_back(static_cast<uint8_t>(g));
      img.rgb.push_back(static_cast<uint8_t>(b));
    }
  return img;
}

}  // namespace lr::test
