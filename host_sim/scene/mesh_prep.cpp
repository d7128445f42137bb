// Mesh preparation: bounds, --fit, procedural meshes, OBJ writer (see mesh_prep.hpp).
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/vec3d.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <unordered_map>
#include <utility>

#include "lineraster/host_sim/scene/tangents.hpp"

namespace lr::host {
namespace {

constexpr int kMaxCount = 2048;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

int clamp_count(int n, int lo) {
  return std::clamp(n, lo, kMaxCount);
}

Vec3d normalized(const Vec3d& v) {
  const double len = std::sqrt(dot(v, v));
  if (!(len > 0.0)) return {0.0, 0.0, 1.0};
  return {v[0] / len, v[1] / len, v[2] / len};
}

uint32_t u32(int v) {
  return static_cast<uint32_t>(v);
}

void add_quad(HostMesh& m, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  m.triangles.push_back({a, b, c});
  m.triangles.push_back({a, c, d});
}

void finish(HostMesh& m) {
  m.triangle_material.assign(m.triangles.size(), -1);
  compute_tangents(m);
}

// Appends the shortest round-trip form of v.
void append_number(std::string& s, double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, res.ptr);
}

// Largest absolute coordinate over all positions.
double max_abs(const HostMesh& mesh) {
  double m = 0.0;
  for (const Vec3d& p : mesh.positions) {
    m = std::max({m, std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])});
  }
  return m;
}

}  // namespace

Bounds bounds(const HostMesh& mesh) {
  if (mesh.positions.empty()) return {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  Bounds b{mesh.positions[0], mesh.positions[0]};
  for (const Vec3d& p : mesh.positions) {
    for (size_t c = 0; c < 3; ++c) {
      b.min[c] = std::min(b.min[c], p[c]);
      b.max[c] = std::max(b.max[c], p[c]);
    }
  }
  return b;
}

FitTransform fit_transform(const HostMesh& mesh) {
  const double m = max_abs(mesh);
  if (!(m > 0.0) || !std::isfinite(m)) return {{0.0, 0.0, 0.0}, 1.0};
  // Work in coordinates scaled by a power of two (exact) so that nothing overflows.
  const int shift = -(std::ilogb(m) + 1);
  const Bounds b = bounds(mesh);
  Vec3d c{};
  for (size_t i = 0; i < 3; ++i) {
    c[i] = 0.5 * (std::ldexp(b.min[i], shift) + std::ldexp(b.max[i], shift));
  }
  double d2 = 0.0;
  for (const Vec3d& p : mesh.positions) {
    const Vec3d s{std::ldexp(p[0], shift) - c[0], std::ldexp(p[1], shift) - c[1],
                  std::ldexp(p[2], shift) - c[2]};
    d2 = std::max(d2, dot(s, s));
  }
  const Vec3d center{std::ldexp(c[0], -shift), std::ldexp(c[1], -shift), std::ldexp(c[2], -shift)};
  if (!(d2 > 0.0)) return {center, 1.0};
  const double scale = std::ldexp(1.0 / std::sqrt(d2), shift);
  if (!std::isfinite(scale) || !(scale > 0.0)) return {center, 1.0};
  return {center, scale};
}

FitTransform fit_box_transform(const HostMesh& mesh) {
  const Bounds b = bounds(mesh);
  Vec3d center{};
  double half = 0.0;
  for (size_t i = 0; i < 3; ++i) {
    // Halves first: the sum and the difference of two huge coordinates cannot overflow.
    center[i] = 0.5 * b.min[i] + 0.5 * b.max[i];
    half = std::max(half, 0.5 * b.max[i] - 0.5 * b.min[i]);
  }
  const double scale = 1.0 / half;
  if (!(half > 0.0) || !std::isfinite(scale) || !(scale > 0.0)) return {center, 1.0};
  return {center, scale};
}

void apply_fit(HostMesh& mesh, const FitTransform& fit) {
  for (Vec3d& p : mesh.positions) {
    for (size_t c = 0; c < 3; ++c) p[c] = (p[c] - fit.center[c]) * fit.scale;
  }
}

HostMesh make_uv_sphere(int stacks, int slices) {
  stacks = clamp_count(stacks, 2);
  slices = clamp_count(slices, 3);
  HostMesh m;
  auto add = [&m](const Vec3d& p, const Vec2d& uv) {
    m.positions.push_back(p);
    m.normals.push_back(normalized(p));
    m.uvs.push_back(uv);
  };
  // North pole copies (one per slice, for the uvs), rings 1..stacks-1 (slices + 1 vertices each,
  // the last repeating the first position exactly), south pole copies.
  for (int j = 0; j < slices; ++j) add({0.0, 1.0, 0.0}, {(j + 0.5) / slices, 1.0});
  for (int i = 1; i < stacks; ++i) {
    const double theta = std::numbers::pi * i / stacks;
    const double st = std::sin(theta), ct = std::cos(theta);
    for (int j = 0; j <= slices; ++j) {
      const double phi = kTwoPi * (j % slices) / slices;
      add({st * std::sin(phi), ct, st * std::cos(phi)},
          {static_cast<double>(j) / slices, 1.0 - static_cast<double>(i) / stacks});
    }
  }
  const int south = slices + (stacks - 1) * (slices + 1);
  for (int j = 0; j < slices; ++j) add({0.0, -1.0, 0.0}, {(j + 0.5) / slices, 0.0});

  auto ring = [slices](int i, int j) { return u32(slices + (i - 1) * (slices + 1) + j); };
  for (int j = 0; j < slices; ++j) m.triangles.push_back({u32(j), ring(1, j), ring(1, j + 1)});
  for (int i = 1; i + 1 < stacks; ++i) {
    for (int j = 0; j < slices; ++j)
      add_quad(m, ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1));
  }
  for (int j = 0; j < slices; ++j) {
    m.triangles.push_back({ring(stacks - 1, j), u32(south + j), ring(stacks - 1, j + 1)});
  }
  finish(m);
  return m;
}

HostMesh make_torus(double major, double minor, int rings, int sides) {
  HostMesh m;
  if (!(major > 0.0) || !(minor > 0.0) || !std::isfinite(major) || !std::isfinite(minor)) return m;
  rings = clamp_count(rings, 3);
  sides = clamp_count(sides, 3);
  for (int i = 0; i <= rings; ++i) {
    const double u = kTwoPi * (i % rings) / rings;
    const double cu = std::cos(u), su = std::sin(u);
    for (int j = 0; j <= sides; ++j) {
      const double v = kTwoPi * (j % sides) / sides;
      const double cv = std::cos(v), sv = std::sin(v);
      const double r = major + minor * cv;
      m.positions.push_back({r * cu, r * su, minor * sv});
      m.normals.push_back(normalized({cv * cu, cv * su, sv}));
      m.uvs.push_back({static_cast<double>(i) / rings, static_cast<double>(j) / sides});
    }
  }
  auto at = [sides](int i, int j) { return u32(i * (sides + 1) + j); };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < sides; ++j)
      add_quad(m, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  }
  finish(m);
  return m;
}

HostMesh make_cube() {
  // Per face: outward normal n, and axes (u, v) with u x v = n, so corners listed as
  // (-,-), (+,-), (+,+), (-,+) in (u, v) are counter-clockwise seen from outside.
  static const Vec3d kFaces[6][3] = {
      {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},   // +x
      {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},   // -x
      {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},   // +y
      {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},   // -y
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},    // +z
      {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},  // -z
  };
  static const double kCorner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  HostMesh m;
  for (const auto& f : kFaces) {
    const uint32_t base = static_cast<uint32_t>(m.positions.size());
    for (const auto& c : kCorner) {
      Vec3d p{};
      for (size_t k = 0; k < 3; ++k) p[k] = f[0][k] + c[0] * f[1][k] + c[1] * f[2][k];
      m.positions.push_back(p);
      m.normals.push_back(f[0]);
      m.uvs.push_back({(c[0] + 1.0) / 2.0, (c[1] + 1.0) / 2.0});
    }
    add_quad(m, base, base + 1, base + 2, base + 3);
  }
  finish(m);
  return m;
}

HostMesh make_grid(int nx, int ny) {
  nx = clamp_count(nx, 1);
  ny = clamp_count(ny, 1);
  HostMesh m;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const double x = -1.0 + 2.0 * i / nx, y = -1.0 + 2.0 * j / ny;
      m.positions.push_back({x, y, 0.0});
      m.normals.push_back({0.0, 0.0, 1.0});
      m.uvs.push_back({static_cast<double>(i) / nx, static_cast<double>(j) / ny});
    }
  }
  auto at = [nx](int i, int j) { return u32(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i)
      add_quad(m, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  }
  finish(m);
  return m;
}

HostMesh make_torus_knot(int p, int q, double tube, int segments, int sides) {
  HostMesh m;
  if (p < 1 || p > 16 || q < 1 || q > 16 || !(tube > 0.0) || !std::isfinite(tube)) return m;
  segments = clamp_count(segments, 3);
  sides = clamp_count(sides, 3);
  for (int i = 0; i <= segments; ++i) {
    const double t = kTwoPi * (i % segments) / segments;
    const double cp = std::cos(p * t), sp = std::sin(p * t);
    const double cq = std::cos(q * t), sq = std::sin(q * t);
    const double r = 2.0 + cq;
    const Vec3d c{r * cp / 3.0, r * sp / 3.0, -sq / 3.0};
    // Tangent (derivative of the curve) and the direction from the torus' core circle to the curve,
    // made perpendicular to the tangent: a frame that is periodic in t, so the tube closes exactly.
    const Vec3d tangent =
        normalized({-q * sq * cp - p * r * sp, -q * sq * sp + p * r * cp, -q * cq});
    const Vec3d d{cq * cp, cq * sp, -sq};
    const double dt = dot(d, tangent);
    const Vec3d n =
        normalized({d[0] - dt * tangent[0], d[1] - dt * tangent[1], d[2] - dt * tangent[2]});
    const Vec3d b = cross(tangent, n);
    for (int j = 0; j <= sides; ++j) {
      const double a = kTwoPi * (j % sides) / sides;
      const double ca = std::cos(a), sa = std::sin(a);
      const Vec3d dir{ca * n[0] + sa * b[0], ca * n[1] + sa * b[1], ca * n[2] + sa * b[2]};
      m.positions.push_back({c[0] + tube * dir[0], c[1] + tube * dir[1], c[2] + tube * dir[2]});
      m.normals.push_back(normalized(dir));
      m.uvs.push_back({static_cast<double>(i) / segments, static_cast<double>(j) / sides});
    }
  }
  // Along the tangent then around (n -> b): tangent x (d dir / d a) = -dir, so the corners go
  // around first to face outwards.
  auto at = [sides](int i, int j) { return u32(i * (sides + 1) + j); };
  for (int i = 0; i < segments; ++i) {
    for (int j = 0; j < sides; ++j)
      add_quad(m, at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
  }
  finish(m);
  return m;
}

HostMesh subdivide(const HostMesh& mesh, int levels) {
  HostMesh m = mesh;
  for (int level = 0; level < levels; ++level) {
    HostMesh out;
    out.positions = m.positions;
    out.normals = m.normals;
    out.colors = m.colors;
    out.uvs = m.uvs;
    out.materials = m.materials;
    out.source = m.source;
    out.lines = m.lines.size() == m.positions.size() ? m.lines : std::vector<uint32_t>{};
    out.triangles.reserve(4 * m.triangles.size());
    out.triangle_material.reserve(4 * m.triangles.size());
    std::unordered_map<uint64_t, uint32_t> midpoints;
    midpoints.reserve(2 * m.triangles.size());
    auto midpoint = [&](uint32_t a, uint32_t b) {
      if (a > b) std::swap(a, b);  // one order: the same arithmetic for both triangles
      const uint64_t key = (uint64_t{a} << 32) | b;
      const auto [it, added] = midpoints.emplace(key, static_cast<uint32_t>(out.positions.size()));
      if (!added) return it->second;
      const Vec3d& pa = m.positions[a];
      const Vec3d& pb = m.positions[b];
      out.positions.push_back(
          {(pa[0] + pb[0]) * 0.5, (pa[1] + pb[1]) * 0.5, (pa[2] + pb[2]) * 0.5});
      if (!m.normals.empty()) {
        const Vec3d& na = m.normals[a];
        const Vec3d& nb = m.normals[b];
        const Vec3d sum{na[0] + nb[0], na[1] + nb[1], na[2] + nb[2]};
        out.normals.push_back(dot(sum, sum) > 0.0 ? normalized(sum) : na);
      }
      if (!m.colors.empty()) {
        const Vec3d& ca = m.colors[a];
        const Vec3d& cb = m.colors[b];
        out.colors.push_back({(ca[0] + cb[0]) * 0.5, (ca[1] + cb[1]) * 0.5, (ca[2] + cb[2]) * 0.5});
      }
      if (!m.uvs.empty()) {
        const Vec2d& ua = m.uvs[a];
        const Vec2d& ub = m.uvs[b];
        out.uvs.push_back({(ua[0] + ub[0]) * 0.5, (ua[1] + ub[1]) * 0.5});
      }
      if (!out.lines.empty()) out.lines.push_back(0);  // a midpoint: no line of its own
      return it->second;
    };
    for (size_t t = 0; t < m.triangles.size(); ++t) {
      const auto [a, b, c] = m.triangles[t];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      const int32_t material = t < m.triangle_material.size() ? m.triangle_material[t] : -1;
      for (const std::array<uint32_t, 3>& child : {std::array{a, ab, ca}, std::array{ab, b, bc},
                                                   std::array{ca, bc, c}, std::array{ab, bc, ca}}) {
        out.triangles.push_back(child);
        out.triangle_material.push_back(material);
      }
    }
    if (!m.tangents.empty()) compute_tangents(out);
    m = std::move(out);
  }
  return m;
}

void set_colors_from_normals(HostMesh& mesh) {
  mesh.colors.resize(mesh.normals.size());
  for (size_t i = 0; i < mesh.normals.size(); ++i) {
    for (size_t c = 0; c < 3; ++c)
      mesh.colors[i][c] = std::clamp(0.5 + 0.5 * mesh.normals[i][c], 0.0, 1.0);
  }
}

std::string to_obj_text(const HostMesh& mesh) {
  std::string s = "# written by lineraster lr::host::to_obj_text\n";
  const bool colors = mesh.colors.size() == mesh.positions.size() && !mesh.colors.empty();
  const bool uvs = mesh.uvs.size() == mesh.positions.size() && !mesh.uvs.empty();
  const bool normals = mesh.normals.size() == mesh.positions.size() && !mesh.normals.empty();
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    s += "v";
    for (double x : mesh.positions[i]) {
      s += ' ';
      append_number(s, x);
    }
    if (colors) {
      for (double x : mesh.colors[i]) {
        s += ' ';
        append_number(s, x);
      }
    }
    s += '\n';
  }
  if (uvs) {
    for (const Vec2d& t : mesh.uvs) {
      s += "vt ";
      append_number(s, t[0]);
      s += ' ';
      append_number(s, t[1]);
      s += '\n';
    }
  }
  if (normals) {
    for (const Vec3d& n : mesh.normals) {
      s += "vn";
      for (double x : n) {
        s += ' ';
        append_number(s, x);
      }
      s += '\n';
    }
  }
  for (const auto& t : mesh.triangles) {
    s += "f";
    for (uint32_t v : t) {
      const std::string idx = std::to_string(static_cast<uint64_t>(v) + 1);
      s += ' ';
      s += idx;
      if (uvs || normals) {
        s += '/';
        if (uvs) s += idx;
        if (normals) {
          s += '/';
          s += idx;
        }
      }
    }
    s += '\n';
  }
  return s;
}

}  // namespace lr::host
