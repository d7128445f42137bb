// lineraster-asset's round trip: the headers generated at build time (tests/asset/CMakeLists.txt)
// hold, value for value, what the simulator's own conversion (build_fixed_draws + load_texture)
// makes of the same files, and render the same frames with the core. Also the tool's errors:
// one line, exit status 2, no output file.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "cube_rgb565.hpp"
#include "cube_rgb888.hpp"
#include "knot_fine.hpp"
#include "knot_l8.hpp"
#include "knot_palette8.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/programs/asset_writer.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/asset/data/cube_rgb565_before_position_frac.hpp"
#include "tests/support/core_harness.hpp"
#include "tests/support/tmp_dir.hpp"
#include "two_textures.hpp"

namespace lr::host {
namespace {

using test::TmpDir;

const std::string kData = LR_SOURCE_DIR "/tests/host/data/";

// A generated header seen through spans.
struct AssetView {
  std::span<const Mesh> meshes;
  std::span<const Material> materials;
  std::span<const bool> textured;
  const Texture* texture;
};
#define LR_ASSET_VIEW(ns)                                 \
  AssetView {                                             \
    ns::meshes, ns::materials, ns::textured, &ns::texture \
  }

// What the simulator makes of the same files.
struct Loaded {
  std::vector<FixedDraw> draws;
  HostTexture texture;
};

Loaded load(const std::string& obj, const std::string& png, TexelFormat format, bool mipmaps,
            bool fit, bool fine_positions = false) {
  Loaded l;
  HostMesh mesh;
  std::string error;
  EXPECT_TRUE(load_obj(kData + obj, mesh, error)) << error;
  SceneOptions o;
  o.fit = fit;
  o.fine_positions = fine_positions;
  o.use_mesh_materials = true;
  EXPECT_TRUE(build_fixed_draws(mesh, o, l.draws, error)) << error;
  EXPECT_TRUE(load_texture(kData + png, format, mipmaps, l.texture, error)) << error;
  return l;
}

template <class T>
void expect_same(std::span<const T> header, const std::vector<T>& loaded, const char* what,
                 size_t draw) {
  ASSERT_EQ(header.size(), loaded.size()) << what << " of draw " << draw;
  for (size_t i = 0; i < loaded.size(); ++i)
    ASSERT_TRUE(header[i] == loaded[i]) << what << " " << i << " of draw " << draw;
}

void expect_same_material(const Material& a, const Material& b) {
  EXPECT_EQ(a.ambient, b.ambient);
  EXPECT_EQ(a.diffuse, b.diffuse);
  EXPECT_EQ(a.specular, b.specular);
  EXPECT_EQ(a.emission, b.emission);
  EXPECT_EQ(a.shininess_q8, b.shininess_q8);
}

void expect_same_texture(const Texture& h, const Texture& l) {
  ASSERT_EQ(h.format, l.format);
  ASSERT_EQ(h.level_count, l.level_count);
  EXPECT_EQ(validate(h), Status::kOk);
  for (int i = 0; i < l.level_count; ++i) {
    const TextureLevel& a = h.levels[static_cast<size_t>(i)];
    const TextureLevel& b = l.levels[static_cast<size_t>(i)];
    ASSERT_EQ(a.width, b.width) << "level " << i;
    ASSERT_EQ(a.height, b.height) << "level " << i;
    ASSERT_EQ(a.rgb565.size(), b.rgb565.size()) << "level " << i;
    ASSERT_EQ(a.bytes.size(), b.bytes.size()) << "level " << i;
    for (size_t k = 0; k < b.rgb565.size(); ++k)
      ASSERT_EQ(a.rgb565[k], b.rgb565[k]) << "level " << i << " texel " << k;
    for (size_t k = 0; k < b.bytes.size(); ++k)
      ASSERT_EQ(a.bytes[k], b.bytes[k]) << "level " << i << " byte " << k;
  }
  for (int i = l.level_count; i < kMaxMipLevels; ++i) {
    EXPECT_EQ(h.levels[static_cast<size_t>(i)].width, 0);
    EXPECT_TRUE(h.levels[static_cast<size_t>(i)].rgb565.empty());
    EXPECT_TRUE(h.levels[static_cast<size_t>(i)].bytes.empty());
  }
  ASSERT_EQ(h.palette.size(), l.palette.size());
  for (size_t k = 0; k < l.palette.size(); ++k) EXPECT_EQ(h.palette[k], l.palette[k]) << k;
}

void expect_same_data(const AssetView& h, const Loaded& l) {
  ASSERT_EQ(h.meshes.size(), l.draws.size());
  ASSERT_EQ(h.materials.size(), l.draws.size());
  ASSERT_EQ(h.textured.size(), l.draws.size());
  for (size_t d = 0; d < l.draws.size(); ++d) {
    const FixedDraw& fd = l.draws[d];
    const Mesh& m = h.meshes[d];
    EXPECT_EQ(m.position_fraction_bits(), fd.position_frac) << "draw " << d;
    EXPECT_EQ(m.bound, mesh_bound(m.positions)) << "draw " << d;
    expect_same(m.positions, fd.positions, "position", d);
    expect_same(m.normals, fd.normals, "normal", d);
    expect_same(m.colors, fd.colors, "colour", d);
    expect_same(m.uvs, fd.uvs, "uv", d);
    expect_same(m.triangles, fd.triangles, "triangle", d);
    expect_same_material(h.materials[d], fd.material);
  }
  expect_same_texture(*h.texture, l.texture.texture);
}

TEST(AssetRoundTrip, CubeWithMapKdRgb565MipmappedEqualsTheLoadedFiles) {
  const Loaded l = load("cube.obj", "checker.png", TexelFormat::kRgb565, true, false);
  expect_same_data(LR_ASSET_VIEW(cube_rgb565), l);
  // cube.mtl: cube_red (4 faces, no map_Kd), then cube_white (2 faces, map_Kd checker.png).
  ASSERT_EQ(l.draws.size(), 2u);
  EXPECT_EQ(l.draws[0].triangles.size(), 8u);
  EXPECT_EQ(l.draws[1].triangles.size(), 4u);
  EXPECT_FALSE(cube_rgb565::textured[0]);
  EXPECT_TRUE(cube_rgb565::textured[1]);
  EXPECT_EQ(cube_rgb565::texture.level_count, 4);
  // Spot values: the cube's corner (1, -1, -1) in Q16.16 and cube_white's Ns 96 in Q8.8.
  EXPECT_EQ(cube_rgb565::positions_0[0],
            (Vec3{Fixed::from_int(1), Fixed::from_int(-1), Fixed::from_int(-1)}));
  EXPECT_EQ(cube_rgb565::material_1.shininess_q8, 96 * 256);
  EXPECT_EQ(cube_rgb565::uvs_1[2], (TexCoord{1 << 20, 1 << 20}));
}

TEST(AssetRoundTrip, CubeFittedRgb888EqualsTheLoadedFiles) {
  const Loaded l = load("cube.obj", "checker.png", TexelFormat::kRgb888, false, true);
  expect_same_data(LR_ASSET_VIEW(cube_rgb888), l);
  EXPECT_EQ(cube_rgb888::texture.level_count, 1);
  ASSERT_EQ(l.draws.size(), 2u);
  EXPECT_FALSE(cube_rgb888::textured[0]);  // cube_red: no map_Kd
  EXPECT_TRUE(cube_rgb888::textured[1]);   // cube_white: map_Kd checker.png
}

TEST(AssetRoundTrip, TorusKnotWithTexturePalette8EqualsTheLoadedFiles) {
  const Loaded l = load("torus_knot.obj", "checker.png", TexelFormat::kPalette8, true, true);
  expect_same_data(LR_ASSET_VIEW(knot_palette8), l);
  for (bool t : knot_palette8::textured) EXPECT_TRUE(t);  // --texture: every draw with uvs
  EXPECT_FALSE(knot_palette8::texture.palette.empty());
}

TEST(AssetRoundTrip, TorusKnotWithTextureL8EqualsTheLoadedFiles) {
  const Loaded l = load("torus_knot.obj", "checker.png", TexelFormat::kL8, true, false);
  expect_same_data(LR_ASSET_VIEW(knot_l8), l);
  EXPECT_EQ(knot_l8::meshes[0].triangles.size(), 4000u);
}

// --fine-positions: the header's position_frac is the finest the fitted knot allows (30: every
// coordinate within 1 after --fit), its positions the simulator's of the same count, and each
// the Q16.16 header's position to within the Q16.16 rounding (the same vertices, 14 more bits).
TEST(AssetRoundTrip, FinePositionsWriteTheFinestFractionCount) {
  const Loaded l = load("torus_knot.obj", "checker.png", TexelFormat::kL8, false, true, true);
  expect_same_data(LR_ASSET_VIEW(knot_fine), l);
  ASSERT_FALSE(knot_fine::meshes.empty());
  for (const Mesh& m : knot_fine::meshes) EXPECT_EQ(m.position_frac, 30);
  for (const Mesh& m : knot_palette8::meshes) EXPECT_EQ(m.position_frac, 16);  // --fit alone
  const Mesh& fine = knot_fine::meshes[0];
  const Mesh& q16 = knot_palette8::meshes[0];  // --fit, Q16.16
  ASSERT_EQ(fine.positions.size(), q16.positions.size());
  int64_t largest = 0;
  for (size_t i = 0; i < fine.positions.size(); ++i) {
    const Vec3& a = fine.positions[i];
    const Vec3& b = q16.positions[i];
    for (const auto& [f, c] :
         {std::pair{a.x.raw, b.x.raw}, std::pair{a.y.raw, b.y.raw}, std::pair{a.z.raw, b.z.raw}}) {
      const int64_t d = int64_t{f} - (int64_t{c} << 14);  // in units of 2^-30
      largest = std::max(largest, d < 0 ? -d : d);
    }
  }
  EXPECT_LE(largest, 1 << 13);  // half a Q16.16 unit
  EXPECT_GT(largest, 0);        // and finer than it
  // The largest coordinate uses the range: above 2^29 (0.5) and at most 2^30.
  EXPECT_GT(fine.bound, 1u << 29);
  EXPECT_LE(fine.bound, 1u << 30);
}

// A header written before Mesh::position_frac (its meshes have no such field) still compiles and
// its meshes are Q16.16: the same values as today's header of the same files.
TEST(AssetRoundTrip, HeaderWithoutPositionFracIsQ16) {
  const Loaded l = load("cube.obj", "checker.png", TexelFormat::kRgb565, true, false);
  expect_same_data(LR_ASSET_VIEW(cube_rgb565_before_position_frac), l);
  for (const Mesh& m : cube_rgb565_before_position_frac::meshes) {
    EXPECT_EQ(m.position_frac, 0);  // the default
    EXPECT_EQ(m.position_fraction_bits(), 16);
  }
  for (const Mesh& m : cube_rgb565::meshes) EXPECT_EQ(m.position_frac, 16);
}

// ---- Frames ------------------------------------------------------------------------------------

struct Frame {
  ImageRgb8 image;
  size_t covered = 0;
  size_t textured_draws = 0;
};

// Renders meshes[i] with materials[i] and textures[i] (nullptr: untextured) at 160x120 from a
// corner, the model scaled by `scale`.
Frame render_each(std::span<const Mesh> meshes, std::span<const Material> materials,
                  std::span<const Texture* const> textures, Fixed scale) {
  constexpr int kW = 160, kH = 120;
  test::CoreHarness<8> h(kW, kH);
  EXPECT_EQ(h.configured(), Status::kOk);
  Camera cam;
  EXPECT_TRUE(perspective(Fixed::from_int(60), Fixed::ratio(kW, kH), Fixed::from_double(0.1),
                          Fixed::from_int(100), cam.projection));
  cam.eye = {Fixed::from_double(2.5), Fixed::from_int(2), Fixed::from_double(3.5)};
  EXPECT_TRUE(look_at(cam.eye, {}, {Fixed{}, Fixed::from_int(1), Fixed{}}, cam.view));
  LightSet lights;
  const Fixed c = Fixed::from_double(0.57735);
  lights.lights[0] = Light::directional({c, c, c}, {32768, 32768, 32768});
  lights.count = 1;
  EXPECT_EQ(h.begin(Rgb8{0, 0, 0}, cam, lights), Status::kOk);
  Frame f;
  for (size_t i = 0; i < meshes.size(); ++i) {
    DrawState st;
    if (const Texture* texture = textures[i]) {
      st.texture = texture;
      st.sampler.filter = Filter::kNearest;
      st.sampler.mip = texture->level_count > 1 ? MipMode::kNearest : MipMode::kNone;
      ++f.textured_draws;
    }
    EXPECT_EQ(h.renderer().draw(meshes[i], lr::scale(scale), materials[i], st), Status::kOk);
  }
  Status s;
  f.image = h.render(&s);
  EXPECT_EQ(s, Status::kOk);
  for (size_t p = 0; p < h.depth().size(); ++p) f.covered += h.depth()[p] != 0xFFFF;
  return f;
}

// The same with `texture` where textured[i].
Frame render(std::span<const Mesh> meshes, std::span<const Material> materials,
             std::span<const bool> textured, const Texture* texture, Fixed scale) {
  std::vector<const Texture*> each;
  for (size_t i = 0; i < meshes.size(); ++i) each.push_back(textured[i] ? texture : nullptr);
  return render_each(meshes, materials, each, scale);
}

Frame render_loaded(const Loaded& l, std::span<const bool> textured, Fixed scale) {
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  for (const FixedDraw& d : l.draws) {
    meshes.push_back(d.mesh());
    materials.push_back(d.material);
  }
  return render(meshes, materials, textured, &l.texture.texture, scale);
}

// Fitted models (radius 1) are drawn 1.6 times larger, to fill about as much of the frame.
// textured_draws: how many draws the files give the texture (map_Kd, or --texture: every draw
// with uvs); the frames are compared textured, never silently without.
void expect_same_frame(const AssetView& h, const Loaded& l, bool fitted, size_t textured_draws) {
  const Fixed scale = fitted ? Fixed::from_double(1.6) : Fixed::from_int(1);
  const Frame a = render(h.meshes, h.materials, h.textured, h.texture, scale);
  const Frame b = render_loaded(l, h.textured, scale);
  ASSERT_EQ(a.image.rgb.size(), b.image.rgb.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.image.rgb.size(); ++i) differing += a.image.rgb[i] != b.image.rgb[i];
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(a.covered, b.covered);
  EXPECT_GT(a.covered, 160u * 120u / 20) << "the model should fill a good part of the frame";
  ASSERT_EQ(a.textured_draws, textured_draws) << "draws the header gives the texture";
  ASSERT_EQ(b.textured_draws, textured_draws);
  // The texture must show: the textured frame differs from the same draws untextured.
  const auto off = std::make_unique<bool[]>(h.textured.size());  // all false
  const Frame plain = render(h.meshes, h.materials,
                             std::span<const bool>(off.get(), h.textured.size()), nullptr, scale);
  EXPECT_EQ(plain.textured_draws, 0u);
  EXPECT_NE(plain.image.rgb, a.image.rgb) << "the texture does not show";
}

TEST(AssetRoundTripFrames, CubeRgb565RendersTheSameFrameAsTheLoadedFiles) {
  expect_same_frame(LR_ASSET_VIEW(cube_rgb565),
                    load("cube.obj", "checker.png", TexelFormat::kRgb565, true, false), false,
                    1);  // cube_white
}

TEST(AssetRoundTripFrames, CubeRgb888RendersTheSameFrameAsTheLoadedFiles) {
  expect_same_frame(LR_ASSET_VIEW(cube_rgb888),
                    load("cube.obj", "checker.png", TexelFormat::kRgb888, false, true), true, 1);
}

TEST(AssetRoundTripFrames, KnotPalette8RendersTheSameFrameAsTheLoadedFiles) {
  expect_same_frame(LR_ASSET_VIEW(knot_palette8),
                    load("torus_knot.obj", "checker.png", TexelFormat::kPalette8, true, true), true,
                    knot_palette8::draw_count);
}

TEST(AssetRoundTripFrames, KnotL8RendersTheSameFrameAsTheLoadedFiles) {
  expect_same_frame(LR_ASSET_VIEW(knot_l8),
                    load("torus_knot.obj", "checker.png", TexelFormat::kL8, true, false), false,
                    knot_l8::draw_count);
}

// Two materials with a texture each (quirks/two_textures.obj): the header keeps both, each draw
// takes its own, and its frame is the one of the simulator's conversion of the files, textures
// loaded per material.
TEST(AssetRoundTripFrames, EachMaterialKeepsItsOwnTextureAsTheSimulatorDraws) {
  HostMesh mesh;
  std::string error;
  ASSERT_TRUE(load_obj(kData + "quirks/two_textures.obj", mesh, error)) << error;
  SceneOptions o;
  o.use_mesh_materials = true;
  std::vector<FixedDraw> draws;
  ASSERT_TRUE(build_fixed_draws(mesh, o, draws, error)) << error;
  ASSERT_EQ(draws.size(), two_textures::draw_count);
  std::vector<HostTexture> loaded(draws.size());
  std::vector<const Texture*> each;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  for (size_t i = 0; i < draws.size(); ++i) {
    const std::string& map = mesh.materials[static_cast<size_t>(draws[i].material_index)].map_kd;
    ASSERT_TRUE(load_texture(map, TexelFormat::kRgb565, false, loaded[i], error)) << error;
    ASSERT_NE(two_textures::draw_textures[i], nullptr);
    expect_same_texture(*two_textures::draw_textures[i], loaded[i].texture);
    each.push_back(&loaded[i].texture);
    meshes.push_back(draws[i].mesh());
    materials.push_back(draws[i].material);
    expect_same(two_textures::meshes[i].positions, draws[i].positions, "position", i);
  }
  EXPECT_NE(two_textures::draw_textures[0], two_textures::draw_textures[1]);
  const Fixed scale = Fixed::from_double(1.2);
  const Frame header = render_each(two_textures::meshes, two_textures::materials,
                                   two_textures::draw_textures, scale);
  const Frame files = render_each(meshes, materials, each, scale);
  EXPECT_EQ(header.textured_draws, 2u);
  EXPECT_GT(header.covered, 160u * 120u / 20);
  EXPECT_TRUE(header.image.rgb == files.image.rgb);
  // Both textures show: one texture on both draws gives another frame.
  const std::array<const Texture*, 2> first{&two_textures::texture, &two_textures::texture};
  EXPECT_FALSE(render_each(two_textures::meshes, two_textures::materials, first, scale).image.rgb ==
               header.image.rgb);
}

// ---- The tool's command line
// ---------------------------------------------------------------------

struct ToolRun {
  int status = -1;
  std::string err;
};

ToolRun run_tool(const std::string& args, const TmpDir& dir) {
  const std::string err_file = dir.file("stderr.txt");
  const std::string cmd =
      std::string(LR_ASSET_TOOL) + " " + args + " 2>" + err_file + " >/dev/null";
  ToolRun r;
  const int raw = std::system(cmd.c_str());
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(err_file);
  std::stringstream ss;
  ss << in.rdbuf();
  r.err = ss.str();
  std::filesystem::remove(err_file);
  return r;
}

void expect_error(const TmpDir& dir, const std::string& args, const std::string& message) {
  const ToolRun r = run_tool(args, dir);
  EXPECT_EQ(r.status, 2) << args;
  EXPECT_EQ(r.err, "lineraster-asset: " + message + "\n") << args;
  EXPECT_TRUE(dir.entries().empty()) << args << ": output written";
}

TEST(AssetTool, ErrorsAreOneLineExitTwoAndNoOutput) {
  TmpDir dir("lr_asset_test");
  const std::string out = " --out " + dir.file("a.hpp");
  const std::string cube = " --obj " + kData + "cube.obj";
  expect_error(dir, "--name a" + out, "--obj FILE is required");
  expect_error(dir, cube + out, "--name IDENT is required");
  expect_error(dir, cube + " --name a", "--out FILE.hpp is required");
  expect_error(dir, cube + " --name 9lives" + out,
               "--name '9lives' is not a usable C++ identifier");
  expect_error(dir, cube + " --name class" + out, "--name 'class' is not a usable C++ identifier");
  expect_error(dir, cube + " --name a__b" + out, "--name 'a__b' is not a usable C++ identifier");
  expect_error(dir, cube + " --name a --format rgb555" + out,
               "--format needs rgb565, rgb888, l8 or palette8");
  expect_error(dir, cube + " --name a --bogus" + out,
               "unknown option '--bogus' (--help lists them)");
  expect_error(dir, "--obj --name a" + out, "--obj needs a file name");
  expect_error(dir, "--obj " + dir.file("missing.obj") + " --name a" + out,
               dir.file("missing.obj") + ": cannot open: No such file or directory");
  expect_error(dir, cube + " --texture " + dir.file("missing.png") + " --name a" + out,
               dir.file("missing.png") + ": cannot open: No such file or directory");
  // A texture the mesh has no coordinates for.
  { std::ofstream(dir.file("tri.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"; }
  const ToolRun r = run_tool(
      "--obj " + dir.file("tri.obj") + " --texture " + kData + "checker.png --name a" + out, dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "lineraster-asset: " + dir.file("tri.obj") +
                       ": no texture coordinates (vt) for the texture " + kData + "checker.png\n");
  std::filesystem::remove(dir.file("tri.obj"));
  // Onto one of its inputs (the OBJ, its MTL, the texture; by another name too): refused, the
  // input untouched.
  {
    const std::string obj = dir.file("in.obj"), mtl = dir.file("in.mtl"), png = dir.file("in.png");
    std::filesystem::copy_file(kData + "cube.obj", obj);
    { std::ofstream(mtl) << "newmtl m\nKd 1 1 1\nmap_Kd in.png\n"; }
    std::filesystem::copy_file(kData + "checker.png", png);
    {
      std::ifstream in(obj);
      std::stringstream ss;
      ss << in.rdbuf();
      std::string text = ss.str();
      const size_t at = text.find("mtllib ");
      ASSERT_NE(at, std::string::npos);
      text.replace(at, text.find('\n', at) - at, "mtllib in.mtl");
      for (size_t u = text.find("usemtl "); u != std::string::npos; u = text.find("usemtl ", u + 1))
        text.replace(u, text.find('\n', u) - u, "usemtl m");
      std::ofstream(obj) << text;
    }
    const auto before = std::filesystem::file_size(obj);
    for (const std::string& target : {obj, mtl, png, dir.path() + "/./in.obj"}) {
      const ToolRun t = run_tool("--obj " + obj + " --name a --out " + target, dir);
      EXPECT_EQ(t.status, 2) << target;
      EXPECT_NE(t.err.find(": is an input ("), std::string::npos) << t.err;
      EXPECT_NE(t.err.find("refusing to overwrite it"), std::string::npos) << t.err;
    }
    EXPECT_EQ(std::filesystem::file_size(obj), before);
    const ToolRun ok = run_tool("--obj " + obj + " --name a --out " + dir.file("in.hpp"), dir);
    EXPECT_EQ(ok.status, 0) << ok.err;
    for (const std::string& f : {obj, mtl, png, dir.file("in.hpp")}) std::filesystem::remove(f);
  }
  // Into a missing directory: refused, nothing left behind.
  const ToolRun m = run_tool(cube + " --name a --out " + dir.file("no/such/dir.hpp"), dir);
  EXPECT_EQ(m.status, 2);
  EXPECT_EQ(m.err, "lineraster-asset: " + dir.file("no/such/dir.hpp") +
                       ": cannot open for writing: No such file or directory\n");
  EXPECT_TRUE(dir.entries().empty());
}

// A material's texture on a mesh without vt: the header is untextured, and one warning line says
// so (an explicit --texture is still an error, above).
TEST(AssetTool, AMaterialTextureWithoutUvsIsLeftOutWithAWarning) {
  TmpDir dir("lr_asset_test");
  dir.write("t.mtl", "newmtl t\nKd 1 1 1\nmap_Kd " + kData + "checker.png\n");
  dir.write("t.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl t\nf 1 2 3\n");
  const ToolRun r =
      run_tool("--obj " + dir.file("t.obj") + " --name a --out " + dir.file("a.hpp"), dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "lineraster-asset: warning: " + kData +
                       "checker.png: the mesh has no texture coordinates (vt): drawn untextured\n");
  std::ifstream in(dir.file("a.hpp"));
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("draw_count = 1"), std::string::npos);
  EXPECT_EQ(ss.str().find("lr::Texture texture{"), std::string::npos);
}

// --fine-positions: the most fraction bits that hold the largest coordinate (4: 4 2^29 = 2^31 is
// one too many, so 28), written in the mesh and the header's comment; Q16.16 without it.
TEST(AssetTool, FinePositionsTakeTheFinestCountTheBoundAllows) {
  TmpDir dir("lr_asset_test");
  { std::ofstream(dir.file("box.obj")) << "v 0 0 0\nv 4 0 1\nv 0 2 0.1\nf 1 2 3\n"; }
  AssetOptions o;
  o.obj_path = dir.file("box.obj");
  o.name = "box";
  o.fine_positions = true;
  AssetData d;
  std::string error;
  ASSERT_TRUE(load_asset(o, d, error)) << error;
  ASSERT_EQ(d.draws.size(), 1u);
  EXPECT_EQ(d.draws[0].position_frac, 28);
  const std::vector<Vec3>& p = d.draws[0].positions;
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[1].x.raw, 4 << 28);
  EXPECT_EQ(p[2].z.raw, static_cast<int32_t>(std::llround(0.1 * (1 << 28))));
  const std::string text = asset_header_text(o, d);
  EXPECT_NE(text.find("positions Q4.28 (Mesh::position_frac 28)"), std::string::npos);
  EXPECT_NE(text.find(std::to_string(4 << 28) + "u, 28};"), std::string::npos);
  EXPECT_NE(text.find("fine positions (--fine-positions)"), std::string::npos);
  // The tool's flag writes the same; without it Q16.16.
  const ToolRun r = run_tool(
      "--obj " + dir.file("box.obj") + " --fine-positions --name a --out " + dir.file("a.hpp"),
      dir);
  EXPECT_EQ(r.status, 0) << r.err;
  std::stringstream written;
  written << std::ifstream(dir.file("a.hpp")).rdbuf();
  EXPECT_NE(written.str().find("u, 28};"), std::string::npos);
  o.fine_positions = false;
  ASSERT_TRUE(load_asset(o, d, error)) << error;
  EXPECT_EQ(d.draws[0].position_frac, 16);
  EXPECT_EQ(d.draws[0].positions[1].x.raw, 4 << 16);
  EXPECT_NE(asset_header_text(o, d).find("u, 16};"), std::string::npos);
  // Coordinates of 2^14 and more leave no bit beyond Q16.16: 16.
  EXPECT_EQ(position_frac_for(16384.0), 16);
  EXPECT_EQ(position_frac_for(1.0), 30);
  EXPECT_EQ(position_frac_for(1.9999999), 30);
  EXPECT_EQ(position_frac_for(2.0), 29);
}

TEST(AssetTool, FitBoxPutsTheLargestHalfExtentAtOne) {
  TmpDir dir("lr_asset_test");
  // Box [0, 4] x [0, 2] x [0, 1]: centre (2, 1, 0.5), largest half extent 2.
  { std::ofstream(dir.file("box.obj")) << "v 0 0 0\nv 4 0 1\nv 0 2 0\nf 1 2 3\n"; }
  AssetOptions o;
  o.obj_path = dir.file("box.obj");
  o.name = "box";
  o.fit_box = true;
  AssetData d;
  std::string error;
  ASSERT_TRUE(load_asset(o, d, error)) << error;
  ASSERT_EQ(d.draws.size(), 1u);
  const std::vector<Vec3>& p = d.draws[0].positions;
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0], (Vec3{Fixed::from_int(-1), Fixed::from_double(-0.5), Fixed::from_double(-0.25)}));
  EXPECT_EQ(p[1], (Vec3{Fixed::from_int(1), Fixed::from_double(-0.5), Fixed::from_double(0.25)}));
  EXPECT_EQ(p[2], (Vec3{Fixed::from_int(-1), Fixed::from_double(0.5), Fixed::from_double(-0.25)}));
  EXPECT_NE(asset_header_text(o, d).find("fitted to its box (--fit-box)"), std::string::npos);
  o.fit = true;
  EXPECT_FALSE(load_asset(o, d, error));
  EXPECT_EQ(error, "--fit and --fit-box exclude each other");
  const ToolRun r = run_tool(
      "--obj " + dir.file("box.obj") + " --fit --fit-box --name a --out " + dir.file("a.hpp"), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "lineraster-asset: --fit and --fit-box exclude each other\n");
}

TEST(AssetTool, LocalityReordersTheSameTrianglesAndSaysSo) {
  AssetOptions o;
  o.obj_path = kData + "torus_knot.obj";
  o.name = "knot";
  AssetData plain, local;
  std::string error;
  ASSERT_TRUE(load_asset(o, plain, error)) << error;
  o.locality = true;
  ASSERT_TRUE(load_asset(o, local, error)) << error;
  ASSERT_EQ(plain.draws.size(), 1u);
  ASSERT_EQ(local.draws.size(), 1u);
  const FixedDraw& a = plain.draws[0];
  const FixedDraw& b = local.draws[0];
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  EXPECT_NE(a.triangles, b.triangles);
  // The same triangles with the same windings: each as its corners' raw coordinates from its
  // smallest corner on, as a sorted list.
  const auto triangles = [](const FixedDraw& d) {
    std::vector<std::array<std::array<int32_t, 3>, 3>> list;
    for (const auto& t : d.triangles) {
      std::array<std::array<int32_t, 3>, 3> c;
      for (size_t k = 0; k < 3; ++k) {
        const Vec3& p = d.positions[t[k]];
        c[k] = {p.x.raw, p.y.raw, p.z.raw};
      }
      std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
      list.push_back(c);
    }
    std::sort(list.begin(), list.end());
    return list;
  };
  EXPECT_EQ(triangles(a), triangles(b));
  EXPECT_NE(asset_header_text(o, local).find("in spatial order (--locality)"), std::string::npos);
  o.locality = false;
  EXPECT_EQ(asset_header_text(o, plain).find("--locality"), std::string::npos);
}

TEST(AssetTool, WritesAHeaderAndReplacesAnOldOneWhole) {
  TmpDir dir("lr_asset_test");
  const std::string out = dir.file("cube.hpp");
  { std::ofstream(out) << "old"; }
  const ToolRun r =
      run_tool("--obj " + kData + "cube.obj --format l8 --name cube --out " + out, dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"cube.hpp"});  // no .tmp left
  std::ifstream in(out);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  EXPECT_EQ(text.rfind("// Generated by lineraster-asset", 0), 0u);
  EXPECT_NE(text.find("//   mesh:    " + kData + "cube.obj"), std::string::npos);
  EXPECT_NE(text.find("//   texture: " + kData + "checker.png: 8x8 l8, 1 level(s)"),
            std::string::npos);
  EXPECT_NE(text.find("namespace cube {"), std::string::npos);
  EXPECT_NE(text.find("inline constexpr lr::Texture texture{"), std::string::npos);
  // Compact: no line longer than 110 characters.
  std::istringstream lines(text);
  std::string line;
  size_t longest = 0;
  while (std::getline(lines, line))
    if (line.rfind("//", 0) != 0) longest = std::max(longest, line.size());
  EXPECT_LE(longest, 110u);
  // Same conversion as the library call.
  AssetOptions o;
  o.obj_path = kData + "cube.obj";
  o.format = TexelFormat::kL8;
  o.name = "cube";
  AssetData d;
  std::string error;
  ASSERT_TRUE(load_asset(o, d, error)) << error;
  const std::string body = asset_header_text(o, d);
  EXPECT_EQ(text.substr(text.find("#pragma once")), body.substr(body.find("#pragma once")));
}

TEST(AssetTool, NamesAreCheckedAsCppIdentifiers) {
  for (const char* ok : {"a", "_a", "cube_2", "Cube", "my_asset_x"})
    EXPECT_TRUE(valid_asset_name(ok)) << ok;
  for (const char* bad : {"", "2a", "a-b", "a b", "int", "namespace", "_Cube", "a__b", "lr", "std",
                          "uint16_t", "a.b", "\xc3\xa9"})
    EXPECT_FALSE(valid_asset_name(bad)) << bad;
}

}  // namespace
}  // namespace lr::host
