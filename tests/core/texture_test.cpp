// Textured rendering against exact expectations and against the double reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "lineraster/core/span/tex_exact_span.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "tests/support/core_harness.hpp"
#include "tests/support/scene_compare.hpp"
#include "tests/support/scenes.hpp"

namespace lr {
namespace {

constexpr int32_t S = kSubpixel;

using test::pattern;

host::HostTexture make_texture(const host::ImageRgb8& img, TexelFormat f, bool mips) {
  host::HostTexture t;
  std::string err;
  EXPECT_TRUE(host::texture_from_image(img, f, mips, t, err)) << err;
  return t;
}

// Screen-space vertices and their texture entries (draw_screen's two arrays).
struct ScreenQuads {
  std::vector<ScreenVertex> sv;
  std::vector<TexVertex> tv;
  size_t size() const { return sv.size(); }
  ScreenVertex& operator[](size_t i) { return sv[i]; }
};

// A screen-space rectangle [x0, x1) x [y0, y1) (pixels) with texture coordinates u0..u1
// (left to right) and v1..v0 (top to bottom: v grows upwards as in GL).
void screen_quad(ScreenQuads& v, std::vector<std::array<uint16_t, 3>>& t, int x0, int y0, int x1,
                 int y1, double u0, double u1, double v0, double v1) {
  auto base = static_cast<uint16_t>(v.size());
  const int xs[4] = {x0, x0, x1, x1}, ys[4] = {y0, y1, y1, y0};
  const double us[4] = {u0, u0, u1, u1}, vs[4] = {v1, v0, v0, v1};
  for (int k = 0; k < 4; ++k) {
    ScreenVertex sv;
    sv.x = xs[k] * S;
    sv.y = ys[k] * S;
    sv.z = kDepthMax / 2;
    TexVertex tv;
    tv.u = static_cast<int32_t>(std::lround(us[k] * (1 << 20)));
    tv.v = static_cast<int32_t>(std::lround(vs[k] * (1 << 20)));
    sv.color = {Color15::kOne, Color15::kOne, Color15::kOne};
    v.sv.push_back(sv);
    v.tv.push_back(tv);
  }
  t.push_back({base, uint16_t(base + 1), uint16_t(base + 2)});
  t.push_back({base, uint16_t(base + 2), uint16_t(base + 3)});
}

Rgb8 pixel(const host::ImageRgb8& img, int x, int y) {
  size_t p = 3 * (size_t(y) * size_t(img.width) + size_t(x));
  return {img.rgb[p], img.rgb[p + 1], img.rgb[p + 2]};
}

template <SpanSet kSet = kAllSpans>
host::ImageRgb8 render_screen(const ScreenQuads& v, const std::vector<std::array<uint16_t, 3>>& t,
                              const Texture& tex, Sampler smp, Perspective persp, int w, int h) {
  test::CoreHarness<8, Rgb888, kSet> core(w, h);
  core.begin();
  DrawState st;
  st.shading = Shading::kGouraud;
  st.lighting = false;
  st.depth_test = true;
  st.texture = &tex;
  st.sampler = smp;
  st.perspective = persp;
  EXPECT_EQ(core.renderer().draw_screen(v.sv, t, st, v.tv), Status::kOk);
  return core.render();
}

const Perspective kAllModes[] = {Perspective::kExact, Perspective::kSpan8, Perspective::kSpan16,
                                 Perspective::kSpan32, Perspective::kAffine};
const TexelFormat kAllFormats[] = {TexelFormat::kRgb565, TexelFormat::kRgb888, TexelFormat::kL8,
                                   TexelFormat::kPalette8};

TEST(TextureNearest, AxisAlignedQuadHitsTheExpectedTexelOnEveryPixel) {
  const host::ImageRgb8 img = pattern(4, 4);
  for (TexelFormat f : kAllFormats) {
    host::HostTexture tex = make_texture(img, f, false);
    for (Perspective p : kAllModes) {
      ScreenQuads v;
      std::vector<std::array<uint16_t, 3>> t;
      screen_quad(v, t, 8, 4, 72, 68, 0, 1, 0, 1);
      Sampler smp;
      smp.filter = Filter::kNearest;
      smp.env = TexEnv::kReplace;
      host::ImageRgb8 out = render_screen(v, t, tex.texture, smp, p, 80, 72);
      int bad = 0;
      for (int y = 4; y < 68; ++y)
        for (int x = 8; x < 72; ++x) {
          const int col = (x - 8) / 16;
          const int storage_row = 3 - (y - 4) / 16;  // v = 1 at the top: the image's top row
          const Rgb8 want = host::texel_rgb8(tex.texture, 0, col, storage_row);
          bad += !(pixel(out, x, y) == want);
        }
      EXPECT_EQ(bad, 0) << host::texel_format_name(f) << " mode " << int(p);
      EXPECT_EQ(pixel(out, 7, 10), (Rgb8{0, 0, 0}));  // outside the quad
    }
  }
}

TEST(TextureNearest, ImageTopRowShowsAtTheTopOfTheQuad) {
  host::ImageRgb8 img;
  img.width = 1;
  img.height = 2;
  img.rgb = {255, 0, 0, 0, 0, 255};  // top red, bottom blue
  host::HostTexture tex = make_texture(img, TexelFormat::kRgb888, false);
  ScreenQuads v;
  std::vector<std::array<uint16_t, 3>> t;
  screen_quad(v, t, 0, 0, 8, 8, 0, 1, 0, 1);
  Sampler smp;
  smp.filter = Filter::kNearest;
  smp.env = TexEnv::kReplace;
  host::ImageRgb8 out = render_screen(v, t, tex.texture, smp, Perspective::kExact, 8, 8);
  EXPECT_EQ(pixel(out, 3, 1), (Rgb8{255, 0, 0}));
  EXPECT_EQ(pixel(out, 3, 6), (Rgb8{0, 0, 255}));
}

TEST(TextureWrap, RepeatAndClampAreExactForCoordinatesNearPlusMinusAThousand) {
  // 200 pixels spanning u from -1000 to 997.3: every pixel whose u * W is not within 1/100
  // texel of a texel boundary (where rounding may pick either neighbour) must show texel
  // floor(u * W), wrapped or clamped.
  const double u0 = -1000, u1 = 997.3;
  for (int w : {3, 4, 5}) {  // non-powers of two too
    const host::ImageRgb8 img = pattern(w, 3);
    host::HostTexture tex = make_texture(img, TexelFormat::kRgb888, false);
    for (Wrap wrap : {Wrap::kRepeat, Wrap::kClampToEdge}) {
      ScreenQuads v;
      std::vector<std::array<uint16_t, 3>> t;
      screen_quad(v, t, 0, 0, 200, 4, u0, u1, 0.5, 0.5 + 1e-6);
      Sampler smp;
      smp.filter = Filter::kNearest;
      smp.wrap_s = wrap;
      smp.env = TexEnv::kReplace;
      for (Perspective p : {Perspective::kExact, Perspective::kSpan16, Perspective::kAffine}) {
        host::ImageRgb8 out = render_screen(v, t, tex.texture, smp, p, 200, 4);
        int bad = 0, checked = 0;
        for (int x = 0; x < 200; ++x) {
          const double su = (u0 + (u1 - u0) * (x + 0.5) / 200) * w;
          const double frac = su - std::floor(su);
          if (frac < 0.01 || frac > 0.99) continue;
          long i = static_cast<long>(std::floor(su));
          i = wrap == Wrap::kRepeat ? ((i % w) + w) % w : std::clamp<long>(i, 0, w - 1);
          ++checked;
          bad += !(pixel(out, x, 2) == host::texel_rgb8(tex.texture, 0, int(i), 1));
        }
        EXPECT_GT(checked, 180);
        EXPECT_EQ(bad, 0) << "w=" << w << " wrap=" << int(wrap) << " mode=" << int(p);
        if (bad) {
          for (int x = 0; x < 200; ++x) {
            const double su = (u0 + (u1 - u0) * (x + 0.5) / 200) * w;
            long i = static_cast<long>(std::floor(su));
            i = wrap == Wrap::kRepeat ? ((i % w) + w) % w : std::clamp<long>(i, 0, w - 1);
            if (!(pixel(out, x, 2) == host::texel_rgb8(tex.texture, 0, int(i), 1)))
              std::printf("x=%d su=%.4f want %ld got r=%d\n", x, su, i, pixel(out, x, 2).r);
          }
        }
      }
    }
  }
}

// The rows test::ground_view() shows of the plane: its far edge (200 units away, 1 below the
// eye) is 2.8 degrees above the view axis, row 120 - 120 tan(2.8) / tan(30) = 110 of 240, and
// every row below it is covered edge to edge (the plane is wider than the view out to there).
constexpr int kGroundTopRow = 110;
constexpr size_t kGroundPixels = size_t(240 - kGroundTopRow - 1) * 320;  // a row of slack

test::Comparison compare_ground(const host::HostTexture& tex, Filter f, Perspective p, MipMode mip,
                                bool lit = false) {
  host::HostMesh mesh = test::ground_plane(200, 200);
  host::SceneOptions o = test::ground_view();
  o.unlit = !lit;
  o.texture_object = &tex.texture;
  o.filter = f;
  o.perspective = p;
  o.mipmap = mip;
  test::Comparison c;
  std::string err;
  EXPECT_TRUE(test::compare_scene(mesh, o, c, err)) << err;
  EXPECT_GE(c.both, kGroundPixels) << c.summary();
  return c;
}

// The exact (u, v) a pixel centre sees on the ground plane y = 0 (ray cast in double), for the
// test::ground_plane() mapping: u = (x + half) / (2 half) * repeats, v = (half - z) / (2 half) *
// repeats.
bool ground_uv(const host::SceneOptions& o, double half, double repeats, int px, int py, double& u,
               double& v) {
  auto sub = [](host::Vec3d a, host::Vec3d b) {
    return host::Vec3d{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  };
  auto norm = [](host::Vec3d a) {
    double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return host::Vec3d{a[0] / l, a[1] / l, a[2] / l};
  };
  auto cross = [](host::Vec3d a, host::Vec3d b) {
    return host::Vec3d{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                       a[0] * b[1] - a[1] * b[0]};
  };
  const host::Vec3d f = norm(sub(o.target, o.eye)), s = norm(cross(f, o.up)), up = cross(s, f);
  const double th = std::tan(o.fovy * 3.14159265358979323846 / 360.0),
               aspect = double(o.width) / o.height;
  const double xn = (px + 0.5) / (o.width / 2.0) - 1, yn = 1 - (py + 0.5) / (o.height / 2.0);
  host::Vec3d d;
  for (int i = 0; i < 3; ++i)
    d[size_t(i)] = s[size_t(i)] * xn * th * aspect + up[size_t(i)] * yn * th + f[size_t(i)];
  if (d[1] >= 0) return false;
  const double t = -o.eye[1] / d[1];
  const double x = o.eye[0] + t * d[0], z = o.eye[2] + t * d[2];
  u = (x + half) / (2 * half) * repeats;
  v = (half - z) / (2 * half) * repeats;
  return true;
}

TEST(TextureGroundPlane, NearestLandsOnTheExactTexelInExactAndSpanModes) {
  // Every pixel where a texel covers at least half a pixel (level of detail < 1), away from
  // texel boundaries by more than the coordinate precision (1/256 texel; 1/64 here to cover
  // the camera's rounding to Q16.16), must show the texel the exact ray hits.
  const host::ImageRgb8 img = pattern(16, 16);
  host::HostTexture tex = make_texture(img, TexelFormat::kRgb888, false);
  const double half = 200, repeats = 200;
  for (Perspective p :
       {Perspective::kExact, Perspective::kSpan8, Perspective::kSpan16, Perspective::kSpan32}) {
    test::Comparison c = compare_ground(tex, Filter::kNearest, p, MipMode::kNone);
    const host::SceneOptions o = test::ground_view();
    size_t checked = 0, wrong = 0;
    for (int y = 0; y < o.height; ++y)
      for (int x = 0; x < o.width; ++x) {
        const size_t pi = size_t(y) * size_t(o.width) + size_t(x);
        if (c.reference.owner[pi] < 0 || !(c.reference.lod[pi] < 1.0)) continue;
        double u, v;
        if (!ground_uv(o, half, repeats, x, y, u, v)) continue;
        const double su = u * 16, tv = v * 16;
        const double fu = su - std::floor(su), fv = tv - std::floor(tv);
        const double tie = p == Perspective::kExact ? 1.0 / 64 : 1.0 / 16;
        if (fu < tie || fu > 1 - tie || fv < tie || fv > 1 - tie) continue;
        const int col = int(((long(std::floor(su)) % 16) + 16) % 16);
        const int row = int(((long(std::floor(tv)) % 16) + 16) % 16);
        ++checked;
        wrong += !(pixel(c.core.image, x, y) == host::texel_rgb8(tex.texture, 0, col, row));
      }
    std::printf("ground nearest mode %d: %s; exact texel on %zu of %zu checked pixels\n", int(p),
                c.summary().c_str(), checked - wrong, checked);
    EXPECT_EQ(c.coverage_diff, 0u);
    EXPECT_GT(checked, 20000u);
    EXPECT_EQ(wrong, 0u) << "mode " << int(p);
  }
}

// PSNR against the reference over the pixels whose level of detail is below max_lod.
double psnr_where(const test::Comparison& c, double max_lod) {
  double sq = 0;
  size_t n = 0;
  for (size_t p = 0; p < c.reference.owner.size(); ++p) {
    if (c.reference.owner[p] < 0 || !(c.reference.lod[p] < max_lod)) continue;
    for (size_t k = 0; k < 3; ++k) {
      double e = double(c.core.image.rgb[3 * p + k]) - double(c.reference.rgb8[3 * p + k]);
      sq += e * e;
    }
    n += 3;
  }
  return n && sq > 0 ? 10 * std::log10(255.0 * 255.0 * double(n) / sq) : 99.0;
}

TEST(TextureGroundPlane, AffineBendsVisibly) {
  host::HostTexture tex = make_texture(pattern(16, 16), TexelFormat::kRgb888, false);
  test::Comparison c = compare_ground(tex, Filter::kNearest, Perspective::kAffine, MipMode::kNone);
  std::printf("ground nearest affine: %s\n", c.summary().c_str());
  EXPECT_LT(c.fraction_within1(), 0.5);
}

TEST(TextureGroundPlane, BilinearAndMipmapsAgainstTheReference) {
  for (TexelFormat f : {TexelFormat::kRgb888, TexelFormat::kRgb565}) {
    host::HostTexture tex = make_texture(pattern(64, 64), f, true);
    for (MipMode mip : {MipMode::kNone, MipMode::kNearest, MipMode::kLinear}) {
      test::Comparison c = compare_ground(tex, Filter::kBilinear, Perspective::kExact, mip);
      const double mag = psnr_where(c, 0.0);
      std::printf("ground bilinear %s mip %d: %s; PSNR where magnified %.2f dB\n",
                  host::texel_format_name(f), int(mip), c.summary().c_str(), mag);
      EXPECT_EQ(c.coverage_diff, 0u);
      // Magnified, every mode samples level 0 bilinearly: 8-bit weights (RGB888) or 5-bit
      // packed weights (RGB565, quantised to 5/6-bit channels).
      EXPECT_GE(mag, f == TexelFormat::kRgb888 ? 44.0 : 34.0);
      // Minified: without mipmaps both alias (no bound); with them the level of detail is
      // taken per 8-pixel chunk (at its centre) against per pixel in the reference.
      if (mip != MipMode::kNone) {
        EXPECT_GE(c.psnr, 30.0);
      }
    }
  }
}

TEST(TextureGroundPlane, MipmapsStopTheHorizonAliasing) {
  // Distant rows: without mipmaps neighbouring pixels jump between unrelated texels (high
  // variance), with them they average out towards the texture's mean.
  host::HostTexture tex = make_texture(pattern(64, 64), TexelFormat::kRgb888, true);
  test::Comparison none =
      compare_ground(tex, Filter::kBilinear, Perspective::kExact, MipMode::kNone);
  test::Comparison lin =
      compare_ground(tex, Filter::kBilinear, Perspective::kExact, MipMode::kLinear);
  const int w = none.core.image.width, h = none.core.image.height;
  ASSERT_EQ(none.core.depth.size(), size_t(w) * size_t(h));
  ASSERT_EQ(lin.core.depth.size(), size_t(w) * size_t(h));
  // The horizon band: the first rows the plane covers, where the scene puts them, and covered
  // edge to edge in both frames (the roughness is measured on the plane only).
  constexpr int kBand = 12;
  int top = 0;
  while (top < h && none.core.depth[size_t(top) * size_t(w) + size_t(w / 2)] == 0xFFFF) ++top;
  ASSERT_NEAR(top, kGroundTopRow, 1) << "the plane's far edge is not where the scene puts it";
  ASSERT_LE(top + kBand, h);
  for (const test::Comparison* c : {&none, &lin})
    for (int y = top; y < top + kBand; ++y)
      for (int x = 0; x < w; ++x)
        ASSERT_NE(c->core.depth[size_t(y) * size_t(w) + size_t(x)], 0xFFFF)
            << "horizon band not covered at (" << x << ", " << y << ")";
  auto roughness = [](const host::ImageRgb8& img, int y0, int y1) {
    double sum = 0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = 1; x < img.width; ++x) {
        sum += std::abs(int(pixel(img, x, y).r) - int(pixel(img, x - 1, y).r));
        ++n;
      }
    return sum / n;
  };
  const double r_none = roughness(none.core.image, top, top + kBand);
  const double r_lin = roughness(lin.core.image, top, top + kBand);
  std::printf("horizon roughness: no mipmaps %.2f, trilinear %.2f\n", r_none, r_lin);
  EXPECT_GT(r_none, 4 * r_lin);
}

TEST(TextureMipmaps, LevelChoiceFollowsTheReference) {
  // Levels of distinct flat colours: the colour tells which level was sampled.
  host::ImageRgb8 img = pattern(64, 64);
  host::HostTexture tex = make_texture(img, TexelFormat::kRgb888, true);
  const uint8_t colours[7][3] = {{255, 0, 0},   {0, 255, 0},   {0, 0, 255},    {255, 255, 0},
                                 {0, 255, 255}, {255, 0, 255}, {255, 255, 255}};
  for (int l = 0; l < tex.texture.level_count; ++l) {
    const TextureLevel& lv = tex.texture.levels[size_t(l)];
    size_t offset = size_t(lv.bytes.data() - tex.bytes.data());
    for (size_t k = 0; k < size_t(lv.width) * lv.height; ++k)
      for (int c = 0; c < 3; ++c) tex.bytes[offset + 3 * k + size_t(c)] = colours[l][c];
  }
  test::Comparison c =
      compare_ground(tex, Filter::kNearest, Perspective::kExact, MipMode::kNearest);
  std::printf("mip level choice: %s\n", c.summary().c_str());
  // Same level on almost every pixel: the core decides per 8-pixel chunk.
  EXPECT_GE(c.fraction_within1(), 0.97);
  // And several levels are in use.
  std::set<uint32_t> seen;
  for (size_t p = 0; p < c.core.image.rgb.size() / 3; ++p)
    seen.insert(uint32_t(c.core.image.rgb[3 * p]) << 16 |
                uint32_t(c.core.image.rgb[3 * p + 1]) << 8 | c.core.image.rgb[3 * p + 2]);
  EXPECT_GE(seen.size(), 5u);
}

TEST(TextureLighting, ModulateWithSeparateSpecularMatchesTheReference) {
  host::HostTexture tex = make_texture(pattern(8, 8), TexelFormat::kRgb888, false);
  host::HostMesh mesh = test::ground_plane(4, 2);
  host::SceneOptions o;
  o.eye = {0, 3, 3};
  o.target = {0, 0, 0};
  o.light_dirs = {{0.2, 1, 0.4}};
  o.material.specular = {0.9, 0.9, 0.9};
  o.material.shininess = 20;
  o.texture_object = &tex.texture;
  o.filter = Filter::kNearest;
  for (Shading sh : {Shading::kGouraud, Shading::kFlat}) {
    o.shading = sh;
    test::Comparison c;
    std::string err;
    ASSERT_TRUE(test::compare_scene(mesh, o, c, err)) << err;
    std::printf("modulate + specular (%s): %s\n", sh == Shading::kFlat ? "flat" : "gouraud",
                c.summary().c_str());
    // The 8 x 8 plane seen from 45 degrees above, 4.2 units away, fills most of the frame.
    EXPECT_GT(c.both, size_t(o.width) * size_t(o.height) * 3 / 4);
    // Nearest sampling: a pixel centre within rounding of a texel boundary may take the
    // neighbouring texel (rare); everywhere else the lighting arithmetic is within a level.
    EXPECT_GE(c.fraction_within1(), 0.999);
    EXPECT_LT(c.mean_error, sh == Shading::kFlat ? 1.0 : 0.05);
  }
}

}  // namespace
}  // namespace lr

namespace lr {
namespace {

TEST(TextureGroundPlane, SpanModesWithBilinearStayCloseToExact) {
  host::HostTexture tex = make_texture(pattern(64, 64), TexelFormat::kRgb888, true);
  test::Comparison exact =
      compare_ground(tex, Filter::kBilinear, Perspective::kExact, MipMode::kLinear);
  for (Perspective p : {Perspective::kSpan8, Perspective::kSpan16, Perspective::kSpan32}) {
    test::Comparison c = compare_ground(tex, Filter::kBilinear, p, MipMode::kLinear);
    const double mag = psnr_where(c, 0.0);
    std::printf(
        "ground bilinear trilinear mode %d: %s; PSNR where magnified %.2f dB (exact: %.2f)\n",
        int(p), c.summary().c_str(), mag, psnr_where(exact, 0.0));
    // Linear inside chunks of 8..32 pixels: the error grows with the chunk; where magnified it
    // stays within a few levels of the exact mode's (the figures are printed above).
    EXPECT_GE(mag, 50.0);
    EXPECT_GE(c.psnr, 45.0);
  }
}

TEST(TextureMipmaps, NonPowerOfTwoChainAgainstTheReference) {
  // 48 x 40 -> 24 x 20 -> 12 x 10 -> 6 x 5 -> 3 x 2 -> 1 x 1: level coordinates by ratio.
  host::HostTexture tex = make_texture(pattern(48, 40), TexelFormat::kRgb888, true);
  ASSERT_EQ(tex.texture.level_count, 6);
  EXPECT_EQ(tex.texture.levels[4].width, 3);
  EXPECT_EQ(tex.texture.levels[4].height, 2);
  test::Comparison c =
      compare_ground(tex, Filter::kBilinear, Perspective::kExact, MipMode::kLinear);
  std::printf("NPOT 48x40 trilinear: %s; PSNR where magnified %.2f dB\n", c.summary().c_str(),
              psnr_where(c, 0.0));
  // Level coordinates scale by a Q16 ratio (under 1/32 texel of error) where a power of two
  // would shift exactly, so the bound is below the power-of-two chain's.
  EXPECT_GE(psnr_where(c, 0.0), 38.0);
  EXPECT_GE(c.psnr, 38.0);
}

// Replaced RGB565 texels are stored as they are only where the display format packs them so
// (RGB565, byte-swapped or not); an RGB888 strip goes through encode().
static_assert(detail::stores_565<Rgb565Be>());
static_assert(!detail::stores_565<Rgb888>());

// The exact-perspective routine of RGB565 textures (tex_exact_span.hpp: one division per pixel
// in chunks) against the general routine's precise reciprocal (the same image as RGB888): a quad
// whose w grows 12-fold from left to right, so that chunks are foreshortened and texture
// coordinates reach -3 and 5 periods (repeat) or the clamped edges.
// The exact-perspective tests' quad: nearly the whole 320x200 frame, its right edge 12 times
// farther than its left (w), texture coordinates over several repeats.
void receding_quad(ScreenQuads& v, std::vector<std::array<uint16_t, 3>>& t) {
  const uint32_t ws[4] = {1u << 16, 1u << 16, 12u << 16, 12u << 16};
  screen_quad(v, t, 2, 3, 318, 197, -3.0, 5.0, -2.0, 4.0);
  for (size_t k = 0; k < 4; ++k) v[k].w = ws[k];
}

TEST(TextureExactPerspective, Rgb565ChunksPickTheTexelsOfThePreciseReciprocal) {
  host::ImageRgb8 img = pattern(64, 64);
  for (uint8_t& c : img.rgb) c = static_cast<uint8_t>((c & 0xF8u) | (c >> 5));  // 5-bit exact
  for (size_t i = 1; i < img.rgb.size(); i += 3)  // green: 6-bit exact
    img.rgb[i] = static_cast<uint8_t>((img.rgb[i] & 0xFCu) | (img.rgb[i] >> 6));
  host::HostTexture t565 = make_texture(img, TexelFormat::kRgb565, false);
  host::HostTexture t888 = make_texture(img, TexelFormat::kRgb888, false);
  for (Wrap wrap : {Wrap::kRepeat, Wrap::kClampToEdge}) {
    ScreenQuads v;
    std::vector<std::array<uint16_t, 3>> t;
    receding_quad(v, t);
    Sampler smp;
    smp.filter = Filter::kNearest;
    smp.env = TexEnv::kReplace;
    smp.wrap_s = smp.wrap_t = wrap;
    const host::ImageRgb8 fast =
        render_screen(v, t, t565.texture, smp, Perspective::kExact, 320, 200);
    const host::ImageRgb8 precise =
        render_screen(v, t, t888.texture, smp, Perspective::kExact, 320, 200);
    int covered = 0, same = 0;
    for (int y = 3; y < 197; ++y)
      for (int x = 2; x < 318; ++x) {
        ++covered;
        same += pixel(fast, x, y) == pixel(precise, x, y);
      }
    EXPECT_EQ(covered, 316 * 194);
    // 24-bit divisors leave an error of about 2^-16 texel (docs/numerics.md): no pixel of this
    // quad lies that close to a texel boundary. 16-bit divisors changed 3 of them.
    EXPECT_EQ(same, covered) << "wrap " << int(wrap);
    std::printf("exact perspective rgb565 vs precise, wrap %d: %d of %d pixels equal\n", int(wrap),
                same, covered);
  }
}

// Without the inlined fetch (SpanSet::inline_fetch off) the same spans take the shared span
// body: its coordinates come from the per-pixel division of exact_attrs, the inlined routine's
// from its chunk remainder planes (docs/numerics.md). Nearest picks the same texel on every pixel;
// bilinear's Q.8 coordinates may differ by one unit, which moves a 5-bit weight by at most one
// step on each axis: at most 2/32 of the largest step between neighbouring texels (here 255).
TEST(TextureExactPerspective, Rgb565WithoutTheInlinedFetchIsTheSameTexelOrOneWeightStep) {
  host::ImageRgb8 img = pattern(64, 64);
  host::HostTexture t565 = make_texture(img, TexelFormat::kRgb565, false);
  constexpr SpanSet kShared = kAllSpans.only_inline_fetch(false);
  for (Filter filter : {Filter::kNearest, Filter::kBilinear})
    for (TexEnv env : {TexEnv::kReplace, TexEnv::kModulate})
      for (Wrap wrap : {Wrap::kRepeat, Wrap::kClampToEdge}) {
        ScreenQuads v;
        std::vector<std::array<uint16_t, 3>> t;
        receding_quad(v, t);
        Sampler smp;
        smp.filter = filter;
        smp.env = env;
        smp.wrap_s = smp.wrap_t = wrap;
        const host::ImageRgb8 inlined =
            render_screen(v, t, t565.texture, smp, Perspective::kExact, 320, 200);
        const host::ImageRgb8 shared =
            render_screen<kShared>(v, t, t565.texture, smp, Perspective::kExact, 320, 200);
        int differ = 0, max = 0;
        for (int y = 3; y < 197; ++y)
          for (int x = 2; x < 318; ++x) {
            const Rgb8 a = pixel(inlined, x, y), b = pixel(shared, x, y);
            differ += a == b ? 0 : 1;
            for (int d : {a.r - b.r, a.g - b.g, a.b - b.b}) max = std::max(max, std::abs(d));
          }
        std::printf(
            "shared fetch vs inlined, filter %d env %d wrap %d: %d of %d pixels differ, "
            "max %d\n",
            int(filter), int(env), int(wrap), differ, 316 * 194, max);
        if (filter == Filter::kNearest) {
          EXPECT_EQ(differ, 0) << "env " << int(env) << " wrap " << int(wrap);
        } else {
          EXPECT_LE(max, 2 * 255 / 32 + 1) << "env " << int(env) << " wrap " << int(wrap);
        }
      }
}

}  // namespace
}  // namespace lr
