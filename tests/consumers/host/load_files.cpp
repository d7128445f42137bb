// lr::host from an installed package: the project's textured cube (OBJ + MTL), its PNG texture
// and a JPEG, each loaded with the host library and checked against what the files hold.
//   load_files DATA_DIR JPEG   (DATA_DIR: tests/host/data; JPEG: a 16x8 RGB JPEG)
// Prints what it found; exits 1 on the first difference.
#include <cstdio>
#include <lineraster/host_sim/formats/jpeg_io.hpp>
#include <lineraster/host_sim/formats/obj_loader.hpp>
#include <lineraster/host_sim/formats/texture_load.hpp>
#include <string>

namespace {

int failures = 0;
void expect(bool ok, const std::string& what) {
  std::printf("%s: %s\n", ok ? "ok  " : "FAIL", what.c_str());
  failures += ok ? 0 : 1;
}
bool ends_with(const std::string& s, const std::string& end) {
  return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}
bool is(const lr::Rgb8& c, int r, int g, int b) {
  return c.r == r && c.g == g && c.b == b;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: load_files DATA_DIR JPEG\n");
    return 2;
  }
  const std::string data = argv[1];
  std::printf("%d installed headers compiled\n", LR_INSTALLED_HEADERS);

  // cube.obj: 6 quads of 4 corners each (per-face normals and uvs: no corner shared), cube_red
  // on the first 4, cube_white (map_Kd checker.png) on the last 2.
  lr::host::HostMesh mesh;
  std::string error;
  expect(lr::host::load_obj(data + "/cube.obj", mesh, error), "load_obj cube.obj " + error);
  expect(mesh.positions.size() == 24 && mesh.triangles.size() == 12 && mesh.uvs.size() == 24,
         "24 vertices with uvs, 12 triangles");
  expect(mesh.materials.size() == 2 && mesh.materials[0].name == "cube_red" &&
             mesh.materials[1].name == "cube_white",
         "materials cube_red, cube_white (cube.mtl)");
  expect(mesh.triangle_material.size() == 12 && mesh.triangle_material[0] == 0 &&
             mesh.triangle_material[7] == 0 && mesh.triangle_material[8] == 1 &&
             mesh.triangle_material[11] == 1,
         "triangles 0-7 cube_red, 8-11 cube_white");
  expect(mesh.materials.size() == 2 && mesh.materials[0].diffuse[0] == 0.8 &&
             mesh.materials[0].diffuse[1] == 0.1 && mesh.materials[0].shininess == 32,
         "cube_red: Kd 0.8 0.1 0.1, Ns 32");
  const std::string map = mesh.materials.size() == 2 ? mesh.materials[1].map_kd : "";
  expect(ends_with(map, "checker.png"), "cube_white's map_Kd: " + map);

  // checker.png: 8x8 of 2x2 cells, (230, 230, 230) at the top-left, (40, 40, 160) beside it;
  // texture rows are stored bottom row first.
  lr::host::HostTexture texture;
  expect(lr::host::load_texture(map, lr::TexelFormat::kRgb888, false, texture, error),
         "load_texture " + error);
  const lr::Texture& t = texture.texture;
  expect(t.level_count == 1 && t.levels[0].width == 8 && t.levels[0].height == 8,
         "the texture is 8x8, one level");
  expect(is(lr::host::texel_rgb8(t, 0, 0, 7), 230, 230, 230) &&
             is(lr::host::texel_rgb8(t, 0, 2, 7), 40, 40, 160) &&
             is(lr::host::texel_rgb8(t, 0, 0, 0), 40, 40, 160),
         "texels: top-left light, (2, top) and bottom-left blue");

  // A JPEG through libjpeg, which the installed lr::host links.
  lr::host::ImageRgb8 jpeg;
  expect(lr::host::jpeg_supported(), "the package was built with JPEG support");
  expect(lr::host::read_jpeg(argv[2], jpeg, error), "read_jpeg " + error);
  expect(jpeg.width == 16 && jpeg.height == 8 && jpeg.rgb.size() == 16 * 8 * 3,
         "the JPEG is 16x8 RGB");
  std::printf("load_files: %s\n", failures == 0 ? "every file as expected" : "FAILED");
  return failures == 0 ? 0 : 1;
}
