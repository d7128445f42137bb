#include "lineraster/core/binning/strip_inputs.hpp"

#include "lineraster/core/binning/draw_record.hpp"
#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/core/texture/texture.hpp"
#include "lineraster/core/vertex/screen_vertex.hpp"
#include "lineraster/core/vertex/surface_vertex.hpp"

namespace lr {

void InputHash::add(const void* p) {
  const auto a = reinterpret_cast<uintptr_t>(p);
  add(static_cast<uint32_t>(a));
  if constexpr (sizeof(uintptr_t) > 4) add(static_cast<uint32_t>(uint64_t{a} >> 32));
}

void InputHash::add(const ScreenVertex& v) {
  add(v.x);
  add(v.y);
  add(v.z);
  add(v.w);
  add(v.color);
}

void InputHash::add(const TexVertex& t) {
  add(t.u);
  add(t.v);
  add(t.spec);
}

void InputHash::add(const SurfaceVertex& s) {
  add(s.normal.x);
  add(s.normal.y);
  add(s.normal.z);
  add(s.position);
  add(static_cast<uint32_t>(static_cast<uint16_t>(s.tangent[0])) |
      static_cast<uint32_t>(static_cast<uint16_t>(s.tangent[1])) << 16);
  add(static_cast<uint32_t>(static_cast<uint16_t>(s.tangent[2])) |
      static_cast<uint32_t>(static_cast<uint16_t>(s.handedness)) << 16);
}

void InputHash::add(const Texture& t) {
  add(static_cast<const void*>(&t));
  add(uint32_t{static_cast<uint8_t>(t.format)} | uint32_t{t.level_count} << 8);
  for (uint8_t i = 0; i < t.level_count && i < t.levels.size(); ++i) {
    const TextureLevel& l = t.levels[i];
    add(static_cast<const void*>(l.rgb565.data()));
    add(static_cast<const void*>(l.bytes.data()));
    add(uint32_t{l.width} | uint32_t{l.height} << 16);
  }
  add(static_cast<const void*>(t.palette.data()));
  add(static_cast<uint32_t>(t.palette.size()));
}

void InputHash::add(const Material& m) {
  add(m.ambient);
  add(m.diffuse);
  add(m.specular);
  add(m.emission);
  add(uint32_t{m.shininess_q8});
}

void InputHash::add(const LightSet& s) {
  add(uint32_t{s.count} | uint32_t{s.local_viewer} << 8 | uint32_t{s.two_sided} << 9);
  add(s.global_ambient);
  for (uint8_t i = 0; i < s.count && i < s.lights.size(); ++i) {
    const Light& l = s.lights[i];
    add(uint32_t{static_cast<uint8_t>(l.kind)});
    add(l.position);
    add(l.ambient);
    add(l.diffuse);
    add(l.specular);
    add(l.constant);
    add(l.linear);
    add(l.quadratic);
  }
}

void InputHash::add(const Camera& c) {
  add(c.view);
  add(c.projection);
  add(c.eye);
}

void InputHash::add(const DrawRecord& d) {
  add(uint32_t{static_cast<uint8_t>(d.colors)} | uint32_t{d.depth} << 8 | uint32_t{d.flat} << 9 |
      uint32_t{d.phong} << 10 | uint32_t{d.two_sided} << 11 | uint32_t{d.position} << 12 |
      uint32_t{d.table_bilinear} << 13 | uint32_t{d.hue.valid} << 14);
  if (d.hue.valid) {
    add(d.hue.red);
    add(d.hue.blue);
  }
  add(uint32_t{static_cast<uint8_t>(d.filter)} | uint32_t{static_cast<uint8_t>(d.persp)} << 8 |
      uint32_t{d.span_len} << 16 | uint32_t{static_cast<uint8_t>(d.env)} << 24);
  add(uint32_t{static_cast<uint8_t>(d.mip)} | uint32_t{static_cast<uint8_t>(d.wrap_s)} << 8 |
      uint32_t{static_cast<uint8_t>(d.wrap_t)} << 16 |
      uint32_t{static_cast<uint8_t>(d.method)} << 24);
  for (const Texture* t : {d.texture, d.envmap, d.normal_map}) {
    if (t != nullptr)
      add(*t);
    else
      add(uint32_t{0});
  }
  add(uint32_t{d.table.size} | uint32_t{d.table.split} << 16);
  // The view matrix is the camera's, in every strip's seed (FrontEnd::begin_frame).
}

}  // namespace lr
