// The renderer's calls out of order, and the draws it refuses: each returns the status that
// names the misuse, counts what docs/api-errors.md says, leaves the state it gives, and a
// refused render() never reaches the sink. One test per row of that table (named there).
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "lineraster/core/raster/frame_storage.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "tests/support/recording_sink.hpp"

namespace lr {
namespace {

constexpr int kW = 64, kH = 32, kK = 8;
using PF = Rgb888;
constexpr Rgb8 kBackground{10, 20, 30};
constexpr Rgb8 kRed{250, 0, 0}, kGreen{0, 250, 0};

static_assert(std::has_unique_object_representations_v<FrameStats>);
bool same(const FrameStats& a, const FrameStats& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Every store, each large enough for these tests' frames.
constexpr FrameCapacities kCaps{.width = kW,
                                .height = kH,
                                .strip_height = kK,
                                .vertices = 64,
                                .triangles = 64,
                                .draws = 4,
                                .active = 16,
                                .surfaces = 64,
                                .lighting_table_words = 2 * lighting_table_words(16, true),
                                .pixel_lights = 2,
                                .tex_vertices = 64,
                                .active_extra = 16,
                                .triangle_colors = 64};

// A square of `size` pixels at (x, y) in screen space, two triangles, in one colour.
struct Square {
  std::array<ScreenVertex, 4> v{};
  std::array<std::array<uint16_t, 3>, 2> t{{{0, 1, 2}, {2, 1, 3}}};
  std::array<TexVertex, 4> tex{};
};
Square square(int x, int y, int size, Rgb8 c) {
  Square s;
  for (size_t k = 0; k < 4; ++k) {
    s.v[k].x = (x + (k & 1 ? size : 0)) * kSubpixel;
    s.v[k].y = (y + (k & 2 ? size : 0)) * kSubpixel;
    s.v[k].z = kDepthMax / 2;
    s.v[k].color = from_rgb8(c);
  }
  return s;
}

// Unlit, one colour per vertex: a draw that needs no optional store.
DrawState plain() {
  DrawState s;
  s.lighting = false;
  s.depth_test = false;
  return s;
}
DrawState flat() {
  DrawState s = plain();
  s.shading = Shading::kFlat;
  return s;
}
DrawState phong(PixelLighting how = PixelLighting::kExact) {
  DrawState s;
  s.shading = Shading::kPhong;
  s.pixel_lighting = how;
  s.table.size = 16;
  return s;
}

// A 1 x 1 texture (green).
const Texture& green_texture() {
  static host::HostTexture tex;  // filled in place: its Texture points into its own arrays
  static const bool loaded = [] {
    host::ImageRgb8 img;
    img.width = img.height = 1;
    img.rgb = {kGreen.r, kGreen.g, kGreen.b};
    std::string err;
    const bool ok = host::texture_from_image(img, TexelFormat::kRgb888, false, tex, err);
    EXPECT_TRUE(ok) << err;
    return ok;
  }();
  (void)loaded;
  return tex.texture;
}
DrawState textured() {
  DrawState s = plain();
  s.texture = &green_texture();
  s.sampler.filter = Filter::kNearest;
  s.sampler.env = TexEnv::kReplace;
  return s;
}

// One triangle facing the camera at the viewport's centre (the default Camera: identity view and
// projection, so positions are normalised device coordinates), with normals and uvs.
struct Tri {
  std::array<Vec3, 3> p{{{Fixed::from_double(-0.5), Fixed::from_double(-0.5), Fixed{}},
                         {Fixed::from_double(0.5), Fixed::from_double(-0.5), Fixed{}},
                         {Fixed{}, Fixed::from_double(0.5), Fixed{}}}};
  std::array<Normal16, 3> n{{{0, 0, 16384}, {0, 0, 16384}, {0, 0, 16384}}};
  std::array<TexCoord, 3> uv{};
  std::array<std::array<uint16_t, 3>, 1> t{{{0, 1, 2}}};
  Mesh mesh() const { return Mesh{p, n, {}, uv, t, {}}; }
};

// A renderer, its storage (kCaps, or changed by the test) and a recording sink.
template <SpanSet kSet = kAllSpans>
struct Rig {
  explicit Rig(FrameCapacities caps = kCaps) : store(caps) {}
  BasicFrameStorage<std::vector> store;
  std::unique_ptr<Renderer<PF, kK, kSet>> r = std::make_unique<Renderer<PF, kK, kSet>>();
  test::RecordingSink<PF> sink{size_t{kW} * kK};

  Status configure() { return r->configure(store.storage(), kW, kH); }
  Status begin(const LightSet& lights = {}) {
    return r->begin_frame(Camera{}, lights, kBackground);
  }
  // Configured and begun (the expectations say which step failed).
  bool ready() { return configure() == Status::kOk && begin() == Status::kOk; }
  Status draw_square(const Square& s, const DrawState& st) {
    return r->draw_screen(
        s.v, s.t, st,
        st.texture ? std::span<const TexVertex>(s.tex) : std::span<const TexVertex>());
  }
  Status draw_tri(const DrawState& st, const Material& m = {}) {
    static const Tri tri;
    return r->draw(tri.mesh(), Mat4::identity(), m, st);
  }
  Status render() { return r->render(sink); }
  Rgb8 pixel(int x, int y) const {
    return PF::decode(sink.frame()[static_cast<size_t>(y) * kW + static_cast<size_t>(x)]);
  }
};

// Renders a frame after the misuse: the renderer works as new.
template <SpanSet kSet>
void expect_usable(Rig<kSet>& rig) {
  ASSERT_EQ(rig.begin(), Status::kOk);
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  ASSERT_EQ(rig.render(), Status::kOk);
  EXPECT_EQ(rig.sink.faults(), 0u);
  EXPECT_EQ(rig.pixel(8, 8), kRed);
  EXPECT_EQ(rig.pixel(40, 20), kBackground);
}

// ---- Order ----------------------------------------------------------------------------------

TEST(ApiErrors, BeginFrameBeforeConfigure) {
  Rig rig;
  EXPECT_EQ(rig.begin(), Status::kNotConfigured);
  EXPECT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kNotConfigured);
  EXPECT_TRUE(same(rig.r->stats(), FrameStats{}));
  ASSERT_EQ(rig.configure(), Status::kOk);
  expect_usable(rig);
}

TEST(ApiErrors, DrawBeforeConfigure) {
  Rig rig;
  EXPECT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kNotConfigured);
  EXPECT_EQ(rig.draw_tri(plain()), Status::kNotConfigured);
  EXPECT_TRUE(same(rig.r->stats(), FrameStats{}));  // not even counted as refused
  ASSERT_EQ(rig.configure(), Status::kOk);
  expect_usable(rig);
}

TEST(ApiErrors, RenderBeforeConfigure) {
  Rig rig;
  EXPECT_EQ(rig.render(), Status::kNotConfigured);
  EXPECT_EQ(rig.sink.calls().total(), 0u);
  ASSERT_EQ(rig.configure(), Status::kOk);
  expect_usable(rig);
}

// The call that used to hang: configure() leaves the buckets as the caller gave them (zeros
// here: every strip's list starting at triangle 0, whose next is 0), and only begin_frame()
// makes them lists. render() refuses before walking them.
TEST(ApiErrors, RenderBeforeBeginFrame) {
  Rig rig;
  ASSERT_EQ(rig.configure(), Status::kOk);
  EXPECT_EQ(rig.render(), Status::kNoFrame);
  EXPECT_EQ(rig.sink.calls().total(), 0u);
  EXPECT_EQ(rig.render(), Status::kNoFrame);  // still no frame
  expect_usable(rig);
}

TEST(ApiErrors, DrawBeforeBeginFrame) {
  Rig rig;
  ASSERT_EQ(rig.configure(), Status::kOk);
  EXPECT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kNoFrame);
  EXPECT_EQ(rig.draw_tri(plain()), Status::kNoFrame);
  EXPECT_TRUE(same(rig.r->stats(), FrameStats{}));
  expect_usable(rig);
}

TEST(ApiErrors, RenderTwice) {
  Rig rig;
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  ASSERT_EQ(rig.render(), Status::kOk);
  const FrameStats after_first = rig.r->stats();
  const auto calls = rig.sink.calls().total();
  EXPECT_EQ(rig.render(), Status::kFrameRendered);
  EXPECT_EQ(rig.sink.calls().total(), calls);  // the sink saw nothing of it
  EXPECT_TRUE(same(rig.r->stats(), after_first));
  EXPECT_EQ(rig.pixel(8, 8), kRed);
  expect_usable(rig);
}

TEST(ApiErrors, DrawAfterRender) {
  Rig rig;
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  ASSERT_EQ(rig.render(), Status::kOk);
  const FrameStats rendered = rig.r->stats();
  EXPECT_EQ(rig.draw_square(square(30, 4, 8, kGreen), plain()), Status::kFrameRendered);
  EXPECT_EQ(rig.draw_tri(plain()), Status::kFrameRendered);
  EXPECT_TRUE(same(rig.r->stats(), rendered));  // the rendered frame's statistics stay
  // The next frame holds only its own draws.
  ASSERT_EQ(rig.begin(), Status::kOk);
  ASSERT_EQ(rig.draw_square(square(30, 4, 8, kGreen), plain()), Status::kOk);
  ASSERT_EQ(rig.render(), Status::kOk);
  EXPECT_EQ(rig.pixel(34, 8), kGreen);
  EXPECT_EQ(rig.pixel(8, 8), kBackground);
  EXPECT_EQ(rig.r->stats().triangles_in, 2u);
}

TEST(ApiErrors, BeginFrameWithTooManyLights) {
  Rig rig;
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  LightSet five;
  five.count = kMaxLights + 1;
  EXPECT_EQ(rig.begin(five), Status::kInvalidArgument);
  // No frame is begun: the one begun before is abandoned.
  EXPECT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kNoFrame);
  EXPECT_EQ(rig.render(), Status::kNoFrame);
  EXPECT_EQ(rig.sink.calls().total(), 0u);
  expect_usable(rig);
}

TEST(ApiErrors, BeginFrameAgainStartsOver) {
  Rig rig;
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  ASSERT_EQ(rig.begin(), Status::kOk);
  ASSERT_EQ(rig.draw_square(square(30, 4, 8, kGreen), plain()), Status::kOk);
  ASSERT_EQ(rig.render(), Status::kOk);
  EXPECT_EQ(rig.pixel(8, 8), kBackground);
  EXPECT_EQ(rig.pixel(34, 8), kGreen);
  EXPECT_EQ(rig.r->stats().triangles_in, 2u);
}

TEST(ApiErrors, ConfigureDuringAFrame) {
  Rig rig;
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  ASSERT_EQ(rig.configure(), Status::kOk);
  EXPECT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kNoFrame);
  EXPECT_EQ(rig.render(), Status::kNoFrame);
  EXPECT_EQ(rig.sink.calls().total(), 0u);
  expect_usable(rig);
}

TEST(ApiErrors, RenderAfterASinkError) {
  Rig rig;
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  rig.sink.fail_at(2);  // the first acquire
  EXPECT_EQ(rig.render(), Status::kDisplayError);
  EXPECT_TRUE(rig.sink.failed());
  rig.sink.fail_at(0);
  const auto calls = rig.sink.calls().total();
  EXPECT_EQ(rig.render(), Status::kFrameRendered);  // the frame is over
  EXPECT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kFrameRendered);
  EXPECT_EQ(rig.sink.calls().total(), calls);
  expect_usable(rig);
}

TEST(ApiErrors, InvalidateStripsInAnyState) {
  Rig rig;
  rig.r->invalidate_strips();
  EXPECT_EQ(rig.render(), Status::kNotConfigured);
  ASSERT_EQ(rig.configure(), Status::kOk);
  rig.r->invalidate_strips();
  EXPECT_EQ(rig.render(), Status::kNoFrame);
  ASSERT_EQ(rig.begin(), Status::kOk);
  rig.r->invalidate_strips();
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  ASSERT_EQ(rig.render(), Status::kOk);
  rig.r->invalidate_strips();
  EXPECT_EQ(rig.render(), Status::kFrameRendered);
  expect_usable(rig);
}

// ---- Configuration --------------------------------------------------------------------------

TEST(ApiErrors, ConfigureWithABadViewport) {
  Rig rig;
  ASSERT_TRUE(rig.ready());
  constexpr std::pair<int, int> kBad[] = {
      {0, kH}, {kW, 0}, {-1, kH}, {kMaxViewport + 1, kH}, {kW, kMaxViewport + 1}};
  for (const auto& [w, h] : kBad) {
    SCOPED_TRACE(std::to_string(w) + " x " + std::to_string(h));
    EXPECT_EQ(rig.r->configure(rig.store.storage(), w, h), Status::kInvalidArgument);
    // Not configured any more: the frame begun before is gone.
    EXPECT_EQ(rig.begin(), Status::kNotConfigured);
    EXPECT_EQ(rig.render(), Status::kNotConfigured);
  }
  EXPECT_EQ(rig.sink.calls().total(), 0u);
  ASSERT_EQ(rig.configure(), Status::kOk);
  expect_usable(rig);
}

TEST(ApiErrors, ConfigureWithStoresTooSmall) {
  BasicFrameStorage<std::vector> store(FrameCapacities{.width = kW,
                                                       .height = kH,
                                                       .strip_height = kK,
                                                       .vertices = 16,
                                                       .triangles = 16,
                                                       .draws = 2,
                                                       .active = 4,
                                                       .active_extra = 4,
                                                       .triangle_colors = 16,
                                                       .strip_skipping = true});
  const FrameStorage good = store.storage();
  using Shorten = void (*)(FrameStorage&);
  const std::pair<const char*, Shorten> cases[] = {
      {"buckets: one per strip", [](FrameStorage& s) { s.buckets = s.buckets.first(3); }},
      {"depth: width x K", [](FrameStorage& s) { s.depth = s.depth.first(s.depth.size() - 1); }},
      {"active: none", [](FrameStorage& s) { s.active = {}; }},
      {"active_index: 2 x active",
       [](FrameStorage& s) { s.active_index = s.active_index.first(7); }},
      {"active_extra: as active",
       [](FrameStorage& s) { s.active_extra = s.active_extra.first(3); }},
      {"triangle_colors: as triangles",
       [](FrameStorage& s) { s.triangle_colors = s.triangle_colors.first(15); }},
      {"strip_inputs: 2 x strips",
       [](FrameStorage& s) { s.strip_inputs = s.strip_inputs.first(7); }},
      {"draws: none", [](FrameStorage& s) { s.draws = {}; }},
      {"vertices: none", [](FrameStorage& s) { s.vertices = {}; }},
      {"triangles: none", [](FrameStorage& s) { s.triangles = {}; }},
  };
  auto r = std::make_unique<Renderer<PF, kK>>();
  for (const auto& [what, shorten] : cases) {
    SCOPED_TRACE(what);
    ASSERT_EQ(r->configure(good, kW, kH), Status::kOk);
    FrameStorage s = good;
    shorten(s);
    EXPECT_EQ(r->configure(s, kW, kH), Status::kStoreTooSmall);
    EXPECT_EQ(r->begin_frame({}, {}, kBackground), Status::kNotConfigured);
  }
  // The same stores for a taller viewport: too few buckets.
  EXPECT_EQ(r->configure(good, kW, kH + 1), Status::kStoreTooSmall);
  EXPECT_EQ(r->configure(good, kW, kH), Status::kOk);
}

TEST(ApiErrors, ConfigureWithStoresBeyondTheirIndex) {
  FrameCapacities caps = kCaps;
  caps.draws = 257;  // draw indices are 8-bit
  Rig many_draws(caps);
  EXPECT_EQ(many_draws.configure(), Status::kInvalidArgument);
  EXPECT_EQ(many_draws.begin(), Status::kNotConfigured);
  caps = kCaps;
  caps.active = kMaxStoreEntries + 1;  // active slots are 16-bit
  caps.active_extra = 0;
  Rig many_active(caps);
  EXPECT_EQ(many_active.configure(), Status::kInvalidArgument);
  EXPECT_EQ(many_active.begin(), Status::kNotConfigured);
}

// ---- Refused draws --------------------------------------------------------------------------

// A frame with an untextured square (red, left) and a refused draw (right): the refusal is
// counted, render() returns its status and draws the rest.
template <SpanSet kSet>
void expect_refused_then_rendered(Rig<kSet>& rig, Status why) {
  EXPECT_EQ(rig.r->stats().triangles_in, 2u);  // the red square's: refused draws add none
  EXPECT_EQ(rig.render(), why);
  EXPECT_EQ(rig.sink.faults(), 0u);
  EXPECT_EQ(rig.pixel(8, 8), kRed);
  EXPECT_EQ(rig.pixel(34, 8), kBackground);
  EXPECT_EQ(rig.pixel(32, 16), kBackground);  // the triangle's centre
  EXPECT_EQ(rig.r->stats().triangles_binned, 2u);
}

TEST(ApiErrors, TexturedDrawWithoutTexVertices) {
  FrameCapacities caps = kCaps;
  caps.tex_vertices = 0;
  Rig rig(caps);
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  EXPECT_EQ(rig.draw_square(square(30, 4, 8, kRed), textured()), Status::kMissingStore);
  EXPECT_EQ(rig.draw_tri(textured()), Status::kMissingStore);
  EXPECT_EQ(rig.r->stats().draws_refused_missing_store, 2u);
  EXPECT_EQ(rig.r->stats().dropped_vertex_capacity, 0u);  // not a capacity problem
  expect_refused_then_rendered(rig, Status::kMissingStore);
}

TEST(ApiErrors, TexturedDrawWithoutActiveExtra) {
  FrameCapacities caps = kCaps;
  caps.active_extra = 0;
  Rig rig(caps);
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  EXPECT_EQ(rig.draw_square(square(30, 4, 8, kRed), textured()), Status::kMissingStore);
  EXPECT_EQ(rig.draw_tri(textured()), Status::kMissingStore);
  EXPECT_EQ(rig.r->stats().draws_refused_missing_store, 2u);
  expect_refused_then_rendered(rig, Status::kMissingStore);
}

TEST(ApiErrors, PhongDrawWithoutItsStores) {
  using Remove = void (*)(FrameCapacities&);
  const std::pair<const char*, Remove> cases[] = {
      {"surfaces", [](FrameCapacities& c) { c.surfaces = 0; }},
      {"pixel_lights", [](FrameCapacities& c) { c.pixel_lights = 0; }},
      {"active_extra", [](FrameCapacities& c) { c.active_extra = 0; }},
      {"lighting_tables", [](FrameCapacities& c) { c.lighting_table_words = 0; }},
  };
  for (const auto& [what, remove] : cases) {
    SCOPED_TRACE(what);
    FrameCapacities caps = kCaps;
    remove(caps);
    Rig rig(caps);
    ASSERT_TRUE(rig.ready());
    ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
    EXPECT_EQ(rig.draw_tri(phong(PixelLighting::kTable)), Status::kMissingStore);
    // Exact per-pixel lighting needs no table pool.
    const bool tables = std::string(what) == "lighting_tables";
    EXPECT_EQ(rig.draw_tri(phong(PixelLighting::kExact)),
              tables ? Status::kOk : Status::kMissingStore);
    EXPECT_EQ(rig.r->stats().draws_refused_missing_store, tables ? 1u : 2u);
    EXPECT_EQ(rig.r->stats().dropped_triangle_capacity + rig.r->stats().dropped_vertex_capacity,
              0u);
    if (!tables) expect_refused_then_rendered(rig, Status::kMissingStore);
  }
}

TEST(ApiErrors, FlatDrawWithoutTriangleColors) {
  FrameCapacities caps = kCaps;
  caps.triangle_colors = 0;
  Rig rig(caps);
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  EXPECT_EQ(rig.draw_square(square(30, 4, 8, kRed), flat()), Status::kMissingStore);
  EXPECT_EQ(rig.draw_tri(flat()), Status::kMissingStore);
  EXPECT_EQ(rig.r->stats().draws_refused_missing_store, 2u);
  EXPECT_EQ(rig.r->stats().dropped_triangle_capacity, 0u);
  expect_refused_then_rendered(rig, Status::kMissingStore);
}

TEST(ApiErrors, PhongDrawInARendererWithoutPhongSpans) {
  Rig<kUntexturedSpans> rig;
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  EXPECT_EQ(rig.draw_tri(phong()), Status::kNotLinked);
  EXPECT_EQ(rig.r->stats().draws_refused_not_linked, 1u);
  EXPECT_EQ(rig.r->stats().vertices_transformed, 0u);  // the triangle's were not
  expect_refused_then_rendered(rig, Status::kNotLinked);
}

TEST(ApiErrors, DrawOutsideTheSpanSet) {
  Rig<kUntexturedSpans> rig;
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  EXPECT_EQ(rig.draw_square(square(30, 4, 8, kRed), textured()), Status::kNotLinked);
  EXPECT_EQ(rig.draw_tri(textured()), Status::kNotLinked);
  // A renderer without textured spans links no test of textures: an invalid one is refused as
  // outside the set too (one with textured spans finds it invalid).
  Texture broken = green_texture();
  broken.level_count = 0;
  DrawState bad = textured();
  bad.texture = &broken;
  EXPECT_EQ(rig.draw_tri(bad), Status::kNotLinked);
  EXPECT_EQ(rig.r->stats().draws_refused_not_linked, 3u);
  expect_refused_then_rendered(rig, Status::kNotLinked);
  Rig<kAllSpans> every;
  ASSERT_TRUE(every.ready());
  EXPECT_EQ(every.draw_tri(bad), Status::kInvalidArgument);
}

// Nor any other check of a textured or Phong draw's maps (FrontEndRoutines::check_maps): a
// mipmapped sampler on a texture without levels, texture coordinates that are not one per vertex
// are refused as outside the set by a renderer without textured and Phong spans, and found
// invalid by one with them.
TEST(ApiErrors, MapChecksOfADrawOutsideTheSpanSet) {
  DrawState mip = textured();
  mip.sampler.mip = MipMode::kNearest;  // green_texture() has one level
  const Tri tri;
  const std::array<TexCoord, 2> two_uvs{};
  Mesh short_uvs = tri.mesh();
  short_uvs.uvs = two_uvs;
  Rig<kUntexturedSpans> rig;
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  EXPECT_EQ(rig.draw_tri(mip), Status::kNotLinked);
  EXPECT_EQ(rig.r->draw(short_uvs, Mat4::identity(), Material{}, textured()), Status::kNotLinked);
  EXPECT_EQ(rig.r->stats().draws_refused_not_linked, 2u);
  EXPECT_EQ(rig.r->stats().draws_refused_invalid, 0u);
  expect_refused_then_rendered(rig, Status::kNotLinked);
  Rig<kAllSpans> every;
  ASSERT_TRUE(every.ready());
  EXPECT_EQ(every.draw_tri(mip), Status::kInvalidArgument);
  EXPECT_EQ(every.r->draw(short_uvs, Mat4::identity(), Material{}, textured()),
            Status::kInvalidArgument);
  EXPECT_EQ(every.r->stats().draws_refused_invalid, 2u);
}

// A renderer links flat shading's face lighting only when its set admits flat-shaded draws,
// and the lighting that reads the position (point lights, the local viewer) of Gouraud, flat
// and textured draws only when the set admits the position (SpanSet::position): the draws that
// would need a routine it does not link are refused. Linked, the same draw renders as with
// every routine.
TEST(ApiErrors, LitDrawWhoseLightingTheSpanSetLeavesOut) {
  // The footprint's Gouraud renderer: colour planes only (no flat draws), no position.
  constexpr SpanSet kGouraud =
      kUntexturedSpans.only(ColorPlanes::kPerspective).only_position(false);
  DrawState gouraud;  // lit Gouraud
  gouraud.depth_test = false;
  DrawState flat_lit = gouraud;
  flat_lit.shading = Shading::kFlat;
  const Color15 white{Color15::kOne, Color15::kOne, Color15::kOne};
  LightSet directional;
  directional.count = 1;
  directional.lights[0] = Light::directional({Fixed{}, Fixed{}, Fixed::from_int(1)}, white);
  LightSet point = directional;
  point.lights[0] = Light::point({Fixed{}, Fixed{}, Fixed::from_int(2)}, white);
  LightSet local_viewer = directional;
  local_viewer.local_viewer = true;

  for (const LightSet* lights : {&directional, &point, &local_viewer}) {
    const bool position = lights != &directional;
    SCOPED_TRACE(position ? "lights that read the position" : "directional lights");
    Rig<kGouraud> rig;
    ASSERT_EQ(rig.configure(), Status::kOk);
    ASSERT_EQ(rig.begin(*lights), Status::kOk);
    ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
    EXPECT_EQ(rig.draw_tri(flat_lit), Status::kNotLinked);
    if (position) {
      EXPECT_EQ(rig.draw_tri(gouraud), Status::kNotLinked);
    }
    EXPECT_EQ(rig.r->stats().draws_refused_not_linked, position ? 2u : 1u);
    expect_refused_then_rendered(rig, Status::kNotLinked);
  }

  // With the position admitted, the point-lit triangle is drawn, as by a renderer with every
  // routine.
  Rig<kUntexturedSpans.only(ColorPlanes::kPerspective)> linked;
  Rig<> every;
  ASSERT_EQ(linked.configure(), Status::kOk);
  ASSERT_EQ(every.configure(), Status::kOk);
  ASSERT_EQ(linked.begin(point), Status::kOk);
  ASSERT_EQ(every.begin(point), Status::kOk);
  ASSERT_EQ(linked.draw_tri(gouraud), Status::kOk);
  ASSERT_EQ(every.draw_tri(gouraud), Status::kOk);
  ASSERT_EQ(linked.render(), Status::kOk);
  ASSERT_EQ(every.render(), Status::kOk);
  EXPECT_NE(linked.pixel(32, 16), kBackground);  // the triangle's centre, lit
  EXPECT_EQ(linked.sink.frame(), every.sink.frame());
}

TEST(ApiErrors, DrawWithArgumentsThatDisagree) {
  Rig rig;
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  // Texture entries one short of the vertices.
  Square s = square(30, 4, 8, kRed);
  EXPECT_EQ(rig.r->draw_screen(s.v, s.t, textured(), std::span<const TexVertex>(s.tex).first(3)),
            Status::kInvalidArgument);
  // Two normals for three positions.
  const Tri tri;
  Mesh m = tri.mesh();
  m.normals = m.normals.first(2);
  DrawState lit;
  lit.depth_test = false;
  EXPECT_EQ(rig.r->draw(m, Mat4::identity(), Material{}, lit), Status::kInvalidArgument);
  EXPECT_EQ(rig.r->stats().draws_refused_invalid, 2u);
  expect_refused_then_rendered(rig, Status::kInvalidArgument);
}

// Fraction counts outside [16, 30] (docs/api-errors.md): a mesh's position_frac (but 0, the
// default: Q16.16) or a fine
// model's frac refuses the draw, a camera's fine_projection's frac (given: not nullptr) the
// frame. Counts inside the range draw the same triangle as the Q16.16 draw.
TEST(ApiErrors, FractionCountsOutsideTheirRange) {
  Rig rig;
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  const Tri tri;
  for (const int frac : {1, 15, 31, 255}) {
    Mesh m = tri.mesh();
    m.position_frac = static_cast<uint8_t>(frac);
    EXPECT_EQ(rig.r->draw(m, Mat4::identity(), Material{}, plain()), Status::kInvalidArgument)
        << frac;
  }
  for (const int32_t frac : {0, 15, 31}) {
    FineMat4 model = to_fine(Mat4::identity());
    model.frac = frac;
    EXPECT_EQ(rig.r->draw(tri.mesh(), model, Material{}, plain()), Status::kInvalidArgument)
        << frac;
  }
  EXPECT_EQ(rig.r->stats().draws_refused_invalid, 7u);
  expect_refused_then_rendered(rig, Status::kInvalidArgument);

  // The camera: a fine projection of 12 fraction bits refuses begin_frame (no frame begun).
  Camera camera;
  FineMat4 projection = to_fine(Mat4::identity());
  projection.frac = 12;
  camera.fine_projection = &projection;
  EXPECT_EQ(rig.r->begin_frame(camera, {}, kBackground), Status::kInvalidArgument);
  EXPECT_EQ(rig.draw_tri(plain()), Status::kNoFrame);
  expect_usable(rig);

  // In range: positions in Q13.19 (frac 19), the model and projection as frac-30 identities.
  Rig fine, coarse;
  ASSERT_TRUE(fine.configure() == Status::kOk && coarse.ready());
  projection = to_fine(Mat4::identity()) * to_fine(Mat4::identity());
  EXPECT_EQ(projection.frac, 30);
  ASSERT_EQ(fine.r->begin_frame(camera, {}, kBackground), Status::kOk);
  std::array<Vec3, 3> p19 = tri.p;
  for (Vec3& v : p19)
    v = {Fixed::from_raw(v.x.raw * 8), Fixed::from_raw(v.y.raw * 8), Fixed::from_raw(v.z.raw * 8)};
  Mesh m = tri.mesh();
  m.positions = p19;
  m.position_frac = 19;
  const FineMat4 model = projection;
  EXPECT_EQ(fine.r->draw(m, model, Material{}, plain()), Status::kOk);
  EXPECT_EQ(coarse.draw_tri(plain()), Status::kOk);
  ASSERT_EQ(fine.render(), Status::kOk);
  ASSERT_EQ(coarse.render(), Status::kOk);
  EXPECT_EQ(fine.sink.frame(), coarse.sink.frame());
  EXPECT_NE(fine.pixel(32, 16), kBackground);
}

TEST(ApiErrors, DrawWithAFullStore) {
  FrameCapacities caps = kCaps;
  caps.draws = 1;
  Rig rig(caps);
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  EXPECT_EQ(rig.draw_square(square(30, 4, 8, kRed), plain()), Status::kCapacity);
  const FrameStats& s = rig.r->stats();
  EXPECT_EQ(s.draws_refused_capacity, 1u);
  EXPECT_EQ(s.dropped_triangle_capacity, 2u);  // a capacity refusal counts its triangles
  EXPECT_EQ(s.triangles_in, 4u);
  EXPECT_EQ(rig.render(), Status::kCapacity);
  EXPECT_EQ(rig.pixel(8, 8), kRed);
  EXPECT_EQ(rig.pixel(34, 8), kBackground);
}

TEST(ApiErrors, RenderReportsTheFirstRefusedDraw) {
  FrameCapacities caps = kCaps;
  caps.draws = 2;
  caps.triangle_colors = 0;
  Rig rig(caps);
  ASSERT_TRUE(rig.ready());
  ASSERT_EQ(rig.draw_square(square(4, 4, 8, kRed), plain()), Status::kOk);
  EXPECT_EQ(rig.draw_tri(flat()), Status::kMissingStore);
  ASSERT_EQ(rig.draw_tri(plain()), Status::kOk);
  EXPECT_EQ(rig.draw_tri(plain()), Status::kCapacity);
  const FrameStats& s = rig.r->stats();
  EXPECT_EQ(s.draws_refused_missing_store, 1u);
  EXPECT_EQ(s.draws_refused_capacity, 1u);
  EXPECT_EQ(rig.render(), Status::kMissingStore);
  EXPECT_EQ(rig.pixel(8, 8), kRed);
  EXPECT_NE(rig.pixel(32, 16), kBackground);  // the triangle that was taken
}

}  // namespace
}  // namespace lr
