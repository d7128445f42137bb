// Inputs at the limits of each fixed-point format, NaN / Inf / huge values through the host API,
// and depth precision (16-bit window depth).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/setup/untextured_setup.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/stress/random_stress.hpp"

namespace lr {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- Host conversions and render_scene ----

TEST(Limits, HostConversionsRejectWhatTheFormatsCannotHold) {
  Fixed f;
  for (double bad : {kNaN, kInf, -kInf, 1e30, -1e30, 32767.5, -32767.5, 32768.0, 1e300})
    EXPECT_FALSE(host::to_fixed(bad, f)) << bad;
  ASSERT_TRUE(host::to_fixed(32767.49, f));
  EXPECT_EQ(f.raw, std::lround(32767.49 * 65536));
  ASSERT_TRUE(host::to_fixed(-32767.49, f));
  EXPECT_EQ(f.raw, -std::lround(32767.49 * 65536));
  TexCoord t;
  for (double bad : {kNaN, kInf, -kInf, 1e30, 2047.999, -2047.999, 4096.0}) {
    EXPECT_FALSE(host::to_texcoord({bad, 0.5}, t)) << bad;
    EXPECT_FALSE(host::to_texcoord({0.5, bad}, t)) << bad;
  }
  ASSERT_TRUE(host::to_texcoord({2047.998, -2047.998}, t));
  EXPECT_EQ(t.u, std::lround(2047.998 * (1 << TexCoord::kFracBits)));
  EXPECT_EQ(t.v, -std::lround(2047.998 * (1 << TexCoord::kFracBits)));
  // Colours clamp (GL clamps colours), NaN becomes 0.
  Color15 c = host::to_color15({kNaN, kInf, -kInf});
  EXPECT_EQ(c.r, 0);
  EXPECT_EQ(c.g, Color15::kOne);
  EXPECT_EQ(c.b, 0);
}

host::HostMesh quad_mesh() {
  host::HostMesh m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TEST(Limits, RenderSceneRejectsNonFiniteAndHugeCoordinatesWithAnError) {
  host::SceneOptions o;
  o.width = 32;
  o.height = 24;
  host::RenderResult r;
  std::string error;
  ASSERT_TRUE(host::render_scene(quad_mesh(), o, r, error)) << error;
  EXPECT_GT(r.stats.pixels_written, 0u);
  for (double bad : {kNaN, kInf, -kInf, 1e30, -1e30, 40000.0}) {
    for (int axis = 0; axis < 3; ++axis) {
      host::HostMesh m = quad_mesh();
      m.positions[2][static_cast<size_t>(axis)] = bad;
      host::RenderResult out;
      error.clear();
      EXPECT_FALSE(host::render_scene(m, o, out, error)) << bad;
      EXPECT_NE(error.find("not finite or outside"), std::string::npos) << error;
      EXPECT_EQ(out.stats.pixels_written, 0u);
    }
  }
  for (double bad : {kNaN, kInf, 1e30}) {
    host::HostMesh m = quad_mesh();
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.uvs[1][0] = bad;
    host::RenderResult out;
    error.clear();
    EXPECT_FALSE(host::render_scene(m, o, out, error));
    EXPECT_NE(error.find("texture coordinate"), std::string::npos) << error;
  }
  // Non-finite camera, projection or model options are errors too, never a frame.
  for (int which = 0; which < 5; ++which) {
    host::SceneOptions b = o;
    if (which == 0) b.eye = {kNaN, 0, 3};
    if (which == 1) b.fovy = kInf;
    if (which == 2) b.near = kNaN;
    if (which == 3) b.model_scale = 1e30;
    if (which == 4) b.light_dirs = {{kNaN, 1, 1}};
    host::RenderResult out;
    error.clear();
    EXPECT_FALSE(host::render_scene(quad_mesh(), b, out, error)) << which;
    EXPECT_FALSE(error.empty());
  }
}

// ---- Q16.16 positions and matrix entries at their limits ----

TEST(Limits, HugePositionsAndMatrixEntriesAreClippedOrRejectedNeverDrawnWrong) {
  // Identity camera: the clip coordinates are exactly model * p, computed here in double too.
  // Matrix entries of every magnitude up to 32767, positions up to +-32767: clip coordinates
  // beyond 2^19 are rejected (counted in rejected_invalid), the rest clipped and drawn inside
  // the triangle's exactly projected box.
  std::mt19937_64 rng(5);
  test::CoreHarness<8> core(stress::kW, stress::kH);
  uint64_t frames = 0, rejected = 0, drawn = 0, clipped = 0, outside = 0, stats_bad = 0;
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 3000; ++i) {
    Mat4 m{};
    const double mag = std::ldexp(1.0, static_cast<int>(rng() % 16)) * (1 - 1.0 / 65536);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) m.m[r][c] = stress::fixed_of(u(rng) * mag);
    m.m[3][2] = Fixed::from_int(-1);  // w = -z_model: a perspective divide
    if (rng() % 4 == 0) m.m[3][3] = stress::fixed_of(u(rng) * mag);
    Vec3 p[3];
    const double pm = rng() % 2 ? 32767.0 : std::ldexp(1.0, static_cast<int>(rng() % 15));
    for (auto& v : p)
      v = {stress::fixed_of(u(rng) * pm), stress::fixed_of(u(rng) * pm),
           stress::fixed_of(u(rng) * pm)};
    if (rng() % 8 == 0)
      p[0] = {Fixed::from_raw(INT32_MAX), Fixed::from_raw(INT32_MIN), Fixed::from_raw(-INT32_MAX)};
    std::vector<Rgb8> col(3, Rgb8{1, 0, 0});
    std::vector<std::array<uint16_t, 3>> tri = {{0, 1, 2}};
    core.begin();
    ASSERT_EQ(core.renderer().draw(Mesh{std::span<const Vec3>(p, 3), {}, col, {}, tri}, m,
                                   Material{}, test::coverage_state()),
              Status::kOk);
    host::ImageRgb8 img = core.render();
    const FrameStats& s = core.renderer().stats();
    stats_bad += stress::accounted(s) != 1;
    rejected += s.rejected_invalid;
    clipped += s.clipped;
    ++frames;
    double box[4];
    bool has = stress::projected_bbox(m, p, stress::kW, stress::kH, box);
    for (int y = 0; y < stress::kH; ++y)
      for (int x = 0; x < stress::kW; ++x) {
        if (test::id_of(img, static_cast<size_t>(y * stress::kW + x)) < 0) continue;
        ++drawn;
        double cx = x + 0.5, cy = y + 0.5;
        outside += !has || cx < box[0] - 1 || cx > box[2] + 1 || cy < box[1] - 1 || cy > box[3] + 1;
      }
  }
  EXPECT_EQ(stats_bad, 0u);
  EXPECT_EQ(outside, 0u);
  EXPECT_GT(rejected, 100u);
  EXPECT_GT(drawn, 1000u);
  std::printf(
      "[ stress ] %llu triangles with matrix entries up to 32767 and positions up to +-32767: "
      "%llu rejected out of range (counted), %llu clipped, %llu pixels drawn, 0 outside\n",
      (unsigned long long)frames, (unsigned long long)rejected, (unsigned long long)clipped,
      (unsigned long long)drawn);
}

// ---- Screen-space limits: depth 0 and 1, coordinate limit ----

ScreenVertex sv(int64_t x, int64_t y, uint32_t z, Rgb8 c) {
  ScreenVertex v;
  v.x = static_cast<int32_t>(x);
  v.y = static_cast<int32_t>(y);
  v.z = z;
  v.color = from_rgb8(c);
  return v;
}

DrawState flat_depth() {
  DrawState s = test::coverage_state();
  s.depth_test = true;
  return s;
}

// A full-viewport quad (two triangles) with the given depths at its four corners.
void quad(std::vector<ScreenVertex>& v, std::vector<std::array<uint16_t, 3>>& t, int w, int h,
          const uint32_t z[4], Rgb8 c) {
  auto b = static_cast<uint16_t>(v.size());
  const int64_t S = kSubpixel;
  v.push_back(sv(0, 0, z[0], c));
  v.push_back(sv(0, h * S, z[1], c));
  v.push_back(sv(w * S, h * S, z[2], c));
  v.push_back(sv(w * S, 0, z[3], c));
  t.push_back({b, uint16_t(b + 1), uint16_t(b + 2)});
  t.push_back({b, uint16_t(b + 2), uint16_t(b + 3)});
}

// Quads of 16 x 16 pixels (set up in int32: edges below 64 pixels) and 200 x 100 (the 32-bit
// short path) at one depth, at both ends of the range: every pixel gets the 16-bit depth
// round(65535 depth) = (z + 2^15) >> 16 (the half-depth plane's (z / 2 + 2^14) >> 15 is the same
// for every z), or nothing where that is 65535, the cleared value.
TEST(Limits, DepthZeroIsDrawnDepthOneLosesToTheClearValueBeyondIsRejected) {
  constexpr uint32_t kHalfStep = 1u << 15;
  for (const auto& [w, h] : {std::pair{16, 16}, std::pair{200, 100}}) {
    for (uint32_t z :
         {0u, 1u, kHalfStep - 1, kHalfStep, kDepthMax - kHalfStep - 1, kDepthMax - kHalfStep,
          kDepthMax - kHalfStep + 1, kDepthMax - 1, kDepthMax, kDepthMax + 1, 0xFFFFFFFFu}) {
      std::vector<ScreenVertex> v;
      std::vector<std::array<uint16_t, 3>> t;
      const uint32_t zz[4] = {z, z, z, z};
      quad(v, t, w, h, zz, {9, 9, 9});
      test::CoreHarness<4> core(w, h);
      core.begin();
      core.renderer().draw_screen(v, t, flat_depth());
      core.render();
      const FrameStats& s = core.renderer().stats();
      EXPECT_EQ(stress::accounted(s), 2u);
      const size_t n = size_t(w) * size_t(h);
      size_t other_depth = 0;
      if (z > kDepthMax) {
        EXPECT_EQ(s.rejected_invalid, 2u) << z;
        EXPECT_EQ(s.pixels_written, 0u);
      } else if (z >= kDepthMax - kHalfStep) {
        // Rounds to 65535, the cleared value: LESS fails, as in GL with depth 1.0.
        EXPECT_EQ(s.pixels_written, 0u) << w << " x " << h << ", z " << z;
      } else {
        EXPECT_EQ(s.pixels_written, n) << w << " x " << h << ", z " << z;
        for (size_t i = 0; i < n; ++i) other_depth += core.depth()[i] != (z + kHalfStep) >> 16;
      }
      EXPECT_EQ(other_depth, 0u) << w << " x " << h << ", z " << z;
    }
  }
}

// ---- Depth precision ----

// The depth plane of the triangle (sorted by y) as the strip loop sets it up, in half units
// (docs/numerics.md#depth), and the exact plane through the same half depths z / 2 + 2^14 at
// pixel (x, y)'s centre.
Plane depth_plane(const ScreenVertex* const tv[3], int w, int h) {
  UntexturedInput in;
  in.colors = ColorPlanes::kNone;
  in.depth = true;
  ActiveTriangle t{};
  EXPECT_TRUE(setup_untextured_triangle(tv, RowWindow{0, h - 1, w}, in, t).pixels());
  return t.z;
}
double exact_half_depth(const ScreenVertex* const tv[3], int x, int y) {
  const double px = (x + 0.5) * kSubpixel, py = (y + 0.5) * kSubpixel;
  const double x0 = tv[0]->x, y0 = tv[0]->y;
  const double e1x = tv[1]->x - x0, e1y = tv[1]->y - y0, e2x = tv[2]->x - x0, e2y = tv[2]->y - y0;
  const double d = e1x * e2y - e2x * e1y;
  const double l1 = ((px - x0) * e2y - (py - y0) * e2x) / d;
  const double l2 = ((py - y0) * e1x - (px - x0) * e1y) / d;
  double z[3];
  for (int k = 0; k < 3; ++k) z[k] = double(tv[k]->z >> 1) + (1 << 14);
  return z[0] + l1 * (z[1] - z[0]) + l2 * (z[2] - z[0]);
}

// Two planes drawn over the whole viewport; B's vertex depths are A's plus delta.
// Documented rule (docs/numerics.md#depth): the untextured family's depth plane interpolates the
// half depths z / 2 (rounded down) with 2^14 in its base, the 16-bit value is the plane's value
// >> 15, compared with LESS: where the values differ the nearer wins, where they are equal
// (planes closer than 1/65535 may tie) the first drawn wins. The model takes each plane as setup
// builds it (setup_untextured_triangle, the strip loop's call), checks it against the exact
// plane, and applies the rule. Planes at least 1/65535 apart always resolve to the nearer: for
// an even delta B's half depths are A's plus delta / 2 exactly (the same gradients, the same
// rounding), for an odd one they differ from that by the dropped low bits (0 or 1 per vertex).
TEST(DepthPrecision, NearCoplanarScreenPlanesResolveAsTheSixteenBitRuleSays) {
  const int w = 48, h = 40;
  std::mt19937_64 rng(17);
  std::uniform_int_distribution<uint32_t> base(0, kDepthMax - (3u << 16));
  std::uniform_int_distribution<int32_t> slope(-(1 << 20), 1 << 20);
  uint64_t pixels = 0, resolved = 0, ties = 0, wrong = 0, far_shown = 0;
  double max_plane_error = 0;  // half-depth units (2^15 a 16-bit step)
  for (int trial = 0; trial < 300; ++trial) {
    uint32_t za[4];
    const uint32_t b0 = base(rng);
    for (auto& z : za) {
      int64_t v = int64_t{b0} + (trial % 3 == 0 ? 0 : slope(rng));
      z = static_cast<uint32_t>(std::clamp<int64_t>(v, 0, kDepthMax - (2u << 16)));
    }
    // delta: exactly 1/65535 (2^16 units), more, or less.
    const uint32_t deltas[5] = {1u << 16, (1u << 16) + 1, 3u << 15, (1u << 16) - 1, 1u << 14};
    const uint32_t delta = deltas[trial % 5];
    uint32_t zb[4];
    for (int k = 0; k < 4; ++k) zb[k] = za[k] + delta;
    const bool a_first = trial % 2 == 0;
    std::vector<ScreenVertex> v;
    std::vector<std::array<uint16_t, 3>> t;
    if (a_first) {
      quad(v, t, w, h, za, {255, 0, 0});
      quad(v, t, w, h, zb, {0, 255, 0});
    } else {
      quad(v, t, w, h, zb, {0, 255, 0});
      quad(v, t, w, h, za, {255, 0, 0});
    }
    test::CoreHarness<8> core(w, h);
    core.begin();
    core.renderer().draw_screen(v, t, flat_depth());
    host::ImageRgb8 img = core.render();
    // Each triangle of each quad has its own plane (vertices sorted by y; the fixed network
    // keeps ties in order): [quad A, B][upper, lower].
    const ScreenVertex* tv[2][2][3];
    Plane planes[2][2];
    for (int q = 0; q < 2; ++q)
      for (int lower = 0; lower < 2; ++lower) {
        const size_t o = (q == 0) == a_first ? 0 : 4;
        const ScreenVertex** s = tv[q][lower];
        s[0] = &v[o];
        s[1] = &v[o + (lower ? 1 : 2)];
        s[2] = &v[o + (lower ? 2 : 3)];
        if (s[1]->y < s[0]->y) std::swap(s[0], s[1]);
        if (s[2]->y < s[1]->y) std::swap(s[1], s[2]);
        if (s[1]->y < s[0]->y) std::swap(s[0], s[1]);
        planes[q][lower] = depth_plane(s, w, h);
      }
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t p = size_t(y) * w + size_t(x);
        // Which of the two triangles covers the centre: the diagonal from (0,0) to (w,h).
        const int lower = double(y + 0.5) * w > double(x + 0.5) * h ? 1 : 0;
        const uint32_t zpa = planes[0][lower].at(x, y), zpb = planes[1][lower].at(x, y);
        for (int q = 0; q < 2; ++q)
          max_plane_error = std::max(
              max_plane_error,
              std::fabs(double(q == 0 ? zpa : zpb) - exact_half_depth(tv[q][lower], x, y)));
        const uint32_t da = zpa >> 15, db = zpb >> 15;
        const bool a_wins = da < db || (da == db && a_first);
        const bool shows_a = img.rgb[3 * p] == 255;
        ++pixels;
        (da < db ? resolved : ties)++;
        if (a_wins != shows_a) ++wrong;
        // >= 1/65535 apart: the nearer, always.
        if (delta >= (1u << 16) && !shows_a) ++far_shown;
      }
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_EQ(far_shown, 0u);
  EXPECT_GT(ties, 0u);
  // The planes within 1/64 of a 16-bit step of the exact ones (docs/numerics.md#depth).
  EXPECT_LT(max_plane_error, 512.0);
  std::printf(
      "[ stress ] depth: %llu pixels of near-coplanar plane pairs, %llu resolved by 16-bit depth "
      "(all planes >= 1/65535 apart among them), %llu ties won by the first drawn, %llu not as "
      "the rule says, %llu farther shown; planes within %.1f half-depth units (%.4f of a step) "
      "of the exact ones\n",
      (unsigned long long)pixels, (unsigned long long)resolved, (unsigned long long)ties,
      (unsigned long long)wrong, (unsigned long long)far_shown, max_plane_error,
      max_plane_error / 32768);
}

// Through the 3D path: two tilted quads 'eps' apart along the view axis. Where their exact window
// depths (double, at the pixel centre) differ by at least 1/65535 plus a margin for vertex
// snapping, the rounding of the projected depth and the plane's drift (1/65535 in all), the
// nearer one must show.
TEST(DepthPrecision, NearCoplanarSurfacesThroughThe3dPath) {
  const int w = 64, h = 48;
  Camera cam;
  ASSERT_TRUE(perspective(Fixed::from_int(60), Fixed::ratio(w, h), Fixed::from_int(1),
                          Fixed::from_int(20), cam.projection));
  const double n = 1, f = 20;
  uint64_t checked = 0, wrong = 0, close = 0;
  for (int32_t eps_raw : {4, 12, 24, 48, 96, 400}) {
    for (int order = 0; order < 2; ++order) {
      for (double tilt : {0.0, 0.35, -0.8}) {
        auto make = [&](int32_t dz, Rgb8 c, std::vector<Vec3>& pos, std::vector<Rgb8>& col,
                        std::vector<std::array<uint16_t, 3>>& tri) {
          auto b = uint16_t(pos.size());
          for (auto [x, y] : {std::pair{-9.0, -9.0}, {9.0, -9.0}, {9.0, 9.0}, {-9.0, 9.0}}) {
            Fixed z = Fixed::from_raw(stress::fixed_of(-6.0 + tilt * x * 0.3).raw - dz);
            pos.push_back({stress::fixed_of(x), stress::fixed_of(y), z});
            col.push_back(c);
          }
          tri.push_back({b, uint16_t(b + 1), uint16_t(b + 2)});
          tri.push_back({b, uint16_t(b + 2), uint16_t(b + 3)});
        };
        std::vector<Vec3> pos;
        std::vector<Rgb8> col;
        std::vector<std::array<uint16_t, 3>> tri;
        // A is nearer (dz = 0); B is eps further away.
        if (order == 0) {
          make(0, {255, 0, 0}, pos, col, tri);
          make(eps_raw, {0, 255, 0}, pos, col, tri);
        } else {
          make(eps_raw, {0, 255, 0}, pos, col, tri);
          make(0, {255, 0, 0}, pos, col, tri);
        }
        test::CoreHarness<8> core(w, h);
        core.begin({0, 0, 0}, cam);
        DrawState st = flat_depth();
        ASSERT_EQ(
            core.renderer().draw(Mesh{pos, {}, col, {}, tri}, Mat4::identity(), Material{}, st),
            Status::kOk);
        host::ImageRgb8 img = core.render();
        // Exact window depth at a pixel centre: intersect the eye ray with the plane
        // z = z0 + k x (z0 = -6 - dz, k = 0.3 tilt).
        const double t = std::tan(30.0 * M_PI / 180);
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const double nx = (x + 0.5) / w * 2 - 1, ny = 1 - (y + 0.5) / h * 2;
            const double rx = nx * t * w / h, ry = ny * t;  // ray (rx, ry, -1) * s
            auto depth = [&](int32_t dz) {
              const double z0 = stress::fixed_of(-6.0).raw / 65536.0 - dz / 65536.0;
              const double k = tilt * 0.3;
              const double s = -z0 / (1 + k * rx);  // -s = z0 + k s rx
              const double ze = -s;
              (void)ry;
              return (f + n) / (f - n) / 2 + f * n / (f - n) / ze + 0.5;
            };
            const double da = depth(0), db = depth(eps_raw);
            const size_t p = size_t(y) * w + size_t(x);
            if (img.rgb[3 * p] == 0 && img.rgb[3 * p + 1] == 0) continue;  // not covered
            if (db - da >= 2.0 / 65535) {
              ++checked;
              if (img.rgb[3 * p] != 255) ++wrong;
            } else {
              ++close;
            }
          }
      }
    }
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(checked, 10000u);
  std::printf(
      "[ stress ] depth, 3D: %llu pixels with surfaces >= 2/65535 apart all resolved, %llu closer "
      "(either may show)\n",
      (unsigned long long)checked, (unsigned long long)close);
}

}  // namespace
}  // namespace lr
