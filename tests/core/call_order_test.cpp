// Random sequences of the renderer's public calls (configure, begin_frame, draw, draw_screen,
// render, invalidate_strips) with random arguments: viewports out of range, every store from
// none through one short to oversized, huge and small coordinates, indices out of range,
// textured, flat and Phong draws whose stores may be missing, sinks that fail. Every call must
// return (a hang fails the test at its CTest timeout) with the status a small model of the
// renderer's states predicts (docs/api-errors.md), a call out of order must change nothing,
// and every frame's statistics must add up. Seeded: the same sequences on every run.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "lineraster/core/raster/frame_storage.hpp"
#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "tests/support/recording_sink.hpp"

namespace lr {
namespace {

using PF = Rgb565Be;

// Deterministic draws from the generator (no std distribution: their output differs between
// standard libraries).
class Dice {
 public:
  explicit Dice(uint32_t seed) : g_(seed) {}
  uint32_t bits() { return static_cast<uint32_t>(g_()); }
  int range(int lo, int hi) {  // [lo, hi]
    return lo + static_cast<int>(bits() % static_cast<uint32_t>(hi - lo + 1));
  }
  size_t upto(size_t hi) { return static_cast<size_t>(bits() % (hi + 1)); }  // [0, hi]
  bool chance(int percent) { return range(0, 99) < percent; }
  int32_t i32() { return static_cast<int32_t>(bits()); }
  Fixed fixed_within(double limit) {  // |value| <= limit
    const auto l = static_cast<int32_t>(limit * 65536);
    return Fixed::from_raw(range(-l, l));
  }
  // A coordinate: mostly near the origin, sometimes far, sometimes any Q16.16 value.
  Fixed coordinate() {
    const int r = range(0, 9);
    return r < 6 ? fixed_within(1.5) : r < 9 ? fixed_within(200) : Fixed::from_raw(i32());
  }

 private:
  std::mt19937 g_;
};

static_assert(std::has_unique_object_representations_v<FrameStats>);
bool same(const FrameStats& a, const FrameStats& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

uint32_t outcomes(const FrameStats& s) {
  return s.binned_inputs + s.culled_backface + s.culled_zero_area + s.culled_offscreen +
         s.clipped_away + s.rejected_invalid + s.dropped_vertex_capacity +
         s.dropped_triangle_capacity;
}

// Two textures: 1 x 1 without mipmaps (a mip mode is refused with it), 4 x 4 RGB565 with them.
struct Textures {
  host::HostTexture plain, mipmapped;
  Textures() {
    host::ImageRgb8 one;
    one.width = one.height = 1;
    one.rgb = {0, 200, 0};
    host::ImageRgb8 four;
    four.width = four.height = 4;
    for (int i = 0; i < 16; ++i) four.rgb.insert(four.rgb.end(), {uint8_t(16 * i), 90, 200});
    std::string err;
    EXPECT_TRUE(host::texture_from_image(one, TexelFormat::kRgb888, false, plain, err)) << err;
    EXPECT_TRUE(host::texture_from_image(four, TexelFormat::kRgb565, true, mipmapped, err)) << err;
  }
};
const Textures& textures() {
  static const Textures t;
  return t;
}

// Every store of FrameStorage, sized independently (FrameCapacities would keep them in step).
struct Stores {
  std::vector<ScreenVertex> vertices;
  std::vector<BinnedTriangle> triangles;
  std::vector<DrawRecord> draws;
  std::vector<uint16_t> buckets;
  std::vector<ActiveTriangle> active;
  std::vector<uint16_t> active_index;
  std::vector<uint16_t> depth;
  std::vector<SurfaceVertex> surfaces;
  std::vector<uint32_t> lighting_tables;
  std::vector<PreparedLighting> pixel_lights;
  std::vector<uint32_t> strip_inputs;
  std::vector<TexVertex> tex_vertices;
  std::vector<ActiveExtra> active_extra;
  std::vector<TriangleColors> triangle_colors;

  FrameStorage storage() {
    return {vertices,     triangles,    draws,        buckets,         active,
            active_index, depth,        surfaces,     lighting_tables, pixel_lights,
            strip_inputs, tex_vertices, active_extra, triangle_colors};
  }
};

// A size for a store whose right size is `right`. Fitting: right or larger. Else also none,
// one short, or anything up to twice as large.
size_t size_near(Dice& d, size_t right, bool fitting) {
  if (fitting) return right + (d.chance(25) ? d.upto(8) : 0);
  const int r = d.range(0, 19);
  if (r < 3) return 0;
  if (r < 7) return right > 0 ? right - 1 : 0;
  if (r < 14) return right;
  return d.upto(2 * right + 4);
}
// An optional store: none in `none_percent` of the draws, else near its right size.
size_t optional_near(Dice& d, size_t right, int none_percent, bool fitting) {
  return d.chance(none_percent) ? 0 : size_near(d, right, fitting);
}

// Random stores for a viewport of sw x sh in strips of K rows: fitting it (each optional
// store none or large enough), or any size.
template <int K>
std::unique_ptr<Stores> random_stores(Dice& d, int sw, int sh, bool fitting) {
  auto s = std::make_unique<Stores>();
  const size_t strips = static_cast<size_t>((sh + K - 1) / K);
  // Vertex and triangle stores from a few entries (frames in bands, drops) to many.
  const size_t v = !fitting && d.chance(8) ? 0
                   : d.chance(50)          ? static_cast<size_t>(d.range(1, 40))
                                           : static_cast<size_t>(d.range(41, 160));
  const size_t t = !fitting && d.chance(5) ? 0
                   : d.chance(50)          ? static_cast<size_t>(d.range(1, 24))
                                           : static_cast<size_t>(d.range(25, 200));
  const size_t draws = !fitting && d.chance(3)   ? 0
                       : !fitting && d.chance(1) ? 257
                                                 : static_cast<size_t>(d.range(1, 8));
  const size_t active = !fitting && d.chance(3)   ? 0
                        : !fitting && d.chance(1) ? kMaxStoreEntries + 1
                                                  : static_cast<size_t>(d.range(1, 40));
  s->vertices.resize(v);
  s->triangles.resize(t);
  s->draws.resize(draws);
  s->buckets.resize(size_near(d, strips, fitting));
  s->active.resize(active);
  s->active_index.resize(size_near(d, 2 * active, fitting));
  s->depth.resize(size_near(d, static_cast<size_t>(sw) * K, fitting));
  s->surfaces.resize(optional_near(d, v, 30, fitting));
  const size_t words = lighting_table_words(static_cast<uint16_t>(8 << d.range(0, 2)), true);
  s->lighting_tables.resize(d.chance(30) ? 0 : words * d.upto(2));
  s->pixel_lights.resize(d.chance(30) ? 0 : d.upto(3));
  s->strip_inputs.resize(optional_near(d, 2 * strips, 40, fitting));
  s->tex_vertices.resize(optional_near(d, v, 30, fitting));
  s->active_extra.resize(optional_near(d, active > kMaxStoreEntries ? 0 : active, 30, fitting));
  s->triangle_colors.resize(optional_near(d, t, 30, fitting));
  return s;
}

// What configure() must answer for these stores and this viewport: kOk, or the problems found
// (configure returns one of them; a viewport out of range is always the one).
struct ConfigureWant {
  bool bad_viewport = false, invalid = false, too_small = false;
};
template <int K>
ConfigureWant configure_want(const Stores& s, int w, int h) {
  ConfigureWant c;
  c.bad_viewport = w < 1 || h < 1 || w > kMaxViewport || h > kMaxViewport;
  if (c.bad_viewport) return c;
  const size_t strips = static_cast<size_t>((h + K - 1) / K);
  c.invalid = s.draws.size() > 256 || s.active.size() > kMaxStoreEntries;
  c.too_small = s.draws.empty() || s.vertices.empty() || s.triangles.empty() ||
                s.buckets.size() < strips ||
                (!s.strip_inputs.empty() && s.strip_inputs.size() < 2 * strips) ||
                (!s.triangle_colors.empty() && s.triangle_colors.size() < s.triangles.size()) ||
                s.depth.size() < static_cast<size_t>(w) * K || s.active.empty() ||
                s.active_index.size() < 2 * s.active.size() ||
                (!s.active_extra.empty() && s.active_extra.size() < s.active.size());
  return c;
}

// A draw() call: its mesh, state, material and matrix, and what the model needs to know.
struct MeshCall {
  std::vector<Vec3> positions;
  std::vector<Normal16> normals;
  std::vector<Rgb8> colors;
  std::vector<TexCoord> uvs;
  std::vector<std::array<uint16_t, 3>> triangles;
  DrawState state;
  Material material;
  Mat4 model = Mat4::identity();
  Mesh mesh() const { return {positions, normals, colors, uvs, triangles, {}}; }
};

std::vector<std::array<uint16_t, 3>> random_triangles(Dice& d, size_t n, size_t count) {
  std::vector<std::array<uint16_t, 3>> tris(count);
  for (auto& t : tris)
    for (uint16_t& i : t)
      i = n > 0 && d.chance(95) ? static_cast<uint16_t>(d.upto(n - 1))
          : d.chance(50)        ? uint16_t{0xFFFF}
                                : static_cast<uint16_t>(n + d.upto(4));
  return tris;
}

void random_sampler(Dice& d, DrawState& s) {
  const Textures& tx = textures();
  s.texture = d.chance(50) ? &tx.plain.texture : &tx.mipmapped.texture;
  s.sampler.filter = d.chance(50) ? Filter::kNearest : Filter::kBilinear;
  s.sampler.wrap_s = d.chance(50) ? Wrap::kRepeat : Wrap::kClampToEdge;
  s.sampler.wrap_t = d.chance(50) ? Wrap::kRepeat : Wrap::kClampToEdge;
  s.sampler.mip = static_cast<MipMode>(d.range(0, 2));
  s.sampler.env = d.chance(50) ? TexEnv::kReplace : TexEnv::kModulate;
}

MeshCall random_mesh_call(Dice& d) {
  MeshCall c;
  const int size = d.range(0, 9);
  const size_t n = size == 0  ? 0
                   : size < 8 ? static_cast<size_t>(d.range(1, 24))
                              : static_cast<size_t>(d.range(80, 130));
  c.positions.resize(n);
  for (Vec3& p : c.positions) p = {d.coordinate(), d.coordinate(), d.coordinate()};
  // Normals: one per position, none, or one too many.
  const int nr = d.range(0, 99);
  c.normals.resize(nr < 90 ? n : nr < 96 ? 0 : n + 1);
  for (Normal16& v : c.normals)
    v = {static_cast<int16_t>(d.range(-16384, 16384)), static_cast<int16_t>(d.range(-16384, 16384)),
         static_cast<int16_t>(d.range(-16384, 16384))};
  const int cr = d.range(0, 99);
  c.colors.resize(cr < 30 ? n : cr < 33 ? n + 1 : 0);
  for (Rgb8& v : c.colors) v = {uint8_t(d.bits()), uint8_t(d.bits()), uint8_t(d.bits())};
  c.triangles = random_triangles(d, n, d.upto(d.chance(90) ? 40 : 3 * n + 2));
  DrawState& s = c.state;
  s.lighting = d.chance(60);
  s.depth_test = d.chance(60);
  s.cull = static_cast<Cull>(d.range(0, 2));
  s.perspective = static_cast<Perspective>(d.range(0, 4));
  const int kind = d.range(0, 9);
  s.shading = kind < 3 ? Shading::kGouraud : kind < 5 ? Shading::kFlat : Shading::kPhong;
  if (d.chance(35)) {
    random_sampler(d, s);
    const int ur = d.range(0, 9);
    c.uvs.resize(ur < 7 ? n : ur < 9 ? 0 : n + 2);
    for (TexCoord& uv : c.uvs) uv = {d.range(-(3 << 20), 3 << 20), d.range(-(3 << 20), 3 << 20)};
  }
  s.pixel_lighting = d.chance(50) ? PixelLighting::kExact : PixelLighting::kTable;
  const int tr = d.range(0, 9);
  s.table.size = static_cast<uint16_t>(tr < 8 ? 8 << d.range(0, 2) : tr < 9 ? 4 : 300);
  s.table.bilinear = d.chance(50);
  c.material.diffuse = from_rgb8({uint8_t(d.bits()), uint8_t(d.bits()), uint8_t(d.bits())});
  c.material.specular = from_rgb8({uint8_t(d.bits()), uint8_t(d.bits()), uint8_t(d.bits())});
  c.material.shininess_q8 = static_cast<uint16_t>(d.range(0, 128 * 256));
  const int mr = d.range(0, 9);
  if (mr >= 5 && mr < 9)
    c.model = translate({d.fixed_within(2), d.fixed_within(2), d.fixed_within(2)}) *
              rotate_y(Fixed::from_int(d.range(0, 359))) * scale(d.fixed_within(3));
  else if (mr == 9)
    for (auto& row : c.model.m)
      for (Fixed& e : row) e = Fixed::from_raw(d.i32());
  return c;
}

// A draw_screen() call.
struct ScreenCall {
  std::vector<ScreenVertex> vertices;
  std::vector<TexVertex> tex;
  std::vector<std::array<uint16_t, 3>> triangles;
  DrawState state;
};

ScreenCall random_screen_call(Dice& d) {
  ScreenCall c;
  const size_t n = d.chance(85) ? d.upto(30) : static_cast<size_t>(d.range(31, 120));
  c.vertices.resize(n);
  const int shift = d.range(0, 20);
  for (ScreenVertex& v : c.vertices) {
    if (d.chance(80)) {  // in or near a small viewport
      v.x = d.range(-8 * kSubpixel, 120 * kSubpixel);
      v.y = d.range(-8 * kSubpixel, 120 * kSubpixel);
      v.z = d.chance(95) ? d.bits() % (kDepthMax + 1) : d.bits();
    } else {
      v.x = d.i32() >> shift;
      v.y = d.i32() >> shift;
      v.z = d.bits();
    }
    v.w = d.chance(50) ? 0 : d.bits();
    v.color = from_rgb8({uint8_t(d.bits()), uint8_t(d.bits()), uint8_t(d.bits())});
  }
  c.triangles = random_triangles(d, n, d.upto(40));
  DrawState& s = c.state;
  const int kind = d.range(0, 9);
  s.shading = kind < 5 ? Shading::kGouraud : kind < 9 ? Shading::kFlat : Shading::kPhong;
  s.depth_test = d.chance(50);
  s.cull = static_cast<Cull>(d.range(0, 2));
  s.perspective = static_cast<Perspective>(d.range(0, 4));
  if (d.chance(35)) random_sampler(d, s);
  // Texture entries: one per vertex, or (one draw in seven) one more or one fewer.
  const bool off = d.chance(15);
  c.tex.resize(off ? (n > 0 && d.chance(50) ? n - 1 : n + 1) : n);
  for (TexVertex& t : c.tex) {
    t.u = d.range(-(3 << 20), 3 << 20);
    t.v = d.range(-(3 << 20), 3 << 20);
  }
  return c;
}

LightSet random_lights(Dice& d) {
  LightSet l;
  l.count =
      static_cast<uint8_t>(d.chance(5) ? d.range(kMaxLights + 1, 255) : d.range(0, kMaxLights));
  l.local_viewer = d.chance(20);
  l.two_sided = d.chance(20);
  l.global_ambient = from_rgb8({uint8_t(d.bits()), uint8_t(d.bits()), uint8_t(d.bits())});
  for (Light& light : l.lights) {
    light.kind = d.chance(70) ? LightKind::kDirectional : LightKind::kPoint;
    light.position = {d.fixed_within(100), d.fixed_within(100), d.fixed_within(100)};
    if (light.position == Vec3{}) light.position.z = Fixed::from_int(1);
    light.diffuse = from_rgb8({uint8_t(d.bits()), uint8_t(d.bits()), uint8_t(d.bits())});
  }
  return l;
}

Camera random_camera(Dice& d, int w, int h) {
  Camera cam;
  const int r = d.range(0, 9);
  if (r < 3) return cam;  // identity: positions are device coordinates
  if (r < 8) {
    Mat4 proj, view;
    if (perspective(Fixed::from_int(d.range(20, 120)), Fixed::ratio(w > 0 ? w : 1, h > 0 ? h : 1),
                    d.fixed_within(1) + Fixed::from_double(0.05), Fixed::from_int(d.range(2, 60)),
                    proj))
      cam.projection = proj;
    cam.eye = {d.fixed_within(5), d.fixed_within(5), d.fixed_within(5)};
    if (look_at(cam.eye, Vec3{}, Vec3{Fixed{}, Fixed::from_int(1), Fixed{}}, view)) cam.view = view;
    return cam;
  }
  for (Mat4* m : {&cam.view, &cam.projection})
    for (auto& row : m->m)
      for (Fixed& e : row) e = Fixed::from_raw(d.i32());
  cam.eye = {Fixed::from_raw(d.i32()), Fixed::from_raw(d.i32()), Fixed::from_raw(d.i32())};
  return cam;
}

class CountingDepth final : public DepthSink {
 public:
  void on_depth(const StripRect&, std::span<const uint16_t>) override { ++strips; }
  uint32_t strips = 0;
};

// The model: where the renderer is (docs/api-errors.md), and what this frame's draws did.
struct Model {
  bool configured = false;
  enum class Phase { kIdle, kOpen, kRendered } phase = Phase::kIdle;
  int width = 0, height = 0;
  LightSet lights;
  uint32_t records = 0, triangles_in = 0;
  uint32_t invalid = 0, not_linked = 0, missing = 0, capacity = 0;
  Status first_refusal = Status::kOk;

  // The status of a call that needs a frame begun, when there is none (kOk: there is).
  Status out_of_order() const {
    if (!configured) return Status::kNotConfigured;
    if (phase == Phase::kIdle) return Status::kNoFrame;
    return phase == Phase::kRendered ? Status::kFrameRendered : Status::kOk;
  }
  void begin(const LightSet& l) {
    phase = Phase::kOpen;
    lights = l;
    records = triangles_in = invalid = not_linked = missing = capacity = 0;
    first_refusal = Status::kOk;
  }
  // A draw's status once taken: counts as the renderer does.
  void drew(Status st, size_t triangles) {
    if (st == Status::kOk) ++records;
    if (st == Status::kOk || st == Status::kCapacity)
      triangles_in += static_cast<uint32_t>(triangles);
    if (st != Status::kOk && first_refusal == Status::kOk) first_refusal = st;
    invalid += st == Status::kInvalidArgument;
    not_linked += st == Status::kNotLinked;
    missing += st == Status::kMissingStore;
    capacity += st == Status::kCapacity;
  }
  void expect_counts(const FrameStats& s) const {
    EXPECT_EQ(s.triangles_in, triangles_in);
    EXPECT_EQ(s.draws_refused_invalid, invalid);
    EXPECT_EQ(s.draws_refused_not_linked, not_linked);
    EXPECT_EQ(s.draws_refused_missing_store, missing);
    EXPECT_EQ(s.draws_refused_capacity, capacity);
  }
};

// The smallest store a mesh larger than it is drawn through (docs/bands.md: the vertex cache).
constexpr size_t kMinCachedStore = 80;

// How often each call returned each status over a test's sequences (and how many rendered
// frames were binned in bands): the sequences must reach every state, or they test little.
enum Call { kConfigure, kBeginFrame, kDraw, kDrawScreen, kRender, kCalls };
constexpr const char* kCallNames[kCalls] = {"configure", "begin_frame", "draw", "draw_screen",
                                            "render"};
constexpr int kStatuses = static_cast<int>(Status::kNotLinked) + 1;
struct Tally {
  std::array<std::array<uint32_t, kStatuses>, kCalls> seen{};
  uint32_t banded_frames = 0, skipped_strips = 0;
  uint32_t operator()(Call c, Status s) const { return seen[c][static_cast<size_t>(s)]; }
  void print() const {
    for (int c = 0; c < kCalls; ++c) {
      std::printf("%s:", kCallNames[c]);
      for (int s = 0; s < kStatuses; ++s)
        if (seen[static_cast<size_t>(c)][static_cast<size_t>(s)] != 0)
          std::printf(" %s %u,", to_string(static_cast<Status>(s)),
                      seen[static_cast<size_t>(c)][static_cast<size_t>(s)]);
      std::printf("\n");
    }
    std::printf("frames in bands %u, strips skipped %u\n", banded_frames, skipped_strips);
  }
};

template <int K, SpanSet kSet>
class Sequence {
 public:
  Sequence(uint32_t seed, Tally& tally) : d_(seed), tally_(tally) {}

  // Each call drawn with weights by the renderer's state: mostly what the state expects next,
  // always sometimes anything.
  void run() {
    const int calls = d_.range(1, 40);
    for (int i = 0; i < calls && !::testing::Test::HasFailure(); ++i) {
      SCOPED_TRACE("call " + std::to_string(i));
      struct Weights {
        int configure, begin, draw, draw_screen, render;  // invalidate_strips: the rest of 100
      };
      const Status where = m_.out_of_order();
      const Weights w = where == Status::kNotConfigured ? Weights{50, 14, 12, 12, 10}
                        : where != Status::kOk          ? Weights{5, 50, 15, 12, 12}
                                                        : Weights{3, 6, 38, 30, 20};
      int c = d_.range(0, 99);
      if ((c -= w.configure) < 0)
        configure();
      else if ((c -= w.begin) < 0)
        begin_frame();
      else if ((c -= w.draw) < 0)
        draw();
      else if ((c -= w.draw_screen) < 0)
        draw_screen();
      else if ((c -= w.render) < 0)
        render();
      else
        r_->invalidate_strips();
    }
  }

 private:
  static constexpr bool kTexturedLinked = kSet.has(SpanFamily::kTextured);
  static constexpr bool kPhongLinked = kSet.has(SpanFamily::kPhong);

  void configure() {
    const int sw = d_.range(1, 48), sh = d_.range(1, 48);
    std::unique_ptr<Stores> fresh = random_stores<K>(d_, sw, sh, d_.chance(60));
    int w = sw, h = sh;
    const int r = d_.range(0, 19);
    if (r == 0) w = d_.range(-2, 0);
    if (r == 1) h = d_.range(-2, 0);
    if (r == 2) w = kMaxViewport + d_.range(1, 4);
    if (r == 3) h = d_.range(100, kMaxViewport);
    if (r == 4) w = d_.range(1, 200);
    SCOPED_TRACE("configure " + std::to_string(w) + " x " + std::to_string(h));
    const ConfigureWant want = configure_want<K>(*fresh, w, h);
    const Status st = r_->configure(fresh->storage(), w, h);
    count(kConfigure, st);
    if (want.bad_viewport) {
      EXPECT_EQ(st, Status::kInvalidArgument);
    } else if (!want.invalid && !want.too_small) {
      EXPECT_EQ(st, Status::kOk);
    } else {
      EXPECT_TRUE((want.invalid && st == Status::kInvalidArgument) ||
                  (want.too_small && st == Status::kStoreTooSmall))
          << to_string(st);
    }
    // The renderer holds the new stores, or (refused) none: the old ones can go.
    stores_ = std::move(fresh);
    m_.configured = st == Status::kOk;
    m_.phase = Model::Phase::kIdle;
    if (m_.configured) {
      m_.width = w;
      m_.height = h;
    }
  }

  void begin_frame() {
    // A third of the frames repeat the last one's camera, lights and background (and maybe its
    // draws): unchanged strips are then skipped.
    if (!d_.chance(33)) {
      last_lights_ = random_lights(d_);
      last_camera_ = random_camera(d_, m_.width, m_.height);
      last_background_ = {uint8_t(d_.bits()), uint8_t(d_.bits()), uint8_t(d_.bits())};
    }
    const LightSet lights = last_lights_;
    const Camera cam = last_camera_;
    const Rgb8 bg = last_background_;
    const FrameStats before = r_->stats();
    const Status st = r_->begin_frame(cam, lights, bg);
    count(kBeginFrame, st);
    if (!m_.configured) {
      EXPECT_EQ(st, Status::kNotConfigured);
      EXPECT_TRUE(same(r_->stats(), before));
    } else if (lights.count > kMaxLights) {
      EXPECT_EQ(st, Status::kInvalidArgument);
      EXPECT_TRUE(same(r_->stats(), before));
      m_.phase = Model::Phase::kIdle;
    } else {
      EXPECT_EQ(st, Status::kOk);
      m_.begin(lights);
      m_.expect_counts(r_->stats());
    }
  }

  // Stores as the renderer sees them (it uses at most kMaxStoreEntries of the index stores).
  size_t vertices() const { return std::min(stores_->vertices.size(), kMaxStoreEntries); }
  size_t tex() const { return std::min(stores_->tex_vertices.size(), kMaxStoreEntries); }

  void draw() {
    if (meshes_.empty() || !d_.chance(30))
      meshes_.push_back(std::make_unique<MeshCall>(random_mesh_call(d_)));
    const MeshCall& c = *meshes_.back();
    const FrameStats before = r_->stats();
    const Status st = r_->draw(c.mesh(), c.model, c.material, c.state);
    count(kDraw, st);
    if (const Status order = m_.out_of_order(); order != Status::kOk) {
      EXPECT_EQ(st, order);
      EXPECT_TRUE(same(r_->stats(), before));
      return;
    }
    // front_end.cpp's checks, in their order.
    const DrawState& s = c.state;
    const size_t n = c.positions.size();
    const bool phong = s.lighting && s.shading == Shading::kPhong;
    const bool textured = s.texture != nullptr;
    const bool table = phong && s.pixel_lighting == PixelLighting::kTable;
    const Stores& k = *stores_;
    Status want = Status::kOk;
    bool maybe_capacity = false;
    // A textured or Phong draw's maps are checked only by a renderer with textured or Phong
    // spans (FrontEndRoutines::maps); the others refuse such a draw as not linked.
    const bool maps_invalid =
        (textured && s.sampler.mip != MipMode::kNone && s.texture->level_count < 2) ||
        (textured && !c.uvs.empty() && c.uvs.size() != n) ||
        (table && (!m_.lights.normal_only() || s.table.size < kMinLightingTable ||
                   s.table.size > kMaxLightingTable));
    if ((!c.normals.empty() && c.normals.size() != n) ||
        (!c.colors.empty() && c.colors.size() != n) ||
        (s.lighting && s.shading != Shading::kFlat && c.normals.empty()) ||
        ((kTexturedLinked || kPhongLinked) && maps_invalid)) {
      want = Status::kInvalidArgument;
    } else if ((textured && !kTexturedLinked) || (phong && !kPhongLinked)) {
      want = Status::kNotLinked;
    } else if ((textured && k.tex_vertices.empty()) ||
               ((textured || phong) && k.active_extra.empty()) ||
               (phong && (k.surfaces.empty() || k.pixel_lights.empty() ||
                          (table && k.lighting_tables.empty()))) ||
               (s.shading == Shading::kFlat && k.triangle_colors.empty())) {
      want = Status::kMissingStore;
    } else if ((n > vertices() && vertices() < kMinCachedStore) ||
               (phong && n > k.surfaces.size() && k.surfaces.size() < kMinCachedStore) ||
               (textured && n > tex() && tex() < kMinCachedStore) || m_.records >= k.draws.size()) {
      want = Status::kCapacity;
    } else {
      maybe_capacity = phong;  // the lighting pools: shared per material, not modelled
    }
    if (maybe_capacity)
      EXPECT_TRUE(st == Status::kOk || st == Status::kCapacity) << to_string(st);
    else
      EXPECT_EQ(st, want) << to_string(st) << " for " << to_string(want) << ": " << describe(s)
                          << " n=" << n;
    m_.drew(st, c.triangles.size());
    expect_frame_counts();
  }

  // A draw's state and the stores it may need, for failure messages.
  std::string describe(const DrawState& s) const {
    const Stores& k = *stores_;
    return "shading " + std::to_string(static_cast<int>(s.shading)) + " lit " +
           std::to_string(s.lighting) + " textured " + std::to_string(s.texture != nullptr) +
           " table " + std::to_string(s.pixel_lighting == PixelLighting::kTable) +
           "; stores: vertices " + std::to_string(k.vertices.size()) + ", tex " +
           std::to_string(k.tex_vertices.size()) + ", surfaces " +
           std::to_string(k.surfaces.size()) + ", extra " + std::to_string(k.active_extra.size()) +
           ", colours " + std::to_string(k.triangle_colors.size()) + ", lights " +
           std::to_string(k.pixel_lights.size()) + ", tables " +
           std::to_string(k.lighting_tables.size()) + ", draws " + std::to_string(k.draws.size());
  }

  void draw_screen() {
    if (screens_.empty() || !d_.chance(30))
      screens_.push_back(std::make_unique<ScreenCall>(random_screen_call(d_)));
    const ScreenCall& c = *screens_.back();
    const FrameStats before = r_->stats();
    const Status st = r_->draw_screen(c.vertices, c.triangles, c.state, c.tex);
    count(kDrawScreen, st);
    if (const Status order = m_.out_of_order(); order != Status::kOk) {
      EXPECT_EQ(st, order);
      EXPECT_TRUE(same(r_->stats(), before));
      return;
    }
    const DrawState& s = c.state;
    const size_t n = c.vertices.size();
    const bool textured = s.texture != nullptr;
    const Stores& k = *stores_;
    Status want = Status::kOk;
    if (textured && c.tex.size() != n)
      want = Status::kInvalidArgument;
    else if (textured && !kTexturedLinked)
      want = Status::kNotLinked;
    else if ((textured && (k.tex_vertices.empty() || k.active_extra.empty())) ||
             (s.shading != Shading::kGouraud && k.triangle_colors.empty()))
      want = Status::kMissingStore;
    else if (n > vertices() || (textured && n > tex()) || m_.records >= k.draws.size())
      want = Status::kCapacity;
    EXPECT_EQ(st, want) << to_string(st) << " for " << to_string(want) << ": " << describe(s)
                        << " n=" << n;
    m_.drew(st, c.triangles.size());
    expect_frame_counts();
  }

  // After each draw: the counts, and every triangle's outcome counted once (bands count theirs
  // at render()).
  void expect_frame_counts() {
    const FrameStats& s = r_->stats();
    m_.expect_counts(s);
    if (r_->front_end().needs_bands())
      EXPECT_LE(outcomes(s), s.triangles_in);
    else
      EXPECT_EQ(outcomes(s), s.triangles_in);
  }

  void render() {
    sink_.set_retain(d_.chance(50));
    const bool fail = d_.chance(10);
    const int strips = m_.configured ? (m_.height + K - 1) / K : 1;
    sink_.fail_at(fail ? static_cast<uint32_t>(d_.range(1, 2 * strips + 2)) : 0);
    CountingDepth depth;
    const bool with_depth = d_.chance(20);
    const FrameStats before = r_->stats();
    const auto calls = sink_.calls();
    const Status st = r_->render(sink_, with_depth ? &depth : nullptr);
    count(kRender, st);
    if (const Status order = m_.out_of_order(); order != Status::kOk) {
      EXPECT_EQ(st, order);
      EXPECT_TRUE(same(r_->stats(), before));
      EXPECT_EQ(sink_.calls().total(), calls.total());  // the sink was not called
      return;
    }
    m_.phase = Model::Phase::kRendered;
    const FrameStats& s = r_->stats();
    tally_.banded_frames += s.bands > 1 ? 1u : 0u;
    tally_.skipped_strips += s.strips_skipped;
    m_.expect_counts(s);
    EXPECT_EQ(sink_.calls().begin_frame, calls.begin_frame + 1);
    if (sink_.failed()) {
      EXPECT_EQ(st, Status::kDisplayError);
      return;
    }
    const bool dropped = s.dropped_vertex_capacity + s.dropped_triangle_capacity != 0;
    if (m_.first_refusal != Status::kOk) {
      EXPECT_EQ(st, m_.first_refusal);
    } else {
      EXPECT_TRUE(st == Status::kOk || st == Status::kCapacity) << to_string(st);
      EXPECT_EQ(st == Status::kCapacity, dropped) << to_string(st);
    }
    // The frame arrived whole: every strip sent or kept once, and counted.
    EXPECT_EQ(sink_.calls().end_frame, calls.end_frame + 1);
    EXPECT_EQ(sink_.faults(), 0u);
    EXPECT_EQ(s.strips, static_cast<uint32_t>(strips));
    EXPECT_EQ(sink_.submitted() + sink_.kept(), static_cast<uint32_t>(strips));
    EXPECT_EQ(s.strips_skipped, sink_.kept());
    if (with_depth) {
      EXPECT_EQ(depth.strips, static_cast<uint32_t>(strips));
    }
    // A frame binned once counts each triangle once; in bands, a drop in each band that had it.
    if (st == Status::kOk || s.bands <= 1)
      EXPECT_EQ(outcomes(s), s.triangles_in);
    else
      EXPECT_GE(outcomes(s), s.triangles_in);
    EXPECT_LE(s.pixels_written, s.pixels_tested);
    EXPECT_LE(s.max_active, stores_->active.size());
    EXPECT_LE(s.empty_strips, s.strips);
    if (s.pixels_written == 0 && sink_.kept() == 0) {
      // Nothing drawn: every pixel is the background.
      const auto bg = sink_.frame().empty() ? PF::Storage{} : sink_.frame()[0];
      for (const auto& p : sink_.frame()) ASSERT_EQ(std::memcmp(&p, &bg, sizeof p), 0);
    }
  }

  void count(Call c, Status st) { ++tally_.seen[c][static_cast<size_t>(st)]; }

  Dice d_;
  Tally& tally_;
  Model m_;
  // The last frame's inputs, to repeat; every draw's arrays, which must stay valid until
  // render() returns (a frame in bands reads them again): kept for the sequence, the last ones
  // repeated too.
  LightSet last_lights_;
  Camera last_camera_;
  Rgb8 last_background_{};
  std::vector<std::unique_ptr<MeshCall>> meshes_;
  std::vector<std::unique_ptr<ScreenCall>> screens_;
  std::unique_ptr<Stores> stores_ = std::make_unique<Stores>();
  std::unique_ptr<Renderer<PF, K, kSet>> r_ = std::make_unique<Renderer<PF, K, kSet>>();
  // One strip buffer as wide as any viewport these stores can be configured for.
  test::RecordingSink<PF> sink_{size_t{128} * K};
};

template <int K, SpanSet kSet>
Tally run_sequences(uint32_t first_seed, int count) {
  Tally tally;
  for (int i = 0; i < count && !::testing::Test::HasFailure(); ++i) {
    const uint32_t seed = first_seed + static_cast<uint32_t>(i);
    SCOPED_TRACE("seed " + std::to_string(seed));
    Sequence<K, kSet>(seed, tally).run();
  }
  if (std::getenv("LR_CALL_ORDER_TALLY") != nullptr) tally.print();
  // Every call out of order, every refusal and every render outcome was reached.
  for (Call c : {kBeginFrame, kDraw, kDrawScreen, kRender})
    EXPECT_GT(tally(c, Status::kNotConfigured), 0u) << kCallNames[c];
  for (Call c : {kDraw, kDrawScreen, kRender}) {
    EXPECT_GT(tally(c, Status::kNoFrame), 0u) << kCallNames[c];
    EXPECT_GT(tally(c, Status::kFrameRendered), 0u) << kCallNames[c];
    for (Status s :
         {Status::kOk, Status::kInvalidArgument, Status::kMissingStore, Status::kCapacity})
      EXPECT_GT(tally(c, s), 0u) << kCallNames[c] << " " << to_string(s);
  }
  for (Status s : {Status::kOk, Status::kInvalidArgument, Status::kStoreTooSmall})
    EXPECT_GT(tally(kConfigure, s), 0u) << to_string(s);
  EXPECT_GT(tally(kBeginFrame, Status::kInvalidArgument), 0u);
  EXPECT_GT(tally(kRender, Status::kDisplayError), 0u);
  const bool restricted = !kSet.has(SpanFamily::kTextured);
  EXPECT_EQ(tally(kDraw, Status::kNotLinked) > 0, restricted);
  EXPECT_GT(tally.banded_frames, 0u);
  EXPECT_GT(tally.skipped_strips, 0u);
  return tally;
}

TEST(CallOrder, RandomSequencesInStripsOfEight) {
  run_sequences<8, kAllSpans>(1, 2000);
}
TEST(CallOrder, RandomSequencesInStripsOfOne) {
  run_sequences<1, kAllSpans>(100001, 1000);
}
TEST(CallOrder, RandomSequencesWithoutTexturedOrPhongSpans) {
  run_sequences<8, kUntexturedSpans>(200001, 1000);
}

}  // namespace
}  // namespace lr
