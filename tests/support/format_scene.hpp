// A scene that goes through every family of span routines, for tests that render it into more
// than one pixel format or sink: a Gouraud-lit sphere with specular highlights, a cube with an
// RGB565 texture replaced (stored raw in RGB565 formats) and one modulated by the lit colour, a
// Phong-shaded sphere, a flat-shaded unlit cube, and a small lit cube that moves (build's x, y).
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/support/scenes.hpp"

namespace lr::test {

// A host mesh in the core's formats.
struct FixedMesh {
  std::vector<Vec3> positions;
  std::vector<Normal16> normals;
  std::vector<TexCoord> uvs;
  std::vector<std::array<uint16_t, 3>> triangles;
  Mesh mesh() const { return Mesh{positions, normals, {}, uvs, triangles}; }
};

inline Fixed fx(double v) {
  Fixed f;
  EXPECT_TRUE(host::to_fixed(v, f)) << v;
  return f;
}
inline Vec3 v3(double x, double y, double z) {
  return {fx(x), fx(y), fx(z)};
}

inline FixedMesh to_fixed_mesh(const host::HostMesh& h) {
  FixedMesh m;
  for (const auto& p : h.positions) m.positions.push_back(v3(p[0], p[1], p[2]));
  auto q14 = [](double v) { return static_cast<int16_t>(std::lround(v * 16384.0)); };
  for (const auto& n : h.normals) m.normals.push_back(Normal16{q14(n[0]), q14(n[1]), q14(n[2])});
  for (const auto& uv : h.uvs) {
    TexCoord t;
    EXPECT_TRUE(host::to_texcoord(uv, t));
    m.uvs.push_back(t);
  }
  for (const auto& t : h.triangles)
    m.triangles.push_back(
        {static_cast<uint16_t>(t[0]), static_cast<uint16_t>(t[1]), static_cast<uint16_t>(t[2])});
  return m;
}

// Capacities with room for the scene's draws (Phong surfaces, textured vertices, lights).
inline FrameCapacities format_scene_capacities(int width, int height, int k, bool skipping) {
  return FrameCapacities{.width = width,
                         .height = height,
                         .strip_height = k,
                         .vertices = 4096,
                         .triangles = 4096,
                         .draws = 16,
                         .active = 256,
                         .surfaces = 4096,
                         .pixel_lights = 8,
                         .tex_vertices = 4096,
                         .active_extra = 256,
                         .triangle_colors = 4096,
                         .strip_skipping = skipping};
}

struct FormatScene {
  FixedMesh sphere = to_fixed_mesh(host::make_uv_sphere(12, 18));
  FixedMesh cube = to_fixed_mesh(host::make_cube());
  host::HostTexture texture;
  Camera camera;
  LightSet lights;
  Rgb8 background{16, 24, 48};

  FormatScene(int width, int height) {
    std::string err;
    EXPECT_TRUE(
        host::texture_from_image(pattern(16, 16), TexelFormat::kRgb565, false, texture, err))
        << err;
    EXPECT_TRUE(
        perspective(fx(60), fx(double(width) / height), fx(0.1), fx(50), camera.projection));
    camera.eye = v3(0, 0, 4);
    EXPECT_TRUE(look_at(camera.eye, v3(0, 0, 0), v3(0, 1, 0), camera.view));
    lights.lights[0] = Light::directional(v3(0.5, 1, 1), Color15{32768, 32768, 32768});
    lights.lights[1] = Light::directional(v3(-1, -0.2, 0.4), Color15{8192, 12000, 20000});
    lights.count = 2;
  }

  // Begins a frame and draws the scene, the small cube at (x, y).
  template <class R>
  void build(R& renderer, double x = -0.8, double y = 0.6) const {
    ASSERT_EQ(renderer.begin_frame(camera, lights, background), Status::kOk);
    Material shiny;
    shiny.specular = Color15{16384, 16384, 16384};
    shiny.shininess_q8 = 32 * 256;
    DrawState gouraud;
    gouraud.cull = Cull::kBack;
    ASSERT_EQ(
        renderer.draw(sphere.mesh(), translate(v3(-1.1, 0.3, 0)) * scale(fx(0.8)), shiny, gouraud),
        Status::kOk);
    DrawState phong = gouraud;
    phong.shading = Shading::kPhong;
    ASSERT_EQ(
        renderer.draw(sphere.mesh(), translate(v3(1.1, 0.5, 0)) * scale(fx(0.7)), shiny, phong),
        Status::kOk);
    DrawState replaced;
    replaced.texture = &texture.texture;
    replaced.cull = Cull::kBack;
    replaced.sampler.env = TexEnv::kReplace;
    ASSERT_EQ(renderer.draw(cube.mesh(),
                            translate(v3(1.0, -0.8, -0.5)) * rotate_y(fx(30)) * scale(fx(0.5)),
                            Material{}, replaced),
              Status::kOk);
    DrawState modulated = replaced;
    modulated.sampler.env = TexEnv::kModulate;
    modulated.sampler.filter = Filter::kBilinear;
    ASSERT_EQ(renderer.draw(cube.mesh(),
                            translate(v3(-0.9, -0.9, 0)) * rotate_y(fx(-25)) * scale(fx(0.5)),
                            shiny, modulated),
              Status::kOk);
    DrawState flat;
    flat.shading = Shading::kFlat;
    flat.lighting = false;
    Material kd;
    kd.diffuse = Color15{30000, 9000, 4000};
    ASSERT_EQ(renderer.draw(cube.mesh(), translate(v3(0, -0.2, -1)) * scale(fx(0.3)), kd, flat),
              Status::kOk);
    ASSERT_EQ(renderer.draw(cube.mesh(), translate(v3(x, y, 1)) * scale(fx(0.15)), shiny, gouraud),
              Status::kOk);
  }
};

}  // namespace lr::test
