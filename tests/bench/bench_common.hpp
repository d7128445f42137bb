// Plumbing shared by the texture and quality benchmarks: the names of the core's settings (as
// their command lines spell them), parsing them, and a scene prepared once in the core's
// formats (meshes, camera, lights, model, draw state) so that the timed frame converts nothing.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"

namespace lr::bench {

// Prints "WHO: WHAT" and exits with status 2.
[[noreturn]] inline void die(const char* who, const std::string& what) {
  std::fprintf(stderr, "%s: %s\n", who, what.c_str());
  std::exit(2);
}

inline const char* name(Shading s) {
  return s == Shading::kFlat ? "flat" : s == Shading::kGouraud ? "gouraud" : "phong";
}
inline const char* name(Filter f) {
  return f == Filter::kNearest ? "nearest" : "bilinear";
}
inline const char* name(Perspective p) {
  switch (p) {
    case Perspective::kExact:
      return "exact";
    case Perspective::kSpan8:
      return "span8";
    case Perspective::kSpan16:
      return "span16";
    case Perspective::kSpan32:
      return "span32";
    case Perspective::kAffine:
      return "affine";
  }
  return "?";
}
inline const char* name(MipMode m) {
  return m == MipMode::kNone ? "none" : m == MipMode::kNearest ? "nearest" : "linear";
}

inline const char* name(TexelFormat f) {
  return f == TexelFormat::kRgb565 ? "rgb565" : "rgb888";
}

inline const Filter kFilters[] = {Filter::kNearest, Filter::kBilinear};
inline const Perspective kModes[] = {Perspective::kExact, Perspective::kSpan8, Perspective::kSpan16,
                                     Perspective::kSpan32, Perspective::kAffine};
inline const MipMode kMips[] = {MipMode::kNone, MipMode::kNearest, MipMode::kLinear};

// The element of `all` whose name(e) is s (name found by argument-dependent lookup for a
// benchmark's own enums).
template <class E, size_t N>
bool parse(const char* s, const E (&all)[N], E& out) {
  for (E e : all)
    if (std::strcmp(s, name(e)) == 0) {
      out = e;
      return true;
    }
  return false;
}

// A scene in the core's formats, prepared once: meshes, camera, lights, model, draw state
// (built exactly as host::render_scene builds them, so the timed frame is the compared one).
struct Prepared {
  std::vector<host::FixedDraw> draws;
  Camera camera;
  LightSet lights;
  Rgb8 background{0, 0, 0};
  Mat4 model = Mat4::identity();
  DrawState state;
};

inline bool fixed3(const host::Vec3d& v, Vec3& out) {
  return host::to_fixed(v[0], out.x) && host::to_fixed(v[1], out.y) && host::to_fixed(v[2], out.z);
}

// Exits through die(who, ...) on a scene the core cannot take.
inline Prepared prepare(const host::HostMesh& mesh, const host::SceneOptions& o, const char* who) {
  Prepared p;
  std::string err;
  if (!host::build_fixed_draws(mesh, o, p.draws, err)) die(who, err);
  Fixed fovy, near, far, scale, rot;
  Vec3 eye, target, up, tr;
  if (!host::to_fixed(o.fovy, fovy) || !host::to_fixed(o.near, near) ||
      !host::to_fixed(o.far, far) || !fixed3(o.eye, eye) || !fixed3(o.target, target) ||
      !fixed3(o.up, up) || !host::to_fixed(o.model_scale, scale) ||
      !host::to_fixed(o.model_rotate_y, rot) || !fixed3(o.model_translate, tr))
    die(who, "scene values out of range");
  p.camera.eye = eye;
  if (!perspective(fovy, Fixed::ratio(o.width, o.height), near, far, p.camera.projection) ||
      !look_at(eye, target, up, p.camera.view))
    die(who, "bad camera");
  if (o.lights.empty()) {
    for (const host::Vec3d& d : o.light_dirs) {
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      Vec3 fd;
      if (!fixed3({d[0] / len, d[1] / len, d[2] / len}, fd)) die(who, "bad light");
      p.lights.lights[p.lights.count++] =
          Light::directional(fd, {Color15::kOne, Color15::kOne, Color15::kOne});
    }
  } else {
    // As host::render_scene builds them (directions normalised, colours and attenuation).
    for (const host::LightOption& l : o.lights) {
      Vec3 v;
      Fixed kc, kl, kq;
      host::Vec3d xyz = l.xyz;
      if (!l.point) {
        const double len = std::sqrt(xyz[0] * xyz[0] + xyz[1] * xyz[1] + xyz[2] * xyz[2]);
        xyz = {xyz[0] / len, xyz[1] / len, xyz[2] / len};
      }
      if (!fixed3(xyz, v) || !host::to_fixed(l.constant, kc) || !host::to_fixed(l.linear, kl) ||
          !host::to_fixed(l.quadratic, kq))
        die(who, "bad light");
      const Color15 c = host::to_color15(l.color);
      p.lights.lights[p.lights.count++] =
          l.point ? Light::point(v, c, kc, kl, kq) : Light::directional(v, c);
    }
  }
  p.lights.two_sided = o.two_sided;
  p.lights.global_ambient = host::to_color15(o.global_ambient);
  p.lights.local_viewer = o.local_viewer;
  p.background = to_rgb8(host::to_color15(o.background));
  p.model = translate(tr) * rotate_y(rot) * lr::scale(scale);
  p.state.shading = o.shading;
  p.state.lighting = !o.unlit;
  p.state.depth_test = o.depth_test;
  p.state.cull = o.cull;
  p.state.perspective = o.perspective;
  p.state.texture = o.texture_object;
  p.state.sampler.filter = o.filter;
  p.state.sampler.wrap_s = p.state.sampler.wrap_t = o.wrap;
  p.state.sampler.mip = o.mipmap;
  p.state.sampler.env = o.unlit ? TexEnv::kReplace : TexEnv::kModulate;
  p.state.pixel_lighting = o.pixel_lighting;
  p.state.table = o.table;
  return p;
}

}  // namespace lr::bench
