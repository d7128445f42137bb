// Per-pixel lighting in the core: the inverse-square-root table, point-light attenuation, the
// highlight Gouraud misses, two-sided lighting, the normal-indexed lighting table, and the
// environment and normal maps on scenes whose answer is known exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/lighting/lighting_table.hpp"
#include "lineraster/core/math/inv_sqrt.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/support/core_harness.hpp"

namespace lr {
namespace {

constexpr Color15 kWhite{Color15::kOne, Color15::kOne, Color15::kOne};

Fixed fx(double v) {
  return Fixed::from_raw(static_cast<int32_t>(std::lround(v * 65536.0)));
}
Normal16 n16(double x, double y, double z) {
  double l = std::sqrt(x * x + y * y + z * z);
  auto c = [l](double v) { return static_cast<int16_t>(std::lround(v / l * 16384.0)); };
  return {c(x), c(y), c(z)};
}
Color15 c15(double r, double g, double b) {
  auto c = [](double v) { return static_cast<uint16_t>(std::lround(v * 32768.0)); };
  return {c(r), c(g), c(b)};
}

// A camera at (0, 0, 3) looking at the origin, 60 degrees, 320x240.
Camera front_camera(int w = 320, int h = 240) {
  Camera cam;
  EXPECT_TRUE(perspective(Fixed::from_int(60), Fixed::ratio(w, h), fx(0.1), Fixed::from_int(100),
                          cam.projection));
  cam.eye = {Fixed{}, Fixed{}, Fixed::from_int(3)};
  EXPECT_TRUE(look_at(cam.eye, {}, {Fixed{}, Fixed::from_int(1), Fixed{}}, cam.view));
  return cam;
}

LightSet one_light(Light l) {
  LightSet s;
  s.count = 1;
  s.lights[0] = l;
  return s;
}

// An equilateral triangle of circumradius 1 in the plane z = 0, facing +z, with vertex normals
// tilted 45 degrees outwards: the interpolated normal is +z only in the middle.
struct TiltedTriangle {
  std::vector<Vec3> positions;
  std::vector<Normal16> normals;
  std::vector<std::array<uint16_t, 3>> triangles{{0, 1, 2}};
  TiltedTriangle() {
    for (int i = 0; i < 3; ++i) {
      double a = M_PI / 2 + i * 2 * M_PI / 3;
      positions.push_back({fx(std::cos(a)), fx(std::sin(a)), Fixed{}});
      normals.push_back(n16(std::cos(a), std::sin(a), 1.0));
    }
  }
  Mesh mesh() const { return {positions, normals, {}, {}, triangles}; }
};

Rgb8 pixel(const host::ImageRgb8& img, int x, int y) {
  size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(img.width) + static_cast<size_t>(x));
  return {img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]};
}

// ---- The inverse-square-root table ----

template <int B, int N>
double worst_rsqrt_error() {
  double worst = 0;
  for (uint64_t x = uint64_t{1} << 30; x < (uint64_t{1} << 32); x += 997) {
    double f = double(x) / 1073741824.0;
    double r = InvSqrtTable<B, N>::rsqrt_q30(static_cast<uint32_t>(x)) / 1073741824.0;
    worst = std::max(worst, std::fabs(r * std::sqrt(f) - 1));
  }
  return worst;
}

TEST(InvSqrt, ErrorOfEachTableSizeAsDocumented) {
  // The figures of docs/numerics.md#inverse-square-root-table-and-newton-step, each within 10 %
  // (so the table there stays true).
  auto near = [](double got, double doc) { return got <= doc * 1.1 && got >= doc * 0.9; };
  EXPECT_PRED2(near, (worst_rsqrt_error<4, 0>()), 5.6e-2);
  EXPECT_PRED2(near, (worst_rsqrt_error<4, 1>()), 4.7e-3);
  EXPECT_PRED2(near, (worst_rsqrt_error<4, 2>()), 3.4e-5);
  EXPECT_PRED2(near, (worst_rsqrt_error<6, 0>()), 1.5e-2);
  EXPECT_PRED2(near, (worst_rsqrt_error<6, 1>()), 3.5e-4);
  EXPECT_PRED2(near, (worst_rsqrt_error<8, 0>()), 3.9e-3);
  EXPECT_PRED2(near, (worst_rsqrt_error<8, 1>()), 2.3e-5);
  EXPECT_PRED2(near, (worst_rsqrt_error<10, 0>()), 9.8e-4);
  EXPECT_PRED2(near, (worst_rsqrt_error<10, 1>()), 1.5e-6);
}

TEST(InvSqrt, RenormalisedNormalsAreUnitWithinOneQ14Lsb) {
  // Interpolated normals of every length and direction, down to a few units and up to 2^61.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    double scale = std::ldexp(1.0, 2 + i % 59);
    int64_t x = std::llround(u(rng) * scale), y = std::llround(u(rng) * scale),
            z = std::llround(u(rng) * scale);
    Unit30 n;
    if (!DefaultInvSqrt::normalize(x, y, z, n)) continue;
    double len =
        std::sqrt(double(n.x) * n.x + double(n.y) * n.y + double(n.z) * n.z) / 1073741824.0;
    worst = std::max(worst, std::fabs(len - 1));
  }
  EXPECT_LE(worst, std::ldexp(1.0, -15));  // half an LSB of Q1.14
  Unit30 keep{1, 2, 3};
  EXPECT_FALSE(DefaultInvSqrt::normalize(0, 0, 0, keep));
  EXPECT_EQ(keep.x, 1);
}

// ---- Lights ----

TEST(PointLight, AttenuationIsGls) {
  // A point light 2 units above a surface facing it: 1 / (1 + 0.5 * 2 + 0.25 * 4) = 1/3 of its
  // ambient and diffuse terms reach the point.
  Material m;
  m.ambient = c15(0.3, 0.3, 0.3);
  m.diffuse = c15(0.9, 0.6, 0.3);
  m.specular = {};
  LightSet s = one_light(Light::point({Fixed{}, Fixed{}, Fixed::from_int(2)}, kWhite,
                                      Fixed::from_int(1), fx(0.5), fx(0.25)));
  PreparedLighting pl = prepare_lighting(s, m, {Fixed{}, Fixed{}, Fixed::from_int(1)}, {});
  Color15 c = light_point(pl, Unit30{0, 0, 1 << 30}, Vec3{});
  EXPECT_NEAR(c.r, (0.3 + 0.9) / 3 * 32768, 3);
  EXPECT_NEAR(c.g, (0.3 + 0.6) / 3 * 32768, 3);
  EXPECT_NEAR(c.b, (0.3 + 0.3) / 3 * 32768, 3);
  // At 4 units and with a grazing normal (60 degrees): 1 / (1 + 2 + 4) and cos = 0.5.
  Vec3 p{Fixed{}, Fixed{}, Fixed::from_int(-2)};
  Unit30 n{static_cast<int32_t>(std::lround(std::sin(M_PI / 3) * 1073741824.0)), 0,
           static_cast<int32_t>(std::lround(0.5 * 1073741824.0))};
  c = light_point(pl, n, p);
  EXPECT_NEAR(c.r, (0.3 + 0.9 * 0.5) / 7 * 32768, 3);
  // Without attenuation a point light is as bright as a directional one from the same side.
  LightSet plain = one_light(Light::point({Fixed{}, Fixed{}, Fixed::from_int(5)}, kWhite));
  LightSet dir = one_light(Light::directional({Fixed{}, Fixed{}, Fixed::from_int(1)}, kWhite));
  Color15 a = light_point(prepare_lighting(plain, m, {Fixed{}, Fixed{}, Fixed::from_int(1)}, {}),
                          Unit30{0, 0, 1 << 30}, Vec3{});
  Color15 b = light_point(prepare_lighting(dir, m, {Fixed{}, Fixed{}, Fixed::from_int(1)}, {}),
                          Unit30{0, 0, 1 << 30}, Vec3{});
  EXPECT_EQ(a, b);
}

// ---- Phong against Gouraud ----

struct HighlightFrames {
  host::ImageRgb8 gouraud, phong, table;
};

HighlightFrames render_tilted(bool two_sided_back = false) {
  TiltedTriangle tri;
  Material m;
  m.ambient = {};
  m.diffuse = c15(0.5, 0.5, 0.5);
  m.specular = c15(0.5, 0.5, 0.5);
  m.shininess_q8 = 64 * 256;
  LightSet lights = one_light(Light::directional({Fixed{}, Fixed{}, Fixed::from_int(1)}, kWhite));
  lights.two_sided = two_sided_back;
  Camera cam = front_camera();
  if (two_sided_back) {  // from behind: the triangle is a back face, its normals point away
    cam.eye = {Fixed{}, Fixed{}, Fixed::from_int(-3)};
    look_at(cam.eye, {}, {Fixed{}, Fixed::from_int(1), Fixed{}}, cam.view);
    lights.lights[0].position = {Fixed{}, Fixed{}, Fixed::from_int(-1)};
  }
  HighlightFrames f;
  for (int mode = 0; mode < 3; ++mode) {
    test::CoreHarness<8, Rgb888> h(320, 240);
    EXPECT_EQ(h.begin({0, 0, 0}, cam, lights), Status::kOk);
    DrawState st;
    st.shading = mode == 0 ? Shading::kGouraud : Shading::kPhong;
    st.pixel_lighting = mode == 2 ? PixelLighting::kTable : PixelLighting::kExact;
    st.table.size = 64;
    EXPECT_EQ(h.renderer().draw(tri.mesh(), Mat4::identity(), m, st), Status::kOk);
    Status s;
    host::ImageRgb8 img = h.render(&s);
    EXPECT_EQ(s, Status::kOk);
    (mode == 0 ? f.gouraud : mode == 1 ? f.phong : f.table) = img;
  }
  return f;
}

TEST(Phong, ShowsTheHighlightInsideALargeTriangleThatGouraudMisses) {
  HighlightFrames f = render_tilted();
  // The triangle's centroid (the origin) projects to the centre of the screen. There the
  // interpolated normal is +z = the half vector: diffuse 0.5 + specular 0.5 = 255. At the
  // vertices N.H = cos 45: 0.5 * 0.707 + 0.5 * 0.707^64 = 0.354 -> 90, and Gouraud keeps that.
  Rgb8 g = pixel(f.gouraud, 160, 120), p = pixel(f.phong, 160, 120), t = pixel(f.table, 160, 120);
  EXPECT_GE(p.r, 253);
  EXPECT_GE(t.r, 250);
  EXPECT_NEAR(g.r, 90, 2);
  // Phong's highlight is concentrated: 40 pixels from the centre N.H ~ 0.99, so it has fallen.
  EXPECT_LT(pixel(f.phong, 200, 120).r, p.r - 30);
}

TEST(Phong, TwoSidedLightingLightsBackFacesWithTheNegatedNormal) {
  // Seen from behind with the light behind too: a back face whose negated normals tilt like
  // the front face's above, so the frame mirrors it. Without two-sided lighting the back face's
  // normals point away from the light: black.
  HighlightFrames front = render_tilted(false);
  HighlightFrames back = render_tilted(true);
  for (int x : {120, 160, 200})
    for (int y : {100, 120, 140}) {
      EXPECT_EQ(pixel(back.phong, x, y), pixel(front.phong, 319 - x, y)) << x << "," << y;
      EXPECT_NEAR(pixel(back.gouraud, x, y).r, pixel(front.gouraud, 319 - x, y).r, 1);
    }
}

// ---- The lighting table ----

struct SphereScene {
  host::HostMesh host_mesh = host::make_uv_sphere(24, 32);
  std::vector<host::FixedDraw> draws;
  SphereScene() {
    std::string err;
    host::SceneOptions o;
    EXPECT_TRUE(host::build_fixed_draws(host_mesh, o, draws, err)) << err;
  }
};

host::ImageRgb8 render_sphere(const SphereScene& sc, const DrawState& st, const LightSet& lights,
                              const Material& m) {
  test::CoreHarness<8, Rgb888> h(320, 240);
  EXPECT_EQ(h.begin({0, 0, 0}, front_camera(), lights), Status::kOk);
  EXPECT_EQ(h.renderer().draw(sc.draws[0].mesh(), Mat4::identity(), m, st), Status::kOk);
  return h.render();
}

Material shiny() {
  Material m;
  m.ambient = c15(0.1, 0.1, 0.1);
  m.diffuse = c15(0.7, 0.5, 0.3);
  m.specular = c15(0.6, 0.6, 0.6);
  m.shininess_q8 = 48 * 256;
  return m;
}

TEST(LightingTable, ErrorAgainstExactPerPixelLightingShrinksWithSize) {
  SphereScene sc;
  LightSet lights;
  lights.count = 2;
  lights.lights[0] =
      Light::directional({Fixed::from_int(1), Fixed::from_int(1), Fixed::from_int(1)}, kWhite);
  lights.lights[1] =
      Light::directional({Fixed::from_int(-1), Fixed{}, fx(0.5)}, c15(0.3, 0.3, 0.5));
  DrawState exact;
  exact.shading = Shading::kPhong;
  host::ImageRgb8 ref = render_sphere(sc, exact, lights, shiny());
  // Largest channel error (levels of 255) over the sphere, nearest and bilinear, per size. The
  // largest errors sit in the highlight (shininess 48), where the table's samples are furthest
  // apart relative to the lobe; the mean error over the frame is 0.07 levels at 64 bilinear.
  struct Bound {
    uint16_t size;
    int nearest, bilinear;
  };
  const Bound bounds[] = {{16, 95, 66}, {32, 66, 27}, {64, 32, 12}, {128, 17, 6}, {256, 9, 3}};
  int last_n = 1000, last_b = 1000;
  for (const Bound& b : bounds) {
    for (bool bil : {false, true}) {
      DrawState st = exact;
      st.pixel_lighting = PixelLighting::kTable;
      st.table = {b.size, bil};
      host::ImageRgb8 img = render_sphere(sc, st, lights, shiny());
      int worst = 0;
      for (size_t i = 0; i < img.rgb.size(); ++i)
        worst = std::max(worst, std::abs(int(img.rgb[i]) - int(ref.rgb[i])));
      EXPECT_LE(worst, bil ? b.bilinear : b.nearest) << "size " << b.size << " bilinear " << bil;
      EXPECT_LE(worst, bil ? last_b : last_n) << "size " << b.size;
      (bil ? last_b : last_n) = worst;
    }
  }
}

TEST(LightingTable, RefusesLightsThatDependOnPosition) {
  SphereScene sc;
  DrawState st;
  st.shading = Shading::kPhong;
  st.pixel_lighting = PixelLighting::kTable;
  for (int which = 0; which < 3; ++which) {
    LightSet lights = one_light(Light::directional({Fixed{}, Fixed{}, Fixed::from_int(1)}, kWhite));
    if (which == 0) lights.lights[0] = Light::point({Fixed{}, Fixed{}, Fixed::from_int(2)}, kWhite);
    if (which == 1) lights.local_viewer = true;
    if (which == 2) st.table.size = 300;
    test::CoreHarness<8, Rgb888> h(320, 240);
    ASSERT_EQ(h.begin({0, 0, 0}, front_camera(), lights), Status::kOk);
    EXPECT_EQ(h.renderer().draw(sc.draws[0].mesh(), Mat4::identity(), shiny(), st),
              Status::kInvalidArgument);
    EXPECT_EQ(h.renderer().stats().triangles_binned, 0u);
  }
}

// Storage for tests of the stores' capacities: 320x240 in strips of 8, room for 8192 vertices
// and triangles, the given Phong stores.
struct SmallStorage : BasicFrameStorage<std::vector> {
  SmallStorage(size_t n_surfaces, size_t n_table_words, size_t n_pls)
      : BasicFrameStorage(FrameCapacities{.width = 320,
                                          .height = 240,
                                          .strip_height = 8,
                                          .vertices = 8192,
                                          .triangles = 8192,
                                          .draws = 8,
                                          .active = 256,
                                          .surfaces = n_surfaces,
                                          .lighting_table_words = n_table_words,
                                          .pixel_lights = n_pls,
                                          .tex_vertices = 8192,
                                          .active_extra = 256,
                                          .triangle_colors = 8192}) {}
};

TEST(LightingTable, DrawsOfOneMaterialShareOneTable) {
  SphereScene sc;
  const Mesh mesh = sc.draws[0].mesh();
  // Room for exactly two 32-cell tables and two prepared materials.
  SmallStorage mem(8192, 2 * lighting_table_words(32, false), 2);
  Renderer<Rgb888, 8> r;
  ASSERT_EQ(r.configure(mem.storage(), 320, 240), Status::kOk);
  LightSet lights = one_light(Light::directional({Fixed{}, Fixed{}, Fixed::from_int(1)}, kWhite));
  ASSERT_EQ(r.begin_frame(front_camera(), lights, {}), Status::kOk);
  DrawState st;
  st.shading = Shading::kPhong;
  st.pixel_lighting = PixelLighting::kTable;
  st.table.size = 32;
  Material other = shiny(), third = shiny();
  other.diffuse = c15(0.2, 0.9, 0.2);
  third.diffuse = c15(0.9, 0.2, 0.2);
  EXPECT_EQ(r.draw(mesh, Mat4::identity(), shiny(), st), Status::kOk);
  EXPECT_EQ(r.draw(mesh, translate({fx(0.5), Fixed{}, Fixed{}}), shiny(), st), Status::kOk);
  EXPECT_EQ(r.draw(mesh, Mat4::identity(), other, st), Status::kOk);
  EXPECT_EQ(r.draw(mesh, translate({fx(-0.5), Fixed{}, Fixed{}}), other, st), Status::kOk);
  // A third material finds both stores full: dropped whole, and counted.
  const uint32_t before = r.stats().dropped_triangle_capacity;
  EXPECT_EQ(r.draw(mesh, Mat4::identity(), third, st), Status::kCapacity);
  EXPECT_EQ(r.stats().dropped_triangle_capacity - before, mesh.triangles.size());
}

// ---- Capacity ----

TEST(Phong, WithoutRoomInItsStoresADrawIsDroppedAndCounted) {
  SphereScene sc;
  const Mesh mesh = sc.draws[0].mesh();
  const size_t n = mesh.triangles.size();
  LightSet lights = one_light(Light::directional({Fixed{}, Fixed{}, Fixed::from_int(1)}, kWhite));
  DrawState st;
  st.shading = Shading::kPhong;
  {
    SmallStorage mem(16, 0, 1);  // far too few surface vertices
    Renderer<Rgb888, 8> r;
    ASSERT_EQ(r.configure(mem.storage(), 320, 240), Status::kOk);
    ASSERT_EQ(r.begin_frame(front_camera(), lights, {}), Status::kOk);
    EXPECT_EQ(r.draw(mesh, Mat4::identity(), shiny(), st), Status::kCapacity);
    EXPECT_EQ(r.stats().dropped_vertex_capacity, n);
    EXPECT_EQ(r.stats().triangles_binned, 0u);
  }
  SmallStorage mem(8192, 0, 1);  // no table pool, one prepared material
  Renderer<Rgb888, 8> r;
  ASSERT_EQ(r.configure(mem.storage(), 320, 240), Status::kOk);
  ASSERT_EQ(r.begin_frame(front_camera(), lights, {}), Status::kOk);
  st.pixel_lighting = PixelLighting::kTable;
  EXPECT_EQ(r.draw(mesh, Mat4::identity(), shiny(), st), Status::kMissingStore);
  EXPECT_EQ(r.stats().draws_refused_missing_store, 1u);
  EXPECT_EQ(r.stats().dropped_triangle_capacity, 0u);
  // Exact lighting needs no table; a second material finds the prepared-lighting store full.
  st.pixel_lighting = PixelLighting::kExact;
  EXPECT_EQ(r.draw(mesh, Mat4::identity(), shiny(), st), Status::kOk);
  Material other = shiny();
  other.shininess_q8 = 5 * 256;
  EXPECT_EQ(r.draw(mesh, Mat4::identity(), other, st), Status::kCapacity);
  EXPECT_EQ(r.stats().dropped_triangle_capacity, n);
  EXPECT_EQ(r.stats().draws_refused_capacity, 1u);
  // What fit renders; render() names the first refused draw's reason.
  host::CaptureDisplay<Rgb888> display(320 * 8);
  EXPECT_EQ(r.render(display), Status::kMissingStore);
  EXPECT_GT(r.stats().pixels_written, 10000u);
}

// ---- Environment and normal maps on scenes with a known answer ----

// A square facing the camera (normal +z), with uvs and tangents (+x, right-handed).
struct FacingSquare {
  std::vector<Vec3> positions{{fx(-1), fx(-1), Fixed{}},
                              {fx(1), fx(-1), Fixed{}},
                              {fx(1), fx(1), Fixed{}},
                              {fx(-1), fx(1), Fixed{}}};
  std::vector<Normal16> normals = std::vector<Normal16>(4, n16(0, 0, 1));
  std::vector<TexCoord> uvs{{0, 0}, {1 << 20, 0}, {1 << 20, 1 << 20}, {0, 1 << 20}};
  std::vector<Tangent16> tangents = std::vector<Tangent16>(4, Tangent16{16384, 0, 0, 16384});
  std::vector<std::array<uint16_t, 3>> triangles{{0, 1, 2}, {0, 2, 3}};
  Mesh mesh() const { return {positions, normals, {}, uvs, triangles, tangents}; }
};

// A w x h RGB888 texture of one colour, with an optional different centre texel.
struct SolidTexture {
  std::vector<uint8_t> bytes;
  Texture tex;
  SolidTexture(uint16_t w, uint16_t h, Rgb8 c, Rgb8 centre) : bytes(size_t{w} * h * 3) {
    for (size_t i = 0; i < size_t{w} * h; ++i) {
      bytes[3 * i] = c.r;
      bytes[3 * i + 1] = c.g;
      bytes[3 * i + 2] = c.b;
    }
    size_t m = (size_t{h} / 2) * w + w / 2;
    bytes[3 * m] = centre.r;
    bytes[3 * m + 1] = centre.g;
    bytes[3 * m + 2] = centre.b;
    tex.format = TexelFormat::kRgb888;
    tex.level_count = 1;
    tex.levels[0].bytes = bytes;
    tex.levels[0].width = w;
    tex.levels[0].height = h;
  }
};

host::ImageRgb8 render_square(const DrawState& st, const Material& m, const LightSet& lights) {
  FacingSquare sq;
  test::CoreHarness<8, Rgb888> h(320, 240);
  EXPECT_EQ(h.begin({0, 0, 0}, front_camera(), lights), Status::kOk);
  EXPECT_EQ(h.renderer().draw(sq.mesh(), Mat4::identity(), m, st), Status::kOk);
  return h.render();
}

TEST(NormalMap, AFlatNormalMapChangesNothing) {
  // (128, 128, 255) decodes to (0.004, 0.004, 1), a tilt of 0.3 degrees: diffuse lighting
  // stays within a level of plain Phong (a sharp highlight would move by that angle).
  SolidTexture flat(8, 8, {128, 128, 255}, {128, 128, 255});
  LightSet lights = one_light(Light::directional({fx(0.3), fx(0.4), Fixed::from_int(1)}, kWhite));
  DrawState plain;
  plain.shading = Shading::kPhong;
  DrawState mapped = plain;
  mapped.normal_map = &flat.tex;
  Material m = shiny();
  m.specular = {};
  host::ImageRgb8 a = render_square(plain, m, lights), b = render_square(mapped, m, lights);
  int worst = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) worst = std::max(worst, std::abs(a.rgb[i] - b.rgb[i]));
  EXPECT_LE(worst, 1);
}

TEST(NormalMap, ATiltedNormalMapTurnsTheSurfaceTowardsTheLight) {
  // The map's normal (0.6, 0, 0.8) in tangent space is (0.6, 0, 0.8) in world space here (T = +x,
  // B = +y, N = +z); with the light along it the square is lit fully (diffuse 1).
  SolidTexture tilted(4, 4, {204, 128, 229}, {204, 128, 229});
  LightSet lights = one_light(Light::directional({fx(0.6), Fixed{}, fx(0.8)}, kWhite));
  Material m;
  m.ambient = {};
  m.diffuse = c15(0.8, 0.8, 0.8);
  m.specular = {};
  DrawState st;
  st.shading = Shading::kPhong;
  st.normal_map = &tilted.tex;
  host::ImageRgb8 img = render_square(st, m, lights);
  EXPECT_NEAR(pixel(img, 160, 120).r, 204, 2);  // 0.8 * N.L with N.L ~ 1
  st.normal_map = nullptr;
  img = render_square(st, m, lights);
  EXPECT_NEAR(pixel(img, 160, 120).r, 163, 1);  // 0.8 * 0.8
}

TEST(EnvMap, AViewerFacingSurfaceReflectsTheMapCentre) {
  // Infinite viewer, normal = view direction: r = v for every pixel, so (s, t) = (1/2, 1/2): the
  // centre texel of a 3x3 map, exactly (bilinear at a texel centre).
  SolidTexture env(3, 3, {0, 0, 255}, {255, 128, 0});
  LightSet lights = one_light(Light::directional({Fixed{}, Fixed{}, Fixed::from_int(1)}, kWhite));
  Material m;
  m.ambient = {};
  m.diffuse = c15(0.8, 0.8, 0.8);
  m.specular = {};
  DrawState st;
  st.shading = Shading::kPhong;
  st.envmap = &env.tex;
  for (auto method : {PixelLighting::kExact, PixelLighting::kTable}) {
    st.pixel_lighting = method;
    host::ImageRgb8 img = render_square(st, m, lights);
    for (int x : {100, 160, 220}) {
      Rgb8 p = pixel(img, x, 120);
      EXPECT_NEAR(p.r, 204, 1) << x;  // 255 x 0.8
      EXPECT_NEAR(p.g, 102, 1) << x;  // 128 x 0.8
      EXPECT_EQ(p.b, 0) << x;
    }
  }
}

}  // namespace
}  // namespace lr
