#include "lineraster/host_sim/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <type_traits>
#include <unordered_map>

#include "lineraster/core/lighting/lighting_table.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/tangents.hpp"

namespace lr::host {
namespace {

uint16_t c15(double v) {
  if (!(v > 0)) return 0;
  if (v >= 1) return Color15::kOne;
  return static_cast<uint16_t>(std::lround(v * Color15::kOne));
}

int16_t n14(double v) {
  double c = std::fmin(1.0, std::fmax(-1.0, v));
  return static_cast<int16_t>(std::lround(c * (1 << Normal16::kFracBits)));
}

Material to_core_material(const Vec3d& ka, const Vec3d& kd, const Vec3d& ks, const Vec3d& ke,
                          double ns) {
  Material m;
  m.ambient = to_color15(ka);
  m.diffuse = to_color15(kd);
  m.specular = to_color15(ks);
  m.emission = to_color15(ke);
  double s = std::fmin(128.0, std::fmax(0.0, std::isfinite(ns) ? ns : 0.0));
  m.shininess_q8 = static_cast<uint16_t>(std::lround(s * 256.0));
  return m;
}

bool fixed_vec(const Vec3d& v, Vec3& out) {
  return to_fixed(v[0], out.x) && to_fixed(v[1], out.y) && to_fixed(v[2], out.z);
}

// v in fixed point of frac fraction bits (16: to_fixed); false when not finite or outside int32.
bool fine_vec(const Vec3d& v, int frac, Vec3& out) {
  if (frac == 16) return fixed_vec(v, out);
  Fixed* c[3] = {&out.x, &out.y, &out.z};
  for (int i = 0; i < 3; ++i) {
    const double s = std::ldexp(v[static_cast<size_t>(i)], frac);
    if (!std::isfinite(s) || std::fabs(s) >= 2147483647.5) return false;
    *c[i] = Fixed::from_raw(static_cast<int32_t>(std::llround(s)));
  }
  return true;
}

// "FILE:LINE: v (x, y, z) " for a vertex read from a file, else "mesh: vertex N (x, y, z) ".
std::string vertex_place(const HostMesh& mesh, uint32_t vi) {
  const Vec3d& p = mesh.positions[vi];
  char xyz[96];
  std::snprintf(xyz, sizeof xyz, "(%.9g, %.9g, %.9g) ", p[0], p[1], p[2]);
  const uint32_t line = vi < mesh.lines.size() ? mesh.lines[vi] : 0;
  if (!mesh.source.empty() && line != 0)
    return mesh.source + ":" + std::to_string(line) + ": v " + xyz;
  return "mesh: vertex " + std::to_string(vi) + " " + xyz;
}

}  // namespace

bool build_fixed_draws(const HostMesh& mesh, const SceneOptions& o, std::vector<FixedDraw>& draws,
                       std::string& error) {
  ModelTransform mt = model_transform(mesh, o);
  // The positions' fraction bits: the finest the fitted mesh's largest coordinate allows.
  int frac = 16;
  if (o.fine_positions) {
    double m = 0;
    for (const Vec3d& p : mesh.positions)
      for (int i = 0; i < 3; ++i)
        m = std::max(m,
                     std::fabs((p[static_cast<size_t>(i)] - mt.fit_center[static_cast<size_t>(i)]) *
                               mt.fit_scale));
    frac = position_frac_for(m);
  }
  const size_t nt = mesh.triangles.size();
  const bool tangents = !mesh.tangents.empty();
  if (tangents && mesh.tangents.size() != mesh.positions.size()) {
    error = "mesh: " + std::to_string(mesh.tangents.size()) + " tangents for " +
            std::to_string(mesh.positions.size()) + " vertices";
    return false;
  }
  // Group triangles by material, in first-use order, keeping submission order inside a group.
  std::vector<int32_t> order_of;
  std::vector<std::vector<uint32_t>> groups;
  std::unordered_map<int32_t, size_t> group_index;
  for (uint32_t t = 0; t < nt; ++t) {
    int32_t mat =
        o.use_mesh_materials && t < mesh.triangle_material.size() ? mesh.triangle_material[t] : -1;
    auto it = group_index.find(mat);
    if (it == group_index.end()) {
      it = group_index.emplace(mat, groups.size()).first;
      groups.emplace_back();
      order_of.push_back(mat);
    }
    groups[it->second].push_back(t);
  }
  for (size_t g = 0; g < groups.size(); ++g) {
    int32_t mat = order_of[g];
    Material material;
    if (mat >= 0 && static_cast<size_t>(mat) < mesh.materials.size()) {
      const HostMaterial& hm = mesh.materials[static_cast<size_t>(mat)];
      material = to_core_material(hm.ambient, hm.diffuse, hm.specular, hm.emission, hm.shininess);
    } else {
      const MaterialOptions& m = o.material;
      material = to_core_material(m.ambient, m.diffuse, m.specular, m.emission, m.shininess);
    }
    std::unordered_map<uint32_t, uint16_t> local;
    FixedDraw d;
    d.material = material;
    d.material_index = mat;
    d.position_frac = static_cast<uint8_t>(frac);
    auto flush = [&]() {
      if (!d.triangles.empty()) draws.push_back(std::move(d));
      d = FixedDraw{};
      d.material = material;
      d.material_index = mat;
      d.position_frac = static_cast<uint8_t>(frac);
      local.clear();
    };
    for (uint32_t t : groups[g]) {
      if (d.positions.size() + 3 > 0xFFFF) flush();
      std::array<uint16_t, 3> tri{};
      for (int k = 0; k < 3; ++k) {
        uint32_t vi = mesh.triangles[t][static_cast<size_t>(k)];
        if (vi >= mesh.positions.size()) {
          error = "mesh: triangle " + std::to_string(t) + " uses vertex " + std::to_string(vi) +
                  " of " + std::to_string(mesh.positions.size());
          return false;
        }
        auto [it, fresh] = local.emplace(vi, static_cast<uint16_t>(d.positions.size()));
        if (fresh) {
          const Vec3d& p = mesh.positions[vi];
          Vec3d q{(p[0] - mt.fit_center[0]) * mt.fit_scale,
                  (p[1] - mt.fit_center[1]) * mt.fit_scale,
                  (p[2] - mt.fit_center[2]) * mt.fit_scale};
          Vec3 fp;
          if (!fine_vec(q, frac, fp)) {
            error = vertex_place(mesh, vi) + "is not finite or outside the core's range " +
                    "(|x| < 32768" + (o.fit ? " after --fit" : "") + ")" +
                    (o.fit ? "" : "; try --fit");
            return false;
          }
          d.positions.push_back(fp);
          const Vec3d& n = vi < mesh.normals.size() ? mesh.normals[vi] : Vec3d{0, 0, 1};
          d.normals.push_back(Normal16{n14(n[0]), n14(n[1]), n14(n[2])});
          if (mesh.has_colors()) {
            const Vec3d& c = mesh.colors[vi];
            d.colors.push_back(to_rgb8(to_color15(c)));
          }
          if (mesh.has_uvs()) {
            TexCoord tc;
            if (!to_texcoord(mesh.uvs[vi], tc)) {
              error = "mesh: texture coordinate of vertex " + std::to_string(vi) +
                      " is not finite or outside the core's range (|u|, |v| < 2048)";
              return false;
            }
            d.uvs.push_back(tc);
          }
          if (tangents) {
            Tangent16 tan16;
            if (!to_tangent16(mesh.tangents[vi], tan16)) {
              error = "mesh: tangent of vertex " + std::to_string(vi) + " is not finite";
              return false;
            }
            d.tangents.push_back(tan16);
          }
        }
        tri[static_cast<size_t>(k)] = it->second;
      }
      d.triangles.push_back(tri);
    }
    flush();
  }
  return true;
}

namespace {

// The texture of each draw (nullptr: untextured), loaded once per file, and the frame's
// environment and normal maps (nullptr: none).
struct DrawTextures {
  std::vector<std::pair<std::string, std::unique_ptr<HostTexture>>> loaded;
  std::vector<const Texture*> per_draw;
  HostTexture envmap, normal_map;
  bool has_envmap = false, has_normal_map = false;
  std::vector<std::string> warnings;  // a material's texture left out
};

bool load_draw_textures(const HostMesh& mesh, const std::vector<FixedDraw>& draws,
                        const SceneOptions& o, DrawTextures& out, std::string& error) {
  for (const FixedDraw& d : draws) {
    if (o.texture_object != nullptr) {
      out.per_draw.push_back(o.texture_object);
      continue;
    }
    std::string path = o.texture;
    if (path.empty() && d.material_index >= 0 && size_t(d.material_index) < mesh.materials.size())
      path = mesh.materials[size_t(d.material_index)].map_kd;
    if (path.empty()) {
      out.per_draw.push_back(nullptr);
      continue;
    }
    if (d.uvs.empty() && o.texture.empty()) {
      // A material's map_Kd on faces without vt: drawn untextured, as other loaders do.
      const std::string w = path +
                            ": the faces of its material have no texture coordinates (vt): "
                            "drawn untextured";
      if (std::find(out.warnings.begin(), out.warnings.end(), w) == out.warnings.end())
        out.warnings.push_back(w);
      out.per_draw.push_back(nullptr);
      continue;
    }
    if (d.uvs.empty()) {
      error = path + ": the mesh has no texture coordinates (vt) to map it with";
      return false;
    }
    const HostTexture* found = nullptr;
    for (const auto& [p, t] : out.loaded)
      if (p == path) found = t.get();
    if (!found) {
      auto t = std::make_unique<HostTexture>();
      if (!load_texture(path, o.texture_format, o.mipmap != MipMode::kNone, *t, error))
        return false;
      found = t.get();
      out.loaded.emplace_back(path, std::move(t));
    }
    out.per_draw.push_back(&found->texture);
  }
  return true;
}

// The frame's lights: o.lights when given, else white directional lights along o.light_dirs.
bool build_lights(const SceneOptions& o, LightSet& lights, std::string& error) {
  std::vector<LightOption> list = o.lights;
  if (list.empty()) {
    for (const Vec3d& d : o.light_dirs) {
      LightOption l;
      l.xyz = d;
      list.push_back(l);
    }
  }
  if (list.size() > static_cast<size_t>(kMaxLights)) {
    error = "lights: at most " + std::to_string(kMaxLights);
    return false;
  }
  for (const LightOption& l : list) {
    const Color15 c = to_color15(l.color);
    if (!l.point) {
      const Vec3d& d = l.xyz;
      double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      Vec3 fd;
      if (!(len > 0) || !std::isfinite(len) ||
          !fixed_vec({d[0] / len, d[1] / len, d[2] / len}, fd)) {
        error = "light: direction must be finite and non-zero";
        return false;
      }
      lights.lights[lights.count++] = Light::directional(fd, c);
      continue;
    }
    Vec3 pos;
    if (!fixed_vec(l.xyz, pos)) {
      error = "light: point light position is not finite or outside the core's range (|x| < 32768)";
      return false;
    }
    Fixed kc, kl, kq;
    if (!(l.constant >= 0) || !(l.linear >= 0) || !(l.quadratic >= 0) ||
        !to_fixed(l.constant, kc) || !to_fixed(l.linear, kl) || !to_fixed(l.quadratic, kq) ||
        (kc.raw == 0 && kl.raw == 0 && kq.raw == 0)) {
      error = "light: attenuation coefficients must be finite, in [0, 32767] and not all 0";
      return false;
    }
    lights.lights[lights.count++] = Light::point(pos, c, kc, kl, kq);
  }
  lights.global_ambient = to_color15(o.global_ambient);
  lights.local_viewer = o.local_viewer;
  lights.two_sided = o.two_sided;
  return true;
}

// How many distinct materials the draws have (the core prepares lighting, and fills lighting
// tables, once per material).
size_t distinct_materials(const std::vector<FixedDraw>& draws) {
  std::vector<Material> seen;
  for (const FixedDraw& d : draws)
    if (std::find(seen.begin(), seen.end(), d.material) == seen.end()) seen.push_back(d.material);
  return seen.size();
}

template <class PF, int K>
bool render_k(const std::vector<FixedDraw>& draws, const DrawTextures& textures,
              const SceneOptions& o, RenderResult& out, std::string& error) {
  // Phong only: a SurfaceVertex per vertex-store entry, the lighting prepared per material, and
  // for kTable the table pool: one table per material, split (two words per sample) as textured
  // or environment-mapped draws need it.
  const bool phong = o.shading == Shading::kPhong;
  const size_t materials = phong ? distinct_materials(draws) : 0;
  FrameCapacities caps;
  caps.width = std::max(o.width, 0);
  caps.height = std::max(o.height, 0);
  caps.strip_height = K;
  caps.vertices = o.stores.vertices;
  caps.triangles = o.stores.triangles;
  caps.draws = 256;
  caps.active = o.stores.active;
  caps.surfaces = phong ? caps.vertices : 0;
  // Texture coordinates: a textured draw, or a Phong draw with a normal map.
  bool uv = phong && textures.has_normal_map;
  for (const Texture* t : textures.per_draw) uv = uv || t != nullptr;
  caps.tex_vertices = uv ? caps.vertices : 0;
  bool textured = false;
  for (const Texture* t : textures.per_draw) textured = textured || t != nullptr;
  caps.active_extra = phong || textured ? caps.active : 0;
  caps.triangle_colors = o.shading == Shading::kFlat ? caps.triangles : 0;
  caps.pixel_lights = materials;
  caps.lighting_table_words = o.pixel_lighting == PixelLighting::kTable
                                  ? materials * lighting_table_words(o.table.size, true)
                                  : 0;
  BasicFrameStorage<std::vector> store(caps);
  const FrameStorage storage = store.storage();
  auto renderer = std::make_unique<Renderer<PF, K>>();
  if (const Status cs = renderer->configure(storage, o.width, o.height); cs != Status::kOk) {
    error = cs == Status::kInvalidArgument
                ? "viewport: width and height must be 1.." + std::to_string(kMaxViewport)
                : std::string("stores: ") + to_string(cs);
    return false;
  }
  Fixed fovy, near, far;
  Vec3 eye, target, up;
  if (!to_fixed(o.fovy, fovy) || !to_fixed(o.near, near) || !to_fixed(o.far, far) ||
      !fixed_vec(o.eye, eye) || !fixed_vec(o.target, target) || !fixed_vec(o.up, up)) {
    error = "camera: a value is not finite or outside the core's range (|x| < 32768)";
    return false;
  }
  Camera cam;
  cam.eye = eye;
  Fixed aspect = Fixed::ratio(o.width, o.height);
  if (!perspective(fovy, aspect, near, far, cam.projection)) {
    error = "camera: need 0 < fovy < 180 and 0 < near < far";
    return false;
  }
  if (!look_at(eye, target, up, cam.view)) {
    error = "camera: eye equals target, or up is parallel to the view direction";
    return false;
  }
  LightSet lights;
  if (!build_lights(o, lights, error)) return false;
  if (phong && o.pixel_lighting == PixelLighting::kTable && !o.unlit && !lights.normal_only()) {
    error =
        "lighting table: needs directional lights only and no local viewer (use exact lighting)";
    return false;
  }
  Rgb8 bg = to_rgb8(to_color15(o.background));
  if (const Status bs = renderer->begin_frame(cam, lights, bg); bs != Status::kOk) {
    error = std::string("begin_frame: ") + to_string(bs);
    return false;
  }

  Fixed scale, rot_y, rot_x, rot_z;
  Vec3 tr;
  if (!to_fixed(o.model_scale, scale) || !to_fixed(o.model_rotate_y, rot_y) ||
      !to_fixed(o.model_rotate_x, rot_x) || !to_fixed(o.model_rotate_z, rot_z) ||
      !fixed_vec(o.model_translate, tr)) {
    error = "model: a transform value is not finite or outside the core's range";
    return false;
  }
  // Turned about z, then x, then y (SceneOptions); a rotation of 0 is left out, so a frame
  // without x and z rotations is the same matrix, bit for bit, as before they existed.
  Mat4 model = translate(tr) * rotate_y(rot_y);
  if (rot_x.raw != 0) model = model * rotate_x(rot_x);
  if (rot_z.raw != 0) model = model * rotate_z(rot_z);
  model = model * lr::scale(scale);
  DrawState st;
  st.shading = o.shading;
  st.lighting = !o.unlit;
  st.depth_test = o.depth_test;
  st.cull = o.cull;
  st.perspective = o.perspective;
  st.pixel_lighting = o.pixel_lighting;
  st.table = o.table;
  st.envmap = textures.has_envmap ? &textures.envmap.texture : nullptr;
  st.normal_map = textures.has_normal_map ? &textures.normal_map.texture : nullptr;
  out.incomplete = false;
  for (size_t i = 0; i < draws.size(); ++i) {
    const FixedDraw& d = draws[i];
    Mesh m = d.mesh();
    st.texture = textures.per_draw[i];
    st.sampler.filter = o.filter;
    st.sampler.wrap_s = st.sampler.wrap_t = o.wrap;
    st.sampler.mip = o.mipmap;
    st.sampler.env = o.unlit ? TexEnv::kReplace : TexEnv::kModulate;
    Status s = renderer->draw(m, model, d.material, st);
    if (s != Status::kOk && s != Status::kCapacity) {
      error = std::string("draw: ") + to_string(s);
      return false;
    }
    out.incomplete = out.incomplete || s == Status::kCapacity;
  }
  CaptureDisplay<PF> display(static_cast<size_t>(caps.width) * K);  // one strip
  DepthCapture depth_capture;
  depth_capture.resize(o.width, o.height);
  // kCapacity: a draw was refused for a full store, or a strip held more than the stores (the
  // frame is what fit; the statistics count what was dropped, and the caller is told:
  // RenderResult::incomplete). A draw refused for any other reason failed above.
  Status s = renderer->render(display, &depth_capture);
  if (s != Status::kOk && s != Status::kCapacity) {
    error = std::string("render: ") + to_string(s) + " " + display.error();
    return false;
  }
  out.image = display.image();
  out.rgb565.clear();
  if constexpr (std::is_same_v<PF, Rgb565Be>) {
    out.rgb565.reserve(display.raw_frame().size());
    for (const uint16_t p : display.raw_frame())
      out.rgb565.push_back(static_cast<uint16_t>(PF::to_value(p)));
  }
  out.depth = depth_capture.depth();
  out.stats = renderer->stats();
  out.incomplete = out.incomplete || s == Status::kCapacity ||
                   out.stats.dropped_vertex_capacity + out.stats.dropped_triangle_capacity > 0;
  out.strips = display.strips();
  out.bytes = display.bytes();
  return true;
}

}  // namespace

bool to_texcoord(const Vec2d& uv, TexCoord& out) {
  constexpr double kOne = double(1 << TexCoord::kFracBits);
  if (!std::isfinite(uv[0]) || !std::isfinite(uv[1]) || std::fabs(uv[0]) >= 2047.999 ||
      std::fabs(uv[1]) >= 2047.999)
    return false;
  out.u = static_cast<int32_t>(std::lround(uv[0] * kOne));
  out.v = static_cast<int32_t>(std::lround(uv[1] * kOne));
  return true;
}

bool to_tangent16(const Vec4d& t, Tangent16& out) {
  for (double c : t)
    if (!std::isfinite(c)) return false;
  out = Tangent16{
      n14(t[0]), n14(t[1]), n14(t[2]),
      static_cast<int16_t>(t[3] >= 0 ? 1 << Tangent16::kFracBits : -(1 << Tangent16::kFracBits))};
  return true;
}

int position_frac_for(double max_abs) {
  for (int frac = Mesh::kMaxPositionFrac; frac > Mesh::kMinPositionFrac; --frac)
    if (std::isfinite(max_abs) && std::llround(std::ldexp(max_abs, frac)) <= 2147483647)
      return frac;
  return Mesh::kMinPositionFrac;
}

bool to_fixed(double v, Fixed& out) {
  if (!std::isfinite(v) || std::fabs(v) >= 32767.5) return false;
  out = Fixed::from_raw(static_cast<int32_t>(std::lround(v * Fixed::kOne)));
  return true;
}

Color15 to_color15(const Vec3d& c) {
  return {c15(c[0]), c15(c[1]), c15(c[2])};
}

ModelTransform model_transform(const HostMesh& mesh, const SceneOptions& o) {
  ModelTransform mt;
  if (o.fit && !mesh.positions.empty()) {
    FitTransform f = fit_transform(mesh);
    mt.fit_center = f.center;
    mt.fit_scale = f.scale;
  }
  return mt;
}

bool render_scene(const HostMesh& mesh, const SceneOptions& o, RenderResult& out,
                  std::string& error) {
  const bool phong = o.shading == Shading::kPhong;
  if (!o.envmap.empty() && !phong) {
    error = o.envmap + ": an environment map needs Phong shading";
    return false;
  }
  if (!o.normalmap.empty() && !phong) {
    error = o.normalmap + ": a normal map needs Phong shading";
    return false;
  }
  if (phong && o.pixel_lighting == PixelLighting::kTable &&
      (o.table.size < 8 || o.table.size > 256)) {
    error = "lighting table: size must be 8..256 cells per side";
    return false;
  }
  // A normal map needs uvs and tangents: the mesh's, or computed here on a copy.
  const HostMesh* src = &mesh;
  HostMesh with_tangents;
  if (!o.normalmap.empty()) {
    if (!mesh.has_uvs()) {
      error = o.normalmap + ": the mesh has no texture coordinates (vt) to map it with";
      return false;
    }
    if (mesh.tangents.size() != mesh.positions.size()) {
      with_tangents = mesh;
      compute_tangents(with_tangents);
      src = &with_tangents;
    }
  }
  std::vector<FixedDraw> draws;
  if (!build_fixed_draws(*src, o, draws, error)) return false;
  if (draws.size() > 256) {
    error = "mesh: more than 256 draws (materials x 65535-vertex pieces)";
    return false;
  }
  DrawTextures textures;
  if (!load_draw_textures(*src, draws, o, textures, error)) return false;
  out.warnings = textures.warnings;
  if (!o.envmap.empty()) {
    if (!load_texture(o.envmap, o.texture_format, false, textures.envmap, error)) return false;
    textures.has_envmap = true;
  }
  if (!o.normalmap.empty()) {
    if (!load_texture(o.normalmap, TexelFormat::kRgb888, false, textures.normal_map, error))
      return false;
    textures.has_normal_map = true;
  }
  auto render_pf = [&]<class PF>(PF /*format*/, const SceneOptions& so) {
    switch (so.strip_height) {
      case 1:
        return render_k<PF, 1>(draws, textures, so, out, error);
      case 2:
        return render_k<PF, 2>(draws, textures, so, out, error);
      case 4:
        return render_k<PF, 4>(draws, textures, so, out, error);
      case 8:
        return render_k<PF, 8>(draws, textures, so, out, error);
      case 16:
        return render_k<PF, 16>(draws, textures, so, out, error);
      case 32:
        return render_k<PF, 32>(draws, textures, so, out, error);
      default:
        error = "strip height must be 1, 2, 4, 8, 16 or 32";
        return false;
    }
  };
  auto render_with = [&](const SceneOptions& so) {
    return so.rgb565 ? render_pf(Rgb565Be{}, so) : render_pf(Rgb888{}, so);
  };
  SceneOptions so = o;
  if (!render_with(so)) return false;
  // A strip touching more triangles than the binned store holds is the one thing bands cannot
  // split: narrower strips touch fewer, and the frame is the same at every strip height.
  while (out.incomplete && out.stats.dropped_triangle_capacity > 0 && so.strip_height > 1) {
    so.strip_height /= 2;
    if (!render_with(so)) return false;
  }
  out.strip_height = so.strip_height;
  return true;
}

}  // namespace lr::host
