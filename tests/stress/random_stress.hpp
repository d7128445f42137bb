// Random-triangle stress runs shared by the quick (10^6) and long (10^7) tests.
//
// Screen space (draw_screen): batches of triangles with id colours, painter's order, no depth,
// 64 x 64 viewport. Mix: general, sub-pixel, needles, degenerate (collinear, repeated vertices),
// vertices on pixel centres, giants up to draw_screen's limit (|x| < 3 x 4096 pixels) and
// out-of-limit ones (rejected). Per frame: every pixel's owner equals the exact reference's,
// pixels written equal the reference's hits (so no extra write can hide under a later triangle
// without a missing one elsewhere), every input triangle is accounted for in exactly one
// FrameStats reason, and every binned triangle's pixels lie in its bounding box.
//
// 3D (Renderer::draw with a perspective camera): random triangles in front, crossing the
// near plane, through the eye plane (w ~ 0, also with a near plane of 2^-12), behind, huge
// (|coordinate| up to 32767, far outside the guard band). Per frame: the core's coverage equals
// the reference's on the core's own snapped, clipped pieces; stats conservation; every snapped
// vertex inside the guard band; and every written pixel inside the bounding box (+1 pixel) of
// the input triangle clipped to the near plane in double precision and projected: clipping
// never draws outside the triangle.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "lineraster/core/scene/camera.hpp"
#include "tests/support/core_harness.hpp"

namespace lr::stress {

inline constexpr int64_t S = kSubpixel;
inline constexpr int kW = 64, kH = 64;

// Each input triangle counted in exactly one outcome.
inline uint64_t accounted(const FrameStats& s) {
  return uint64_t{s.binned_inputs} + s.culled_backface + s.culled_zero_area + s.culled_offscreen +
         s.clipped_away + s.rejected_invalid + s.dropped_vertex_capacity +
         s.dropped_triangle_capacity;
}

struct RunFigures {
  uint64_t triangles = 0, frames = 0, binned = 0, rejected = 0, clipped = 0, culled = 0;
  uint64_t pixels = 0, owner_mismatch = 0, write_mismatch = 0, outside_bbox = 0, stats_bad = 0;
  uint64_t out_of_band = 0;
};

// Owner/id of every pixel of the core's frame against the reference's coverage of `tris`
// (id_of_tri maps a reference triangle to the id colour it was drawn with).
inline void compare_frame(const host::ImageRgb8& img, const std::vector<ref::ScreenTri>& tris,
                          const std::vector<int32_t>& id_of_tri, uint32_t written, RunFigures& f) {
  std::vector<int32_t> hits, owner;
  ref::coverage(tris, kW, kH, kSubpixelBits, hits, owner);
  uint64_t ref_hits = 0;
  for (size_t p = 0; p < hits.size(); ++p) {
    ref_hits += static_cast<uint64_t>(hits[p]);
    int32_t expect = owner[p] < 0 ? -1 : id_of_tri[static_cast<size_t>(owner[p])];
    if (test::id_of(img, p) != expect) ++f.owner_mismatch;
  }
  if (ref_hits != written) ++f.write_mismatch;
  f.pixels += written;
}

inline int64_t rnd(std::mt19937_64& rng, int64_t lo, int64_t hi) {
  return std::uniform_int_distribution<int64_t>(lo, hi)(rng);
}

// One random screen-space triangle (subpixels) of category `kind`.
inline std::array<int64_t, 6> screen_triangle(std::mt19937_64& rng, int kind) {
  const int64_t lim = int64_t{kMaxViewport} * 3 * S - 1;  // draw_screen's accepted range
  std::array<int64_t, 6> v{};
  auto around = [&](int64_t r) {
    int64_t x = rnd(rng, -8 * S, (kW + 8) * S), y = rnd(rng, -8 * S, (kH + 8) * S);
    v = {x, y, x + rnd(rng, -r, r), y + rnd(rng, -r, r), x + rnd(rng, -r, r), y + rnd(rng, -r, r)};
  };
  switch (kind) {
    case 0:  // general, a few pixels to the viewport's size
      around(rnd(rng, 1, 48) * S);
      break;
    case 1:  // sub-pixel
      around(rnd(rng, 1, S));
      break;
    case 2: {  // needle: long, one subpixel or less thick, any direction
      int64_t x = rnd(rng, -8 * S, (kW + 8) * S), y = rnd(rng, -8 * S, (kH + 8) * S);
      int64_t dx = rnd(rng, -90 * S, 90 * S), dy = rnd(rng, -90 * S, 90 * S);
      v = {x, y, x + dx, y + dy, x + dx / 2 + rnd(rng, -2, 2), y + dy / 2 + rnd(rng, -2, 2)};
      break;
    }
    case 3: {  // degenerate: collinear or a repeated vertex
      around(rnd(rng, 1, 40) * S);
      if (rng() % 2) {
        v[4] = v[0];
        v[5] = v[1];
      } else {
        int64_t k = rnd(rng, -3, 3);
        v[4] = v[0] + k * (v[2] - v[0]);
        v[5] = v[1] + k * (v[3] - v[1]);
      }
      break;
    }
    case 4:  // vertices on pixel centres (edges through many centres)
      around(rnd(rng, 1, 30) * S);
      for (auto& c : v) c = (c / S) * S + S / 2;
      break;
    case 5:  // giant, up to the accepted limit
      for (auto& c : v) c = rnd(rng, -lim, lim);
      if (rng() % 2) {  // pinned to the limit
        v[0] = -lim;
        v[3] = lim;
      }
      break;
    default: {  // one vertex beyond the limit: rejected, counted
      around(20 * S);
      v[static_cast<size_t>(rng() % 6)] = (rng() % 2 ? 1 : -1) * (lim + 1 + rnd(rng, 0, 1 << 20));
      break;
    }
  }
  return v;
}

inline void run_screen(uint64_t count, uint64_t seed, RunFigures& f) {
  std::mt19937_64 rng(seed);
  constexpr int kBatch = 500;
  test::CoreHarness<8> core(kW, kH);
  ASSERT_EQ(core.configured(), Status::kOk);
  // Category weights per 64: giants cost the reference a full frame each, keep them rarer.
  static constexpr int kWeights[7] = {20, 14, 10, 8, 8, 2, 2};
  while (f.triangles < count) {
    const int n = static_cast<int>(std::min<uint64_t>(kBatch, count - f.triangles));
    test::ScreenScene scene;
    std::vector<bool> limited(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      int pick = static_cast<int>(rng() % 64), kind = 0;
      while (pick >= kWeights[kind]) pick -= kWeights[kind++];
      auto v = screen_triangle(rng, kind);
      scene.add(v[0], v[1], v[2], v[3], v[4], v[5]);
      limited[static_cast<size_t>(i)] = kind == 6;
    }
    core.begin();
    Status st =
        core.renderer().draw_screen(scene.vertices, scene.triangles, test::coverage_state());
    ASSERT_EQ(st, Status::kOk);
    Status rs;
    host::ImageRgb8 img = core.render(&rs);
    ASSERT_EQ(rs, Status::kOk);
    const FrameStats& s = core.renderer().stats();
    if (accounted(s) != s.triangles_in || s.triangles_in != static_cast<uint32_t>(n)) ++f.stats_bad;
    // The reference is given only what the core accepts (the rejected ones are counted).
    uint32_t rejected = 0;
    std::vector<ref::ScreenTri> tris;
    std::vector<int32_t> ids;
    for (int i = 0; i < n; ++i) {
      if (limited[static_cast<size_t>(i)]) {
        ++rejected;
        continue;
      }
      tris.push_back(scene.ref[static_cast<size_t>(i)]);
      ids.push_back(i);
    }
    if (s.rejected_invalid != rejected) ++f.stats_bad;
    compare_frame(img, tris, ids, s.pixels_written, f);
    // Bounding boxes: every pixel showing triangle i has its centre inside i's box.
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        int32_t id = test::id_of(img, static_cast<size_t>(y * kW + x));
        if (id < 0) continue;
        const ref::ScreenTri& t = scene.ref[static_cast<size_t>(id)];
        int64_t cx = x * S + S / 2, cy = y * S + S / 2;
        if (cx < std::min({t.x[0], t.x[1], t.x[2]}) || cx > std::max({t.x[0], t.x[1], t.x[2]}) ||
            cy < std::min({t.y[0], t.y[1], t.y[2]}) || cy > std::max({t.y[0], t.y[1], t.y[2]}))
          ++f.outside_bbox;
      }
    f.triangles += static_cast<uint64_t>(n);
    f.binned += s.binned_inputs;
    f.rejected += s.rejected_invalid;
    f.culled += s.culled_zero_area + s.culled_offscreen + s.culled_backface;
    ++f.frames;
  }
}

// ---- 3D ----

struct Vec3dd {
  double x, y, z;
};

inline double fx(Fixed f) {
  return f.raw / 65536.0;
}

// The projected bounding box (pixels, display y down) of a world triangle clipped to the near
// and far planes in double precision. mvp: the core's own matrix. False if nothing is left.
inline bool projected_bbox(const Mat4& mvp, const Vec3 p[3], int w, int h, double box[4]) {
  std::vector<std::array<double, 4>> poly;
  for (int k = 0; k < 3; ++k) {
    std::array<double, 4> c{};
    double in[4] = {fx(p[k].x), fx(p[k].y), fx(p[k].z), 1.0};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) c[static_cast<size_t>(i)] += fx(mvp.m[i][j]) * in[j];
    poly.push_back(c);
  }
  // Clip against the near plane z >= -w, the far plane z <= w and w >= 2^-16 (the planes the
  // core clips against besides the guard band, which only removes more).
  auto clip = [](const std::vector<std::array<double, 4>>& in, auto dist) {
    std::vector<std::array<double, 4>> o;
    for (size_t i = 0; i < in.size(); ++i) {
      const auto& a = in[i];
      const auto& b = in[(i + 1) % in.size()];
      double da = dist(a), db = dist(b);
      if (da >= 0) o.push_back(a);
      if ((da >= 0) != (db >= 0)) {
        double t = da / (da - db);
        std::array<double, 4> m{};
        for (size_t k = 0; k < 4; ++k) m[k] = a[k] + t * (b[k] - a[k]);
        o.push_back(m);
      }
    }
    return o;
  };
  std::vector<std::array<double, 4>> out =
      clip(poly, [](const std::array<double, 4>& c) { return c[2] + c[3]; });
  out = clip(out, [](const std::array<double, 4>& c) { return c[3] - c[2]; });
  out = clip(out, [](const std::array<double, 4>& c) { return c[3] - 1.0 / 65536; });
  if (out.empty()) return false;
  box[0] = box[1] = 1e300;
  box[2] = box[3] = -1e300;
  for (const auto& c : out) {
    double ww = std::max(c[3], 1.0 / 65536);
    double sx = (c[0] / ww + 1) * w / 2, sy = (1 - c[1] / ww) * h / 2;
    box[0] = std::min(box[0], sx);
    box[1] = std::min(box[1], sy);
    box[2] = std::max(box[2], sx);
    box[3] = std::max(box[3], sy);
  }
  return true;
}

inline Fixed fixed_of(double v) {
  return Fixed::from_raw(
      static_cast<int32_t>(std::llround(std::clamp(v, -32767.0, 32767.0) * 65536.0)));
}

inline Vec3 random_point(std::mt19937_64& rng, int kind) {
  std::uniform_real_distribution<double> u(-1, 1);
  auto in_view = [&](double zmin, double zmax) {
    double z = -std::uniform_real_distribution<double>(zmin, zmax)(rng);
    return Vec3{fixed_of(u(rng) * -z), fixed_of(u(rng) * -z), fixed_of(z)};
  };
  switch (kind) {
    case 0:  // in the view volume
      return in_view(0.2, 60);
    case 1:  // near the eye plane: w ~ 0 (a few 2^-16 either side)
      return {fixed_of(u(rng) * 3), fixed_of(u(rng) * 3),
              Fixed::from_raw(static_cast<int32_t>(rnd(rng, -40, 40)))};
    case 2:  // behind the eye
      return in_view(-60, -0.05);
    case 3:  // huge: anywhere up to the Q16.16 limit
      return {fixed_of(u(rng) * 32767), fixed_of(u(rng) * 32767), fixed_of(u(rng) * 32767)};
    default:  // just in front of or behind the near plane (0.1)
      return in_view(0.05, 0.15);
  }
}

inline void run_3d(uint64_t count, uint64_t seed, RunFigures& f) {
  std::mt19937_64 rng(seed);
  constexpr int kBatch = 200;
  test::CoreHarness<8> core(kW, kH);
  ASSERT_EQ(core.configured(), Status::kOk);
  Camera cams[2];
  const double nears[2] = {0.1, 1.0 / 4096};
  for (int c = 0; c < 2; ++c)
    ASSERT_TRUE(perspective(Fixed::from_int(60), Fixed::from_int(1),
                            Fixed::from_raw(static_cast<int32_t>(nears[c] * 65536)),
                            Fixed::from_int(100), cams[c].projection));
  uint64_t frame = 0;
  while (f.triangles < count) {
    const int n = static_cast<int>(std::min<uint64_t>(kBatch, count - f.triangles));
    const Camera& cam = cams[frame % 2];
    ++frame;
    std::vector<Vec3> pos;
    std::vector<Rgb8> col;
    std::vector<std::array<uint16_t, 3>> tri;
    for (int i = 0; i < n; ++i) {
      // Mostly in view; the rest mixes every kind of vertex.
      int base_kind = rng() % 4 == 0 ? 0 : static_cast<int>(rng() % 5);
      for (int k = 0; k < 3; ++k) {
        int kind = rng() % 3 == 0 ? static_cast<int>(rng() % 5) : base_kind;
        pos.push_back(random_point(rng, kind));
        col.push_back(to_rgb8(test::id_color(static_cast<uint32_t>(i))));
      }
      auto b = static_cast<uint16_t>(3 * i);
      tri.push_back({b, static_cast<uint16_t>(b + 1), static_cast<uint16_t>(b + 2)});
    }
    core.begin({0, 0, 0}, cam);
    DrawState st = test::coverage_state();
    st.cull = frame % 3 == 0 ? Cull::kBack : Cull::kNone;
    ASSERT_EQ(core.renderer().draw(Mesh{pos, {}, col, {}, tri}, Mat4::identity(), Material{}, st),
              Status::kOk);
    Status rs;
    host::ImageRgb8 img = core.render(&rs);
    ASSERT_EQ(rs, Status::kOk);
    const FrameStats& s = core.renderer().stats();
    if (accounted(s) != s.triangles_in) ++f.stats_bad;

    // The reference on the core's own snapped pieces.
    std::vector<ref::ScreenTri> tris;
    std::vector<int32_t> ids;
    auto sv = core.renderer().screen_vertices();
    constexpr int64_t kBand = int64_t{1} << 22;
    const auto colors = core.renderer().triangle_colors();
    size_t ids_seen = 0;
    for (const BinnedTriangle& bt : core.renderer().binned_triangles()) {
      ref::ScreenTri t{};
      for (int k = 0; k < 3; ++k) {
        t.x[k] = sv[bt.v[k]].x;
        t.y[k] = sv[bt.v[k]].y;
        if (std::abs(t.x[k]) >= kBand || std::abs(t.y[k]) >= kBand) ++f.out_of_band;
      }
      tris.push_back(t);
      const Rgb8 c = colors[ids_seen++].primary;  // flat: the provoking vertex's colour
      ids.push_back(static_cast<int32_t>(c.r | (c.g << 8) | (c.b << 16)) - 1);
    }
    compare_frame(img, tris, ids, s.pixels_written, f);

    // Clipping never draws outside the (near-clipped, projected) input triangle.
    const Mat4 mvp = cam.projection * cam.view * Mat4::identity();
    std::vector<std::array<double, 4>> boxes(static_cast<size_t>(n));
    std::vector<bool> has_box(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i)
      has_box[static_cast<size_t>(i)] = projected_bbox(mvp, &pos[3 * static_cast<size_t>(i)], kW,
                                                       kH, boxes[static_cast<size_t>(i)].data());
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        int32_t id = test::id_of(img, static_cast<size_t>(y * kW + x));
        if (id < 0) continue;
        const auto& b = boxes[static_cast<size_t>(id)];
        double cx = x + 0.5, cy = y + 0.5;
        if (!has_box[static_cast<size_t>(id)] || cx < b[0] - 1 || cx > b[2] + 1 || cy < b[1] - 1 ||
            cy > b[3] + 1)
          ++f.outside_bbox;
      }
    f.triangles += static_cast<uint64_t>(n);
    f.binned += s.binned_inputs;
    f.rejected += s.rejected_invalid;
    f.clipped += s.clipped;
    f.culled += s.culled_zero_area + s.culled_offscreen + s.culled_backface + s.clipped_away;
    ++f.frames;
  }
}

inline void expect_clean(const RunFigures& f) {
  EXPECT_EQ(f.owner_mismatch, 0u);
  EXPECT_EQ(f.write_mismatch, 0u);
  EXPECT_EQ(f.outside_bbox, 0u);
  EXPECT_EQ(f.stats_bad, 0u);
  EXPECT_EQ(f.out_of_band, 0u);
}

// Zero mismatches mean nothing if nothing was drawn: lower bounds on the work, from the mix.
// Screen space: the general, on-centre and giant triangles (30 of every 64) nearly all reach
// the edge table, the general ones alone cover over a hundred pixels each on average; the
// out-of-limit ones (2 of 64) are rejected.
inline void expect_screen_work(const RunFigures& f) {
  EXPECT_GE(f.binned, f.triangles * 2 / 5) << "binned";
  EXPECT_GE(f.pixels, f.triangles * 30) << "pixels written";
  EXPECT_GE(f.rejected, f.triangles / 40) << "rejected beyond the limit";
  EXPECT_LE(f.rejected, f.triangles / 20) << "rejected beyond the limit";
}

// 3D: more than one triangle in seven has its three vertices in the view volume and spans a
// good part of the 64 x 64 view; most others have near-plane, eye-plane or huge vertices and
// keep a piece after clipping: at least a third binned, a quarter clipped.
inline void expect_3d_work(const RunFigures& f) {
  EXPECT_GE(f.binned, f.triangles / 3) << "binned";
  EXPECT_GE(f.clipped, f.triangles / 4) << "clipped";
  EXPECT_GE(f.pixels, f.triangles * 100) << "pixels written";
}

}  // namespace lr::stress
