#include "tests/reference/ref_renderer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "tests/reference/int128.hpp"

namespace lr::ref {
namespace {

#if defined(__SIZEOF_INT128__)
__extension__ typedef __int128 i128;
#else
using i128 = Int128;  // 32-bit targets (the armhf test build): the same exact values
#endif

// Largest |snapped coordinate| accepted: differences fit in int64 and edge-function products
// (< 2^61 * 2^62) fit in __int128 with room to spare.
constexpr double kMaxSub = 1152921504606846976.0;  // 2^60

int clamp_bits(int bits) {
  return std::clamp(bits, 1, 16);
}

int64_t floor_div(int64_t a, int64_t b) {  // b > 0
  int64_t q = a / b;
  if (a % b != 0 && a < 0) --q;
  return q;
}

int64_t ceil_div(int64_t a, int64_t b) {
  return -floor_div(-a, b);
}

double clamp01(double c) {
  return c > 0.0 ? (c < 1.0 ? c : 1.0) : 0.0;
}  // NaN -> 0

Vec3d clamp01(const Vec3d& c) {
  return {clamp01(c[0]), clamp01(c[1]), clamp01(c[2])};
}

uint8_t to_byte(double c) {
  return static_cast<uint8_t>(std::lround(255.0 * clamp01(c)));
}

i128 area2_exact(const ScreenTri& t) {
  return static_cast<i128>(t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) -
         static_cast<i128>(t.x[2] - t.x[0]) * (t.y[1] - t.y[0]);
}

// A triangle reordered to positive signed display area (clockwise on screen), so that the edge
// function of every edge is positive inside.
struct TriSetup {
  bool valid = false;
  int64_t x[3] = {}, y[3] = {};
  int order[3] = {0, 1, 2};  // original index of each reordered vertex
  bool owned[3] = {};        // edge k runs from vertex k to vertex k + 1 (reordered)
  i128 area = 0;             // > 0 when valid
};

TriSetup setup_tri(const ScreenTri& t) {
  TriSetup s;
  const i128 a = area2_exact(t);
  if (a == 0) return s;
  s.valid = true;
  s.area = a > 0 ? a : -a;
  if (a < 0) {
    s.order[1] = 2;
    s.order[2] = 1;
  }
  for (int k = 0; k < 3; ++k) {
    s.x[k] = t.x[s.order[k]];
    s.y[k] = t.y[s.order[k]];
  }
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    const int64_t dx = s.x[k1] - s.x[k];
    const int64_t dy = s.y[k1] - s.y[k];
    // Inward normal of the edge is (-dy, dx). Left edge: interior at larger x (-dy > 0).
    // Bottom edge: horizontal with the interior at smaller display y (dx < 0).
    s.owned[k] = dy < 0 || (dy == 0 && dx < 0);
  }
  return s;
}

// Edge function of edge k at p: the (unnormalized) barycentric weight of vertex k + 2.
i128 edge_fn(const TriSetup& s, int k, int64_t px, int64_t py) {
  const int k1 = (k + 1) % 3;
  return static_cast<i128>(s.x[k1] - s.x[k]) * (py - s.y[k]) -
         static_cast<i128>(s.y[k1] - s.y[k]) * (px - s.x[k]);
}

// Fill rule at p. On success w[i] holds the weight of ORIGINAL vertex i (sum = s.area).
bool inside(const TriSetup& s, int64_t px, int64_t py, i128 w[3]) {
  for (int k = 0; k < 3; ++k) {
    const i128 e = edge_fn(s, k, px, py);
    if (e < 0 || (e == 0 && !s.owned[k])) return false;
    w[s.order[(k + 2) % 3]] = e;
  }
  return true;
}

bool in_range(const ScreenTri& t) {
  for (int k = 0; k < 3; ++k) {
    const double ax = static_cast<double>(t.x[k]), ay = static_cast<double>(t.y[k]);
    if (!(std::fabs(ax) <= kMaxSub) || !(std::fabs(ay) <= kMaxSub)) return false;
  }
  return true;
}

// Calls fn(i, j, w) for every covered pixel centre on the screen, row by row.
template <class F>
void raster(const TriSetup& s, int width, int height, int bits, F&& fn) {
  if (!s.valid || width <= 0 || height <= 0) return;
  const int64_t S = int64_t{1} << bits, half = S / 2;
  const int64_t minx = std::min({s.x[0], s.x[1], s.x[2]});
  const int64_t maxx = std::max({s.x[0], s.x[1], s.x[2]});
  const int64_t miny = std::min({s.y[0], s.y[1], s.y[2]});
  const int64_t maxy = std::max({s.y[0], s.y[1], s.y[2]});
  const int64_t i0 = std::max<int64_t>(0, ceil_div(minx - half, S));
  const int64_t i1 = std::min<int64_t>(width - 1, floor_div(maxx - half, S));
  const int64_t j0 = std::max<int64_t>(0, ceil_div(miny - half, S));
  const int64_t j1 = std::min<int64_t>(height - 1, floor_div(maxy - half, S));
  i128 w[3];
  for (int64_t j = j0; j <= j1; ++j) {
    const int64_t py = j * S + half;
    for (int64_t i = i0; i <= i1; ++i) {
      if (inside(s, i * S + half, py, w)) fn(static_cast<int>(i), static_cast<int>(j), w);
    }
  }
}

// Precomputed lighting state for one render call.
class Lighting {
 public:
  explicit Lighting(const RefParams& p) : p_(p) {
    for (const RefLight& l : p.lights) dirs_.push_back(normalize(l.direction));
    // Infinite viewer: the eye-space +Z axis (towards the eye) expressed in world space.
    v_inf_ = normalize(Vec3d{p.view.m[2][0], p.view.m[2][1], p.view.m[2][2]});
    Mat4d inv;
    if (invert(p.view, inv)) {
      const Vec4d e = transform(inv, Vec4d{0, 0, 0, 1});
      if (e[3] != 0.0) eye_ = {e[0] / e[3], e[1] / e[3], e[2] / e[3]};
    }
  }

  // The unit vector from pos towards the viewer.
  Vec3d view_dir(const Vec3d& pos) const {
    return p_.local_viewer ? normalize(sub(eye_, pos)) : v_inf_;
  }

  Vec3d at(const Vec3d& n, const Vec3d& pos) const {
    Vec3d c, spec;
    accumulate<false>(n, pos, c, spec);
    return clamp01(c);
  }

  // GL_SEPARATE_SPECULAR_COLOR: the same terms as at(), specular kept apart; each part clamped.
  RefLitColor separate(const Vec3d& n, const Vec3d& pos) const {
    Vec3d c, spec;
    accumulate<true>(n, pos, c, spec);
    return {clamp01(c), clamp01(spec)};
  }

 private:
  // c = emission + global ambient * Ka + per light (La Ka + max(N.L, 0) Ld Kd [+ specular]),
  // specular = max(N.H, 0)^shininess Ls Ks where N.L > 0, added to c or (kSplit) to spec.
  // Directional lights are not attenuated (the arithmetic of the original directional-only
  // renderer, bit for bit); point lights multiply each of their terms by the attenuation.
  template <bool kSplit>
  void accumulate(const Vec3d& n, const Vec3d& pos, Vec3d& c, Vec3d& spec) const {
    const RefMaterial& m = p_.material;
    c = add(m.emission, cmul(p_.global_ambient, m.ambient));
    spec = {0, 0, 0};
    const Vec3d v = view_dir(pos);
    for (size_t i = 0; i < dirs_.size(); ++i) {
      const RefLight& light = p_.lights[i];
      const Vec3d& la = light.separate_colors ? light.ambient : light.color;
      const Vec3d& ld = light.separate_colors ? light.diffuse : light.color;
      const Vec3d& ls = light.separate_colors ? light.specular : light.color;
      const bool point = light.kind == RefLightKind::Point;
      Vec3d l = dirs_[i];
      double att = 1.0;
      if (point) {
        const Vec3d to_light = sub(light.position, pos);
        const double d = length(to_light);
        l = normalize(to_light);
        att = 1.0 / (light.constant + light.linear * d + light.quadratic * d * d);
      }
      Vec3d amb = cmul(la, m.ambient);
      if (point) amb = muls(amb, att);
      c = add(c, amb);
      const double ndl = dot(n, l);
      if (ndl > 0.0) {
        Vec3d dif = muls(cmul(ld, m.diffuse), ndl);
        if (point) dif = muls(dif, att);
        c = add(c, dif);
        const Vec3d h = normalize(add(l, v));
        const double ndh = std::max(dot(n, h), 0.0);
        Vec3d spe = muls(cmul(ls, m.specular), std::pow(ndh, m.shininess));
        if (point) spe = muls(spe, att);
        if constexpr (kSplit) {
          spec = add(spec, spe);
        } else {
          c = add(c, spe);
        }
      }
    }
  }

  const RefParams& p_;
  std::vector<Vec3d> dirs_;
  Vec3d v_inf_{0, 0, 1};
  Vec3d eye_{0, 0, 0};
};

Vec3d lerp3(const Vec3d& a, const Vec3d& b, double t) {
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

// Perspective-correct interpolation: (q0 a + q1 b + q2 c) * qs per component.
Vec3d persp3(const Vec3d& a, const Vec3d& b, const Vec3d& c, double q0, double q1, double q2,
             double qs) {
  Vec3d r{};
  for (size_t k = 0; k < 3; ++k) r[k] = (q0 * a[k] + q1 * b[k] + q2 * c[k]) * qs;
  return r;
}

Vec3d neg(const Vec3d& a) {
  return {-a[0], -a[1], -a[2]};
}

// Spherical linear interpolation of unit vectors a and b; normalized lerp where the angle (or
// its sine) is below 1e-9.
Vec3d slerp(const Vec3d& a, const Vec3d& b, double t) {
  const double th = std::acos(std::clamp(dot(a, b), -1.0, 1.0));
  const double st = std::sin(th);
  if (!(th >= 1e-9) || !(st >= 1e-9)) return normalize(lerp3(a, b, t));
  return add(muls(a, std::sin((1.0 - t) * th) / st), muls(b, std::sin(t * th) / st));
}

// RefNormalInterp::Slerp at pixel centre (px, py) of the screen triangle (xs, ys) (pixels,
// display coordinates) with unit vertex normals n.
Vec3d scanline_slerp(const double xs[3], const double ys[3], const Vec3d n[3], double px,
                     double py) {
  bool found = false;
  double xl = 0, xr = 0;
  Vec3d nl{0, 0, 0}, nr{0, 0, 0};
  for (int e = 0; e < 3; ++e) {
    const int a = e, b = (e + 1) % 3;
    if (ys[a] == ys[b]) continue;  // horizontal: its ends are crossings of the other edges
    if (py < std::min(ys[a], ys[b]) || py > std::max(ys[a], ys[b])) continue;
    const double t = std::clamp((py - ys[a]) / (ys[b] - ys[a]), 0.0, 1.0);
    const double x = xs[a] + t * (xs[b] - xs[a]);
    const Vec3d ne = slerp(n[a], n[b], t);
    if (!found || x < xl) {
      xl = x;
      nl = ne;
    }
    if (!found || x > xr) {
      xr = x;
      nr = ne;
    }
    found = true;
  }
  if (!found) return n[0];  // not reached for covered pixel centres
  if (!(xr > xl)) return nl;
  return slerp(nl, nr, std::clamp((px - xl) / (xr - xl), 0.0, 1.0));
}

struct ClipVert {
  Vec4d c;                // clip coordinates
  Vec3d col;              // colour (Gouraud / unlit vertex colour); textured + lit: primary
  Vec3d spec{0, 0, 0};    // textured + lit: secondary (specular) colour
  double uv[2] = {0, 0};  // texture coordinates
  // Two-sided Gouraud: col and spec lit with the negated normal (for back faces).
  Vec3d col_b{0, 0, 0}, spec_b{0, 0, 0};
  // Phong: world normal, world position, model position, world tangent.
  Vec3d nrm{0, 0, 0}, wpos{0, 0, 0}, mpos{0, 0, 0}, tan{0, 0, 0};
};

constexpr int kMaxPoly = 9;

// Sutherland-Hodgman against one plane; dist(v) >= 0 is kept. Intersections are always computed
// from the inside vertex towards the outside one, so an edge shared by two triangles gives
// bit-identical points whichever way each triangle walks it.
template <class Dist>
int clip_poly(const ClipVert* in, int n, ClipVert* out, Dist dist) {
  int m = 0;
  for (int k = 0; k < n; ++k) {
    const ClipVert& a = in[k];
    const ClipVert& b = in[(k + 1) % n];
    const double da = dist(a.c), db = dist(b.c);
    const bool ina = da >= 0.0, inb = db >= 0.0;
    if (ina) out[m++] = a;
    if (ina != inb) {
      const ClipVert& vi = ina ? a : b;
      const ClipVert& vo = ina ? b : a;
      const double di = ina ? da : db, dout = ina ? db : da;
      const double t = di / (di - dout);
      ClipVert r;
      for (size_t q = 0; q < 4; ++q) r.c[q] = vi.c[q] + t * (vo.c[q] - vi.c[q]);
      for (size_t q = 0; q < 3; ++q) r.col[q] = vi.col[q] + t * (vo.col[q] - vi.col[q]);
      for (size_t q = 0; q < 3; ++q) r.spec[q] = vi.spec[q] + t * (vo.spec[q] - vi.spec[q]);
      for (size_t q = 0; q < 2; ++q) r.uv[q] = vi.uv[q] + t * (vo.uv[q] - vi.uv[q]);
      r.col_b = lerp3(vi.col_b, vo.col_b, t);
      r.spec_b = lerp3(vi.spec_b, vo.spec_b, t);
      r.nrm = lerp3(vi.nrm, vo.nrm, t);
      r.wpos = lerp3(vi.wpos, vo.wpos, t);
      r.mpos = lerp3(vi.mpos, vo.mpos, t);
      r.tan = lerp3(vi.tan, vo.tan, t);
      out[m++] = r;
    }
  }
  return m;
}

bool finite4(const Vec4d& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) && std::isfinite(v[3]);
}

// Wraps the integer texel index i (a whole number held in a double) into [0, size - 1].
int wrap_index(double i, int size, RefWrap wrap) {
  const double n = static_cast<double>(size);
  if (wrap == RefWrap::Repeat) {
    double r = std::fmod(i, n);  // exact; sign of i
    if (r < 0.0) r += n;
    return std::clamp(static_cast<int>(r), 0, size - 1);
  }
  return static_cast<int>(std::clamp(i, 0.0, n - 1.0));
}

// Texel coordinate s = u * size; non-finite coordinates become 0 (no texel is defined for them).
double texel_coord(double u, int size) {
  const double s = u * static_cast<double>(size);
  return std::isfinite(s) ? s : 0.0;
}

bool level_ok(const RefLevel& l) {
  return l.width > 0 && l.height > 0 &&
         l.texels.size() >= static_cast<size_t>(l.width) * static_cast<size_t>(l.height);
}

}  // namespace

double signed_area2(const ScreenTri& tri) {
  return static_cast<double>(area2_exact(tri));
}

bool covers(const ScreenTri& tri, int64_t px_centre_x_sub, int64_t px_centre_y_sub) {
  if (!in_range(tri)) return false;
  const TriSetup s = setup_tri(tri);
  if (!s.valid) return false;
  i128 w[3];
  return inside(s, px_centre_x_sub, px_centre_y_sub, w);
}

void coverage(const std::vector<ScreenTri>& tris, int width, int height, int subpixel_bits,
              std::vector<int32_t>& hits, std::vector<int32_t>& owner) {
  const int w = std::max(width, 0), h = std::max(height, 0);
  const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
  hits.assign(n, 0);
  owner.assign(n, -1);
  const int bits = clamp_bits(subpixel_bits);
  for (size_t t = 0; t < tris.size(); ++t) {
    if (!in_range(tris[t])) continue;
    raster(setup_tri(tris[t]), w, h, bits, [&](int i, int j, const i128*) {
      const size_t p = static_cast<size_t>(j) * static_cast<size_t>(w) + static_cast<size_t>(i);
      ++hits[p];
      owner[p] = static_cast<int32_t>(t);
    });
  }
}

Vec3d light_point(const RefParams& params, const Vec3d& normal_world, const Vec3d& position_world) {
  return Lighting(params).at(normal_world, position_world);
}

RefLitColor light_point_separate(const RefParams& params, const Vec3d& normal_world,
                                 const Vec3d& position_world) {
  return Lighting(params).separate(normal_world, position_world);
}

Vec3d sample_level(const RefLevel& level, double u, double v, RefFilter filter, RefWrap wrap_s,
                   RefWrap wrap_t) {
  if (!level_ok(level)) return {0, 0, 0};
  const int w = level.width, h = level.height;
  const double s = texel_coord(u, w), t = texel_coord(v, h);
  if (filter == RefFilter::Nearest) {
    return level.at(wrap_index(std::floor(s), w, wrap_s), wrap_index(std::floor(t), h, wrap_t));
  }
  const double x = s - 0.5, y = t - 0.5;
  const double fi = std::floor(x), fj = std::floor(y);
  const double a = x - fi, b = y - fj;
  const int i0 = wrap_index(fi, w, wrap_s), i1 = wrap_index(fi + 1.0, w, wrap_s);
  const int j0 = wrap_index(fj, h, wrap_t), j1 = wrap_index(fj + 1.0, h, wrap_t);
  const Vec3d& t00 = level.at(i0, j0);
  const Vec3d& t10 = level.at(i1, j0);
  const Vec3d& t01 = level.at(i0, j1);
  const Vec3d& t11 = level.at(i1, j1);
  Vec3d r{};
  for (size_t c = 0; c < 3; ++c)
    r[c] =
        (1 - a) * (1 - b) * t00[c] + a * (1 - b) * t10[c] + (1 - a) * b * t01[c] + a * b * t11[c];
  return r;
}

Vec3d sample_texture(const RefTexture& texture, const RefParams& params, double u, double v,
                     double lambda) {
  if (texture.levels.empty() || !level_ok(texture.levels[0])) return {0, 0, 0};  // incomplete
  // q: the last usable level (a broken level ends the chain).
  size_t nlev = 1;
  while (nlev < texture.levels.size() && level_ok(texture.levels[nlev])) ++nlev;
  const double q = static_cast<double>(nlev - 1);
  auto at_level = [&](double d) {
    return sample_level(texture.levels[static_cast<size_t>(d)], u, v, params.filter, params.wrap_s,
                        params.wrap_t);
  };
  // Magnification (lambda <= 0, -infinity or NaN) and non-mipmapped filters: level 0.
  if (params.mip == RefMipMode::None || !(lambda > 0.0)) return at_level(0.0);
  if (params.mip == RefMipMode::Nearest) {
    const double d = std::ceil(std::min(lambda, q + 1.0) + 0.5) - 1.0;  // lambda <= 1/2 -> 0
    return at_level(std::clamp(d, 0.0, q));
  }
  const double l = std::min(lambda, q);
  const double d1 = std::floor(l);
  const double d2 = std::min(d1 + 1.0, q);
  const double f = l - d1;
  return lerp3(at_level(d1), at_level(d2), f);
}

double texture_lod(double du_dx, double dv_dx, double du_dy, double dv_dy, int width0,
                   int height0) {
  const double w = width0, h = height0;
  const double rx = std::hypot(du_dx * w, dv_dx * h);
  const double ry = std::hypot(du_dy * w, dv_dy * h);
  return std::log2(std::max(rx, ry));  // log2(0) = -infinity
}

void render(const host::HostMesh& mesh, const RefParams& params, RefFrame& out) {
  const int W = std::max(params.width, 0), H = std::max(params.height, 0);
  const size_t npix = static_cast<size_t>(W) * static_cast<size_t>(H);
  out.width = W;
  out.height = H;
  out.color.assign(npix, clamp01(params.background));
  out.rgb8.resize(npix * 3);
  for (size_t p = 0; p < npix; ++p)
    for (size_t q = 0; q < 3; ++q) out.rgb8[p * 3 + q] = to_byte(params.background[q]);
  out.depth.assign(npix, 1.0);
  out.owner.assign(npix, -1);
  out.lod.assign(npix, std::numeric_limits<double>::quiet_NaN());
  out.normal.assign(npix, Vec3d{0, 0, 0});
  if (npix == 0) return;

  const int bits = clamp_bits(params.subpixel_bits);
  const double S = static_cast<double>(int64_t{1} << bits);
  const Mat4d mvp = mul(params.projection, mul(params.view, params.model));
  const Lighting lighting(params);
  const bool flat = params.shading == RefShading::Flat;
  const bool phong = params.shading == RefShading::Phong;
  const bool lit = !params.unlit;
  const bool two_sided = params.two_sided && lit;
  const size_t nv = mesh.positions.size();
  const bool have_colors = mesh.colors.size() == nv && nv > 0;
  const bool have_normals = mesh.normals.size() == nv;
  const bool have_tangents = mesh.tangents.size() == nv;
  const RefTexture* tex = params.texture;
  const bool have_uvs = mesh.uvs.size() == nv;
  const int tex_w0 = tex && !tex->levels.empty() ? tex->levels[0].width : 0;
  const int tex_h0 = tex && !tex->levels.empty() ? tex->levels[0].height : 0;
  // Lit Phong's maps (level 0 only; an empty texture samples black like an incomplete one).
  const RefLevel kNoLevel{};
  const RefTexture* env = phong && lit ? params.envmap : nullptr;
  const RefTexture* nmap = phong && lit ? params.normal_map : nullptr;
  const RefLevel& env0 = env && !env->levels.empty() ? env->levels[0] : kNoLevel;
  const RefLevel& nmap0 = nmap && !nmap->levels.empty() ? nmap->levels[0] : kNoLevel;

  // Per-vertex work: clip position, world position and (for Gouraud / unlit) the colour; with a
  // texture and lighting, the colour is the primary colour and vspec the secondary one.
  // Two-sided Gouraud also lights every vertex with the negated normal (vcol_b, vspec_b); Phong
  // keeps the world normal and tangent.
  std::vector<Vec4d> clip(nv);
  std::vector<Vec3d> world(nv), vcol(nv), vspec(nv, Vec3d{0, 0, 0});
  std::vector<Vec3d> vcol_b, vspec_b, vnrm, vtan;
  if (two_sided && !flat && !phong) {
    vcol_b.assign(nv, Vec3d{0, 0, 0});
    vspec_b.assign(nv, Vec3d{0, 0, 0});
  }
  if (phong) {
    vnrm.assign(nv, Vec3d{0, 0, 0});
    vtan.assign(nv, Vec3d{0, 0, 0});
  }
  for (size_t v = 0; v < nv; ++v) {
    const Vec3d& p = mesh.positions[v];
    clip[v] = transform(mvp, Vec4d{p[0], p[1], p[2], 1.0});
    world[v] = transform_point(params.model, p);
    if (phong) {
      if (have_normals) vnrm[v] = transform_normal(params.model, mesh.normals[v]);
      if (have_tangents) {
        const auto& tg = mesh.tangents[v];
        vtan[v] = normalize(transform_dir(params.model, Vec3d{tg[0], tg[1], tg[2]}));
      }
    }
    if (lit) {
      if (!flat && !phong) {
        const Vec3d n =
            have_normals ? transform_normal(params.model, mesh.normals[v]) : Vec3d{0, 0, 0};
        if (tex) {
          const RefLitColor lc = lighting.separate(n, world[v]);
          vcol[v] = lc.primary;
          vspec[v] = lc.secondary;
          if (two_sided) {
            const RefLitColor lb = lighting.separate(neg(n), world[v]);
            vcol_b[v] = lb.primary;
            vspec_b[v] = lb.secondary;
          }
        } else {
          vcol[v] = lighting.at(n, world[v]);
          if (two_sided) vcol_b[v] = lighting.at(neg(n), world[v]);
        }
      }
    } else {
      vcol[v] = have_colors ? mesh.colors[v] : params.material.diffuse;
    }
  }

  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    if (tri[0] >= nv || tri[1] >= nv || tri[2] >= nv) continue;
    const size_t vi[3] = {tri[0], tri[1], tri[2]};
    if (!finite4(clip[vi[0]]) || !finite4(clip[vi[1]]) || !finite4(clip[vi[2]])) continue;

    // Flat: one colour for the whole triangle (and one for its back, two-sided).
    Vec3d face_col{0, 0, 0}, face_spec{0, 0, 0}, face_col_b{0, 0, 0}, face_spec_b{0, 0, 0};
    if (flat) {
      if (lit) {
        const Vec3d n =
            normalize(cross(sub(world[vi[1]], world[vi[0]]), sub(world[vi[2]], world[vi[0]])));
        const Vec3d centroid = muls(add(add(world[vi[0]], world[vi[1]]), world[vi[2]]), 1.0 / 3.0);
        if (tex) {
          const RefLitColor lc = lighting.separate(n, centroid);
          face_col = lc.primary;
          face_spec = lc.secondary;
          if (two_sided) {
            const RefLitColor lb = lighting.separate(neg(n), centroid);
            face_col_b = lb.primary;
            face_spec_b = lb.secondary;
          }
        } else {
          face_col = lighting.at(n, centroid);
          if (two_sided) face_col_b = lighting.at(neg(n), centroid);
        }
      } else {
        face_col = vcol[vi[2]];  // provoking vertex: the last one
      }
    }
    // Normal mapping: the handedness of the triangle's first vertex.
    const double handedness = have_tangents ? mesh.tangents[vi[0]][3] : 1.0;

    ClipVert poly_a[kMaxPoly], poly_b[kMaxPoly];
    for (int k = 0; k < 3; ++k) {
      ClipVert& cv = poly_a[k];
      const size_t v = vi[k];
      cv.c = clip[v];
      cv.col = flat ? face_col : vcol[v];
      cv.spec = flat ? face_spec : vspec[v];
      if (have_uvs) {
        cv.uv[0] = mesh.uvs[v][0];
        cv.uv[1] = mesh.uvs[v][1];
      }
      if (!vcol_b.empty()) {
        cv.col_b = vcol_b[v];
        cv.spec_b = vspec_b[v];
      }
      if (phong) {
        cv.nrm = vnrm[v];
        cv.wpos = world[v];
        cv.mpos = mesh.positions[v];
        cv.tan = vtan[v];
      }
    }
    int n = clip_poly(poly_a, 3, poly_b, [](const Vec4d& c) { return c[2] + c[3]; });  // near
    if (n < 3) continue;
    n = clip_poly(poly_b, n, poly_a, [](const Vec4d& c) { return c[3] - c[2]; });  // far
    if (n < 3) continue;

    // Project, viewport, snap.
    int64_t sx[kMaxPoly], sy[kMaxPoly];
    double zw[kMaxPoly], inv_w[kMaxPoly];
    bool ok = true;
    for (int k = 0; k < n && ok; ++k) {
      const Vec4d& c = poly_a[k].c;
      if (!(c[3] > 0.0) || !finite4(c)) {
        ok = false;
        break;
      }
      const double iw = 1.0 / c[3];
      const double x = (c[0] * iw + 1.0) * W * 0.5;
      const double y = (1.0 - c[1] * iw) * H * 0.5;
      const double xs = x * S, ys = y * S;
      if (!(std::fabs(xs) <= kMaxSub) || !(std::fabs(ys) <= kMaxSub)) {
        ok = false;
        break;
      }
      sx[k] = std::llround(xs);
      sy[k] = std::llround(ys);
      zw[k] = (c[2] * iw + 1.0) * 0.5;
      inv_w[k] = iw;
    }
    if (!ok) continue;

    for (int k = 1; k + 1 < n; ++k) {
      const int f[3] = {0, k, k + 1};
      ScreenTri st{};
      for (int q = 0; q < 3; ++q) {
        st.x[q] = sx[f[q]];
        st.y[q] = sy[f[q]];
      }
      const TriSetup s = setup_tri(st);
      if (!s.valid) continue;  // zero snapped area
      const bool back = area2_exact(st) > 0;
      if (params.cull_back && back) continue;  // back face
      const bool use_back = two_sided && back;
      // The piece's three vertices; two-sided back faces take the colours lit with -n.
      ClipVert pv[3] = {poly_a[f[0]], poly_a[f[1]], poly_a[f[2]]};
      if (use_back && !phong) {
        for (ClipVert& cv : pv) {
          cv.col = cv.col_b;
          cv.spec = cv.spec_b;
        }
      }
      const Vec3d& fcol = use_back ? face_col_b : face_col;
      const Vec3d& fspec = use_back ? face_spec_b : face_spec;
      const double area = static_cast<double>(s.area);
      // Texturing: d(barycentric b_q of vertex q)/d(window x, y in pixels) from the edge
      // functions (constant over the triangle), hence the derivatives of the homogeneous sums
      // A = sum b_q u_q / w_q and B = sum b_q / w_q; at every pixel u = A / B and
      // du = (dA - u dB) / B exactly (likewise v).
      double dB[2] = {0, 0}, dAu[2] = {0, 0}, dAv[2] = {0, 0};
      if (tex) {
        for (int e = 0; e < 3; ++e) {
          const int e1 = (e + 1) % 3;
          const int q = s.order[(e + 2) % 3];  // the vertex edge e weighs
          const double g[2] = {-static_cast<double>(s.y[e1] - s.y[e]) * S / area,
                               static_cast<double>(s.x[e1] - s.x[e]) * S / area};
          const ClipVert& cv = poly_a[f[q]];
          for (int a = 0; a < 2; ++a) {
            dB[a] += g[a] * inv_w[f[q]];
            dAu[a] += g[a] * inv_w[f[q]] * cv.uv[0];
            dAv[a] += g[a] * inv_w[f[q]] * cv.uv[1];
          }
        }
      }
      // Phong, Slerp: the piece's screen vertices (pixels) and unit vertex normals.
      double pxs[3] = {0, 0, 0}, pys[3] = {0, 0, 0};
      Vec3d unit_n[3];
      if (phong) {
        for (int q = 0; q < 3; ++q) {
          pxs[q] = static_cast<double>(sx[f[q]]) / S;
          pys[q] = static_cast<double>(sy[f[q]]) / S;
          unit_n[q] = normalize(pv[q].nrm);
        }
      }
      raster(s, W, H, bits, [&](int i, int j, const i128* w) {
        const double b[3] = {static_cast<double>(w[0]) / area, static_cast<double>(w[1]) / area,
                             static_cast<double>(w[2]) / area};
        const size_t p = out.index(i, j);
        const double z =
            clamp01(b[0] * zw[f[0]] + b[1] * zw[f[1]] + b[2] * zw[f[2]]);  // affine in screen
        if (params.depth_test) {
          if (!(z < out.depth[p])) return;
          out.depth[p] = z;
        }
        const ClipVert &v0 = pv[0], &v1 = pv[1], &v2 = pv[2];
        if (phong) {
          const double q0 = b[0] * inv_w[f[0]], q1 = b[1] * inv_w[f[1]], q2 = b[2] * inv_w[f[2]];
          const double qs = 1.0 / (q0 + q1 + q2);
          Vec3d nn;
          switch (params.normal_interp) {
            case RefNormalInterp::Slerp:
              nn = normalize(scanline_slerp(pxs, pys, unit_n, i + 0.5, j + 0.5));
              break;
            case RefNormalInterp::SphereAnalytic:
              nn = transform_normal(params.model,
                                    normalize(persp3(v0.mpos, v1.mpos, v2.mpos, q0, q1, q2, qs)));
              break;
            case RefNormalInterp::Linear:
            default:
              nn = normalize(persp3(v0.nrm, v1.nrm, v2.nrm, q0, q1, q2, qs));
              break;
          }
          if (use_back) nn = neg(nn);
          if (lit) {
            const double u = (q0 * v0.uv[0] + q1 * v1.uv[0] + q2 * v2.uv[0]) * qs;
            const double v = (q0 * v0.uv[1] + q1 * v1.uv[1] + q2 * v2.uv[1]) * qs;
            if (nmap) {
              Vec3d tg = persp3(v0.tan, v1.tan, v2.tan, q0, q1, q2, qs);
              tg = normalize(sub(tg, muls(nn, dot(nn, tg))));
              const Vec3d bt = muls(cross(nn, tg), handedness);
              const Vec3d c =
                  sample_level(nmap0, u, v, params.filter, params.wrap_s, params.wrap_t);
              const Vec3d tn{2.0 * c[0] - 1.0, 2.0 * c[1] - 1.0, 2.0 * c[2] - 1.0};
              nn = normalize(add(add(muls(tg, tn[0]), muls(bt, tn[1])), muls(nn, tn[2])));
            }
            const Vec3d pos = persp3(v0.wpos, v1.wpos, v2.wpos, q0, q1, q2, qs);
            Vec3d col;
            double lambda = std::numeric_limits<double>::quiet_NaN();
            Vec3d modulate{1, 1, 1};
            if (tex) {
              lambda =
                  texture_lod((dAu[0] - u * dB[0]) * qs, (dAv[0] - v * dB[0]) * qs,
                              (dAu[1] - u * dB[1]) * qs, (dAv[1] - v * dB[1]) * qs, tex_w0, tex_h0);
              modulate = sample_texture(*tex, params, u, v, lambda);
            }
            if (env) {
              const Vec3d vd = lighting.view_dir(pos);
              const Vec3d r_world = sub(muls(nn, 2.0 * dot(nn, vd)), vd);
              const Vec3d r = transform_dir(params.view, r_world);
              const double m =
                  2.0 * std::sqrt(r[0] * r[0] + r[1] * r[1] + (r[2] + 1.0) * (r[2] + 1.0));
              const double es = m == 0.0 ? 0.5 : r[0] / m + 0.5;
              const double et = m == 0.0 ? 0.5 : r[1] / m + 0.5;
              modulate = cmul(modulate, sample_level(env0, es, et, RefFilter::Bilinear,
                                                     RefWrap::ClampToEdge, RefWrap::ClampToEdge));
            }
            if (tex && params.tex_env == RefTexEnv::Replace) {
              col = modulate;
            } else if (tex || env) {
              const RefLitColor lc = lighting.separate(nn, pos);
              col = add(cmul(modulate, lc.primary), lc.secondary);
            } else {
              col = lighting.at(nn, pos);
            }
            col = clamp01(col);
            out.color[p] = col;
            for (size_t ch = 0; ch < 3; ++ch) out.rgb8[p * 3 + ch] = to_byte(col[ch]);
            out.owner[p] = static_cast<int32_t>(t);
            out.lod[p] = lambda;
            out.normal[p] = nn;
            return;
          }
          out.normal[p] = nn;  // unlit Phong: shaded as unlit Gouraud below
        }
        if (tex) {
          const double q0 = b[0] * inv_w[f[0]], q1 = b[1] * inv_w[f[1]], q2 = b[2] * inv_w[f[2]];
          const double B = q0 + q1 + q2, qs = 1.0 / B;
          const double u = (q0 * v0.uv[0] + q1 * v1.uv[0] + q2 * v2.uv[0]) * qs;
          const double v = (q0 * v0.uv[1] + q1 * v1.uv[1] + q2 * v2.uv[1]) * qs;
          const double lambda =
              texture_lod((dAu[0] - u * dB[0]) * qs, (dAv[0] - v * dB[0]) * qs,
                          (dAu[1] - u * dB[1]) * qs, (dAv[1] - v * dB[1]) * qs, tex_w0, tex_h0);
          const Vec3d texel = sample_texture(*tex, params, u, v, lambda);
          Vec3d col = texel;
          if (params.tex_env == RefTexEnv::Modulate) {
            Vec3d prim = fcol, sec = fspec;
            if (!flat) {
              for (size_t ch = 0; ch < 3; ++ch) {
                prim[ch] = (q0 * v0.col[ch] + q1 * v1.col[ch] + q2 * v2.col[ch]) * qs;
                sec[ch] = (q0 * v0.spec[ch] + q1 * v1.spec[ch] + q2 * v2.spec[ch]) * qs;
              }
            }
            col = add(cmul(texel, clamp01(prim)), clamp01(sec));
          }
          col = clamp01(col);
          out.color[p] = col;
          for (size_t ch = 0; ch < 3; ++ch) out.rgb8[p * 3 + ch] = to_byte(col[ch]);
          out.owner[p] = static_cast<int32_t>(t);
          out.lod[p] = lambda;
          return;
        }
        Vec3d col = fcol;
        if (!flat) {
          const double q0 = b[0] * inv_w[f[0]], q1 = b[1] * inv_w[f[1]], q2 = b[2] * inv_w[f[2]];
          const double qs = 1.0 / (q0 + q1 + q2);
          for (size_t ch = 0; ch < 3; ++ch)
            col[ch] = (q0 * v0.col[ch] + q1 * v1.col[ch] + q2 * v2.col[ch]) * qs;
        }
        col = clamp01(col);
        out.color[p] = col;
        for (size_t ch = 0; ch < 3; ++ch) out.rgb8[p * 3 + ch] = to_byte(col[ch]);
        out.owner[p] = static_cast<int32_t>(t);
      });
    }
  }
}

}  // namespace lr::ref
