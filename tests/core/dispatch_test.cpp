// Span dispatch: the state space (core/span/span_state.hpp), the routine tables generated from it,
// and renderers restricted to part of it.
//   - every state of the full set selects a non-null routine (and fetcher), distinct per state;
//     outside a restricted set every entry is nullptr;
//   - for every state of the enumeration, under the smallest set holding it: the set's tables
//     give the state the full set's routines, and the set's admission function takes it and
//     refuses other states and textures; likewise for every texel fetcher;
//   - for a sample of those states and fetchers (every value of every dimension among them), a
//     whole renderer restricted to the set draws the full renderer's frame bit for bit;
//   - per family, the routine does what its state says (depth, colour planes, filter, mip, the
//     Phong maps and lighting).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <set>
#include <utility>
#include <vector>

#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/span/admission.hpp"
#include "lineraster/core/span/span_state.hpp"
#include "lineraster/core/texture/mipmap.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"

namespace lr {
namespace {

using PF = Rgb888;
constexpr int kW = 32, kH = 32, kK = 8;

Fixed fx(double v) {
  return Fixed::from_raw(static_cast<int32_t>(std::lround(v * 65536.0)));
}

// ---- Assets ----------------------------------------------------------------------------------

// An RGB888 texture with its levels given texel by texel: rows of colours.
struct OwnedTexture {
  std::vector<std::vector<uint8_t>> bytes;
  std::vector<std::vector<uint16_t>> words;
  std::vector<uint16_t> palette;
  Texture tex;
};

// size x size, level l's texel (x, y) = f(l, x, y); a full chain when mips.
template <class F>
std::unique_ptr<OwnedTexture> make_texture(TexelFormat format, uint16_t size, bool mips, F f) {
  auto t = std::make_unique<OwnedTexture>();
  t->tex.format = format;
  if (format == TexelFormat::kPalette8)
    for (uint32_t i = 0; i < 256; ++i)  // index i: r = i's top 5 bits, g and b from i
      t->palette.push_back(static_cast<uint16_t>(((i >> 3) << 11) | ((i & 63u) << 5) | (i & 31u)));
  t->tex.palette = t->palette;
  int levels = mips ? mip_level_count(size, size) : 1;
  t->bytes.resize(static_cast<size_t>(levels));
  t->words.resize(static_cast<size_t>(levels));
  uint16_t s = size;
  for (int l = 0; l < levels; ++l) {
    auto& b = t->bytes[static_cast<size_t>(l)];
    auto& w = t->words[static_cast<size_t>(l)];
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x) {
        const Rgb8 c = f(l, x, y);
        switch (format) {
          case TexelFormat::kRgb888:
            b.insert(b.end(), {c.r, c.g, c.b});
            break;
          case TexelFormat::kRgb565:
            w.push_back(static_cast<uint16_t>(((c.r >> 3) << 11) | ((c.g >> 2) << 5) | (c.b >> 3)));
            break;
          case TexelFormat::kL8:
            b.push_back(c.g);
            break;
          case TexelFormat::kPalette8:
            b.push_back(c.r);
            break;
        }
      }
    TextureLevel& lv = t->tex.levels[static_cast<size_t>(l)];
    lv.width = lv.height = s;
    if (format == TexelFormat::kRgb565)
      lv.rgb565 = w;
    else
      lv.bytes = b;
    s = static_cast<uint16_t>(s > 1 ? s / 2 : 1);
  }
  t->tex.level_count = static_cast<uint8_t>(levels);
  return t;
}

// The sweep's texture: a 16 x 16 two-colour checker of 2-texel cells, each level of the chain
// its own pair of colours.
std::unique_ptr<OwnedTexture> checker(TexelFormat format) {
  return make_texture(format, 16, true, [](int l, int x, int y) {
    const bool on = ((x >> 1) + (y >> 1)) % 2 == 0;
    const auto k = static_cast<uint8_t>(40 * l);
    return on ? Rgb8{static_cast<uint8_t>(230 - k), 200, k}
              : Rgb8{k, 60, static_cast<uint8_t>(200 - k)};
  });
}

struct Assets {
  std::unique_ptr<OwnedTexture> texture = checker(TexelFormat::kRgb888);
  // Normals tilting across the map (RGB = (n + 1) / 2).
  std::unique_ptr<OwnedTexture> normal_map =
      make_texture(TexelFormat::kRgb888, 8, false, [](int, int x, int y) {
        return Rgb8{static_cast<uint8_t>(96 + 8 * x), static_cast<uint8_t>(96 + 8 * y), 230};
      });
  std::unique_ptr<OwnedTexture> envmap =
      make_texture(TexelFormat::kRgb888, 8, false, [](int, int x, int y) {
        return Rgb8{static_cast<uint8_t>(255 - 20 * x), static_cast<uint8_t>(100 + 15 * y), 180};
      });
};
const Texture& other_format_texture() {
  static const auto t = checker(TexelFormat::kRgb565);
  return t->tex;
}
const Assets& assets() {
  static const Assets a;
  return a;
}

// A unit square in the xy plane facing +z, with every attribute.
struct Quad {
  std::array<Vec3, 4> positions;
  std::array<Normal16, 4> normals;
  std::array<Rgb8, 4> colors;
  std::array<TexCoord, 4> uvs;
  std::array<Tangent16, 4> tangents;
  std::array<std::array<uint16_t, 3>, 2> triangles{{{0, 1, 2}, {0, 2, 3}}};
  Quad(std::array<Rgb8, 4> c, double uv_scale) : colors(c) {
    const double xs[4] = {-1, 1, 1, -1}, ys[4] = {-1, -1, 1, 1};
    for (size_t i = 0; i < 4; ++i) {
      positions[i] = {fx(xs[i]), fx(ys[i]), fx(0)};
      normals[i] = {0, 0, 16384};
      uvs[i] = {static_cast<int32_t>((xs[i] + 1) / 2 * uv_scale * (1 << 20)),
                static_cast<int32_t>((ys[i] + 1) / 2 * uv_scale * (1 << 20))};
      tangents[i] = {16384, 0, 0, 16384};
    }
  }
  Mesh mesh() const { return {positions, normals, colors, uvs, triangles, tangents}; }
};

Camera camera() {
  Camera c;  // at the origin looking down -z
  EXPECT_TRUE(perspective(Fixed::from_double(60), Fixed::from_int(1), Fixed::from_double(0.5),
                          Fixed::from_double(20), c.projection));
  return c;
}

Mat4 place(double x, double y, double z, double rx, double ry) {
  return translate({fx(x), fx(y), fx(z)}) * rotate_x(fx(rx)) * rotate_y(fx(ry));
}

// ---- A renderer with its storage -------------------------------------------------------------

// Storage and display (no template: compiled once); Rig<kSet> adds the renderer.
class RigBase {
 public:
  virtual ~RigBase() = default;
  FrontEnd& r() { return *builder_; }
  // Whether its front end checks textured and Phong draws' maps (FrontEndRoutines::maps:
  // a renderer with textured or Phong spans; the others refuse those draws, kNotLinked, before
  // any check of their maps).
  virtual bool checks_maps() const { return true; }
  // want: what render() returns (a frame with a refused draw: the refusal's status).
  host::ImageRgb8 render(Status want = Status::kOk) {
    EXPECT_EQ(render_frame(), want);
    return display_.image();
  }

 protected:
  RigBase()
      : store_(FrameCapacities{.width = kW,
                               .height = kH,
                               .strip_height = kK,
                               .vertices = 256,
                               .triangles = 256,
                               .draws = 8,
                               .active = 64,
                               .surfaces = 256,
                               .lighting_table_words = 4 * lighting_table_words(32, true),
                               .pixel_lights = 8,
                               .tex_vertices = 256,
                               .active_extra = 64,
                               .triangle_colors = 256}),
        display_(kW * kK) {}
  FrameStorage storage() { return store_.storage(); }
  virtual Status render_frame() = 0;

  BasicFrameStorage<std::vector> store_;
  host::CaptureDisplay<PF> display_;
  FrontEnd* builder_ = nullptr;
};

template <SpanSet kSet>
class Rig final : public RigBase {
 public:
  Rig() : renderer_(std::make_unique<Renderer<PF, kK, kSet>>()) {
    builder_ = &renderer_->front_end();
    EXPECT_EQ(renderer_->configure(storage(), kW, kH), Status::kOk);
  }
  bool checks_maps() const override {
    return kSet.has(SpanFamily::kTextured) || kSet.has(SpanFamily::kPhong);
  }

 private:
  Status render_frame() override { return renderer_->render(display_); }
  std::unique_ptr<Renderer<PF, kK, kSet>> renderer_;
};

// A front end that admits what `admit` admits, rendering through the full strip loop: the
// admission of a restricted renderer without its tables (no template: compiled once).
class AdmitRig final : public RigBase {
 public:
  explicit AdmitRig(AdmitFn admit, PhongRecordFn phong = &DrawRecords::phong_record)
      : routines_{.admit = admit, .phong = phong} {
    builder_ = &front_;
    EXPECT_EQ(strip_.configure(storage().strip_loop(), kW), Status::kOk);
    EXPECT_EQ(front_.configure(storage().front_end(), kW, kH, kK, &routines_), Status::kOk);
  }

 private:
  // What Renderer::render does around the strip loop (a frame that fits: one band).
  Status render_frame() override {
    if (const Status open = front_.frame_status(); open != Status::kOk) return open;
    front_.end_frame();
    const Status st = strip_.render(front_.frame(), front_.mutable_stats(), display_, nullptr);
    return st == Status::kOk ? front_.refused() : st;
  }
  FrontEndRoutines routines_;  // (the front end keeps its address)
  FrontEnd front_;
  StripLoop<PF, kK> strip_;
};

// ---- The scene of a state --------------------------------------------------------------------

// The draw state, lights and material that select `s` (the inverse of span_state_of,
// core/span/admission.hpp).
struct DrawSetup {
  DrawState state;
  LightSet lights;
  Material material;
};

DrawSetup setup_for(const SpanState& s, const Assets& a) {
  DrawSetup u;
  DrawState& d = u.state;
  d.depth_test = s.depth;
  d.cull = Cull::kNone;
  u.lights.count = 1;
  u.lights.lights[0].position = {Fixed::from_double(0.3), Fixed::from_double(0.5),
                                 Fixed::from_double(1)};
  u.lights.global_ambient = {3000, 3000, 3000};
  u.material.specular = {20000, 20000, 20000};
  u.material.shininess_q8 = 20 << 8;
  switch (s.family) {
    case SpanFamily::kUntextured:
      d.lighting = false;  // the quads' vertex colours
      d.shading = s.colors == ColorPlanes::kNone ? Shading::kFlat : Shading::kGouraud;
      d.perspective = s.colors == ColorPlanes::kAffine ? Perspective::kAffine : Perspective::kExact;
      break;
    case SpanFamily::kTextured:
      d.lighting = false;  // modulated by the vertex colours
      d.perspective = s.persp == TexPersp::kExact    ? Perspective::kExact
                      : s.persp == TexPersp::kAffine ? Perspective::kAffine
                                                     : Perspective::kSpan8;
      d.texture = &a.texture->tex;
      d.sampler = {s.filter, Wrap::kRepeat, Wrap::kRepeat, s.mip, s.env};
      break;
    case SpanFamily::kPhong:
      d.lighting = true;
      d.shading = Shading::kPhong;
      d.pixel_lighting = s.method;
      d.table = {16, s.table_bilinear};
      if (s.position) {  // a point light near the quads
        u.lights.lights[0].kind = LightKind::kPoint;
        u.lights.lights[0].position = {Fixed::from_double(0.2), Fixed::from_double(0.3),
                                       Fixed::from_double(-1.5)};
      }
      d.texture = s.texture ? &a.texture->tex : nullptr;
      d.normal_map = s.normal_map ? &a.normal_map->tex : nullptr;
      d.envmap = s.envmap ? &a.envmap->tex : nullptr;
      d.sampler = {s.filter, Wrap::kRepeat, Wrap::kRepeat, s.mip, TexEnv::kModulate};
      break;
  }
  return u;
}

const Quad& near_quad() {
  static const Quad q({Rgb8{255, 40, 40}, Rgb8{40, 255, 40}, Rgb8{40, 40, 255}, Rgb8{255, 255, 40}},
                      3.0);
  return q;
}
const Quad& far_quad() {
  static const Quad q(
      {Rgb8{40, 200, 200}, Rgb8{200, 40, 200}, Rgb8{200, 200, 40}, Rgb8{90, 90, 90}}, 5.0);
  return q;
}

// Two quads, the nearer drawn first and overlapping the farther: the depth test decides the
// overlap. Both tilted (perspective matters), the far one minified.
Status draw_scene(RigBase& rig, const DrawSetup& u, bool near = true, bool far = true) {
  Status st = rig.r().begin_frame(camera(), u.lights, Rgb8{8, 8, 8});
  if (st != Status::kOk) return st;
  if (near)
    st = rig.r().draw(near_quad().mesh(), place(-0.25, -0.2, -3.0, -50, 20), u.material, u.state);
  if (st != Status::kOk || !far) return st;
  return rig.r().draw(far_quad().mesh(), place(0.4, 0.3, -4.5, -20, -30), u.material, u.state);
}

constexpr SpanSet restricted(const SpanState& s) {
  return span_set_of(s).only(TexelFormat::kRgb888).only_wraps(Wrap::kRepeat, Wrap::kRepeat);
}

bool is_fg(const host::ImageRgb8& img, size_t p) {
  return img.rgb[3 * p] != 8 || img.rgb[3 * p + 1] != 8 || img.rgb[3 * p + 2] != 8;
}
int count_fg(const host::ImageRgb8& img) {
  int n = 0;
  for (size_t p = 0; p < img.rgb.size() / 3; ++p) n += is_fg(img, p) ? 1 : 0;
  return n;
}
Rgb8 pixel(const host::ImageRgb8& img, size_t p) {
  return {img.rgb[3 * p], img.rgb[3 * p + 1], img.rgb[3 * p + 2]};
}

constexpr SpanState first_state(SpanFamily f) {
  for (const SpanState& s : kSpanStates)
    if (s.family == f) return s;
  return {};
}

// ---- (a) The tables ----------------------------------------------------------------------------

template <class T, size_t N>
bool all_null(const std::array<T, N>& a) {
  for (T p : a)
    if (p != nullptr) return false;
  return true;
}

// admits<kSet> of a set of untextured spans only (its short form, without span_state_of)
// answers as draw_admitted(kSet, ...) for every depth test, shading, perspective, lighting,
// texture and draw kind.
template <SpanSet kSet>
void expect_admits_as_draw_admitted() {
  static_assert(kSet.families == detail::bit(SpanFamily::kUntextured));
  static const Texture texture{};  // (only its presence is read: the set has no textured spans)
  int admitted = 0;
  for (const bool depth : {false, true})
    for (const Shading shading : {Shading::kFlat, Shading::kGouraud, Shading::kPhong})
      for (const Perspective persp : {Perspective::kExact, Perspective::kAffine})
        for (const bool textured : {false, true})
          for (const bool phong : {false, true})
            for (const bool planes : {false, true}) {
              DrawState st;
              st.depth_test = depth;
              st.shading = shading;
              st.perspective = persp;
              st.texture = textured ? &texture : nullptr;
              const DrawKind kind{phong, planes, false};
              const bool want = draw_admitted(kSet, st, kind);
              EXPECT_EQ(admits<kSet>(st, kind), want)
                  << "depth " << depth << " shading " << static_cast<int>(shading)
                  << " perspective " << static_cast<int>(persp) << " textured " << textured
                  << " phong " << phong << " planes " << planes;
              admitted += want ? 1 : 0;
            }
  EXPECT_GT(admitted, 0);
}

TEST(SpanDispatch, AnUntexturedSetAdmitsAsDrawAdmitted) {
  expect_admits_as_draw_admitted<kUntexturedSpans>();
  expect_admits_as_draw_admitted<kUntexturedSpans.only_depth(true)>();
  expect_admits_as_draw_admitted<kUntexturedSpans.only(ColorPlanes::kPerspective)>();
  expect_admits_as_draw_admitted<kUntexturedSpans.only(ColorPlanes::kNone).only_depth(false)>();
}

TEST(SpanDispatch, TheEnumerationCoversEveryFamilyOnceAndTheFullSetAdmitsIt) {
  EXPECT_EQ(kSpanStateCount, 6u + 72u + 240u);
  for (size_t i = 0; i < kSpanStateCount; ++i) {
    EXPECT_TRUE(kAllSpans.admits(kSpanStates[i])) << i;
    EXPECT_TRUE(span_set_of(kSpanStates[i]).admits(kSpanStates[i])) << i;
    for (size_t j = 0; j < i; ++j) EXPECT_FALSE(kSpanStates[i] == kSpanStates[j]) << i << " " << j;
  }
}

// A set's routine tables, their entries as addresses.
struct Tables {
  std::array<const void*, 2 * kUntexturedKinds> untextured{};  // the row loops
  std::array<const void*, kTexturedRoutines> textured{};
  std::array<const void*, kPhongRoutines> phong{};
  std::array<const void*, kFetchRoutines> fetch{};
  std::array<const void*, kEnvFetchRoutines> env_fetch{};
  friend bool operator==(const Tables&, const Tables&) = default;
};

template <class Fn, size_t N>
std::array<const void*, N> addresses(const std::array<Fn, N>& table) {
  std::array<const void*, N> a{};
  for (size_t i = 0; i < N; ++i) a[i] = reinterpret_cast<const void*>(table[i]);
  return a;
}

template <SpanSet kSet>
Tables tables_of() {
  return {addresses(kUntexturedRowTable<PF, kSet>), addresses(kTexSpanTable<PF, kSet>),
          addresses(kPhongSpanTable<PF, kSet>), addresses(kFetchTable<kSet>),
          addresses(kEnvFetchTable<kSet>)};
}

// The tables of a set as their builder (make_table, core/span/dispatch.hpp) fills them from the
// entries the set uses (used_routines): the full table's entry where used, nullptr elsewhere.
// Not a template: a set's tables without instantiating them.
Tables tables_using(const UsedRoutines& used) {
  Tables t = tables_of<kAllSpans>();
  auto keep = [](auto& entries, const auto& flags) {
    for (size_t i = 0; i < entries.size(); ++i)
      if (!flags[i]) entries[i] = nullptr;
  };
  for (size_t i = 0; i < t.untextured.size(); ++i)
    if (!untextured_row_used<PF>(used, i)) t.untextured[i] = nullptr;
  keep(t.textured, used.textured);
  keep(t.phong, used.phong);
  keep(t.fetch, used.fetch);
  keep(t.env_fetch, used.env_fetch);
  return t;
}

// What a state runs with under a set's tables: the span routine and its fetcher(s), for
// textures of format f that repeat.
std::array<const void*, 3> routines_in(const Tables& t, const SpanState& s, TexelFormat f) {
  std::array<const void*, 3> r{};
  switch (s.family) {
    case SpanFamily::kUntextured:
      r[0] = t.untextured[untextured_row_index(s.depth, primary_kind<PF>(s.colors))];
      break;
    case SpanFamily::kTextured:
      r[0] = t.textured[textured_index(s.depth, s.persp, s.env, s.mip)];
      r[1] = t.fetch[fetch_index(f, s.filter, Wrap::kRepeat, Wrap::kRepeat)];
      break;
    case SpanFamily::kPhong:
      r[0] = t.phong[phong_index(s.depth, s.method, s.position || s.table_bilinear, s.texture,
                                 s.normal_map, s.envmap)];
      if (s.texture || s.normal_map)
        r[1] = t.fetch[fetch_index(f, s.filter, Wrap::kRepeat, Wrap::kRepeat)];
      if (s.envmap) r[2] = t.env_fetch[env_fetch_index(f)];
      break;
  }
  return r;
}

template <SpanSet kSet>
std::array<const void*, 3> routines_of(const SpanState& s, TexelFormat f) {
  return routines_in(tables_of<kSet>(), s, f);
}

TEST(SpanDispatch, EveryStateOfTheFullSetHasItsOwnNonNullRoutines) {
  std::set<std::array<const void*, 3>> seen;
  for (const SpanState& s : kSpanStates) {
    // The mip mode of a Phong draw is a per-chunk choice inside its routine, not an instance.
    if (s.family == SpanFamily::kPhong && s.mip != MipMode::kNone) continue;
    const auto r = routines_of<kAllSpans>(s, TexelFormat::kRgb888);
    EXPECT_NE(r[0], nullptr);
    if (s.family == SpanFamily::kTextured || s.texture || s.normal_map) {
      EXPECT_NE(r[1], nullptr);
    }
    if (s.envmap) {
      EXPECT_NE(r[2], nullptr);
    }
    EXPECT_TRUE(seen.insert(r).second) << "two states share their routines";
  }
  // Every instance of each table, every fetcher: non-null and distinct.
  std::set<const void*> all;
  for (auto p : kUntexturedRowTable<PF>)  // Rgb888: no lanes kind
    if (p != nullptr) all.insert(reinterpret_cast<const void*>(p));
  for (auto p : kTexSpanTable<PF>) all.insert(reinterpret_cast<const void*>(p));
  for (auto p : kPhongSpanTable<PF>) all.insert(reinterpret_cast<const void*>(p));
  for (auto p : kFetchTable<>) all.insert(reinterpret_cast<const void*>(p));
  for (auto p : kEnvFetchTable<>) all.insert(reinterpret_cast<const void*>(p));
  EXPECT_EQ(all.size(), 2 * (kUntexturedKinds - 1) + kTexturedRoutines + kPhongRoutines +
                            kFetchRoutines);  // environment maps use 4 of the fetchers
  EXPECT_EQ(all.count(nullptr), 0u);
}

// The helpers restrict one dimension each; a product set over two families is exact per family,
// while the union of two sets is the smallest product set holding both (it may hold more).
constexpr SpanSet kPhongPlain = kPhongOnly.only_depth(true)
                                    .only(PixelLighting::kExact)
                                    .only_position(false)
                                    .only_maps(false, false, false);
static_assert(kPhongPlain.admits([] {
  SpanState s = first_state(SpanFamily::kPhong);  // exact, no maps, no position planes
  s.depth = true;
  return s;
}()));
static_assert(!kPhongOnly.only_table_filter(Filter::kNearest).admits([] {
  SpanState s = first_state(SpanFamily::kPhong);
  s.method = PixelLighting::kTable;
  s.table_bilinear = true;
  return s;
}()));
static_assert(!kPhongPlain.admits([] {
  SpanState s = first_state(SpanFamily::kPhong);
  s.envmap = true;
  return s;
}()));
static_assert((kUntexturedSpans.only(ColorPlanes::kAffine) | kTexturedOnly)
                  .admits(SpanState{SpanFamily::kUntextured, true, ColorPlanes::kNone}));
static_assert(!kTexturedSpans.only(ColorPlanes::kAffine)
                   .admits(SpanState{SpanFamily::kUntextured, true, ColorPlanes::kNone}));

constexpr SpanSet kNearestNoMipExact =
    kTexturedSpans.only(Filter::kNearest).only(MipMode::kNone).only(PixelLighting::kExact);

TEST(SpanDispatch, StatesOutsideARestrictedSetHaveNoRoutine) {
  constexpr SpanSet kSet = kNearestNoMipExact;
  for (const SpanState& s : kSpanStates) {
    const auto r = routines_of<kSet>(s, TexelFormat::kRgb888);
    if (kSet.admits(s)) {
      EXPECT_NE(r[0], nullptr);
    } else if (s.family == SpanFamily::kTextured) {
      // The span routine serves both filters: a bilinear state lacks its fetcher.
      EXPECT_TRUE(r[0] == nullptr || r[1] == nullptr);
    } else {
      EXPECT_EQ(r[0], nullptr);
    }
  }
  EXPECT_TRUE(all_null(kPhongSpanTable<PF, kSet>));
  EXPECT_TRUE(all_null(kEnvFetchTable<kSet>));
  EXPECT_TRUE(all_null(kPhongSpanTable<PF, kUntexturedSpans>));
  EXPECT_TRUE(all_null(kTexSpanTable<PF, kUntexturedSpans>));
  EXPECT_TRUE(all_null(kFetchTable<kUntexturedSpans>));
  EXPECT_FALSE(kUsedRoutines<kUntexturedSpans>.any_fetch());
  // A set that admits no texture format can draw no textured state: no routine either.
  constexpr SpanSet kNoFormat = [] {
    SpanSet set = kTexturedOnly;
    set.formats = 0;
    return set;
  }();
  EXPECT_TRUE(all_null(kTexSpanTable<PF, kNoFormat>));
  EXPECT_TRUE(all_null(kFetchTable<kNoFormat>));
  // Nearest only: exactly the 16 nearest fetchers (4 formats x 4 wraps), the 12 no-mip routines.
  int fetchers = 0, tex = 0;
  for (size_t i = 0; i < kFetchRoutines; ++i)
    if (kFetchTable<kSet>[i] != nullptr) {
      ++fetchers;
      EXPECT_EQ(FetchLayout::field<2>(i), Filter::kNearest)
          << "a bilinear fetcher in a nearest-only set";
    }
  for (auto p : kTexSpanTable<PF, kSet>) tex += p != nullptr ? 1 : 0;
  EXPECT_EQ(fetchers, 16);
  EXPECT_EQ(tex, 12);
}

// ---- (b) Every state under the smallest set holding it ----------------------------------------
//
// A renderer restricted to a set differs from the full one in its routine tables and in its
// front end's admission function (admits<kSet>). Its tables are make_table's: the full table's
// entry where used_routines(kSet) marks it used, nullptr elsewhere. For every state, with the
// set restricted(state): the tables so derived from the set (tables_using, computed at run time,
// since instantiating every set's tables is costly to compile) give the state the full set's
// routines, and a front end admitting only the set (drawing through the full strip loop) takes
// the state, draws the full renderer's frame and refuses other states and textures. Whole
// restricted renderers, whose tables must equal the derived ones entry for entry, draw end to
// end for a sample: every untextured state, and textured and Phong states that between them
// take every value of each dimension of their family.

// State I of the enumeration with `small`, a renderer restricted to restricted(state) or a front
// end admitting only that set.
void check_state_with(size_t I, RigBase& small) {
  const SpanState& state = kSpanStates[I];
  const Assets& a = assets();
  const DrawSetup u = setup_for(state, a);
  Rig<kAllSpans> full;
  ASSERT_EQ(draw_scene(full, u), Status::kOk) << "state " << I;
  ASSERT_EQ(draw_scene(small, u), Status::kOk) << "state " << I << ": refused by its own set";
  const host::ImageRgb8 want = full.render();
  const host::ImageRgb8 got = small.render();
  EXPECT_GT(count_fg(want), 100) << "state " << I;
  EXPECT_TRUE(want.rgb == got.rgb) << "state " << I << ": frames differ";

  // Other states are refused, with nothing added and only the draws counted: kNotLinked where
  // the full set takes the draw (a state whose arguments the quad does not meet, a normal map
  // without tangents, is kInvalidArgument in both, but kNotLinked where the small one checks no
  // maps: a renderer without textured and Phong spans).
  ASSERT_EQ(draw_scene(small, u), Status::kOk);
  ASSERT_EQ(draw_scene(full, u), Status::kOk);
  const FrameStats before = small.r().stats();
  uint32_t not_linked = 0;
  Status first_refusal = Status::kOk;
  for (size_t j : {(I + 1) % kSpanStateCount, (I + kSpanStateCount / 2) % kSpanStateCount,
                   (I + 7) % kSpanStateCount}) {
    const DrawSetup v = setup_for(kSpanStates[j], a);
    const Status in_full =
        full.r().draw(near_quad().mesh(), place(0, 0, -3, 0, 0), v.material, v.state);
    ASSERT_TRUE(in_full == Status::kOk || in_full == Status::kInvalidArgument) << "state " << j;
    const bool maps = kSpanStates[j].family != SpanFamily::kUntextured;  // textured or Phong
    const Status refusal =
        in_full == Status::kOk || (maps && !small.checks_maps()) ? Status::kNotLinked : in_full;
    EXPECT_EQ(small.r().draw(near_quad().mesh(), place(0, 0, -3, 0, 0), v.material, v.state),
              refusal)
        << "state " << I << " admitted state " << j;
    not_linked += refusal == Status::kNotLinked ? 1u : 0u;
    if (first_refusal == Status::kOk) first_refusal = refusal;
  }
  // The same state with a texture of another format, or another wrap, is refused too.
  if (state.family == SpanFamily::kTextured || state.texture) {
    DrawState s = u.state;
    s.texture = &other_format_texture();
    EXPECT_EQ(small.r().draw(near_quad().mesh(), place(0, 0, -3, 0, 0), u.material, s),
              Status::kNotLinked);
    s = u.state;
    s.sampler.wrap_t = Wrap::kClampToEdge;
    EXPECT_EQ(small.r().draw(near_quad().mesh(), place(0, 0, -3, 0, 0), u.material, s),
              Status::kNotLinked);
  }
  const FrameStats& after = small.r().stats();
  EXPECT_EQ(after.triangles_in, before.triangles_in);
  EXPECT_EQ(after.triangles_binned, before.triangles_binned);
  EXPECT_EQ(after.vertices_transformed, before.vertices_transformed);
  EXPECT_EQ(after.draws_refused_not_linked - before.draws_refused_not_linked,
            not_linked + (state.family == SpanFamily::kTextured || state.texture ? 2u : 0u));
  EXPECT_EQ(after.draws_refused_invalid - before.draws_refused_invalid, 3u - not_linked);
  EXPECT_TRUE(small.render(first_refusal).rgb == got.rgb) << "state " << I;
}

// The admission function of restricted(state), per state of the enumeration.
template <size_t... I>
constexpr std::array<AdmitFn, sizeof...(I)> restricted_admits(
    std::index_sequence<I...> /*states*/) {
  return {&admits<restricted(kSpanStates[I])>...};
}
constexpr auto kRestrictedAdmits = restricted_admits(std::make_index_sequence<kSpanStateCount>{});

TEST(SpanDispatch, EveryStateOfARestrictedSetRunsTheFullSetsRoutinesAndRefusesOthers) {
  const Tables full = tables_of<kAllSpans>();
  for (size_t i = 0; i < kSpanStateCount; ++i) {
    const SpanState& s = kSpanStates[i];
    const Tables small_tables = tables_using(used_routines(restricted(s)));
    EXPECT_EQ(routines_in(small_tables, s, TexelFormat::kRgb888),
              routines_in(full, s, TexelFormat::kRgb888))
        << "state " << i;
    AdmitRig small(kRestrictedAdmits[i]);
    check_state_with(i, small);
  }
}

// The sample drawn by whole restricted renderers, and what it must cover.
constexpr size_t first_index(SpanFamily f) {
  for (size_t i = 0; i < kSpanStateCount; ++i)
    if (kSpanStates[i].family == f) return i;
  return kSpanStateCount;
}
constexpr size_t state_count(SpanFamily f) {
  size_t n = 0;
  for (const SpanState& s : kSpanStates) n += s.family == f ? 1 : 0;
  return n;
}

// Every untextured state, then kSampled textured and kSampled Phong states at a stride through
// their family's part of the enumeration.
constexpr size_t kSampled = 10, kTexturedStride = 7, kPhongStride = 23;
constexpr auto kSampledStates = [] {
  std::array<size_t, state_count(SpanFamily::kUntextured) + 2 * kSampled> a{};
  size_t n = 0;
  for (size_t i = 0; i < state_count(SpanFamily::kUntextured); ++i)
    a[n++] = first_index(SpanFamily::kUntextured) + i;
  for (size_t k = 0; k < kSampled; ++k)
    a[n++] = first_index(SpanFamily::kTextured) +
             k * kTexturedStride % state_count(SpanFamily::kTextured);
  for (size_t k = 0; k < kSampled; ++k)
    a[n++] = first_index(SpanFamily::kPhong) + k * kPhongStride % state_count(SpanFamily::kPhong);
  return a;
}();

constexpr SpanSet kNoValues{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};

// The values a state's routines are chosen by: span_set_of's bits for the dimensions that apply
// to its family (and to its maps), every other mask empty.
constexpr SpanSet values_of(const SpanState& s) {
  const SpanSet all = span_set_of(s);
  SpanSet v = kNoValues;
  v.families = all.families;
  v.depth = all.depth;
  switch (s.family) {
    case SpanFamily::kUntextured:
      v.colors = all.colors;
      break;
    case SpanFamily::kTextured:
      v.persp = all.persp;
      v.env = all.env;
      v.mip = all.mip;
      v.filter = all.filter;
      break;
    case SpanFamily::kPhong:
      v.method = all.method;
      if (s.method == PixelLighting::kExact)
        v.position = all.position;
      else
        v.table_filter = all.table_filter;
      v.texture = all.texture;
      v.normal_map = all.normal_map;
      v.envmap = all.envmap;
      if (s.texture || s.normal_map) v.filter = all.filter;
      if (s.texture) v.mip = all.mip;
      break;
  }
  return v;
}

// Whether the sampled states of family f take every value its states take, dimension by
// dimension, and are distinct states of f.
constexpr bool sample_covers(SpanFamily f) {
  SpanSet want = kNoValues, got = kNoValues;
  for (const SpanState& s : kSpanStates)
    if (s.family == f) want = want | values_of(s);
  size_t n = 0;
  for (size_t k = 0; k < kSampledStates.size(); ++k) {
    const size_t i = kSampledStates[k];
    if (i >= kSpanStateCount) return false;
    for (size_t l = 0; l < k; ++l)
      if (kSampledStates[l] == i) return false;
    if (kSpanStates[i].family != f) continue;
    ++n;
    got = got | values_of(kSpanStates[i]);
  }
  return n > 0 && got == want;
}
static_assert(sample_covers(SpanFamily::kUntextured) && sample_covers(SpanFamily::kTextured) &&
              sample_covers(SpanFamily::kPhong));

// State I with a whole renderer restricted to it, whose tables are those the all-states test
// derives from the set's used entries.
template <size_t I>
void check_state() {
  constexpr SpanSet kSet = restricted(kSpanStates[I]);
  EXPECT_TRUE(tables_of<kSet>() == tables_using(used_routines(kSet))) << "state " << I;
  EXPECT_EQ(routines_of<kSet>(kSpanStates[I], TexelFormat::kRgb888),
            routines_of<kAllSpans>(kSpanStates[I], TexelFormat::kRgb888))
      << "state " << I;
  Rig<kSet> small;
  check_state_with(I, small);
}

template <size_t... K>
void check_sampled_states(std::index_sequence<K...> /*sample*/) {
  (check_state<kSampledStates[K]>(), ...);
}

TEST(SpanDispatch, SampledRestrictedRenderersDrawTheFullRenderersFrame) {
  check_sampled_states(std::make_index_sequence<kSampledStates.size()>{});
}

// A front end without Phong records (what a renderer without Phong spans configures, so that it
// links no lighting tables) refuses Phong draws, adding and counting nothing, and draws the
// other families' frames.
TEST(SpanDispatch, AFrontEndWithoutPhongRecordsRefusesPhongDrawsOnly) {
  const Assets& a = assets();
  AdmitRig without(nullptr, nullptr);
  for (SpanFamily f : {SpanFamily::kUntextured, SpanFamily::kTextured}) {
    const DrawSetup u = setup_for(first_state(f), a);
    AdmitRig with(nullptr);
    ASSERT_EQ(draw_scene(with, u), Status::kOk);
    ASSERT_EQ(draw_scene(without, u), Status::kOk);
    const host::ImageRgb8 want = with.render();
    EXPECT_GT(count_fg(want), 100);
    EXPECT_TRUE(without.render().rgb == want.rgb) << "family " << static_cast<int>(f);
  }
  const DrawSetup p = setup_for(first_state(SpanFamily::kPhong), a);
  ASSERT_EQ(draw_scene(without, p, true, false), Status::kNotLinked);
  const FrameStats& s = without.r().stats();
  EXPECT_EQ(s.triangles_in, 0u);
  EXPECT_EQ(s.vertices_transformed, 0u);
  EXPECT_EQ(s.draws_refused_not_linked, 1u);
  EXPECT_EQ(count_fg(without.render(Status::kNotLinked)), 0);
  AdmitRig with(nullptr);
  ASSERT_EQ(draw_scene(with, p), Status::kOk);
  EXPECT_GT(count_fg(with.render()), 100);
}

// ---- (c) Each family's routine does what its state says ---------------------------------------

// Depth on: where the quads overlap, the nearer (drawn first) stays; off: the farther (drawn
// last) covers it. Compared pixel for pixel with frames of each quad alone.
TEST(SpanDispatch, DepthOffDrawsTheHiddenQuadOverInEveryFamily) {
  for (SpanFamily f : {SpanFamily::kUntextured, SpanFamily::kTextured, SpanFamily::kPhong}) {
    SpanState s = first_state(f);
    if (f == SpanFamily::kUntextured) s.colors = ColorPlanes::kPerspective;
    for (bool depth : {true, false}) {
      s.depth = depth;
      const DrawSetup u = setup_for(s, assets());
      Rig<kAllSpans> rig;
      ASSERT_EQ(draw_scene(rig, u, true, false), Status::kOk);
      const host::ImageRgb8 near_only = rig.render();
      ASSERT_EQ(draw_scene(rig, u, false, true), Status::kOk);
      const host::ImageRgb8 far_only = rig.render();
      ASSERT_EQ(draw_scene(rig, u), Status::kOk);
      const host::ImageRgb8 both = rig.render();
      int overlap = 0, differ = 0;
      for (size_t p = 0; p < size_t{kW} * kH; ++p) {
        if (!is_fg(near_only, p) || !is_fg(far_only, p)) continue;
        ++overlap;
        differ += pixel(near_only, p) == pixel(far_only, p) ? 0 : 1;
        const Rgb8 want = depth ? pixel(near_only, p) : pixel(far_only, p);
        EXPECT_EQ(pixel(both, p), want)
            << "family " << static_cast<int>(f) << " depth " << depth << " pixel " << p;
      }
      EXPECT_GT(overlap, 30);
      EXPECT_GT(differ, overlap / 2);  // the two quads tell apart
    }
  }
}

// A single quad with kAllSpans.
host::ImageRgb8 render_quad(const DrawSetup& u, const Quad& q, const Mat4& model) {
  Rig<kAllSpans> rig;
  EXPECT_EQ(rig.r().begin_frame(camera(), u.lights, Rgb8{8, 8, 8}), Status::kOk);
  EXPECT_EQ(rig.r().draw(q.mesh(), model, u.material, u.state), Status::kOk);
  return rig.render();
}

struct Diff {
  int covered = 0, max = 0;
  double mean = 0;
};
// Over the pixels both frames cover (and the coverage must be the same).
Diff diff(const host::ImageRgb8& a, const host::ImageRgb8& b) {
  Diff d;
  long sum = 0;
  for (size_t p = 0; p < size_t{kW} * kH; ++p) {
    EXPECT_EQ(is_fg(a, p), is_fg(b, p)) << p;
    if (!is_fg(a, p) || !is_fg(b, p)) continue;
    ++d.covered;
    for (size_t c = 0; c < 3; ++c) {
      const int e = std::abs(int{a.rgb[3 * p + c]} - int{b.rgb[3 * p + c]});
      d.max = std::max(d.max, e);
      sum += e;
    }
  }
  d.mean = d.covered ? static_cast<double>(sum) / (3.0 * d.covered) : 0;
  return d;
}

// A quad tilted away from the viewer, black along its near edge, white along its far edge.
TEST(SpanDispatch, AffineColoursDifferFromPerspectiveOnATiltedQuad) {
  const Quad q({Rgb8{0, 0, 0}, Rgb8{0, 0, 0}, Rgb8{255, 255, 255}, Rgb8{255, 255, 255}}, 1.0);
  const Mat4 model = place(0, -0.3, -2.2, -70, 0);
  SpanState s = first_state(SpanFamily::kUntextured);
  s.colors = ColorPlanes::kPerspective;
  const host::ImageRgb8 persp = render_quad(setup_for(s, assets()), q, model);
  s.colors = ColorPlanes::kAffine;
  const host::ImageRgb8 affine = render_quad(setup_for(s, assets()), q, model);
  s.colors = ColorPlanes::kNone;  // flat: the last vertex's colour, white
  const host::ImageRgb8 flat = render_quad(setup_for(s, assets()), q, model);
  const Diff d = diff(persp, affine);
  EXPECT_GT(d.covered, 150);
  EXPECT_GE(d.max, 16);
  EXPECT_GE(d.mean, 3.0);
  for (size_t p = 0; p < size_t{kW} * kH; ++p)
    if (is_fg(flat, p)) {
      EXPECT_EQ(pixel(flat, p), (Rgb8{255, 255, 255})) << p;
    }
}

// Unlit, the texel alone (replace), a quad facing the viewer.
DrawSetup replace_setup(const Texture& tex, Filter filter, MipMode mip, TexPersp persp) {
  SpanState s = first_state(SpanFamily::kTextured);
  s.env = TexEnv::kReplace;
  s.filter = filter;
  s.mip = mip;
  s.persp = persp;
  DrawSetup u = setup_for(s, assets());
  u.state.texture = &tex;
  return u;
}

TEST(SpanDispatch, NearestAndBilinearDifferOnAMagnifiedTexture) {
  // 4 x 4 black and white checker over about 20 x 20 pixels.
  const auto tex = make_texture(TexelFormat::kRgb888, 4, false, [](int, int x, int y) {
    const uint8_t v = (x + y) % 2 == 0 ? 255 : 0;
    return Rgb8{v, v, v};
  });
  const Quad q({}, 1.0);
  const Mat4 model = place(0, 0, -3, 0, 0);
  const host::ImageRgb8 nearest = render_quad(
      replace_setup(tex->tex, Filter::kNearest, MipMode::kNone, TexPersp::kExact), q, model);
  const host::ImageRgb8 bilinear = render_quad(
      replace_setup(tex->tex, Filter::kBilinear, MipMode::kNone, TexPersp::kExact), q, model);
  int covered = 0, between = 0;
  for (size_t p = 0; p < size_t{kW} * kH; ++p) {
    if (!is_fg(nearest, p)) continue;
    ++covered;
    const Rgb8 n = pixel(nearest, p);
    EXPECT_TRUE(n == (Rgb8{0, 0, 0}) || n == (Rgb8{255, 255, 255})) << p;
    const Rgb8 b = pixel(bilinear, p);
    between += b.g > 20 && b.g < 235 ? 1 : 0;
  }
  EXPECT_GT(covered, 150);
  EXPECT_GT(between, covered / 4);
}

TEST(SpanDispatch, MipLevelsAreUsedWhenMinifiedAndOnlyWithAMipMode) {
  // Each level one solid colour: 16, 8, 4, 2, 1 texels.
  const Rgb8 kLevel[5] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 0}, {255, 255, 255}};
  const auto tex = make_texture(TexelFormat::kRgb888, 16, true,
                                [&](int l, int, int) { return kLevel[static_cast<size_t>(l)]; });
  const Quad q({}, 6.0);  // 96 texels across about 20 pixels: level of detail ~2.3
  const Mat4 model = place(0, 0, -3, 0, 0);
  auto render = [&](MipMode m) {
    return render_quad(replace_setup(tex->tex, Filter::kNearest, m, TexPersp::kExact), q, model);
  };
  const host::ImageRgb8 none = render(MipMode::kNone), nearest = render(MipMode::kNearest),
                        linear = render(MipMode::kLinear);
  int covered = 0, level2 = 0, blended = 0;
  for (size_t p = 0; p < size_t{kW} * kH; ++p) {
    if (!is_fg(none, p)) continue;
    ++covered;
    EXPECT_EQ(pixel(none, p), kLevel[0]) << p;
    const Rgb8 n = pixel(nearest, p);
    EXPECT_NE(n, kLevel[0]) << p;
    level2 += n == kLevel[2] ? 1 : 0;
    const Rgb8 l = pixel(linear, p);
    EXPECT_NE(l, kLevel[0]) << p;
    bool pure = false;
    for (const Rgb8& c : kLevel) pure = pure || l == c;
    blended += pure ? 0 : 1;
  }
  EXPECT_GT(covered, 150);
  EXPECT_GT(level2, covered / 2);
  EXPECT_GT(blended, covered / 2);
}

TEST(SpanDispatch, TexturedPerspectiveModesDifferOnATiltedQuad) {
  const auto tex = make_texture(TexelFormat::kRgb888, 8, false, [](int, int x, int y) {
    return Rgb8{static_cast<uint8_t>(30 * x), static_cast<uint8_t>(30 * y), 128};
  });
  const Quad q({}, 1.0);
  const Mat4 model = place(0, -0.3, -2.2, -70, 0);
  auto render = [&](TexPersp p) {
    return render_quad(replace_setup(tex->tex, Filter::kBilinear, MipMode::kNone, p), q, model);
  };
  const host::ImageRgb8 exact = render(TexPersp::kExact), span = render(TexPersp::kSpan),
                        affine = render(TexPersp::kAffine);
  const Diff ea = diff(exact, affine), es = diff(exact, span);
  EXPECT_GT(ea.covered, 150);
  EXPECT_GE(ea.max, 30);
  // Span mode is exact at every 8th pixel and interpolates in between: close to exact.
  EXPECT_LT(es.mean, ea.mean / 2);
}

// Phong: one quad facing the viewer, no specular, lit from the front.
DrawSetup phong_setup(PixelLighting method, bool position) {
  SpanState s = first_state(SpanFamily::kPhong);
  s.method = method;
  s.position = method == PixelLighting::kExact && position;
  s.table_bilinear = method == PixelLighting::kTable;
  DrawSetup u = setup_for(s, assets());
  u.material.specular = {0, 0, 0};
  if (!position) u.lights.lights[0].position = {fx(0), fx(0), fx(1)};
  return u;
}

TEST(SpanDispatch, PhongPositionPlanesLightAQuadUnevenlyFromAPointLight) {
  const Quad q({}, 1.0);
  const Mat4 model = place(0, 0, -3, 0, 0);
  DrawSetup u = phong_setup(PixelLighting::kExact, true);
  u.lights.lights[0].position = {fx(-0.8), fx(0), fx(-2.6)};  // close to the quad's left edge
  const host::ImageRgb8 point = render_quad(u, q, model);
  const host::ImageRgb8 directional =
      render_quad(phong_setup(PixelLighting::kExact, false), q, model);
  int lo = 255, hi = 0, dlo = 255, dhi = 0;
  for (size_t p = 0; p < size_t{kW} * kH; ++p) {
    if (!is_fg(point, p)) continue;
    lo = std::min<int>(lo, pixel(point, p).r);
    hi = std::max<int>(hi, pixel(point, p).r);
    dlo = std::min<int>(dlo, pixel(directional, p).r);
    dhi = std::max<int>(dhi, pixel(directional, p).r);
  }
  EXPECT_GE(hi - lo, 40);   // a bright spot near the light
  EXPECT_LE(dhi - dlo, 1);  // a flat quad under a directional light: one colour
  EXPECT_GT(dlo, 100);
}

TEST(SpanDispatch, PhongMapsModulateAndTheTableFollowsTheExactMethod) {
  const Quad q({}, 1.0);
  const Mat4 model = place(0, 0, -3, 0, 0);
  const auto green = make_texture(TexelFormat::kRgb888, 4, false, [](int, int, int) {
    return Rgb8{0, 255, 0};
  });
  const auto blue = make_texture(TexelFormat::kRgb888, 4, false, [](int, int, int) {
    return Rgb8{0, 0, 255};
  });
  // A normal map tilting every normal towards +x (away from the light at +z).
  const auto tilted = make_texture(TexelFormat::kRgb888, 4, false, [](int, int, int) {
    return Rgb8{240, 128, 180};
  });
  const DrawSetup plain = phong_setup(PixelLighting::kExact, false);
  DrawSetup textured = plain, env = plain, mapped = plain;
  textured.state.texture = &green->tex;
  env.state.envmap = &blue->tex;
  mapped.state.normal_map = &tilted->tex;
  const host::ImageRgb8 a = render_quad(plain, q, model), t = render_quad(textured, q, model),
                        e = render_quad(env, q, model), m = render_quad(mapped, q, model),
                        table = render_quad(phong_setup(PixelLighting::kTable, false), q, model);
  int covered = 0;
  for (size_t p = 0; p < size_t{kW} * kH; ++p) {
    if (!is_fg(a, p)) continue;
    ++covered;
    const Rgb8 c = pixel(a, p);
    EXPECT_GT(c.r, 100);
    EXPECT_EQ(pixel(t, p), (Rgb8{0, c.g, 0})) << p;  // texel x lit colour: green only
    EXPECT_EQ(pixel(e, p), (Rgb8{0, 0, c.b})) << p;  // environment x lit colour: blue only
    EXPECT_LE(pixel(m, p).r + 20, c.r) << p;         // tilted normals: darker
  }
  EXPECT_GT(covered, 150);
  const Diff d = diff(a, table);
  EXPECT_LE(d.max, 3);
}

// ---- Every texel fetcher: format x filter x wraps, alone in a set -------------------------------
//
// For every fetcher, the smallest set holding it: its fetcher table holds that fetcher alone,
// and a front end admitting only the set draws the full renderer's frame and refuses another
// format, wrap or filter. A whole restricted renderer draws end to end for one fetcher per
// format.

const Texture& format_texture(TexelFormat f) {
  static const std::array<std::unique_ptr<OwnedTexture>, 4> t = {
      checker(TexelFormat::kRgb565), checker(TexelFormat::kRgb888), checker(TexelFormat::kL8),
      checker(TexelFormat::kPalette8)};
  return t[static_cast<size_t>(f)]->tex;
}

// The textured state the fetcher sweep draws with: the texel alone, level 0.
constexpr SpanState fetch_sweep_state(Filter filter) {
  SpanState s;
  s.family = SpanFamily::kTextured;
  s.env = TexEnv::kReplace;
  s.filter = filter;
  return s;
}

// Fetcher I (fetch_index) with `small`, a renderer restricted to it or a front end admitting
// only its set.
void check_fetcher_with(size_t I, RigBase& small) {
  const TexelFormat format = FetchLayout::field<3>(I);
  const Filter filter = FetchLayout::field<2>(I);
  const Wrap ws = FetchLayout::field<1>(I), wt = FetchLayout::field<0>(I);
  DrawSetup u = setup_for(fetch_sweep_state(filter), assets());
  u.state.texture = &format_texture(format);
  u.state.sampler.wrap_s = ws;
  u.state.sampler.wrap_t = wt;
  Rig<kAllSpans> full;
  ASSERT_EQ(draw_scene(full, u), Status::kOk) << "fetcher " << I;
  ASSERT_EQ(draw_scene(small, u), Status::kOk) << "fetcher " << I;
  const host::ImageRgb8 want = full.render();
  EXPECT_GT(count_fg(want), 100);
  EXPECT_TRUE(small.render().rgb == want.rgb) << "fetcher " << I << ": frames differ";

  // Another format, wrap or filter: refused.
  ASSERT_EQ(draw_scene(small, u), Status::kOk);
  DrawState s = u.state;
  s.texture = &format_texture(static_cast<TexelFormat>((static_cast<size_t>(format) + 1) % 4));
  EXPECT_EQ(small.r().draw(near_quad().mesh(), Mat4::identity(), u.material, s),
            Status::kNotLinked);
  s = u.state;
  s.sampler.wrap_s = ws == Wrap::kRepeat ? Wrap::kClampToEdge : Wrap::kRepeat;
  EXPECT_EQ(small.r().draw(near_quad().mesh(), Mat4::identity(), u.material, s),
            Status::kNotLinked);
  s = u.state;
  s.sampler.filter = filter == Filter::kNearest ? Filter::kBilinear : Filter::kNearest;
  EXPECT_EQ(small.r().draw(near_quad().mesh(), Mat4::identity(), u.material, s),
            Status::kNotLinked);
}

// The smallest set holding fetcher I (fetch_index): the sweep's state with its filter, its
// format and wraps.
template <size_t I>
constexpr SpanSet kFetcherSet = span_set_of(fetch_sweep_state(FetchLayout::field<2>(I)))
                                    .only(FetchLayout::field<3>(I))
                                    .only_wraps(FetchLayout::field<1>(I), FetchLayout::field<0>(I));

// Per fetcher: the fetcher table and the admission function of its set.
struct RestrictedFetcher {
  const std::array<FetchFn, kFetchRoutines>* table;
  AdmitFn admit;
};
template <size_t... I>
constexpr std::array<RestrictedFetcher, sizeof...(I)> restricted_fetchers(
    std::index_sequence<I...> /*fetchers*/) {
  return {RestrictedFetcher{&kFetchTable<kFetcherSet<I>>, &admits<kFetcherSet<I>>}...};
}
constexpr auto kRestrictedFetchers =
    restricted_fetchers(std::make_index_sequence<kFetchRoutines>{});

// check_fetcher_with decodes an index into the fetcher it is.
static_assert([] {
  for (size_t i = 0; i < kFetchRoutines; ++i)
    if (fetch_index(FetchLayout::field<3>(i), FetchLayout::field<2>(i), FetchLayout::field<1>(i),
                    FetchLayout::field<0>(i)) != i)
      return false;
  return true;
}());

TEST(SpanDispatch, EveryFetcherOfARestrictedSetIsTheFullSetsAloneAndOthersAreRefused) {
  for (size_t i = 0; i < kFetchRoutines; ++i) {
    // Only this fetcher in the set's table.
    const std::array<FetchFn, kFetchRoutines>& table = *kRestrictedFetchers[i].table;
    for (size_t j = 0; j < kFetchRoutines; ++j)
      EXPECT_EQ(table[j] != nullptr, j == i) << "fetcher " << i << " entry " << j;
    EXPECT_EQ(table[i], kFetchTable<>[i]) << "fetcher " << i;
    AdmitRig small(kRestrictedFetchers[i].admit);
    check_fetcher_with(i, small);
  }
}

// The fetchers drawn by whole restricted renderers: one per format, each filter and each wrap
// of either axis twice.
constexpr std::array<size_t, 4> kSampledFetchers = {
    fetch_index(TexelFormat::kRgb565, Filter::kNearest, Wrap::kRepeat, Wrap::kRepeat),
    fetch_index(TexelFormat::kRgb888, Filter::kBilinear, Wrap::kClampToEdge, Wrap::kRepeat),
    fetch_index(TexelFormat::kL8, Filter::kNearest, Wrap::kRepeat, Wrap::kClampToEdge),
    fetch_index(TexelFormat::kPalette8, Filter::kBilinear, Wrap::kClampToEdge, Wrap::kClampToEdge)};
static_assert([] {
  size_t formats[4]{}, filters[2]{}, wraps_s[2]{}, wraps_t[2]{};
  for (size_t i : kSampledFetchers) {
    ++formats[static_cast<size_t>(FetchLayout::field<3>(i))];
    ++filters[static_cast<size_t>(FetchLayout::field<2>(i))];
    ++wraps_s[static_cast<size_t>(FetchLayout::field<1>(i))];
    ++wraps_t[static_cast<size_t>(FetchLayout::field<0>(i))];
  }
  return std::ranges::all_of(formats, [](size_t n) { return n == 1; }) && filters[0] == 2 &&
         wraps_s[0] == 2 && wraps_t[0] == 2;
}());

template <size_t I>
void check_fetcher() {
  Rig<kFetcherSet<I>> small;
  check_fetcher_with(I, small);
}

template <size_t... K>
void check_sampled_fetchers(std::index_sequence<K...> /*sample*/) {
  (check_fetcher<kSampledFetchers[K]>(), ...);
}

TEST(SpanDispatch, SampledFetcherRestrictedRenderersDrawTheFullRenderersFrame) {
  check_sampled_fetchers(std::make_index_sequence<kSampledFetchers.size()>{});
}

TEST(SpanDispatch, RepeatAndClampDifferBeyondTheTexture) {
  const Quad q({}, 3.0);  // u, v in [0, 3]
  const Mat4 model = place(0, 0, -3, 0, 0);
  DrawSetup u = setup_for(fetch_sweep_state(Filter::kNearest), assets());
  u.state.texture = &format_texture(TexelFormat::kRgb888);
  const host::ImageRgb8 repeat = render_quad(u, q, model);
  u.state.sampler.wrap_s = u.state.sampler.wrap_t = Wrap::kClampToEdge;
  const host::ImageRgb8 clamp = render_quad(u, q, model);
  const Diff d = diff(repeat, clamp);
  EXPECT_GT(d.covered, 150);
  EXPECT_GE(d.max, 100);
}

// The inlined fetch (SpanSet::inline_fetch) is code, not state: a renderer without it has the
// routines with the fetch through the fetcher (the shared span body), with nearest the same
// pixels (bilinear: tests/core/texture_test.cpp). Replaced and modulated RGB565 quads with exact
// perspective, repeat and clamp: spans the inlined routines take (a modulated quad's colours are
// constant when its vertex colours are).
template <TexEnv kEnv, Wrap kWrap>
void check_shared_fetch() {
  constexpr SpanState kState{.family = SpanFamily::kTextured,
                             .persp = TexPersp::kExact,
                             .env = kEnv,
                             .mip = MipMode::kNone,
                             .filter = Filter::kNearest};
  constexpr SpanSet kInlined =
      span_set_of(kState).only(TexelFormat::kRgb565).only_wraps(kWrap, kWrap);
  constexpr SpanSet kShared = kInlined.only_inline_fetch(false);
  constexpr size_t kIndex = textured_index(true, TexPersp::kExact, kEnv, MipMode::kNone);
  static_assert(kTexSpanTable<PF, kInlined>[kIndex] ==
                &fill_tex_span<PF, true, TexPersp::kExact, kEnv, MipMode::kNone, true>);
  static_assert(kTexSpanTable<PF, kShared>[kIndex] ==
                &fill_tex_span<PF, true, TexPersp::kExact, kEnv, MipMode::kNone, false>);
  const Quad q({Rgb8{200, 180, 90}, Rgb8{200, 180, 90}, Rgb8{200, 180, 90}, Rgb8{200, 180, 90}},
               3.0);
  DrawSetup u = setup_for(kState, assets());
  u.state.texture = &format_texture(TexelFormat::kRgb565);
  u.state.sampler.wrap_s = u.state.sampler.wrap_t = kWrap;
  const Mat4 model = place(0.1, -0.1, -3, -40, 25);
  Rig<kInlined> inlined;
  Rig<kShared> shared;
  for (RigBase* rig : {static_cast<RigBase*>(&inlined), static_cast<RigBase*>(&shared)}) {
    ASSERT_EQ(rig->r().begin_frame(camera(), u.lights, Rgb8{8, 8, 8}), Status::kOk);
    ASSERT_EQ(rig->r().draw(q.mesh(), model, u.material, u.state), Status::kOk);
  }
  const host::ImageRgb8 want = inlined.render();
  const host::ImageRgb8 got = shared.render();
  EXPECT_GT(count_fg(want), 200);
  EXPECT_TRUE(want.rgb == got.rgb)
      << "env " << static_cast<int>(kEnv) << " wrap " << static_cast<int>(kWrap);
}

TEST(SpanDispatch, TheSharedFetchDrawsTheInlinedFetchsFrameWithNearest) {
  check_shared_fetch<TexEnv::kReplace, Wrap::kRepeat>();
  check_shared_fetch<TexEnv::kReplace, Wrap::kClampToEdge>();
  check_shared_fetch<TexEnv::kModulate, Wrap::kRepeat>();
  check_shared_fetch<TexEnv::kModulate, Wrap::kClampToEdge>();
}

}  // namespace
}  // namespace lr
