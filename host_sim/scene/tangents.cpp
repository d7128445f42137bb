// Per-vertex tangents from positions and uvs (see tangents.hpp).
#include "lineraster/host_sim/scene/tangents.hpp"
#include "lineraster/host_sim/scene/vec3d.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace lr::host {
namespace {

// a / |a|, or false when a is zero or not finite.
bool unit(const Vec3d& a, Vec3d& out) {
  const double len = length(a);
  if (!(len > 0.0) || !std::isfinite(len)) return false;
  out = {a[0] / len, a[1] / len, a[2] / len};
  return true;
}

// a minus its component along the unit vector n.
Vec3d reject(const Vec3d& a, const Vec3d& n) {
  const double d = dot(a, n);
  return {a[0] - d * n[0], a[1] - d * n[1], a[2] - d * n[2]};
}

// A unit vector orthogonal to the unit vector n: the coordinate axis least aligned with n, with
// its component along n removed.
Vec3d any_orthogonal(const Vec3d& n) {
  size_t k = 0;
  for (size_t c = 1; c < 3; ++c)
    if (std::fabs(n[c]) < std::fabs(n[k])) k = c;
  Vec3d axis{0.0, 0.0, 0.0};
  axis[k] = 1.0;
  Vec3d t;
  if (!unit(reject(axis, n), t)) t = {1.0, 0.0, 0.0};
  return t;
}

}  // namespace

void compute_tangents(HostMesh& mesh) {
  mesh.tangents.clear();
  if (mesh.uvs.empty()) return;
  const size_t nv = mesh.positions.size();
  std::vector<Vec3d> su(nv, Vec3d{0.0, 0.0, 0.0}), sv(nv, Vec3d{0.0, 0.0, 0.0});
  for (const auto& tri : mesh.triangles) {
    if (tri[0] >= nv || tri[1] >= nv || tri[2] >= nv || tri[0] >= mesh.uvs.size() ||
        tri[1] >= mesh.uvs.size() || tri[2] >= mesh.uvs.size())
      continue;
    const Vec3d& p0 = mesh.positions[tri[0]];
    const Vec2d& t0 = mesh.uvs[tri[0]];
    const Vec3d e1 = sub(mesh.positions[tri[1]], p0), e2 = sub(mesh.positions[tri[2]], p0);
    const double du1 = mesh.uvs[tri[1]][0] - t0[0], dv1 = mesh.uvs[tri[1]][1] - t0[1];
    const double du2 = mesh.uvs[tri[2]][0] - t0[0], dv2 = mesh.uvs[tri[2]][1] - t0[1];
    // p - p0 = (u - u0) * S + (v - v0) * T in the triangle's plane; solve for S and T.
    const double r = du1 * dv2 - du2 * dv1;
    const double scale =
        std::fmax(std::fabs(du1), std::fabs(du2)) * std::fmax(std::fabs(dv1), std::fabs(dv2));
    if (!std::isfinite(r) || !(std::fabs(r) > 1e-12 * scale)) continue;  // degenerate uvs
    const double area2 = length(cross(e1, e2));
    if (!(area2 > 1e-12 * length(e1) * length(e2))) continue;  // degenerate positions
    Vec3d s, t;
    if (!unit({(e1[0] * dv2 - e2[0] * dv1) / r, (e1[1] * dv2 - e2[1] * dv1) / r,
               (e1[2] * dv2 - e2[2] * dv1) / r},
              s) ||
        !unit({(e2[0] * du1 - e1[0] * du2) / r, (e2[1] * du1 - e1[1] * du2) / r,
               (e2[2] * du1 - e1[2] * du2) / r},
              t))
      continue;
    for (size_t k = 0; k < 3; ++k) {
      const Vec3d& p = mesh.positions[tri[k]];
      const Vec3d a = sub(mesh.positions[tri[(k + 1) % 3]], p);
      const Vec3d b = sub(mesh.positions[tri[(k + 2) % 3]], p);
      const double angle = std::atan2(length(cross(a, b)), dot(a, b));
      if (!std::isfinite(angle)) continue;
      Vec3d& acc_u = su[tri[k]];
      Vec3d& acc_v = sv[tri[k]];
      for (size_t c = 0; c < 3; ++c) {
        acc_u[c] += angle * s[c];
        acc_v[c] += angle * t[c];
      }
    }
  }
  mesh.tangents.resize(nv);
  for (size_t i = 0; i < nv; ++i) {
    Vec3d n{0.0, 0.0, 1.0};
    if (i < mesh.normals.size() && !unit(mesh.normals[i], n)) n = {0.0, 0.0, 1.0};
    Vec3d t;
    double w = 1.0;
    const double sum = length(su[i]);
    const Vec3d ortho = reject(su[i], n);
    if (sum > 0.0 && length(ortho) > 1e-6 * sum && unit(ortho, t)) {
      if (dot(cross(n, t), sv[i]) < 0.0) w = -1.0;
    } else {
      t = any_orthogonal(n);
    }
    mesh.tangents[i] = {t[0], t[1], t[2], w};
  }
}

}  // namespace lr::host
