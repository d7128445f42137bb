// Closed random meshes through the whole 3D path: random convex polyhedra (exact hulls of random
// Q16.16 points) and radially jittered spheres (closed, not convex), random cameras, partly off
// screen (guard-band clipping).
//
// For a closed mesh seen from outside, on the core's own snapped vertices, the front pieces
// covering a pixel centre are exactly as many as the back pieces (every line of sight enters
// the surface as often as it leaves it; the fill rule makes this exact per pixel centre), and
// at least one inside the silhouette. Checked with
// the exact reference, and the core's frames must equal the reference's pixel for pixel with
// culling off and with back faces culled; for convex meshes every pixel inside the silhouette is
// then written exactly once. Cameras inside a mesh or cutting it with the near plane open the
// surface: those only check the core against the reference.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>

#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "tests/support/core_harness.hpp"

namespace lr {
namespace {

using i128 = __int128;

struct Poly {
  std::vector<Vec3> pos;
  std::vector<std::array<uint16_t, 3>> tri;
};

// Convex hull of points in general position by brute force (exact integer orientation); false
// when four points are coplanar (then the caller draws again).
bool convex_hull(const std::vector<Vec3>& p, Poly& out) {
  out.pos = p;
  out.tri.clear();
  const size_t n = p.size();
  auto d = [&](size_t a, size_t b, int k) -> i128 {
    const Fixed* pa = &p[a].x;
    const Fixed* pb = &p[b].x;
    return i128{pb[k].raw} - pa[k].raw;
  };
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      for (size_t k = j + 1; k < n; ++k) {
        i128 nx = d(i, j, 1) * d(i, k, 2) - d(i, j, 2) * d(i, k, 1);
        i128 ny = d(i, j, 2) * d(i, k, 0) - d(i, j, 0) * d(i, k, 2);
        i128 nz = d(i, j, 0) * d(i, k, 1) - d(i, j, 1) * d(i, k, 0);
        int pos = 0, neg = 0;
        for (size_t l = 0; l < n; ++l) {
          if (l == i || l == j || l == k) continue;
          i128 s = nx * d(i, l, 0) + ny * d(i, l, 1) + nz * d(i, l, 2);
          if (s == 0) return false;
          (s > 0 ? pos : neg)++;
        }
        if (pos == 0) out.tri.push_back({uint16_t(i), uint16_t(j), uint16_t(k)});
        if (neg == 0) out.tri.push_back({uint16_t(i), uint16_t(k), uint16_t(j)});
      }
  return out.tri.size() == 2 * n - 4;  // Euler: a triangulated convex polyhedron
}

Fixed fx(double v) {
  return Fixed::from_raw(static_cast<int32_t>(std::lround(v * 65536)));
}

Poly random_convex(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0, 1);
  std::uniform_int_distribution<int> count(5, 36);
  std::uniform_real_distribution<double> stretch(0.3, 1.6);
  for (;;) {
    const int n = count(rng);
    const double sx = stretch(rng), sy = stretch(rng), sz = stretch(rng);
    std::vector<Vec3> pts;
    for (int i = 0; i < n; ++i) {
      double x = g(rng), y = g(rng), z = g(rng), l = std::sqrt(x * x + y * y + z * z);
      double r = rng() % 2 ? 1.0 : std::uniform_real_distribution<double>(0.6, 1.0)(rng);
      pts.push_back({fx(sx * r * x / l), fx(sy * r * y / l), fx(sz * r * z / l)});
    }
    Poly p;
    if (convex_hull(pts, p)) return p;
  }
}

Poly jittered_sphere(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> stacks(3, 14), slices(3, 20);
  std::uniform_real_distribution<double> jit(0.75, 1.25);
  host::HostMesh m = host::make_uv_sphere(stacks(rng), slices(rng));
  Poly p;
  // The seam and the poles repeat positions (one vertex per uv): one jitter per position.
  std::map<std::array<long, 3>, double> radius;
  for (const auto& v : m.positions) {
    std::array<long, 3> key{std::lround(v[0] * 1e6), std::lround(v[1] * 1e6),
                            std::lround(v[2] * 1e6)};
    auto [it, fresh] = radius.emplace(key, 0.0);
    if (fresh) it->second = jit(rng);
    double r = it->second;
    p.pos.push_back({fx(r * v[0]), fx(r * v[1]), fx(r * v[2])});
  }
  for (const auto& t : m.triangles)
    p.tri.push_back({uint16_t(t[0]), uint16_t(t[1]), uint16_t(t[2])});
  return p;
}

struct Figures {
  uint64_t meshes = 0, closed_checked = 0, mismatches = 0, write_mismatch = 0, winding_bad = 0,
           convex_double_hits = 0, silhouette_pixels = 0, cracks = 0;
};

struct Frame {
  host::ImageRgb8 img;
  std::vector<ref::ScreenTri> tris;
  std::vector<int32_t> ids;
  std::vector<int64_t> area;
  uint32_t written = 0;
};

// Each face drawn with its own three vertices (same positions as its neighbours') in its id
// colour, flat, no depth.
Frame render(const Poly& p, const Camera& cam, Cull cull, int w, int h) {
  std::vector<Vec3> pos;
  std::vector<Rgb8> col;
  std::vector<std::array<uint16_t, 3>> tri;
  for (size_t t = 0; t < p.tri.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      pos.push_back(p.pos[p.tri[t][size_t(k)]]);
      col.push_back(to_rgb8(test::id_color(uint32_t(t))));
    }
    auto b = uint16_t(3 * t);
    tri.push_back({b, uint16_t(b + 1), uint16_t(b + 2)});
  }
  test::CoreHarness<8> core(w, h);
  core.begin({0, 0, 0}, cam);
  DrawState st = test::coverage_state();
  st.cull = cull;
  EXPECT_EQ(core.renderer().draw(Mesh{pos, {}, col, {}, tri}, Mat4::identity(), Material{}, st),
            Status::kOk);
  Frame f;
  f.img = core.render();
  f.written = core.renderer().stats().pixels_written;
  auto sv = core.renderer().screen_vertices();
  const auto colors = core.renderer().triangle_colors();
  size_t ids_seen = 0;
  for (const BinnedTriangle& bt : core.renderer().binned_triangles()) {
    ref::ScreenTri s{};
    for (int k = 0; k < 3; ++k) {
      s.x[k] = sv[bt.v[k]].x;
      s.y[k] = sv[bt.v[k]].y;
    }
    f.tris.push_back(s);
    const Rgb8 c = colors[ids_seen++].primary;  // flat: the provoking vertex's colour
    f.ids.push_back(int32_t(c.r | (c.g << 8) | (c.b << 16)) - 1);
    f.area.push_back((s.x[1] - s.x[0]) * (s.y[2] - s.y[0]) - (s.x[2] - s.x[0]) * (s.y[1] - s.y[0]));
  }
  return f;
}

// Core frame against the reference on the same pieces; returns the reference's hits.
std::vector<int32_t> compare(const Frame& f, int w, int h, Figures& fig) {
  std::vector<int32_t> hits, owner;
  ref::coverage(f.tris, w, h, kSubpixelBits, hits, owner);
  uint64_t ref_hits = 0;
  for (size_t p = 0; p < hits.size(); ++p) {
    ref_hits += uint64_t(hits[p]);
    int32_t expect = owner[p] < 0 ? -1 : f.ids[size_t(owner[p])];
    fig.mismatches += test::id_of(f.img, p) != expect;
  }
  fig.write_mismatch += ref_hits != f.written;
  return hits;
}

void check_mesh(const Poly& p, bool convex, std::mt19937_64& rng, Figures& fig) {
  std::uniform_real_distribution<double> u(-1, 1), dist(1.2, 7.0);
  std::uniform_int_distribution<int> size(24, 120);
  const int w = size(rng), h = size(rng);
  // Eye: mostly outside (distance 2..7 from the centre, the mesh's radius is <= 1.6), sometimes
  // inside or grazing (near-plane cuts).
  double ex = u(rng), ey = u(rng), ez = u(rng), l = std::sqrt(ex * ex + ey * ey + ez * ez) + 1e-9;
  const double r =
      rng() % 8 == 0 ? std::uniform_real_distribution<double>(0.0, 1.8)(rng) : dist(rng) + 0.8;
  Vec3 eye{fx(r * ex / l), fx(r * ey / l), fx(r * ez / l)};
  Vec3 target{fx(0.6 * u(rng)), fx(0.6 * u(rng)), fx(0.6 * u(rng))};  // partly off screen
  Camera cam;
  cam.eye = eye;
  const double fovy = std::uniform_real_distribution<double>(20, 100)(rng);
  if (!perspective(fx(fovy), Fixed::ratio(w, h), Fixed::from_double(0.05), Fixed::from_int(60),
                   cam.projection) ||
      !look_at(eye, target, {Fixed{}, Fixed::from_int(1), Fixed{}}, cam.view))
    return;
  ++fig.meshes;
  Frame all = render(p, cam, Cull::kNone, w, h);
  Frame front = render(p, cam, Cull::kBack, w, h);
  std::vector<int32_t> hits_all = compare(all, w, h, fig);
  std::vector<int32_t> hits_front = compare(front, w, h, fig);
  // Closed and seen from outside, the near plane not cutting it: the winding identity.
  bool closed = r > 1.6 * std::sqrt(3.0) + 0.1;
  if (!closed) return;
  ++fig.closed_checked;
  std::vector<ref::ScreenTri> back;
  for (size_t i = 0; i < all.tris.size(); ++i)
    if (all.area[i] > 0) back.push_back(all.tris[i]);
  std::vector<int32_t> hits_back, owner;
  ref::coverage(back, w, h, kSubpixelBits, hits_back, owner);
  for (size_t q = 0; q < hits_all.size(); ++q) {
    bool inside = hits_all[q] > 0;
    fig.silhouette_pixels += inside;
    // Every line of sight enters the closed surface as often as it leaves it.
    if (hits_front[q] != hits_back[q] || (inside && hits_front[q] == 0)) ++fig.winding_bad;
    if (convex && hits_front[q] > 1) ++fig.convex_double_hits;
  }
  // A crack: an uncovered pixel whose four neighbours are covered (front faces only).
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      auto at = [&](int xx, int yy) { return hits_front[size_t(yy) * size_t(w) + size_t(xx)] > 0; };
      fig.cracks += !at(x, y) && at(x - 1, y) && at(x + 1, y) && at(x, y - 1) && at(x, y + 1);
    }
}

// The identities hold trivially on an empty frame: the views must show the meshes. A mesh about
// a unit across, 2 to 8 units away, in a 24..120-pixel view: hundreds of pixels on average.
constexpr uint64_t kMinPixelsPerView = 100;

TEST(WatertightStress, RandomConvexPolyhedraAreCoveredExactlyOnceInsideTheSilhouette) {
  std::mt19937_64 rng(31);
  Figures fig;
  for (int i = 0; i < 400; ++i) check_mesh(random_convex(rng), true, rng, fig);
  EXPECT_EQ(fig.mismatches, 0u);
  EXPECT_EQ(fig.write_mismatch, 0u);
  EXPECT_EQ(fig.winding_bad, 0u);
  EXPECT_EQ(fig.convex_double_hits, 0u);
  EXPECT_EQ(fig.cracks, 0u);
  EXPECT_GT(fig.closed_checked, 250u);
  EXPECT_GT(fig.silhouette_pixels, kMinPixelsPerView * fig.closed_checked);
  std::printf(
      "[ stress ] %llu convex polyhedra (%llu seen from outside: %llu silhouette pixels, each "
      "hit once), 0 mismatches with the reference\n",
      (unsigned long long)fig.meshes, (unsigned long long)fig.closed_checked,
      (unsigned long long)fig.silhouette_pixels);
}

TEST(WatertightStress, JitteredSpheresKeepTheWindingIdentity) {
  std::mt19937_64 rng(37);
  Figures fig;
  for (int i = 0; i < 300; ++i) check_mesh(jittered_sphere(rng), false, rng, fig);
  EXPECT_EQ(fig.mismatches, 0u);
  EXPECT_EQ(fig.write_mismatch, 0u);
  EXPECT_EQ(fig.winding_bad, 0u);
  EXPECT_GT(fig.closed_checked, 200u);
  EXPECT_GT(fig.silhouette_pixels, kMinPixelsPerView * fig.closed_checked);
  std::printf(
      "[ stress ] %llu jittered spheres (%llu closed views, %llu silhouette pixels): front hits = "
      "back hits >= 1 inside, 0 outside on every pixel\n",
      (unsigned long long)fig.meshes, (unsigned long long)fig.closed_checked,
      (unsigned long long)fig.silhouette_pixels);
}

}  // namespace
}  // namespace lr
