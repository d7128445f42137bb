// Phong span routines: per-pixel lighting of one row of one triangle.
//
// The normal (and, as needed, the world position, the tangent and the texture coordinates) is
// interpolated perspective-correctly from the triangle's planes. A span is processed in chunks
// of up to 16 pixels:
//   pass A tests depth and, for the pixels that pass only, computes their attributes;
//   the texture and the normal map are fetched for those pixels in one batch each;
//   pass B builds the shading normal (renormalised with the inverse-square-root table; tangent
//   frame and normal-map perturbation), lights it and, with an environment map, computes the
//   sphere-map coordinates of the reflected vector;
//   the environment map is fetched in one batch; pass C combines and writes.
// Lighting (PixelLighting):
//   kExact: light_point_split (the per-vertex lighting code) on the renormalised normal;
//   kTable: the normal-indexed lighting table (lighting_table.hpp). Without a normal map or an
//           environment map the table needs neither the perspective division of the normal
//           nor its renormalisation: the octahedral map is invariant to the vector's length.
// Colour: texel (texture) x texel (environment map) x primary + secondary, per channel clamped
// (GL_MODULATE on two texture units with GL_SEPARATE_SPECULAR_COLOR); untextured: primary +
// secondary.
// One template instance per (depth, method, table filter or position planes, texture, normal
// map, environment map): no per-pixel branch on the draw's state, except that the exact method
// evaluates the lights of the light set in a loop (directional and point lights differ).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "lineraster/core/binning/draw_record.hpp"
#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/lighting/lighting_table.hpp"
#include "lineraster/core/math/inv_sqrt.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/setup/active_triangle.hpp"
#include "lineraster/core/span/sampler.hpp"
#include "lineraster/core/span/span.hpp"
#include "lineraster/core/span/tex_span.hpp"

namespace lr {

template <class PF>
using PhongSpanFn = uint32_t (*)(const ActiveTriangle& t, const DrawRecord& d,
                                 typename PF::Storage* px, uint16_t* depth, int32_t col,
                                 int32_t row, int32_t count);

namespace detail {

// (a . b) of Q1.30 vectors in Q1.30.
constexpr int64_t dot30(const Unit30& a, const Unit30& b) {
  return (int64_t{a.x} * b.x + int64_t{a.y} * b.y + int64_t{a.z} * b.z) >> 30;
}

// A normal-map texel's channel (0..255) as a Q1.14 component in [-1, 1]: 2 c / 255 - 1
// (32897 / 256 = 128.50 = 2 * 16384 / 255 to within 2^-15).
constexpr int32_t normal_map_component(uint32_t c8) {
  return static_cast<int32_t>((c8 * 32897u) >> 8) - 16384;
}

// Sphere-map texel coordinates (Q.8 texels of level 0) of the reflection of the viewer's
// direction v about the unit normal n: r = 2 (n.v) n - v, turned into eye space by the view
// matrix; m = 2 |(r.x, r.y, r.z + 1)|, (s, t) = (r.x / m + 1/2, r.y / m + 1/2) (GL_SPHERE_MAP).
inline void sphere_map_coords(const Unit30& n, const Unit30& v, const Mat4& view, uint32_t w,
                              uint32_t h, int32_t& s, int32_t& t) {
  const int64_t ndv2 = 2 * dot30(n, v);  // Q1.30, |.| <= 2^31
  const int64_t r[3] = {((ndv2 * n.x) >> 30) - v.x, ((ndv2 * n.y) >> 30) - v.y,
                        ((ndv2 * n.z) >> 30) - v.z};  // |.| <= 3 * 2^30
  int64_t e[3];
  // Q16.16 matrix entries (|.| <= 1 for a rigid view) times Q1.30: below 2^50.
  for (int i = 0; i < 3; ++i)
    e[i] = (int64_t{view.m[i][0].raw} * r[0] + int64_t{view.m[i][1].raw} * r[1] +
            int64_t{view.m[i][2].raw} * r[2]) >>
           16;
  Unit30 u{0, 0, 0};
  if (!DefaultInvSqrt::normalize(e[0], e[1], e[2] + (int64_t{1} << 30), u)) {
    s = static_cast<int32_t>(w * 128u);  // r = (0, 0, -1): the map's centre
    t = static_cast<int32_t>(h * 128u);
    return;
  }
  // u = (r.x, r.y) / (m / 2): s = u.x / 2 + 1/2, in Q1.30 then in Q.8 texels.
  const int64_t s30 = (int64_t{u.x} >> 1) + (int64_t{1} << 29);
  const int64_t t30 = (int64_t{u.y} >> 1) + (int64_t{1} << 29);
  s = static_cast<int32_t>((s30 * w) >> 22);
  t = static_cast<int32_t>((t30 * h) >> 22);
}

constexpr uint32_t channel8(Texel t, int c) {
  return (t >> (16 - 8 * c)) & 255u;
}

}  // namespace detail

// kPositionOrBilinear is the method's own switch: the exact method's position planes, the table
// method's bilinear lookup (DrawRecord::position or ::table_bilinear).
template <class PF, bool kDepth, PixelLighting kMethod, bool kPositionOrBilinear, bool kTexture,
          bool kNormalMap, bool kEnv>
uint32_t fill_phong_span(const ActiveTriangle& tri, const DrawRecord& d, typename PF::Storage* px,
                         uint16_t* depth, int32_t col, int32_t row, int32_t count) {
  constexpr bool kExact = kMethod == PixelLighting::kExact;
  constexpr bool kPosition = kExact && kPositionOrBilinear;   // exact: position planes
  constexpr bool kBilinear = !kExact && kPositionOrBilinear;  // table: bilinear lookup
  constexpr bool kUv = kTexture || kNormalMap;
  constexpr bool kSplit = kTexture || kEnv;
  // Whether the normal must be a true unit vector (else the table takes it as it comes).
  constexpr bool kUnit = kExact || kNormalMap || kEnv;
  constexpr bool kDivide = kUnit || kUv || kPosition;
  constexpr int kChunk = 16;
  const PreparedLighting& pl = *d.lighting;

  uint32_t z = 0;
  if constexpr (kDepth) z = detail::depth_start(tri.z, col, row);
  uint32_t q = tri.q.at(col, row), s = 0, t = 0;
  uint32_t n[3], p[3] = {0, 0, 0}, tg[3] = {0, 0, 0};
  for (int c = 0; c < 3; ++c) {
    n[c] = tri.c[c].at(col, row);
    if constexpr (kPosition) p[c] = tri.ext->extra.position[c].at(col, row);
    if constexpr (kNormalMap) tg[c] = tri.ext->tan[c].at(col, row);
  }
  if constexpr (kUv) {
    s = tri.ext->s.at(col, row);
    t = tri.ext->t.at(col, row);
  }

  // Normal-map coordinates: in the texture's texels when both are given (sizes may differ).
  uint32_t nm_ratio_s = 0, nm_ratio_t = 0;
  if constexpr (kNormalMap && kTexture) {
    const TextureLevel& b = d.texture->levels[0];
    const TextureLevel& m = d.normal_map->levels[0];
    // uint16 sizes (TextureLevel): size 2^16 fits 32 bits, a 32-bit division.
    if (b.width != m.width) nm_ratio_s = (uint32_t{m.width} << 16) / b.width;
    if (b.height != m.height) nm_ratio_t = (uint32_t{m.height} << 16) / b.height;
  }
  [[maybe_unused]] const int last_level = kTexture ? d.texture->level_count - 1 : 0;

  int16_t idx[kChunk];
  int32_t nv[kChunk][3];  // interpolated normal (Q1.30 when divided; else n q)
  int32_t tv[kChunk][3];  // interpolated tangent, Q1.30
  Vec3 pos[kChunk];       // world position
  int32_t cs[kChunk], ct[kChunk], ns[kChunk], nt[kChunk], es[kChunk], et[kChunk];
  Texel tex[kChunk], tex1[kChunk], nmap[kChunk], env[kChunk];
  Color15 prim[kChunk], sec[kChunk];
  uint32_t written = 0;

  for (int32_t done = 0; done < count;) {
    const int len = count - done < kChunk ? static_cast<int>(count - done) : kChunk;

    detail::LevelChoice lv;
    if constexpr (kTexture) {
      if (d.mip != MipMode::kNone) {
        detail::PlaneValues pc{};
        const auto half = static_cast<uint32_t>(len / 2);
        pc.q = q + tri.q.gx * half;
        pc.s = s + tri.ext->s.gx * half;
        pc.t = t + tri.ext->t.gx * half;
        const int32_t lod = detail::lod_at(tri, pc);
        lv = d.mip == MipMode::kNearest ? detail::choose_levels<MipMode::kNearest>(lod, last_level)
                                        : detail::choose_levels<MipMode::kLinear>(lod, last_level);
      }
    }

    // Pass A: depth, then the attributes of the visible pixels.
    int m = 0;
    for (int i = 0; i < len; ++i) {
      const int k = static_cast<int>(done) + i;
      bool pass = true;
      if constexpr (kDepth) {
        pass = detail::depth_pass(z, depth[k]);
        z += tri.z.gx;
      }
      if (pass) {
        idx[m] = static_cast<int16_t>(k);
        if constexpr (kDivide) {
          const detail::PreciseRecip rc(q);
          if constexpr (kUnit) {
            for (int c = 0; c < 3; ++c) nv[m][c] = rc.div(n[c] - kPlaneBias, 30);
          } else {
            for (int c = 0; c < 3; ++c) nv[m][c] = unbias(n[c]);
          }
          if constexpr (kNormalMap)
            for (int c = 0; c < 3; ++c) tv[m][c] = rc.div(tg[c] - kPlaneBias, 30);
          if constexpr (kPosition) {
            int32_t w[3];
            for (int c = 0; c < 3; ++c) {
              const int64_t v = int64_t{tri.ext->org[c]} + rc.div(p[c] - kPlaneBias, tri.ext->m_p);
              w[c] = v > INT32_MAX   ? INT32_MAX
                     : v < INT32_MIN ? INT32_MIN
                                     : static_cast<int32_t>(v);
            }
            pos[m] = {Fixed::from_raw(w[0]), Fixed::from_raw(w[1]), Fixed::from_raw(w[2])};
          }
          if constexpr (kUv) {
            cs[m] = detail::wrap_add(rc.div(s, tri.ext->m_s), tri.ext->off_s);
            ct[m] = detail::wrap_add(rc.div(t, tri.ext->m_t), tri.ext->off_t);
          }
        } else {
          for (int c = 0; c < 3; ++c) nv[m][c] = unbias(n[c]);
        }
        ++m;
      }
      q += tri.q.gx;
      for (int c = 0; c < 3; ++c) {
        n[c] += tri.c[c].gx;
        if constexpr (kPosition) p[c] += tri.ext->extra.position[c].gx;
        if constexpr (kNormalMap) tg[c] += tri.ext->tan[c].gx;
      }
      if constexpr (kUv) {
        s += tri.ext->s.gx;
        t += tri.ext->t.gx;
      }
    }
    done += len;
    if (m == 0) continue;

    // Texture and normal-map texels of the visible pixels.
    if constexpr (kTexture) {
      d.fetch(*d.texture, lv.level0, cs, ct, m, tex);
      if (d.mip == MipMode::kLinear && lv.weight != 0) {
        d.fetch(*d.texture, lv.level1, cs, ct, m, tex1);
        for (int j = 0; j < m; ++j) tex[j] = detail::lerp_texel(tex[j], tex1[j], lv.weight);
      }
    }
    if constexpr (kNormalMap) {
      const int32_t* ss = cs;
      const int32_t* tt = ct;
      if constexpr (kTexture) {
        if (nm_ratio_s != 0 || nm_ratio_t != 0) {
          for (int j = 0; j < m; ++j) {
            ns[j] =
                nm_ratio_s == 0 ? cs[j] : static_cast<int32_t>((int64_t{cs[j]} * nm_ratio_s) >> 16);
            nt[j] =
                nm_ratio_t == 0 ? ct[j] : static_cast<int32_t>((int64_t{ct[j]} * nm_ratio_t) >> 16);
          }
          ss = ns;
          tt = nt;
        }
      }
      d.nmap_fetch(*d.normal_map, 0, ss, tt, m, nmap);
    }

    // Pass B: shading normal, lighting, environment-map coordinates.
    for (int j = 0; j < m; ++j) {
      Unit30 nn{nv[j][0], nv[j][1], nv[j][2]};
      if constexpr (kUnit) {
        nn = Unit30{0, 0, 1 << 30};
        DefaultInvSqrt::normalize(nv[j][0], nv[j][1], nv[j][2], nn);
      }
      if constexpr (kNormalMap) {
        // Tangent frame: T made orthogonal to N (Gram-Schmidt), B = handedness x (N x T).
        const Unit30 t0{tv[j][0], tv[j][1], tv[j][2]};
        const int64_t ndt = detail::dot30(nn, t0);
        Unit30 tt{1 << 30, 0, 0};
        DefaultInvSqrt::normalize(t0.x - ((ndt * nn.x) >> 30), t0.y - ((ndt * nn.y) >> 30),
                                  t0.z - ((ndt * nn.z) >> 30), tt);
        int64_t b[3] = {(int64_t{nn.y} * tt.z - int64_t{nn.z} * tt.y) >> 30,
                        (int64_t{nn.z} * tt.x - int64_t{nn.x} * tt.z) >> 30,
                        (int64_t{nn.x} * tt.y - int64_t{nn.y} * tt.x) >> 30};
        if (tri.ext->handedness < 0)
          for (int64_t& c : b) c = -c;
        const int64_t kx = detail::normal_map_component(detail::channel8(nmap[j], 0));
        const int64_t ky = detail::normal_map_component(detail::channel8(nmap[j], 1));
        const int64_t kz = detail::normal_map_component(detail::channel8(nmap[j], 2));
        // Q1.14 x Q1.30: each term below 2^44.
        const int64_t x = kx * tt.x + ky * b[0] + kz * nn.x;
        const int64_t y = kx * tt.y + ky * b[1] + kz * nn.y;
        const int64_t zz = kx * tt.z + ky * b[2] + kz * nn.z;
        DefaultInvSqrt::normalize(x, y, zz, nn);
      }
      if constexpr (kExact) {
        const LitColor lc = light_point_split(pl, nn, kPosition ? pos[j] : Vec3{});
        prim[j] = lc.primary;
        sec[j] = lc.secondary;
      } else {
        lookup_lighting<kBilinear, kSplit>(d.table, nn.x, nn.y, nn.z, prim[j], sec[j]);
      }
      if constexpr (kEnv) {
        Unit30 v = pl.view;
        if constexpr (kPosition) {
          if (pl.local_viewer)
            DefaultInvSqrt::normalize(int64_t{pl.eye.x.raw} - pos[j].x.raw,
                                      int64_t{pl.eye.y.raw} - pos[j].y.raw,
                                      int64_t{pl.eye.z.raw} - pos[j].z.raw, v);
        }
        const TextureLevel& e0 = d.envmap->levels[0];
        detail::sphere_map_coords(nn, v, *d.view, e0.width, e0.height, es[j], et[j]);
      }
    }
    if constexpr (kEnv) d.env_fetch(*d.envmap, 0, es, et, m, env);

    // Pass C: combine and write.
    for (int j = 0; j < m; ++j) {
      Rgb8 out;
      if constexpr (kSplit) {
        uint32_t ch[3];
        for (int c = 0; c < 3; ++c) {
          uint32_t texel = 255;
          if constexpr (kTexture) texel = detail::channel8(tex[j], c);
          if constexpr (kEnv) texel = (texel * detail::channel8(env[j], c) + 127u) / 255u;
          ch[c] = detail::modulate(texel, channel(prim[j], c), channel(sec[j], c));
        }
        out = {static_cast<uint8_t>(ch[0]), static_cast<uint8_t>(ch[1]),
               static_cast<uint8_t>(ch[2])};
      } else if constexpr (kExact) {
        auto sum = [](uint32_t a, uint32_t b) {
          return to_byte(clamp_c15(static_cast<int32_t>(a + b)));
        };
        out = {sum(prim[j].r, sec[j].r), sum(prim[j].g, sec[j].g), sum(prim[j].b, sec[j].b)};
      } else {
        out = {to_byte(clamp_c15(prim[j].r)), to_byte(clamp_c15(prim[j].g)),
               to_byte(clamp_c15(prim[j].b))};
      }
      px[idx[j]] = PF::encode(out);
    }
    written += static_cast<uint32_t>(m);
  }
  return written;
}

// The Phong family (dispatch.hpp): fill_phong_span per (depth test, method, second, texture,
// normal map, environment map); the filter and the mip mode are the draw's, per chunk.
template <class PF>
struct PhongSpans {
  using Layout = PhongLayout;
  using Fn = PhongSpanFn<PF>;
  static constexpr auto kUsed = &UsedRoutines::phong;
  template <bool kDepth, PixelLighting kMethod, bool kSecond, bool kTexture, bool kNormalMap,
            bool kEnv>
  static constexpr Fn routine() {
    return &fill_phong_span<PF, kDepth, kMethod, kSecond, kTexture, kNormalMap, kEnv>;
  }
};

template <class PF, SpanSet kSet = kAllSpans>
inline constexpr std::array<PhongSpanFn<PF>, kPhongRoutines> kPhongSpanTable =
    make_table<PhongSpans<PF>, kSet>();

// The Phong span routine for a draw: generated from the template and the state space, indexed
// by its state (nullptr for a state outside kSet, which draw() refuses).
template <class PF, SpanSet kSet = kAllSpans>
constexpr PhongSpanFn<PF> phong_span_routine(const DrawRecord& d) {
  const bool table = d.method == PixelLighting::kTable;
  return kPhongSpanTable<PF, kSet>[phong_index(
      d.depth, d.method, table ? d.table_bilinear : d.position, d.texture != nullptr,
      d.normal_map != nullptr, d.envmap != nullptr)];
}

}  // namespace lr
