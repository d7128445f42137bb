// The quality benchmark's configurations and scenes, shared by lr_quality_bench (host time,
// error) and lr_quality_scenes (the same frames as generated headers for the Cortex-M4F image
// that counts their instructions: firmware/quality). Host only.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "tests/bench/bench_common.hpp"
#include "tests/support/scene_compare.hpp"
#include "tests/support/scenes.hpp"

namespace lr::quality {

using bench::name;

inline constexpr int kWidth = 320, kHeight = 240;

enum class SceneId { kKnot, kSphere, kClipped, kCube, kGround };
inline const char* name(SceneId s) {
  switch (s) {
    case SceneId::kKnot:
      return "knot";
    case SceneId::kSphere:
      return "sphere";
    case SceneId::kClipped:
      return "clipped";
    case SceneId::kCube:
      return "cube";
    case SceneId::kGround:
      return "ground";
  }
  return "?";
}
inline bool textured(SceneId s) {
  return s == SceneId::kCube || s == SceneId::kGround;
}
inline const SceneId kScenes[] = {SceneId::kKnot, SceneId::kSphere, SceneId::kClipped,
                                  SceneId::kCube, SceneId::kGround};
inline const Shading kShadings[] = {Shading::kFlat, Shading::kGouraud};
inline const int kStrips[] = {1, 8, 32};
inline const TexelFormat kFormats[] = {TexelFormat::kRgb565, TexelFormat::kRgb888};

struct Config {
  SceneId scene = SceneId::kKnot;
  Shading shading = Shading::kGouraud;
  Perspective perspective = Perspective::kExact;
  int strip = 8;
  Filter filter = Filter::kBilinear;
  MipMode mip = MipMode::kNone;
  TexelFormat format = TexelFormat::kRgb565;

  // The columns scene .. format; untextured scenes show "-" for the texture settings.
  std::string key(char sep) const {
    const bool t = textured(scene);
    std::string s = quality::name(scene);
    for (const char* part : {name(shading), name(perspective)}) s += sep + std::string(part);
    s += sep + std::to_string(strip);
    for (const char* part : {t ? name(filter) : "-", t ? name(mip) : "-", t ? name(format) : "-"})
      s += sep + std::string(part);
    return s;
  }
};

inline std::vector<Config> all_configs() {
  std::vector<Config> out;
  for (SceneId s : kScenes) {
    if (textured(s)) {
      for (Filter fi : bench::kFilters)
        for (Perspective pm : bench::kModes)
          for (MipMode m : bench::kMips)
            for (TexelFormat tf : kFormats) out.push_back({s, Shading::kGouraud, pm, 8, fi, m, tf});
    } else {
      for (Shading sh : kShadings)
        for (Perspective pm : bench::kModes)
          for (int k : kStrips) out.push_back({s, sh, pm, k});
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Scenes

inline const host::HostTexture& texture(TexelFormat f) {
  static std::map<TexelFormat, host::HostTexture> cache;
  auto it = cache.find(f);
  if (it == cache.end()) {
    host::HostTexture t;
    std::string err;
    if (!host::texture_from_image(test::checker64(), f, true, t, err))
      bench::die("quality_bench", err);
    it = cache.emplace(f, std::move(t)).first;
  }
  return it->second;
}

inline size_t texture_bytes(const Texture& t, MipMode m) {
  const int levels = m == MipMode::kNone ? 1 : t.level_count;
  size_t n = 0;
  for (int l = 0; l < levels; ++l) {
    const TextureLevel& lv = t.levels[size_t(l)];
    n += level_texels(lv.width, lv.height) * bytes_per_texel(t.format);
  }
  return n;
}

inline const host::HostMesh& scene_mesh(SceneId s) {
  static std::map<SceneId, host::HostMesh> cache;
  auto it = cache.find(s);
  if (it != cache.end()) return it->second;
  host::HostMesh m;
  std::string err;
  switch (s) {
    case SceneId::kKnot:
      if (!host::load_obj(std::string(LR_SOURCE_DIR) + "/tests/host/data/torus_knot.obj", m, err))
        bench::die("quality_bench", err);
      break;
    case SceneId::kSphere:
      m = host::make_uv_sphere(40, 60);
      break;
    case SceneId::kClipped:
      m = test::coloured_ground(50);
      break;
    case SceneId::kCube:
      m = host::make_cube();
      break;
    case SceneId::kGround:
      m = test::ground_plane(200, 200);
      break;
  }
  return cache.emplace(s, std::move(m)).first->second;
}

inline host::SceneOptions scene_options(const Config& c) {
  host::SceneOptions o;
  switch (c.scene) {
    case SceneId::kKnot:  // the demo scene (accuracy_test, frame_bench)
      o = test::gold_options();
      break;
    case SceneId::kSphere:  // accuracy_test's sphere, 320 wide
      o = test::sphere_four_lights();
      break;
    case SceneId::kClipped:  // clipping_test: near corners at |x_ndc| ~ 100
      o.unlit = true;
      o.eye = {0, 1, 0};
      o.target = {0, 0.7, -5};
      o.far = 200;
      break;
    case SceneId::kCube:  // texture_bench's cube: top and two side faces, one light
      o = test::cube_view();
      break;
    case SceneId::kGround:  // texture_bench's ground plane, level camera 1 unit above it
      o = test::level_ground_view();
      break;
  }
  o.width = kWidth;
  o.height = kHeight;
  o.strip_height = c.strip;
  o.shading = c.shading;
  o.perspective = c.perspective;
  if (textured(c.scene)) {
    o.texture_format = c.format;
    o.texture_object = &texture(c.format).texture;
    o.filter = c.filter;
    o.wrap = Wrap::kRepeat;
    o.mipmap = c.mip;
  }
  return o;
}

inline bench::Prepared prepare(const host::HostMesh& mesh, const host::SceneOptions& o) {
  return bench::prepare(mesh, o, "quality_bench");
}

}  // namespace lr::quality
