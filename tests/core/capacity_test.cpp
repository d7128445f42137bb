// Full stores drop work and count it; the frame still renders what fit, unchanged.
#include <gtest/gtest.h>

#include <array>
#include <set>

#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/support/core_harness.hpp"

namespace lr {
namespace {

using test::CoreHarness;
using test::ScreenScene;
constexpr int64_t S = kSubpixel;

// Four separate squares (two triangles each) in different places of a 64 x 64 frame.
ScreenScene squares(int count) {
  ScreenScene s;
  for (int i = 0; i < count; ++i) {
    int64_t x = (4 + 15 * i) * S, y = (3 + 14 * i) * S, e = 10 * S;
    s.add(x, y, x, y + e, x + e, y);
    s.add(x + e, y, x, y + e, x + e, y + e);
  }
  return s;
}

// A frame with more triangles than the store holds is drawn in bands (docs/bands.md): the
// frame of one pass, and the statistics of one pass but for the bands.
TEST(Capacity, TriangleStoreFullDrawsTheFrameInBands) {
  ScreenScene all = squares(4);
  CoreHarness<8> ref(64, 64);
  ref.begin();
  ref.renderer().draw_screen(all.vertices, all.triangles, test::coverage_state());
  const host::ImageRgb8 want = ref.render();
  EXPECT_EQ(ref.renderer().stats().bands, 1u);
  CoreHarness<8> small(64, 64, 100, /*max_triangles=*/4);
  small.begin();
  EXPECT_EQ(small.renderer().draw_screen(all.vertices, all.triangles, test::coverage_state()),
            Status::kOk);
  Status st = Status::kInvalidArgument;
  EXPECT_EQ(small.render(&st).rgb, want.rgb);
  EXPECT_EQ(st, Status::kOk);
  const FrameStats& s = small.renderer().stats();
  EXPECT_GE(s.bands, 2u);
  EXPECT_EQ(s.dropped_triangle_capacity, 0u);
  EXPECT_EQ(s.binned_inputs, 8u);
  EXPECT_EQ(s.triangles_binned, 8u);
  EXPECT_EQ(s.triangles_in, 8u);
}

// Below the minimum (the triangles that touch one strip) the frame is what fit, the drop is
// counted and render() says kCapacity.
TEST(Capacity, AStripThatDoesNotFitTheStoreIsReported) {
  ScreenScene s;
  for (int i = 0; i < 3; ++i)
    s.add((2 + 20 * i) * S, 2 * S, (2 + 20 * i) * S, 6 * S, (18 + 20 * i) * S, 2 * S);
  CoreHarness<8> small(64, 16, 100, /*max_triangles=*/2);
  small.begin();
  EXPECT_EQ(small.renderer().draw_screen(s.vertices, s.triangles, test::coverage_state()),
            Status::kOk);
  Status st = Status::kOk;
  const host::ImageRgb8 got = small.render(&st);
  EXPECT_EQ(st, Status::kCapacity);
  EXPECT_EQ(small.renderer().stats().dropped_triangle_capacity, 1u);
  ScreenScene first;
  for (int i = 0; i < 2; ++i)
    first.add((2 + 20 * i) * S, 2 * S, (2 + 20 * i) * S, 6 * S, (18 + 20 * i) * S, 2 * S);
  CoreHarness<8> ref(64, 16);
  ref.begin();
  ref.renderer().draw_screen(first.vertices, first.triangles, test::coverage_state());
  EXPECT_EQ(got.rgb, ref.render().rgb);
}

TEST(Capacity, VertexStoreFullDropsTheWholeDraw) {
  ScreenScene a = squares(2), b = squares(4);
  CoreHarness<8> small(64, 64, /*max_vertices=*/20);
  small.begin();
  EXPECT_EQ(small.renderer().draw_screen(a.vertices, a.triangles, test::coverage_state()),
            Status::kOk);
  EXPECT_EQ(small.renderer().draw_screen(b.vertices, b.triangles, test::coverage_state()),
            Status::kCapacity);
  Status rendered = Status::kOk;
  host::ImageRgb8 got = small.render(&rendered);
  EXPECT_EQ(rendered, Status::kCapacity);  // the refused draw
  EXPECT_EQ(small.renderer().stats().draws_refused_capacity, 1u);
  EXPECT_EQ(small.renderer().stats().dropped_vertex_capacity, 8u);
  EXPECT_EQ(small.renderer().stats().triangles_in, 12u);
  CoreHarness<8> ref(64, 64);
  ref.begin();
  ref.renderer().draw_screen(a.vertices, a.triangles, test::coverage_state());
  EXPECT_EQ(got.rgb, ref.render().rgb);
}

// Textured draws keep their texture coordinates in the TexVertex store (FrameStorage::
// tex_vertices): without one a textured draw is refused with kMissingStore and counted (as a
// draw: its triangles are not in triangles_in), an untextured one is drawn; draw_screen's
// texture entries must match its vertices. render() reports the first refused draw.
TEST(Capacity, TexturedDrawsNeedTheTexVertexStore) {
  host::ImageRgb8 img;
  img.width = img.height = 1;
  img.rgb = {200, 100, 50};
  host::HostTexture tex;
  std::string err;
  ASSERT_TRUE(host::texture_from_image(img, TexelFormat::kRgb888, false, tex, err)) << err;
  DrawState textured = test::coverage_state();
  textured.shading = Shading::kGouraud;
  textured.texture = &tex.texture;
  textured.sampler.filter = Filter::kNearest;
  textured.sampler.env = TexEnv::kReplace;
  const ScreenScene plain = squares(1), tiled = squares(3);
  ScreenScene second;  // the third square of `tiled` alone
  second.vertices.assign(tiled.vertices.begin() + 12, tiled.vertices.end());
  second.triangles = {{0, 1, 2}, {3, 4, 5}};
  const std::vector<TexVertex> uv(second.vertices.size());
  for (size_t tex_store : {size_t{0}, size_t{100}}) {
    SCOPED_TRACE(tex_store);
    CoreHarness<8> core(64, 64, 100, 100, 16, 8, tex_store);
    core.begin();
    EXPECT_EQ(core.renderer().draw_screen(plain.vertices, plain.triangles, test::coverage_state()),
              Status::kOk);
    EXPECT_EQ(core.renderer().draw_screen(second.vertices, second.triangles, textured,
                                          std::span(uv).first(5)),
              Status::kInvalidArgument);  // one entry short: nothing added, nothing counted
    EXPECT_EQ(core.renderer().stats().triangles_in, 2u);
    EXPECT_EQ(core.renderer().stats().draws_refused_invalid, 1u);
    const Status want = tex_store == 0 ? Status::kMissingStore : Status::kOk;
    EXPECT_EQ(core.renderer().draw_screen(second.vertices, second.triangles, textured, uv), want);
    // A textured mesh: refused before anything is transformed.
    const std::vector<Vec3> pos(3);
    const std::vector<TexCoord> uvs(3);
    const std::vector<std::array<uint16_t, 3>> tri = {{0, 1, 2}};
    const Mesh mesh{pos, {}, {}, uvs, tri, {}};
    DrawState unlit_textured = textured;
    unlit_textured.lighting = false;
    EXPECT_EQ(core.renderer().draw(mesh, Mat4::identity(), Material{}, unlit_textured), want);
    Status rendered = Status::kOk;
    const host::ImageRgb8 got = core.render(&rendered);
    EXPECT_EQ(rendered, Status::kInvalidArgument);  // the short draw_screen, refused first
    const FrameStats& s = core.renderer().stats();
    EXPECT_EQ(s.triangles_in, tex_store == 0 ? 2u : 5u);
    EXPECT_EQ(s.draws_refused_missing_store, tex_store == 0 ? 2u : 0u);
    EXPECT_EQ(s.dropped_vertex_capacity, 0u);
    // The untextured square is drawn either way; the textured one only with the store.
    const size_t first = 6 * 64 + 6, third = (3 + 28 + 4) * 64 + (4 + 30 + 4);
    EXPECT_EQ(test::id_of(got, first), 0);
    EXPECT_EQ(got.rgb[3 * third], tex_store == 0 ? 0 : 200);
    EXPECT_EQ(got.rgb[3 * third + 1], tex_store == 0 ? 0 : 100);
  }
}

// Overlapping triangles without a depth test (the submission order decides every overlap), more
// of them crossing each strip than the active list holds: each crowded strip is drawn in passes
// and the frame is the one-pass frame.
TEST(Capacity, CrowdedStripsAreDrawnInPassesWithTheSameFrame) {
  ScreenScene s;
  for (int i = 0; i < 5; ++i)
    s.add((2 + 9 * i) * S, (2 + 3 * i) * S, (2 + 9 * i) * S, 44 * S, (24 + 9 * i) * S, 5 * S);
  s.add(1 * S, 20 * S, 62 * S, 30 * S, 60 * S, 10 * S);
  CoreHarness<8> ref(64, 48);
  ref.begin();
  ref.renderer().draw_screen(s.vertices, s.triangles, test::coverage_state());
  const host::ImageRgb8 want = ref.render();
  EXPECT_EQ(ref.renderer().stats().strip_passes, 0u);
  EXPECT_EQ(ref.renderer().stats().max_active, 6u);
  for (size_t active = 1; active <= 6; ++active) {
    CoreHarness<8> small(64, 48, 100, 100, active);
    small.begin();
    small.renderer().draw_screen(s.vertices, s.triangles, test::coverage_state());
    EXPECT_EQ(small.render().rgb, want.rgb) << active << " active slots";
    const FrameStats& st = small.renderer().stats();
    EXPECT_EQ(st.strip_passes > 0, active < 6) << active;
    EXPECT_LE(st.max_active, active);
  }
}

// Slivers between pixel centres get no planes and no active slot (rows and edges only): the frame
// is the one with the slivers moved off the viewport (same submission order, same colours), in
// strips where triangles already active and new ones interleave with them (no depth test: the
// active order decides every overlap). Slivers of a pixel of area or more are not tested
// (kSurelyPixelsArea2): they get planes and slots, and the frame is the same.
TEST(Capacity, SliversBetweenPixelCentresTakeNoActiveSlot) {
  auto scene = [](int64_t sliver_dx, int64_t top_width) {
    ScreenScene s;
    s.add(2 * S, 2 * S, 2 * S, 44 * S, 60 * S, 2 * S);  // rows 2..43, from strip 0
    // Thin diagonal slivers whose boxes hold pixel centres (the binner keeps them) but which hold
    // none: on row j the one from x = 10 covers x in [j + 1.10, j + 1.18] (20 subpixels wide at
    // the top: 0.78 pixels of area), or [j + 1.10, j + 1.30] (51: 1.99 pixels).
    auto sliver = [&](int64_t x) {
      x += sliver_dx;
      s.add(x + 154, 10 * S, x + 154 + top_width, 10 * S, x + 20 * S + 179, 30 * S);
    };
    sliver(10 * S);
    s.add(4 * S, 9 * S, 40 * S, 40 * S, 50 * S, 12 * S);  // from strip 1, over the first
    sliver(20 * S);
    s.add(10 * S, 11 * S, 30 * S, 46 * S, 56 * S, 20 * S);  // from strip 1, over both
    s.add(30 * S, 17 * S, 33 * S, 47 * S, 62 * S, 30 * S);  // from strip 2
    return s;
  };
  ScreenScene with = scene(0, 20), without = scene(1000 * S, 20), wide = scene(0, 51);
  CoreHarness<8> a(64, 48), b(64, 48), c(64, 48);
  a.begin();
  a.renderer().draw_screen(with.vertices, with.triangles, test::coverage_state());
  host::ImageRgb8 got = a.render();
  EXPECT_EQ(a.renderer().stats().triangles_binned, 6u);
  EXPECT_EQ(a.renderer().stats().triangles_without_pixels, 2u);
  EXPECT_EQ(a.renderer().stats().triangles_set_up, 4u);
  EXPECT_EQ(a.renderer().stats().max_active, 4u);
  b.begin();
  b.renderer().draw_screen(without.vertices, without.triangles, test::coverage_state());
  EXPECT_EQ(b.renderer().stats().triangles_binned, 4u);
  EXPECT_EQ(got.rgb, b.render().rgb);
  c.begin();
  c.renderer().draw_screen(wide.vertices, wide.triangles, test::coverage_state());
  EXPECT_EQ(c.render().rgb, got.rgb);
  EXPECT_EQ(c.renderer().stats().triangles_without_pixels, 0u);
  EXPECT_EQ(c.renderer().stats().triangles_set_up, 6u);
  // Every triangle shows somewhere: the last one drawn over the others.
  std::set<std::array<uint8_t, 3>> colours;
  for (size_t i = 0; i + 2 < got.rgb.size(); i += 3)
    colours.insert({got.rgb[i], got.rgb[i + 1], got.rgb[i + 2]});
  EXPECT_EQ(colours.size(), 5u);  // four triangles and the background
}

// The same slivers with fewer active slots than the strips' triangles: a bucket that does not
// fit is refused once its triangles run past the free slots (the strip loop sets up those
// before, here slivers), and its crowded strip sets them up again. The frame is the one-pass
// frame and each sliver is counted once.
TEST(Capacity, CrowdedStripsWithSliversCountEachSliverOnce) {
  ScreenScene s;
  s.add(2 * S, 2 * S, 2 * S, 44 * S, 60 * S, 2 * S);      // rows 2..43, from strip 0
  s.add(4 * S, 9 * S, 40 * S, 40 * S, 50 * S, 12 * S);    // from strip 1, over the first
  s.add(10 * S, 11 * S, 30 * S, 46 * S, 56 * S, 20 * S);  // from strip 1, over both
  // Slivers from strip 1 (as above): the first of its bucket (latest submission first).
  for (int64_t x : {10 * S, 14 * S, 20 * S})
    s.add(x + 154, 10 * S, x + 174, 10 * S, x + 20 * S + 179, 30 * S);
  s.add(30 * S, 17 * S, 33 * S, 47 * S, 62 * S, 30 * S);  // from strip 2
  CoreHarness<8> ref(64, 48);
  ref.begin();
  ref.renderer().draw_screen(s.vertices, s.triangles, test::coverage_state());
  const host::ImageRgb8 want = ref.render();
  EXPECT_EQ(ref.renderer().stats().triangles_without_pixels, 3u);
  EXPECT_EQ(ref.renderer().stats().strip_passes, 0u);
  for (size_t active = 1; active <= 3; ++active) {
    CoreHarness<8> small(64, 48, 100, 100, active);
    small.begin();
    small.renderer().draw_screen(s.vertices, s.triangles, test::coverage_state());
    EXPECT_EQ(small.render().rgb, want.rgb) << active << " active slots";
    const FrameStats& st = small.renderer().stats();
    EXPECT_GT(st.strip_passes, 0u) << active;
    EXPECT_EQ(st.triangles_without_pixels, 3u) << active;
    EXPECT_EQ(st.triangles_wide, 0u) << active;
  }
}

TEST(Capacity, DrawTableFullIsReported) {
  ScreenScene a = squares(1);
  CoreHarness<8> small(64, 64, 100, 100, 16, /*max_draws=*/1);
  small.begin();
  EXPECT_EQ(small.renderer().draw_screen(a.vertices, a.triangles, test::coverage_state()),
            Status::kOk);
  EXPECT_EQ(small.renderer().draw_screen(a.vertices, a.triangles, test::coverage_state()),
            Status::kCapacity);
  EXPECT_EQ(small.renderer().stats().dropped_triangle_capacity, 2u);
}

TEST(Capacity, InvalidIndicesAndCoordinatesAreRejectedAndCounted) {
  ScreenScene s = squares(1);
  s.triangles.push_back({0, 1, 200});  // out of range
  ScreenVertex far;
  far.x = 1 << 30;  // beyond the coordinate budget
  s.vertices.push_back(far);
  s.triangles.push_back({0, 1, static_cast<uint16_t>(s.vertices.size() - 1)});
  CoreHarness<8> core(64, 64);
  core.begin();
  core.renderer().draw_screen(s.vertices, s.triangles, test::coverage_state());
  core.render();
  EXPECT_EQ(core.renderer().stats().rejected_invalid, 2u);
  EXPECT_EQ(core.renderer().stats().binned_inputs, 2u);
}

// A renderer on `s` without one of its optional stores, begun: configure() first refuses the
// store `short_size` entries long (too short for what it goes with: kStoreTooSmall), then
// takes none. nullptr when a step fails (the expectations say which).
template <class T>
std::unique_ptr<Renderer<Rgb888, 8>> begun_without(FrameStorage s,
                                                   std::span<T> FrameStorage::*store,
                                                   size_t short_size) {
  std::vector<T> too_short(short_size);
  s.*store = too_short;
  auto r = std::make_unique<Renderer<Rgb888, 8>>();
  EXPECT_EQ(r->configure(s, 64, 64), Status::kStoreTooSmall);
  s.*store = {};
  if (r->configure(s, 64, 64) != Status::kOk || r->begin_frame({}, {}, {0, 0, 0}) != Status::kOk)
    return nullptr;
  return r;
}

// The planes of textured and Phong triangles live in FrameStorage::active_extra: without it
// those draws are refused (kMissingStore, counted) and untextured ones drawn; a store smaller
// than the active list is a configuration error.
TEST(Capacity, TexturedAndPhongDrawsNeedTheActiveExtraStore) {
  FrameCapacities caps{.width = 64,
                       .height = 64,
                       .strip_height = 8,
                       .vertices = 64,
                       .triangles = 64,
                       .draws = 4,
                       .active = 8,
                       .surfaces = 64,
                       .pixel_lights = 2,
                       .tex_vertices = 64,
                       .triangle_colors = 64};
  BasicFrameStorage<std::vector> store(caps);
  const auto r = begun_without(store.storage(), &FrameStorage::active_extra, 7);
  ASSERT_NE(r, nullptr);
  host::ImageRgb8 img;
  img.width = img.height = 1;
  img.rgb = {200, 100, 50};
  host::HostTexture tex;
  std::string err;
  ASSERT_TRUE(host::texture_from_image(img, TexelFormat::kRgb888, false, tex, err)) << err;
  DrawState textured = test::coverage_state();
  textured.texture = &tex.texture;
  const ScreenScene sq = squares(1);
  const std::vector<TexVertex> uv(sq.vertices.size());
  EXPECT_EQ(r->draw_screen(sq.vertices, sq.triangles, textured, uv), Status::kMissingStore);
  const std::vector<Vec3> pos(3);
  const std::vector<Normal16> nrm(3, Normal16{0, 0, 16384});
  const std::vector<std::array<uint16_t, 3>> tri = {{0, 1, 2}};
  DrawState phong;
  phong.shading = Shading::kPhong;
  EXPECT_EQ(r->draw(Mesh{pos, nrm, {}, {}, tri, {}}, Mat4::identity(), Material{}, phong),
            Status::kMissingStore);
  EXPECT_EQ(r->draw_screen(sq.vertices, sq.triangles, test::coverage_state()), Status::kOk);
  EXPECT_EQ(r->stats().draws_refused_missing_store, 2u);
  EXPECT_EQ(r->stats().dropped_vertex_capacity, 0u);
  EXPECT_EQ(r->stats().triangles_in, 2u);
}

// A flat-shaded triangle's colours live in FrameStorage::triangle_colors (a Gouraud triangle is
// 8 bytes without them): without the store flat draws are refused (kMissingStore, counted) and
// Gouraud ones drawn, and render() reports the refusal; a store smaller than the triangles' is
// a configuration error.
TEST(Capacity, FlatDrawsNeedTheTriangleColorStore) {
  FrameCapacities caps{.width = 64,
                       .height = 64,
                       .strip_height = 8,
                       .vertices = 64,
                       .triangles = 16,
                       .draws = 4,
                       .active = 8};
  BasicFrameStorage<std::vector> store(caps);
  const auto r = begun_without(store.storage(), &FrameStorage::triangle_colors, 15);
  ASSERT_NE(r, nullptr);
  const ScreenScene sq = squares(1);
  EXPECT_EQ(r->draw_screen(sq.vertices, sq.triangles, test::coverage_state()),
            Status::kMissingStore);
  const std::vector<Vec3> pos = {{Fixed{}, Fixed{}, Fixed::from_int(-2)},
                                 {Fixed::from_int(1), Fixed{}, Fixed::from_int(-2)},
                                 {Fixed{}, Fixed::from_int(1), Fixed::from_int(-2)}};
  const std::vector<Normal16> nrm(3, Normal16{0, 0, 16384});
  const std::vector<std::array<uint16_t, 3>> tri = {{0, 1, 2}};
  DrawState flat_lit;
  flat_lit.shading = Shading::kFlat;
  EXPECT_EQ(r->draw(Mesh{pos, nrm, {}, {}, tri, {}}, Mat4::identity(), Material{}, flat_lit),
            Status::kMissingStore);
  DrawState gouraud = test::coverage_state();
  gouraud.shading = Shading::kGouraud;
  EXPECT_EQ(r->draw_screen(sq.vertices, sq.triangles, gouraud), Status::kOk);
  EXPECT_EQ(r->stats().draws_refused_missing_store, 2u);
  EXPECT_EQ(r->stats().dropped_triangle_capacity, 0u);
  EXPECT_EQ(r->stats().triangles_in, 2u);
  host::CaptureDisplay<Rgb888> display(64 * 8);
  EXPECT_EQ(r->render(display), Status::kMissingStore);
  EXPECT_EQ(r->stats().pixels_written, 100u);  // the Gouraud square, 10 x 10
}

// The strip loop finds a binned triangle's draw by its first vertex (each draw's vertices are
// one range of the store): flat, Gouraud and flat draws in turn each draw with their own
// state, in one pass and in bands.
TEST(Capacity, EachTriangleIsDrawnWithItsOwnDraw) {
  const ScreenScene all = squares(3);
  // Square k: its 6 vertices and 2 triangles, renumbered from 0; the Gouraud one in white.
  const auto square = [&](size_t k, bool white) {
    ScreenScene s;
    s.vertices.assign(all.vertices.begin() + static_cast<std::ptrdiff_t>(6 * k),
                      all.vertices.begin() + static_cast<std::ptrdiff_t>(6 * k + 6));
    if (white)
      for (ScreenVertex& v : s.vertices) v.color = {Color15::kOne, Color15::kOne, Color15::kOne};
    s.triangles = {{0, 1, 2}, {3, 4, 5}};
    return s;
  };
  const ScreenScene a = square(0, false), b = square(1, true), c = square(2, false);
  DrawState gouraud = test::coverage_state();
  gouraud.shading = Shading::kGouraud;
  for (size_t max_triangles : {16u, 4u}) {
    CoreHarness<8> core(64, 64, 100, max_triangles);
    core.begin();
    ASSERT_EQ(core.renderer().draw_screen(a.vertices, a.triangles, test::coverage_state()),
              Status::kOk);
    ASSERT_EQ(core.renderer().draw_screen(b.vertices, b.triangles, gouraud), Status::kOk);
    ASSERT_EQ(core.renderer().draw_screen(c.vertices, c.triangles, test::coverage_state()),
              Status::kOk);
    Status st = Status::kInvalidArgument;
    const host::ImageRgb8 img = core.render(&st);
    EXPECT_EQ(st, Status::kOk);
    EXPECT_EQ(core.renderer().stats().bands > 1, max_triangles == 4);
    // A pixel inside each triangle: the flat ones their ids' colours, the Gouraud one white.
    const auto at = [&](int x, int y) { return test::id_of(img, size_t(y) * 64 + size_t(x)); };
    EXPECT_EQ(at(5, 4), 0);    // square 0, triangle 0
    EXPECT_EQ(at(12, 11), 1);  // square 0, triangle 1
    const size_t p = size_t(18) * 64 + 20;
    EXPECT_EQ(img.rgb[3 * p], 255);  // square 1
    EXPECT_EQ(img.rgb[3 * p + 1], 255);
    EXPECT_EQ(img.rgb[3 * p + 2], 255);
    EXPECT_EQ(at(35, 32), 4);  // square 2, triangle 0
    EXPECT_EQ(at(42, 39), 5);  // square 2, triangle 1
  }
}

TEST(Capacity, BadConfigurationIsRefused) {
  BasicFrameStorage<std::vector> store(FrameCapacities{.width = 64,
                                                       .height = 64,
                                                       .strip_height = 8,
                                                       .vertices = 10,
                                                       .triangles = 10,
                                                       .draws = 4,
                                                       .active = 4});
  FrameStorage s = store.storage();
  s.buckets = s.buckets.first(3);
  auto r = std::make_unique<Renderer<Rgb888, 8>>();
  EXPECT_EQ(r->configure(s, 64, 64), Status::kStoreTooSmall);  // 8 strips need 8 buckets
  s.buckets = store.storage().buckets;
  EXPECT_EQ(r->configure(s, 64, 64), Status::kOk);
  EXPECT_EQ(r->configure(s, 65, 64), Status::kStoreTooSmall);  // depth too small for the width
  EXPECT_EQ(r->configure(s, 0, 64), Status::kInvalidArgument);
  s.active_index = s.active_index.first(7);
  EXPECT_EQ(r->configure(s, 64, 64), Status::kStoreTooSmall);
}

TEST(StripHeight, OneEightAndThirtyTwoGiveIdenticalFrames) {
  host::HostMesh mesh = host::make_torus_knot(2, 3, 0.2, 160, 12);
  host::SceneOptions o;
  o.fit = true;
  o.light_dirs = {{1, 1, 1}, {-1, 0.3, 0.5}};
  host::RenderResult r1, r8, r32;
  std::string err;
  o.strip_height = 1;
  ASSERT_TRUE(host::render_scene(mesh, o, r1, err)) << err;
  o.strip_height = 8;
  ASSERT_TRUE(host::render_scene(mesh, o, r8, err)) << err;
  o.strip_height = 32;
  ASSERT_TRUE(host::render_scene(mesh, o, r32, err)) << err;
  EXPECT_EQ(r1.image.rgb, r8.image.rgb);
  EXPECT_EQ(r1.image.rgb, r32.image.rgb);
  EXPECT_EQ(r1.depth, r32.depth);
  EXPECT_EQ(r1.strips, 240u);
  EXPECT_EQ(r8.strips, 30u);
  EXPECT_EQ(r32.strips, 8u);  // 7 full strips and one of 16 rows
  EXPECT_EQ(r1.stats.pixels_written, r32.stats.pixels_written);
  EXPECT_GT(r1.stats.pixels_written, 5000u);
}

}  // namespace
}  // namespace lr
