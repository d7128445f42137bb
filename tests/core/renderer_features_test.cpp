// A renderer without some of the front end's features (core/raster/renderer_features.hpp): a
// draw that needs a feature it leaves out gets the status naming it, never a wrong frame; a
// frame that needs none of them is the same, byte for byte, as with every feature.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "lineraster/core/raster/frame_storage.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "tests/support/recording_sink.hpp"

namespace lr {
namespace {

using PF = Rgb565Be;
constexpr int kW = 64, kH = 48, kK = 8;
constexpr Rgb8 kBackground{10, 20, 30};

Fixed fx(double v) {
  return Fixed::from_raw(static_cast<int32_t>(std::lround(v * 65536.0)));
}

// An n x n grid of quads (2 n^2 triangles, (n + 1)^2 vertices) facing the camera, lit per
// vertex, filling most of the viewport. Its normals are unit, or of length `length`.
struct Grid {
  std::vector<Vec3> positions;
  std::vector<Normal16> normals;
  std::vector<std::array<uint16_t, 3>> triangles;
  explicit Grid(int n, double length = 1.0) {
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        positions.push_back({fx(-1.2 + 2.4 * i / n), fx(-0.9 + 1.8 * j / n), fx(-2.0)});
        // Normals leaning with x, so that the lighting varies over the grid.
        const double a = -0.38 + 0.76 * i / n;
        normals.push_back({static_cast<int16_t>(std::lround(16384.0 * length * std::sin(a))), 0,
                           static_cast<int16_t>(std::lround(16384.0 * length * std::cos(a)))});
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const auto a = static_cast<uint16_t>(j * (n + 1) + i);
        const auto b = static_cast<uint16_t>(a + 1), c = static_cast<uint16_t>(a + n + 1),
                   d = static_cast<uint16_t>(a + n + 2);
        triangles.push_back({a, b, d});
        triangles.push_back({a, d, c});
      }
  }
  Mesh mesh() const { return Mesh{positions, normals, {}, {}, triangles, {}}; }
};

// A floor of n x n quads below the eye, from z = -0.2 (in front of the near plane, 0.5: the
// nearest row of quads crosses it) to z = -4.2, lit from above.
struct Floor {
  std::vector<Vec3> positions;
  std::vector<Normal16> normals;
  std::vector<std::array<uint16_t, 3>> triangles;
  explicit Floor(int n) {
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        positions.push_back({fx(-1.5 + 3.0 * i / n), fx(-0.25), fx(-0.2 - 4.0 * j / n)});
        normals.push_back({0, 16384, 0});
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const auto a = static_cast<uint16_t>(j * (n + 1) + i);
        const auto b = static_cast<uint16_t>(a + 1), c = static_cast<uint16_t>(a + n + 1),
                   d = static_cast<uint16_t>(a + n + 2);
        triangles.push_back({a, d, b});
        triangles.push_back({a, c, d});
      }
  }
  Mesh mesh() const { return Mesh{positions, normals, {}, {}, triangles, {}}; }
};

Camera camera() {
  Camera c;
  EXPECT_TRUE(perspective(fx(60), Fixed::ratio(kW, kH), fx(0.5), fx(20), c.projection));
  return c;
}

LightSet lights(bool two_sided = false) {
  LightSet l;
  l.lights[0].position = {fx(0.3), fx(0.5), fx(1.0)};  // directional (w = 0)
  l.count = 1;
  l.global_ambient = {6554, 6554, 6554};
  l.two_sided = two_sided;
  return l;
}

// Diffuse (no specular colour: drawn by every renderer), or shiny (specular: refused by a
// renderer without RendererFeatures::specular).
Material material(bool shiny = false) {
  Material m;
  m.diffuse = {26000, 20000, 9000};
  if (shiny) {
    m.specular = {16000, 16000, 16000};
    m.shininess_q8 = 20 * 256;
  }
  return m;
}

DrawState lit_gouraud() {
  DrawState s;
  s.lighting = true;
  s.shading = Shading::kGouraud;
  s.depth_test = true;
  s.cull = Cull::kBack;
  return s;
}

FrameCapacities caps(size_t vertices = 512, size_t triangles = 512, bool strip_skipping = false,
                     size_t active = 256) {
  FrameCapacities c;
  c.width = kW;
  c.height = kH;
  c.strip_height = kK;
  c.vertices = vertices;
  c.triangles = triangles;
  c.draws = 4;
  c.active = active;
  c.strip_skipping = strip_skipping;
  return c;
}

// A renderer of the given features with its storage and a recording sink.
template <RendererFeatures kFeatures>
struct Rig {
  explicit Rig(FrameCapacities c = caps()) : store(c) {}
  BasicFrameStorage<std::vector> store;
  std::unique_ptr<Renderer<PF, kK, kAllSpans, kFeatures>> r =
      std::make_unique<Renderer<PF, kK, kAllSpans, kFeatures>>();
  test::RecordingSink<PF> sink{size_t{kW} * kK};
  Status status = Status::kOk;

  Status configure() { return r->configure(store.storage(), kW, kH); }
  // Configures, begins, draws the grid (the draw's status) and renders (status).
  Status frame(const Grid& g, bool two_sided = false, const Material& m = material(),
               const DrawState& state = lit_gouraud()) {
    return frame(g.mesh(), two_sided, m, state);
  }
  Status frame(const Mesh& mesh, bool two_sided = false, const Material& m = material(),
               const DrawState& state = lit_gouraud(), const Mat4& model = Mat4::identity(),
               const LightSet* light_set = nullptr) {
    EXPECT_EQ(configure(), Status::kOk);
    EXPECT_EQ(r->begin_frame(camera(), light_set != nullptr ? *light_set : lights(two_sided),
                             kBackground),
              Status::kOk);
    const Status drawn = r->draw(mesh, model, m, state);
    status = r->render(sink);
    return drawn;
  }
  size_t covered() const {
    size_t n = 0;
    for (const auto p : sink.frame()) n += p != PF::encode(kBackground);
    return n;
  }
};

using Full = Rig<kAllFeatures>;
using Lean = Rig<kNoFeatures>;
// Every feature but the crowded strips' passes.
constexpr RendererFeatures kUncrowded{.crowded_strips = false};
using Uncrowded = Rig<kUncrowded>;
// Every feature but specular.
constexpr RendererFeatures kDiffuseOnly{.specular = false};
using DiffuseOnly = Rig<kDiffuseOnly>;
// Every feature but world-space lighting.
constexpr RendererFeatures kModelSpaceOnly{.world_lighting = false};
using ModelSpaceOnly = Rig<kModelSpaceOnly>;

TEST(RendererFeatures, WithoutFeaturesAFrameThatNeedsNoneIsTheSame) {
  const Grid g(6);
  Full full;
  Lean lean;
  ASSERT_EQ(full.frame(g), Status::kOk);
  ASSERT_EQ(lean.frame(g), Status::kOk);
  EXPECT_EQ(full.status, Status::kOk);
  EXPECT_EQ(lean.status, Status::kOk);
  EXPECT_GT(full.covered(), size_t{1000});
  EXPECT_EQ(lean.sink.frame(), full.sink.frame());
  EXPECT_EQ(lean.r->stats().triangles_binned, full.r->stats().triangles_binned);
}

TEST(RendererFeatures, WithoutBandsAFrameLargerThanTheTriangleStoreIsCapacity) {
  const Grid g(8);  // 128 triangles, every one facing the camera
  Full whole;       // stores that hold the frame
  ASSERT_EQ(whole.frame(g), Status::kOk);
  ASSERT_EQ(whole.status, Status::kOk);
  Full banded(caps(512, 64));  // 64 triangles: drawn in bands
  ASSERT_EQ(banded.frame(g), Status::kOk);
  EXPECT_EQ(banded.status, Status::kOk);
  EXPECT_GT(banded.r->stats().bands, 1u);
  EXPECT_EQ(banded.sink.frame(), whole.sink.frame());
  Lean lean(caps(512, 64));
  ASSERT_EQ(lean.frame(g), Status::kOk);  // taken; what does not fit is dropped at binning
  EXPECT_EQ(lean.status, Status::kCapacity);
  EXPECT_EQ(lean.r->stats().bands, 1u);
  EXPECT_EQ(lean.r->stats().triangles_binned, 64u);
  EXPECT_EQ(lean.r->stats().dropped_triangle_capacity, 128u - 64u);
}

TEST(RendererFeatures, WithoutTheVertexCacheAMeshLargerThanTheVertexStoreIsNotLinked) {
  const Grid g(15);  // 256 vertices, 450 triangles
  Full whole;
  ASSERT_EQ(whole.frame(g), Status::kOk);
  Full cached(caps(200));  // through the vertex cache
  ASSERT_EQ(cached.frame(g), Status::kOk);
  EXPECT_EQ(cached.status, Status::kOk);
  EXPECT_EQ(cached.sink.frame(), whole.sink.frame());
  Lean lean(caps(200));
  EXPECT_EQ(lean.frame(g), Status::kNotLinked);
  EXPECT_EQ(lean.status, Status::kNotLinked);
  EXPECT_EQ(lean.r->stats().draws_refused_not_linked, 1u);
  EXPECT_EQ(lean.r->stats().triangles_binned, 0u);
  EXPECT_EQ(lean.covered(), size_t{0});
}

TEST(RendererFeatures, WithoutTwoSidedLightingATwoSidedLitDrawIsNotLinked) {
  const Grid g(4);
  Full full;
  ASSERT_EQ(full.frame(g, true), Status::kOk);
  EXPECT_EQ(full.status, Status::kOk);
  Lean lean;
  EXPECT_EQ(lean.frame(g, true), Status::kNotLinked);
  EXPECT_EQ(lean.status, Status::kNotLinked);
  EXPECT_EQ(lean.r->stats().draws_refused_not_linked, 1u);
  // Unlit, two-sided lighting does not apply: drawn.
  ASSERT_EQ(lean.r->begin_frame(camera(), lights(true), kBackground), Status::kOk);
  DrawState unlit = lit_gouraud();
  unlit.lighting = false;
  EXPECT_EQ(lean.r->draw(g.mesh(), Mat4::identity(), material(), unlit), Status::kOk);
  EXPECT_EQ(lean.r->render(lean.sink), Status::kOk);
  EXPECT_GT(lean.covered(), size_t{1000});
}

TEST(RendererFeatures, WithoutStripSkippingAStripInputsStoreIsNotLinked) {
  Full full(caps(512, 512, true));
  EXPECT_EQ(full.configure(), Status::kOk);
  Lean lean(caps(512, 512, true));
  EXPECT_EQ(lean.configure(), Status::kNotLinked);
  EXPECT_EQ(lean.r->begin_frame(camera(), lights(), kBackground), Status::kNotConfigured);
}

TEST(RendererFeatures, WithoutCrowdedStripsAStripBeyondTheActiveListIsCapacity) {
  const Grid g(8);  // 8 rows of 16 triangles, up to 48 of them active in a strip
  Full whole;       // an active list that holds every strip's triangles
  ASSERT_EQ(whole.frame(g), Status::kOk);
  ASSERT_EQ(whole.status, Status::kOk);
  EXPECT_EQ(whole.r->stats().strip_passes, 0u);
  // Where the active list holds them, the same frame without the passes.
  Uncrowded roomy;
  ASSERT_EQ(roomy.frame(g), Status::kOk);
  EXPECT_EQ(roomy.status, Status::kOk);
  EXPECT_EQ(roomy.sink.frame(), whole.sink.frame());
  EXPECT_EQ(whole.r->stats().max_active, 48u);
  // 32 slots: the full renderer draws the crowded strips in passes, the same frame.
  Full passes(caps(512, 512, false, 32));
  ASSERT_EQ(passes.frame(g), Status::kOk);
  EXPECT_EQ(passes.status, Status::kOk);
  EXPECT_GT(passes.r->stats().strip_passes, 0u);
  EXPECT_EQ(passes.sink.frame(), whole.sink.frame());
  // Without the passes: kCapacity, the triangles starting in a crowded strip dropped and
  // counted, every other pixel as in the whole frame (the grid's triangles do not overlap).
  Uncrowded crowded(caps(512, 512, false, 32));
  ASSERT_EQ(crowded.frame(g), Status::kOk);
  EXPECT_EQ(crowded.status, Status::kCapacity);
  EXPECT_EQ(crowded.r->stats().strip_passes, 0u);
  const uint32_t dropped = crowded.r->stats().dropped_triangle_capacity;
  EXPECT_GT(dropped, 0u);
  EXPECT_LT(dropped, crowded.r->stats().triangles_binned);
  EXPECT_EQ(dropped % 16, 0u);  // whole rows of the grid: those starting in crowded strips
  EXPECT_EQ(crowded.r->stats().triangles_set_up + dropped, whole.r->stats().triangles_set_up);
  size_t same = 0, background = 0;
  const auto bg = PF::encode(kBackground);
  for (size_t i = 0; i < whole.sink.frame().size(); ++i) {
    same += crowded.sink.frame()[i] == whole.sink.frame()[i];
    background += crowded.sink.frame()[i] != whole.sink.frame()[i] && crowded.sink.frame()[i] == bg;
  }
  EXPECT_LT(same, whole.sink.frame().size());
  EXPECT_EQ(same + background, whole.sink.frame().size());
  Lean lean(caps(512, 512, false, 32));
  ASSERT_EQ(lean.frame(g), Status::kOk);
  EXPECT_EQ(lean.status, Status::kCapacity);
  EXPECT_EQ(lean.r->stats().dropped_triangle_capacity, dropped);
  EXPECT_EQ(lean.sink.frame(), crowded.sink.frame());
}

TEST(RendererFeatures, WithoutSpecularALitDrawWithASpecularMaterialIsNotLinked) {
  const Grid g(6);
  // With specular: the highlights change the frame.
  Full diffuse, shiny;
  ASSERT_EQ(diffuse.frame(g), Status::kOk);
  ASSERT_EQ(shiny.frame(g, false, material(true)), Status::kOk);
  EXPECT_EQ(shiny.status, Status::kOk);
  EXPECT_NE(shiny.sink.frame(), diffuse.sink.frame());
  // Without it: a diffuse material gives the same frame (the per-vertex lighting without its
  // specular term), a specular one is refused, counted, and nothing of it drawn.
  for (const bool lean_rig : {false, true}) {
    SCOPED_TRACE(lean_rig ? "kNoFeatures" : "every feature but specular");
    auto check = [&](auto& rig) {
      ASSERT_EQ(rig.frame(g), Status::kOk);
      EXPECT_EQ(rig.status, Status::kOk);
      EXPECT_EQ(rig.sink.frame(), diffuse.sink.frame());
      EXPECT_EQ(rig.frame(g, false, material(true)), Status::kNotLinked);
      EXPECT_EQ(rig.status, Status::kNotLinked);
      EXPECT_EQ(rig.r->stats().draws_refused_not_linked, 1u);
      EXPECT_EQ(rig.r->stats().triangles_binned, 0u);
      EXPECT_EQ(rig.covered(), size_t{0});
      // Unlit, the specular colour does not apply: drawn.
      DrawState unlit = lit_gouraud();
      unlit.lighting = false;
      EXPECT_EQ(rig.frame(g, false, material(true), unlit), Status::kOk);
      EXPECT_EQ(rig.status, Status::kOk);
      EXPECT_GT(rig.covered(), size_t{1000});
    };
    if (lean_rig) {
      Lean lean;
      check(lean);
    } else {
      DiffuseOnly only;
      check(only);
    }
  }
}

TEST(RendererFeatures, WithoutClippingATriangleCrossingAPlaneIsDroppedAndNotLinked) {
  const Floor f(6);
  DrawState both = lit_gouraud();
  both.cull = Cull::kNone;
  Full full;
  ASSERT_EQ(full.frame(f.mesh(), false, material(), both), Status::kOk);
  EXPECT_EQ(full.status, Status::kOk);
  const FrameStats& fs = full.r->stats();
  EXPECT_GT(fs.clipped, 0u);  // the nearest row crosses the near plane
  EXPECT_EQ(fs.dropped_unclipped, 0u);
  EXPECT_GT(full.covered(), size_t{500});
  // Without the clipper: the draw is taken, the triangles that cross a plane are dropped and
  // counted, the others drawn as with it, and render() returns kNotLinked.
  Lean lean;
  ASSERT_EQ(lean.frame(f.mesh(), false, material(), both), Status::kOk);
  EXPECT_EQ(lean.status, Status::kNotLinked);
  const FrameStats& ls = lean.r->stats();
  EXPECT_EQ(ls.dropped_unclipped, fs.clipped);
  EXPECT_EQ(ls.clipped, 0u);
  EXPECT_EQ(ls.draws_refused_not_linked, 0u);
  EXPECT_EQ(ls.triangles_in, fs.triangles_in);
  EXPECT_EQ(ls.binned_inputs + ls.dropped_unclipped + ls.culled_backface + ls.culled_zero_area +
                ls.culled_offscreen + ls.clipped_away + ls.rejected_invalid,
            ls.triangles_in);
  size_t same = 0, background = 0;
  const auto bg = PF::encode(kBackground);
  for (size_t i = 0; i < full.sink.frame().size(); ++i) {
    same += lean.sink.frame()[i] == full.sink.frame()[i];
    background += lean.sink.frame()[i] != full.sink.frame()[i] && lean.sink.frame()[i] == bg;
  }
  EXPECT_LT(same, full.sink.frame().size());
  EXPECT_EQ(same + background, full.sink.frame().size());
  EXPECT_GT(lean.covered(), size_t{100});
  // A frame after it that needs no clipping: kOk again.
  const Grid g(4);
  ASSERT_EQ(lean.frame(g), Status::kOk);
  EXPECT_EQ(lean.status, Status::kOk);
  EXPECT_EQ(lean.r->stats().dropped_unclipped, 0u);
}

TEST(RendererFeatures, WithoutWorldLightingADrawThatNeedsItIsNotLinked) {
  // Lit in model space (a rigid model, unit normals, a directional light): the same frame.
  const Grid unit(6), longer(6, 1.25);
  const Mat4 turned = rotate_y(fx(20));
  Full full;
  ASSERT_EQ(full.frame(unit.mesh(), false, material(), lit_gouraud(), turned), Status::kOk);
  EXPECT_GT(full.covered(), size_t{1000});
  ModelSpaceOnly only;
  ASSERT_EQ(only.frame(unit.mesh(), false, material(), lit_gouraud(), turned), Status::kOk);
  EXPECT_EQ(only.status, Status::kOk);
  EXPECT_EQ(only.sink.frame(), full.sink.frame());
  // Two-sided, with back faces (the general triangle loop lights every vertex through
  // VertexStage::light), shiny (the split of the specular term) and unculled: the same too.
  DrawState both = lit_gouraud();
  both.cull = Cull::kNone;
  std::vector<std::array<uint16_t, 3>> reversed;  // every other triangle a back face
  for (size_t t = 0; t < unit.triangles.size(); ++t) {
    const auto& tri = unit.triangles[t];
    reversed.push_back(t % 2 == 0 ? tri : std::array<uint16_t, 3>{tri[0], tri[2], tri[1]});
  }
  const Mesh mixed{unit.positions, unit.normals, {}, {}, reversed, {}};
  ASSERT_EQ(full.frame(mixed, true, material(true), both, turned), Status::kOk);
  EXPECT_GT(full.covered(), size_t{1000});
  ASSERT_EQ(only.frame(mixed, true, material(true), both, turned), Status::kOk);
  EXPECT_EQ(only.status, Status::kOk);
  EXPECT_EQ(only.sink.frame(), full.sink.frame());
  // What needs the world-space path: normals that are not unit, a model that is not rigid (x
  // scaled), a point light. Drawn with it, refused without it.
  Mat4 stretched = Mat4::identity();
  stretched.m[0][0] = fx(1.5);
  LightSet point = lights();
  point.lights[0] = Light::point({fx(0.5), fx(0.5), fx(0.0)}, {32767, 32767, 32767});
  struct Case {
    const char* what;
    const Grid& grid;
    Mat4 model;
    const LightSet* lights;
  };
  const Case cases[] = {{"normals of length 1.25", longer, Mat4::identity(), nullptr},
                        {"a model scaled along x", unit, stretched, nullptr},
                        {"a point light", unit, Mat4::identity(), &point}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    Full with;
    ASSERT_EQ(with.frame(c.grid.mesh(), false, material(), lit_gouraud(), c.model, c.lights),
              Status::kOk);
    EXPECT_EQ(with.status, Status::kOk);
    EXPECT_GT(with.covered(), size_t{1000});
    ModelSpaceOnly without;
    EXPECT_EQ(without.frame(c.grid.mesh(), false, material(), lit_gouraud(), c.model, c.lights),
              Status::kNotLinked);
    EXPECT_EQ(without.status, Status::kNotLinked);
    EXPECT_EQ(without.r->stats().draws_refused_not_linked, 1u);
    EXPECT_EQ(without.covered(), size_t{0});
    // Unlit, the normals and lights do not matter: drawn.
    DrawState unlit = lit_gouraud();
    unlit.lighting = false;
    EXPECT_EQ(without.frame(c.grid.mesh(), false, material(), unlit, c.model, c.lights),
              Status::kOk);
    EXPECT_EQ(without.status, Status::kOk);
    EXPECT_GT(without.covered(), size_t{1000});
  }
  Lean lean;
  EXPECT_EQ(lean.frame(longer), Status::kNotLinked);
}

// fe configured on store with routines, its frame begun (the front-end tests below).
void begin_front_end(FrontEnd& fe, BasicFrameStorage<std::vector>& store,
                     const FrontEndRoutines& routines) {
  ASSERT_EQ(fe.configure(store.storage().front_end(), kW, kH, kK, &routines), Status::kOk);
  ASSERT_EQ(fe.begin_frame(camera(), lights(), kBackground), Status::kOk);
}

// A front end given no routine for triangles' own colours (FrontEndRoutines::flat: a renderer
// whose span set admits no flat-shaded or one-coloured draw) refuses those draws.
TEST(RendererFeatures, AFrontEndWithoutOwnColoursRefusesFlatAndOneColouredDraws) {
  BasicFrameStorage<std::vector> store(caps());
  FrontEndRoutines routines;  // every routine but that one
  routines.flat = nullptr;
  const auto fe = std::make_unique<FrontEnd>();
  ASSERT_NO_FATAL_FAILURE(begin_front_end(*fe, store, routines));
  const Grid g(2);
  DrawState flat = lit_gouraud();
  flat.shading = Shading::kFlat;
  DrawState one_colour = lit_gouraud();
  one_colour.lighting = false;  // unlit, and the grid has no vertex colours
  EXPECT_EQ(fe->draw(g.mesh(), Mat4::identity(), material(), flat), Status::kNotLinked);
  EXPECT_EQ(fe->draw(g.mesh(), Mat4::identity(), material(), one_colour), Status::kNotLinked);
  EXPECT_EQ(fe->draw(g.mesh(), Mat4::identity(), material(), lit_gouraud()), Status::kOk);
  EXPECT_EQ(fe->stats().draws_refused_not_linked, 2u);
  EXPECT_GT(fe->stats().triangles_binned, 0u);
}

// Nor one given triangles' own colours but no one-coloured draw's colour (FrontEndRoutines::
// one_color).
TEST(RendererFeatures, AFrontEndWithoutOneColourRefusesOneColouredDraws) {
  BasicFrameStorage<std::vector> store(caps());
  FrontEndRoutines routines;  // every routine but that one
  routines.one_color = nullptr;
  const auto fe = std::make_unique<FrontEnd>();
  ASSERT_NO_FATAL_FAILURE(begin_front_end(*fe, store, routines));
  const Grid g(2);
  DrawState one_colour = lit_gouraud();
  one_colour.lighting = false;  // unlit, and the grid has no vertex colours
  EXPECT_EQ(fe->draw(g.mesh(), Mat4::identity(), material(), one_colour), Status::kNotLinked);
  EXPECT_EQ(fe->draw(g.mesh(), Mat4::identity(), material(), lit_gouraud()), Status::kOk);
  EXPECT_EQ(fe->stats().draws_refused_not_linked, 1u);
  EXPECT_GT(fe->stats().triangles_binned, 0u);
}

}  // namespace
}  // namespace lr
