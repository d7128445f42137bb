#include "lineraster/host_sim/formats/polygon_triangulation.hpp"

#include <algorithm>
#include <cmath>

namespace lr::host {

namespace {

struct P2 {
  double u, v;
};

// Twice the signed area of (a, b, c): positive when counter-clockwise.
double cross(const P2& a, const P2& b, const P2& c) {
  return (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u);
}

// The corners in the plane of Newell's normal, counter-clockwise; false when the polygon has no
// area.
bool project(std::span<const Vec3d> c, std::vector<P2>& out) {
  Vec3d n{0, 0, 0};
  for (size_t i = 0; i < c.size(); ++i) {
    const Vec3d& p = c[i];
    const Vec3d& q = c[(i + 1) % c.size()];
    n[0] += (p[1] - q[1]) * (p[2] + q[2]);
    n[1] += (p[2] - q[2]) * (p[0] + q[0]);
    n[2] += (p[0] - q[0]) * (p[1] + q[1]);
  }
  const auto* big = std::max_element(
      n.begin(), n.end(), [](double x, double y) { return std::fabs(x) < std::fabs(y); });
  if (!(std::fabs(*big) > 0)) return false;
  const size_t k = static_cast<size_t>(big - n.begin());
  // The two other axes in cyclic order keep the orientation of n's component k.
  const size_t a = (k + 1) % 3, b = (k + 2) % 3;
  out.resize(c.size());
  for (size_t i = 0; i < c.size(); ++i)
    out[i] = *big > 0 ? P2{c[i][a], c[i][b]} : P2{c[i][b], c[i][a]};
  return true;
}

void fan(size_t n, std::vector<std::array<uint32_t, 3>>& out) {
  for (size_t i = 1; i + 1 < n; ++i)
    out.push_back({0, static_cast<uint32_t>(i), static_cast<uint32_t>(i + 1)});
}

}  // namespace

bool triangulate_polygon(std::span<const Vec3d> corners,
                         std::vector<std::array<uint32_t, 3>>& out) {
  const size_t n = corners.size();
  std::vector<P2> p;
  if (n <= 3 || !project(corners, p)) {
    fan(n, out);
    return true;
  }
  // Areas below this are flat (collinear corners): relative to the polygon's extent.
  double lo_u = p[0].u, hi_u = p[0].u, lo_v = p[0].v, hi_v = p[0].v;
  for (const P2& q : p) {
    lo_u = std::min(lo_u, q.u), hi_u = std::max(hi_u, q.u);
    lo_v = std::min(lo_v, q.v), hi_v = std::max(hi_v, q.v);
  }
  const double extent = std::max(hi_u - lo_u, hi_v - lo_v);
  const double eps = extent * extent * 1e-12;
  // Convex enough to fan: no corner turns right by more than kBend (radians, as a sine). Corners
  // written with 7 decimals on a circle of 100,000 turn either way by 3e-3 from rounding alone; a
  // fan over a corner bent in by less than kBend leaves the polygon by a sliver at most.
  constexpr double kBend = 1e-2;
  bool convex = true;
  for (size_t i = 0; i < n && convex; ++i) {
    const P2 &a = p[(i + n - 1) % n], &b = p[i], &c = p[(i + 1) % n];
    const double lengths = std::hypot(b.u - a.u, b.v - a.v) * std::hypot(c.u - b.u, c.v - b.v);
    convex = cross(a, b, c) >= -eps - kBend * lengths;
  }
  if (convex || n > kMaxEarClippedCorners) {
    fan(n, out);
    return convex;
  }

  std::vector<uint32_t> prev(n), next(n);
  for (size_t i = 0; i < n; ++i) {
    prev[i] = static_cast<uint32_t>((i + n - 1) % n);
    next[i] = static_cast<uint32_t>((i + 1) % n);
  }
  auto same = [&](uint32_t x, uint32_t y) { return p[x].u == p[y].u && p[x].v == p[y].v; };
  // Corner i is an ear when it turns left and no other corner lies in or on its triangle
  // (corners at the same place as the triangle's, a keyhole's doubled edge, do not block it).
  auto is_ear = [&](uint32_t i) {
    const uint32_t a = prev[i], c = next[i];
    if (cross(p[a], p[i], p[c]) <= eps) return false;
    for (uint32_t j = next[c]; j != a; j = next[j]) {
      if (same(j, a) || same(j, i) || same(j, c)) continue;
      if (cross(p[a], p[i], p[j]) >= -eps && cross(p[i], p[c], p[j]) >= -eps &&
          cross(p[c], p[a], p[j]) >= -eps)
        return false;
    }
    return true;
  };
  auto clip = [&](uint32_t i) {
    out.push_back({prev[i], i, next[i]});
    next[prev[i]] = next[i];
    prev[next[i]] = prev[i];
  };
  size_t remaining = n, tried = 0;
  uint32_t i = 0;
  while (remaining > 3) {
    if (is_ear(i)) {
      const uint32_t back = prev[i];
      clip(i);
      --remaining;
      tried = 0;
      i = back;
      continue;
    }
    i = next[i];
    // No ear in a whole round: the polygon crosses itself; clip where it turns most to the left.
    if (++tried > remaining) {
      uint32_t best = i;
      double best_turn = cross(p[prev[i]], p[i], p[next[i]]);
      for (uint32_t j = next[i]; j != i; j = next[j]) {
        const double t = cross(p[prev[j]], p[j], p[next[j]]);
        if (t > best_turn) best = j, best_turn = t;
      }
      i = prev[best];
      clip(best);
      --remaining;
      tried = 0;
    }
  }
  clip(i);
  return true;
}

}  // namespace lr::host
