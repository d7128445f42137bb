// lr_quality_scenes OUT_DIR: the quality benchmark's frames (quality_configs.hpp) as C++ headers
// for the Cortex-M4F image that counts their instructions (firmware/quality):
//   quality_<scene>.hpp           each scene's meshes and materials (lineraster-asset's format)
//   quality_texture_<format>.hpp  the checker texture with its mip chain, RGB565 and RGB888
//   quality_cases.hpp             per scene its camera, lights, background and model; per
//                                 configuration its draw state, strip height and the checksum
//                                 and pixel count of its RGB565 frame as the host renders it
// The image renders every configuration and compares its frame with that checksum, so the
// counted frames are the ones whose error lr_quality_bench measures. Host only.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "firmware/common/ordered_sink.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/host_sim/programs/asset_writer.hpp"
#include "tests/bench/quality_configs.hpp"

namespace {

using namespace lr;

[[noreturn]] void die(const std::string& what) {
  bench::die("lr_quality_scenes", what);
}

void write_file(const std::string& path, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) die(path + ": cannot write: " + std::strerror(errno));
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok) die(path + ": cannot write");
}

std::string raw(int32_t v) {
  return std::to_string(v);
}

void mat(std::string& s, const char* lhs, const Mat4& m) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      s += "  " + std::string(lhs) + ".m[" + std::to_string(i) + "][" + std::to_string(j) +
           "].raw = " + raw(m.m[i][j].raw) + ";\n";
}
void vec(std::string& s, const std::string& lhs, const Vec3& v) {
  s += "  " + lhs + " = {lr::Fixed::from_raw(" + raw(v.x.raw) + "), lr::Fixed::from_raw(" +
       raw(v.y.raw) + "), lr::Fixed::from_raw(" + raw(v.z.raw) + ")};\n";
}
void col(std::string& s, const std::string& lhs, const Color15& c) {
  s += "  " + lhs + " = {" + std::to_string(c.r) + ", " + std::to_string(c.g) + ", " +
       std::to_string(c.b) + "};\n";
}

// The scene's camera, lights, background and model as assignments to a QualitySetup.
std::string setup_function(const char* scene, const bench::Prepared& p) {
  std::string s = "inline void setup_" + std::string(scene) + "(QualitySetup& s) {\n";
  mat(s, "s.camera.view", p.camera.view);
  mat(s, "s.camera.projection", p.camera.projection);
  vec(s, "s.camera.eye", p.camera.eye);
  mat(s, "s.model", p.model);
  s += "  s.background = {" + std::to_string(p.background.r) + ", " +
       std::to_string(p.background.g) + ", " + std::to_string(p.background.b) + "};\n";
  const LightSet& l = p.lights;
  s += "  s.lights.count = " + std::to_string(l.count) + ";\n";
  col(s, "s.lights.global_ambient", l.global_ambient);
  s += "  s.lights.local_viewer = " + std::string(l.local_viewer ? "true" : "false") + ";\n";
  s += "  s.lights.two_sided = " + std::string(l.two_sided ? "true" : "false") + ";\n";
  for (int i = 0; i < l.count; ++i) {
    const Light& li = l.lights[size_t(i)];
    const std::string n = "s.lights.lights[" + std::to_string(i) + "]";
    s += "  " + n + ".kind = static_cast<lr::LightKind>(" +
         std::to_string(static_cast<int>(li.kind)) + ");\n";
    vec(s, n + ".position", li.position);
    col(s, n + ".ambient", li.ambient);
    col(s, n + ".diffuse", li.diffuse);
    col(s, n + ".specular", li.specular);
    s += "  " + n + ".constant.raw = " + raw(li.constant.raw) + ";\n";
    s += "  " + n + ".linear.raw = " + raw(li.linear.raw) + ";\n";
    s += "  " + n + ".quadratic.raw = " + raw(li.quadratic.raw) + ";\n";
  }
  const DrawState& d = p.state;
  s += "  s.state.lighting = " + std::string(d.lighting ? "true" : "false") + ";\n";
  s += "  s.state.depth_test = " + std::string(d.depth_test ? "true" : "false") + ";\n";
  s +=
      "  s.state.cull = static_cast<lr::Cull>(" + std::to_string(static_cast<int>(d.cull)) + ");\n";
  s += "  s.state.sampler.wrap_s = static_cast<lr::Wrap>(" +
       std::to_string(static_cast<int>(d.sampler.wrap_s)) + ");\n";
  s += "  s.state.sampler.wrap_t = static_cast<lr::Wrap>(" +
       std::to_string(static_cast<int>(d.sampler.wrap_t)) + ");\n";
  s += "  s.state.sampler.env = static_cast<lr::TexEnv>(" +
       std::to_string(static_cast<int>(d.sampler.env)) + ");\n";
  s += "}\n\n";
  return s;
}

// The RGB565 frame's checksum as the image computes it (firmware/common/ordered_sink.hpp).
template <int K>
uint32_t checksum(const bench::Prepared& p, uint32_t& pixels) {
  constexpr int kW = 320, kH = 240;
  BasicFrameStorage<std::vector> store{FrameCapacities{.width = kW,
                                                       .height = kH,
                                                       .strip_height = K,
                                                       .vertices = 8192,
                                                       .triangles = 8192,
                                                       .draws = 16,
                                                       .active = 4096,
                                                       .tex_vertices = 8192,
                                                       .active_extra = 4096,
                                                       .triangle_colors = 8192}};
  auto r = std::make_unique<Renderer<Rgb565Be, K>>();
  if (r->configure(store.storage(), kW, kH) != Status::kOk) die("configure failed");
  std::vector<uint16_t> a(size_t(kW) * K), b(size_t(kW) * K);
  fw::ChecksumConsumer<Rgb565Be> sum;
  fw::OrderedStripSink<Rgb565Be, fw::ChecksumConsumer<Rgb565Be>> sink(a, b, sum);
  Status s = r->begin_frame(p.camera, p.lights, p.background);
  for (const host::FixedDraw& d : p.draws)
    if (s == Status::kOk) s = r->draw(d.mesh(), p.model, d.material, p.state);
  if (s == Status::kOk) s = r->render(sink);
  if (s != Status::kOk) die("render failed");
  pixels = r->stats().pixels_written;
  return sum.hash.value;
}

uint32_t checksum(const quality::Config& c, const bench::Prepared& p, uint32_t& pixels) {
  switch (c.strip) {
    case 1:
      return checksum<1>(p, pixels);
    case 8:
      return checksum<8>(p, pixels);
    case 32:
      return checksum<32>(p, pixels);
  }
  die("strip height must be 1, 8 or 32");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: lr_quality_scenes OUT_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  std::string cases =
      "// Generated by lr_quality_scenes (tests/bench/quality_scenes_main.cpp): do not edit.\n"
      "#pragma once\n\n#include \"firmware/quality/quality_setup.hpp\"\n";
  std::string body = "namespace lr::fw::quality_gen {\n\n";
  std::string meshes =
      "inline constexpr std::span<const lr::Mesh> meshes(int scene) {\n  switch (scene) {\n";
  std::string materials =
      "inline std::span<const lr::Material> materials(int scene) {\n  switch (scene) {\n";
  std::string setup = "inline void setup(int scene, QualitySetup& s) {\n  switch (scene) {\n";
  int index = 0;
  for (quality::SceneId id : quality::kScenes) {
    const char* sn = quality::name(id);
    quality::Config first;
    for (const quality::Config& c : quality::all_configs())
      if (c.scene == id) {
        first = c;
        break;
      }
    const bench::Prepared p =
        quality::prepare(quality::scene_mesh(id), quality::scene_options(first));
    host::AssetOptions o;
    o.name = std::string("quality_") + sn;
    o.command_line = std::string("lr_quality_scenes: scene ") + sn;
    host::AssetData d;
    d.draws = p.draws;
    d.textured.assign(p.draws.size(), quality::textured(id));
    write_file(dir + "/" + o.name + ".hpp", host::asset_header_text(o, d));
    cases += "#include \"" + o.name + ".hpp\"\n";
    body += setup_function(sn, p);
    const std::string i = std::to_string(index++);
    meshes += "    case " + i + ":\n      return " + o.name + "::meshes;\n";
    materials += "    case " + i + ":\n      return " + o.name + "::materials;\n";
    setup += "    case " + i + ":\n      setup_" + sn + "(s);\n      return;\n";
  }
  for (TexelFormat f : quality::kFormats) {
    host::AssetOptions o;
    o.name = std::string("quality_texture_") + quality::name(f);
    o.command_line = "lr_quality_scenes: the checker texture with mipmaps";
    host::AssetData d;
    d.has_texture = true;
    d.texture = quality::texture(f);
    write_file(dir + "/" + o.name + ".hpp", host::asset_header_text(o, d));
    cases += "#include \"" + o.name + ".hpp\"\n";
  }
  body += meshes + "  }\n  return {};\n}\n\n" + materials + "  }\n  return {};\n}\n\n" + setup +
          "  }\n}\n\n";
  body +=
      "inline const lr::Texture* texture(int format) {\n"
      "  return format == 0 ? &quality_texture_rgb565::texture : "
      "&quality_texture_rgb888::texture;\n"
      "}\n\n";
  body += "inline constexpr QualityCase kCases[] = {\n";
  size_t n = 0;
  for (const quality::Config& c : quality::all_configs()) {
    const bench::Prepared p =
        quality::prepare(quality::scene_mesh(c.scene), quality::scene_options(c));
    uint32_t pixels = 0;
    const uint32_t sum = checksum(c, p, pixels);
    int scene = 0;
    while (quality::kScenes[scene] != c.scene) ++scene;
    int format = 0;
    while (quality::kFormats[format] != c.format) ++format;
    char line[400];
    std::snprintf(
        line, sizeof line,
        "    {\"%s\", %d, %d, static_cast<lr::Shading>(%d), static_cast<lr::Perspective>(%d), "
        "static_cast<lr::Filter>(%d), static_cast<lr::MipMode>(%d), %d, %s, 0x%08xu, %uu},\n",
        c.key(' ').c_str(), scene, c.strip, static_cast<int>(c.shading),
        static_cast<int>(c.perspective), static_cast<int>(c.filter), static_cast<int>(c.mip),
        format, quality::textured(c.scene) ? "true" : "false", sum, pixels);
    body += line;
    ++n;
  }
  body += "};\n\n}  // namespace lr::fw::quality_gen\n";
  write_file(dir + "/quality_cases.hpp", cases + "\n" + body);
  std::printf("lr_quality_scenes: %zu configurations, %zu scenes -> %s\n", n,
              std::size(quality::kScenes), dir.c_str());
  return 0;
}
