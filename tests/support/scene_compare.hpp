// Renders one scene with the fixed-point core and with the double reference, and measures the
// difference: per-channel error on pixels both cover, and coverage disagreements.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "lineraster/host_sim/scene/tangents.hpp"
#include "tests/reference/ref_renderer.hpp"
#include "tests/reference/ref_texture_core.hpp"

namespace lr::test {

// The reference's parameters for the same options (same matrices in double).
inline ref::RefParams ref_params(const host::HostMesh& mesh, const host::SceneOptions& o) {
  ref::RefParams p;
  p.width = o.width;
  p.height = o.height;
  host::ModelTransform mt = host::model_transform(mesh, o);
  ref::Mat4d fit =
      ref::mul(ref::scale({mt.fit_scale, mt.fit_scale, mt.fit_scale}),
               ref::translate({-mt.fit_center[0], -mt.fit_center[1], -mt.fit_center[2]}));
  const ref::Mat4d rotation =
      ref::mul(ref::rotate_y(o.model_rotate_y),
               ref::mul(ref::rotate_x(o.model_rotate_x), ref::rotate_z(o.model_rotate_z)));
  p.model = ref::mul(ref::mul(ref::translate(o.model_translate), rotation),
                     ref::mul(ref::scale({o.model_scale, o.model_scale, o.model_scale}), fit));
  p.view = ref::look_at(o.eye, o.target, o.up);
  p.projection = ref::perspective(o.fovy, double(o.width) / o.height, o.near, o.far);
  if (o.lights.empty()) {
    for (const auto& d : o.light_dirs) p.lights.push_back(ref::RefLight{d, {1, 1, 1}});
  } else {
    for (const host::LightOption& l : o.lights) {
      ref::RefLight r{l.xyz, l.color};
      if (l.point) {
        r.kind = ref::RefLightKind::Point;
        r.position = l.xyz;
        r.constant = l.constant;
        r.linear = l.linear;
        r.quadratic = l.quadratic;
      }
      p.lights.push_back(r);
    }
  }
  p.two_sided = o.two_sided;
  p.global_ambient = o.global_ambient;
  p.material = {o.material.ambient, o.material.diffuse, o.material.specular, o.material.emission,
                o.material.shininess};
  p.shading = o.shading == Shading::kFlat      ? ref::RefShading::Flat
              : o.shading == Shading::kGouraud ? ref::RefShading::Gouraud
                                               : ref::RefShading::Phong;
  p.unlit = o.unlit;
  p.depth_test = o.depth_test;
  p.cull_back = o.cull == Cull::kBack;
  p.local_viewer = o.local_viewer;
  p.background = o.background;
  return p;
}

struct Comparison {
  size_t both = 0;           // pixels covered by both
  size_t coverage_diff = 0;  // covered by one only
  size_t within1 = 0;        // of `both`: every channel within 1 level
  int max_error = 0;         // of `both`: largest channel difference
  double mean_error = 0;     // of `both`: mean absolute channel difference
  double psnr = 0;           // over `both`
  host::RenderResult core;
  ref::RefFrame reference;

  // 0 when no pixel is covered by both: comparing nothing must not count as accurate. Every
  // test also bounds `both` from below (a frame that lost most of its pixels compares few).
  double fraction_within1() const { return both ? double(within1) / double(both) : 0.0; }
  std::string summary() const {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "both=%zu within1=%.4f%% max=%d mean=%.4f psnr=%.2fdB coverage_diff=%zu", both,
                  100.0 * fraction_within1(), max_error, mean_error, psnr, coverage_diff);
    return buf;
  }
};

// The classic table's gold as CLI options would give it (--fit --material gold).
inline host::SceneOptions gold_options(host::SceneOptions o = {}) {
  o.fit = true;
  o.material = {{0.24725, 0.1995, 0.0745},
                {0.75164, 0.60648, 0.22648},
                {0.628281, 0.555802, 0.366065},
                {0, 0, 0},
                51.2};
  return o;
}

// Fills c's figures from c.core and c.reference (frames of the same size). Coverage: the core's
// depth was written (with depth_test off, a pixel not black), the reference's owner is set.
inline void measure(bool depth_test, Comparison& c) {
  const size_t n = c.core.depth.size();
  double sum = 0, sq = 0;
  for (size_t p = 0; p < n; ++p) {
    bool core_cov = c.core.depth[p] != 0xFFFF || !depth_test;
    bool ref_cov = c.reference.owner[p] >= 0;
    if (!depth_test) {
      const uint8_t* a = &c.core.image.rgb[3 * p];
      core_cov = !(a[0] == 0 && a[1] == 0 && a[2] == 0);
    }
    if (core_cov != ref_cov) {
      ++c.coverage_diff;
      continue;
    }
    if (!core_cov) continue;
    ++c.both;
    int worst = 0;
    for (int k = 0; k < 3; ++k) {
      int e = std::abs(int(c.core.image.rgb[3 * p + size_t(k)]) -
                       int(c.reference.rgb8[3 * p + size_t(k)]));
      worst = std::max(worst, e);
      sum += e;
      sq += double(e) * e;
    }
    c.max_error = std::max(c.max_error, worst);
    if (worst <= 1) ++c.within1;
  }
  if (c.both) {
    c.mean_error = sum / (3.0 * double(c.both));
    double mse = sq / (3.0 * double(c.both));
    c.psnr = mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : 99.0;
  }
}

// Whether render_scene draws mesh with its MTL materials (one draw per material).
inline bool uses_mesh_materials(const host::HostMesh& mesh, const host::SceneOptions& o) {
  if (!o.use_mesh_materials) return false;
  for (int32_t m : mesh.triangle_material)
    if (m >= 0 && size_t(m) < mesh.materials.size()) return true;
  return false;
}

// The reference of a mesh drawn with its MTL materials, as render_scene draws it: the triangles
// of each material (in first-use order, the options' material for triangles without one) rendered
// with that material's colours and map_Kd (loaded as render_scene loads it, unless the options
// give a texture), the frames composited by depth (LESS: a later material's pixel wins where it
// is nearer). `base` holds everything else. Owners are the mesh's triangle indices.
inline bool render_reference_by_material(const host::HostMesh& mesh, const host::SceneOptions& o,
                                         const ref::RefParams& base, ref::RefFrame& out,
                                         std::string& error) {
  std::vector<int32_t> order;  // materials in first-use order
  std::vector<std::vector<uint32_t>> groups;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    int32_t m = t < mesh.triangle_material.size() ? mesh.triangle_material[t] : -1;
    if (m >= 0 && size_t(m) >= mesh.materials.size()) m = -1;
    size_t g = 0;
    while (g < order.size() && order[g] != m) ++g;
    if (g == order.size()) {
      order.push_back(m);
      groups.emplace_back();
    }
    groups[g].push_back(uint32_t(t));
  }
  for (size_t g = 0; g < groups.size(); ++g) {
    host::HostMesh part = mesh;
    part.triangles.clear();
    part.triangle_material.clear();
    for (uint32_t t : groups[g]) {
      part.triangles.push_back(mesh.triangles[t]);
      part.triangle_material.push_back(order[g]);
    }
    ref::RefParams rp = base;
    ref::RefTexture rt;
    if (order[g] >= 0) {
      const host::HostMaterial& hm = mesh.materials[size_t(order[g])];
      rp.material = {hm.ambient, hm.diffuse, hm.specular, hm.emission, hm.shininess};
      if (o.texture_object == nullptr && o.texture.empty()) {
        rp.texture = nullptr;
        if (!hm.map_kd.empty() && mesh.has_uvs()) {
          host::HostTexture loaded;
          if (!host::load_texture(hm.map_kd, o.texture_format, o.mipmap != MipMode::kNone, loaded,
                                  error))
            return false;
          rt = ref::from_core(loaded.texture);
          rp.texture = &rt;
        }
      }
    }
    ref::RefFrame f;
    ref::render(part, rp, f);
    if (g == 0) {
      out = f;
      for (int32_t& owner : out.owner)
        if (owner >= 0) owner = int32_t(groups[g][size_t(owner)]);
      continue;
    }
    for (size_t p = 0; p < f.owner.size(); ++p) {
      if (f.owner[p] < 0) continue;
      if (out.owner[p] >= 0 && base.depth_test && !(f.depth[p] < out.depth[p])) continue;
      out.color[p] = f.color[p];
      for (size_t k = 0; k < 3; ++k) out.rgb8[3 * p + k] = f.rgb8[3 * p + k];
      out.depth[p] = f.depth[p];
      out.owner[p] = int32_t(groups[g][size_t(f.owner[p])]);
      out.lod[p] = f.lod[p];
      out.normal[p] = f.normal[p];
    }
  }
  return true;
}

inline bool compare_scene(const host::HostMesh& mesh, const host::SceneOptions& o, Comparison& c,
                          std::string& error) {
  if (!host::render_scene(mesh, o, c.core, error)) return false;
  ref::RefParams rp = ref_params(mesh, o);
  ref::RefTexture rt, env, nmap;
  // The environment and normal maps as the scene loads them (level 0 only).
  host::HostTexture loaded;
  if (!o.envmap.empty()) {
    if (!host::load_texture(o.envmap, o.texture_format, false, loaded, error)) return false;
    env = ref::from_core(loaded.texture);
    rp.envmap = &env;
  }
  if (!o.normalmap.empty()) {
    if (!host::load_texture(o.normalmap, TexelFormat::kRgb888, false, loaded, error)) return false;
    nmap = ref::from_core(loaded.texture);
    rp.normal_map = &nmap;
    rp.filter = ref::from_core(o.filter);
    rp.wrap_s = rp.wrap_t = ref::from_core(o.wrap);
  }
  Sampler smp;
  smp.filter = o.filter;
  smp.wrap_s = smp.wrap_t = o.wrap;
  smp.mip = o.mipmap;
  smp.env = o.unlit ? TexEnv::kReplace : TexEnv::kModulate;
  if (o.texture_object != nullptr) {
    rt = ref::from_core(*o.texture_object);
    rp.texture = &rt;
    ref::set_sampler(rp, smp);
  }
  host::HostMesh with_tangents;
  const bool tangents = !o.normalmap.empty() && mesh.tangents.empty();
  if (tangents) {
    with_tangents = mesh;  // as the scene computes them
    host::compute_tangents(with_tangents);
  }
  const host::HostMesh& drawn = tangents ? with_tangents : mesh;
  if (uses_mesh_materials(mesh, o)) {
    ref::set_sampler(rp, smp);  // for the materials' textures
    if (!render_reference_by_material(drawn, o, rp, c.reference, error)) return false;
  } else {
    ref::render(drawn, rp, c.reference);
  }
  measure(o.depth_test, c);
  return true;
}

}  // namespace lr::test
