// The span state space: one definition of every state a draw can select a span routine (and a
// texel fetcher) by, the enumeration of all of them, and the restriction type SpanSet.
//
// A draw's state (SpanState) is its family and the dimensions that family's routine is
// instantiated for:
//   untextured: depth test x colour planes (none, perspective, affine)       untextured_span
//   textured:   depth test x perspective mode x environment x mip mode       fill_tex_span
//               x filter (the texel fetcher)
//   Phong:      depth test x lighting method x (exact: world-position planes; fill_phong_span
//               table: bilinear lookup) x texture x normal map x environment map,
//               x filter (texture or normal map) x mip mode (texture)
// The texel fetchers are also chosen by the texture's format and wraps (fetch_index): those are
// checked per texture against the set's masks but do not multiply the span states. Nor does the
// inlined fetch (SpanSet::inline_fetch), a choice of code, not of state: whether the textured
// routines carry copies with the fetch inlined per filter and wrap for the spans that allow it. The
// pixel format is the renderer's PF (every table is per PF). Not instances, so not state
// dimensions: the span length of TexPersp::kSpan (8, 16, 32) and Phong's mip mode (per chunk of 16
// pixels, inside the routine; it is still a dimension of the set, so that "no mipmaps" holds for
// Phong).
//
// SpanSet is the restriction: one mask per dimension (a product set), usable as a non-type
// template parameter: Renderer<PF, K, kSet>. The routine tables of a renderer are generated
// from kSpanStates and kSet (used_routines): an entry no admitted state selects is nullptr, so
// its template instance (and its fetchers) is never referenced and never linked. draw() and
// draw_screen() refuse a draw whose state the set does not admit (kInvalidArgument), with the
// same predicate (SpanSet::admits), so a restricted renderer never reaches a nullptr entry.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/span/index_layout.hpp"
#include "lineraster/core/texture/texture.hpp"

namespace lr {

enum class SpanFamily : uint8_t { kUntextured, kTextured, kPhong };

// The state a draw selects its routine by. Dimensions that do not apply to the family (or to
// the Phong draw's maps) keep their default value.
struct SpanState {
  SpanFamily family = SpanFamily::kUntextured;
  bool depth = true;
  ColorPlanes colors = ColorPlanes::kNone;       // untextured
  TexPersp persp = TexPersp::kExact;             // textured
  TexEnv env = TexEnv::kModulate;                // textured
  MipMode mip = MipMode::kNone;                  // textured; Phong with a texture
  Filter filter = Filter::kNearest;              // textured; Phong with a texture or normal map
  PixelLighting method = PixelLighting::kExact;  // Phong
  // Phong, exact: world-position planes. Other families: the draw may be lit by point lights or
  // the local viewer (the renderer links its per-vertex point lighting; not a routine index).
  bool position = false;
  bool table_bilinear = false;                               // Phong, table: bilinear lookup
  bool texture = false, normal_map = false, envmap = false;  // Phong
  friend constexpr bool operator==(const SpanState&, const SpanState&) = default;
};

namespace detail {
template <class E>
constexpr uint8_t bit(E v) {
  return static_cast<uint8_t>(1u << static_cast<unsigned>(v));
}
constexpr uint8_t bit(bool v) {
  return v ? uint8_t{2} : uint8_t{1};
}
template <class E>
constexpr bool has(uint8_t mask, E v) {
  return (mask & bit(v)) != 0;
}
}  // namespace detail

// A set of span states: a mask per dimension (bit i admits the dimension's value i; for the
// on/off dimensions bit 0 is off, bit 1 on). Masks of dimensions that do not apply to a state
// do not restrict it. The default admits every state (kAllSpans).
struct SpanSet {
  uint8_t families = 0b111;  // SpanFamily
  uint8_t depth = 0b11;
  uint8_t colors = 0b111;  // ColorPlanes
  uint8_t persp = 0b111;   // TexPersp
  uint8_t env = 0b11;      // TexEnv
  uint8_t mip = 0b111;     // MipMode
  uint8_t filter = 0b11;   // Filter: textures and normal maps
  uint8_t method = 0b11;   // PixelLighting
  // Draws whose lighting reads the surface position (point lights, the local viewer): Phong's
  // exact method with its world-position planes; and, as the renderer's link of its point
  // lighting, lit Gouraud, flat and textured draws (the front end refuses those without it).
  uint8_t position = 0b11;
  uint8_t table_filter = 0b11;                               // Filter of the lighting table lookup
  uint8_t texture = 0b11, normal_map = 0b11, envmap = 0b11;  // Phong's maps
  // The texel fetchers: formats of textures, normal maps and environment maps; wraps of
  // textures and normal maps (environment maps clamp).
  uint8_t formats = 0b1111;  // TexelFormat
  uint8_t wrap_s = 0b11, wrap_t = 0b11;
  // Textured spans of an RGB565 texture with exact perspective and no mipmaps, replaced or
  // modulated by constant colours (power-of-two repeat, or clamp): on, a routine per filter and
  // wrap with the fetch inlined; off, the shared span body, which calls the texel fetcher per
  // chunk of pixels. Off trades instructions per pixel for flash; nearest picks the same
  // texels, bilinear's coordinates may differ by 1/256 texel (at most one 5-bit weight step).
  uint8_t inline_fetch = 0b11;

  friend constexpr bool operator==(const SpanSet&, const SpanSet&) = default;

  constexpr bool admits(const SpanState& s) const {
    using detail::has;
    if (!has(families, s.family) || !has(depth, s.depth)) return false;
    switch (s.family) {
      case SpanFamily::kUntextured:
        return has(colors, s.colors);
      case SpanFamily::kTextured:
        return has(persp, s.persp) && has(env, s.env) && has(mip, s.mip) && has(filter, s.filter);
      case SpanFamily::kPhong:
        return has(method, s.method) &&
               (s.method == PixelLighting::kExact ? has(position, s.position)
                                                  : has(table_filter, s.table_bilinear)) &&
               has(texture, s.texture) && has(normal_map, s.normal_map) && has(envmap, s.envmap) &&
               (!(s.texture || s.normal_map) || has(filter, s.filter)) &&
               (!s.texture || has(mip, s.mip));
    }
    return false;
  }
  // A texture or normal map of this format and wraps (its filter is the state's).
  constexpr bool admits_sampler(TexelFormat f, Wrap s, Wrap t) const {
    return detail::has(formats, f) && detail::has(wrap_s, s) && detail::has(wrap_t, t);
  }
  // Spans of this family.
  constexpr bool has(SpanFamily f) const { return detail::has(families, f); }
  // An environment map of this format.
  constexpr bool admits_envmap(TexelFormat f) const { return detail::has(formats, f); }

  // Restrictions to one value of a dimension (chainable: kTexturedSpans.only(Filter::kNearest)).
  constexpr SpanSet only(SpanFamily v) const { return with(&SpanSet::families, detail::bit(v)); }
  constexpr SpanSet only(ColorPlanes v) const { return with(&SpanSet::colors, detail::bit(v)); }
  constexpr SpanSet only(TexPersp v) const { return with(&SpanSet::persp, detail::bit(v)); }
  constexpr SpanSet only(TexEnv v) const { return with(&SpanSet::env, detail::bit(v)); }
  constexpr SpanSet only(MipMode v) const { return with(&SpanSet::mip, detail::bit(v)); }
  constexpr SpanSet only(Filter v) const { return with(&SpanSet::filter, detail::bit(v)); }
  constexpr SpanSet only(PixelLighting v) const { return with(&SpanSet::method, detail::bit(v)); }
  constexpr SpanSet only(TexelFormat v) const { return with(&SpanSet::formats, detail::bit(v)); }
  constexpr SpanSet only_depth(bool on) const { return with(&SpanSet::depth, detail::bit(on)); }
  constexpr SpanSet only_wraps(Wrap s, Wrap t) const {
    return with(&SpanSet::wrap_s, detail::bit(s)).with(&SpanSet::wrap_t, detail::bit(t));
  }
  constexpr SpanSet only_position(bool on) const {
    return with(&SpanSet::position, detail::bit(on));
  }
  constexpr SpanSet only_inline_fetch(bool on) const {
    return with(&SpanSet::inline_fetch, detail::bit(on));
  }
  constexpr SpanSet only_table_filter(Filter v) const {
    return with(&SpanSet::table_filter, detail::bit(v));
  }
  // Phong draws with (true) or without (false) each map.
  constexpr SpanSet only_maps(bool texture_map, bool normal, bool environment) const {
    return with(&SpanSet::texture, detail::bit(texture_map))
        .with(&SpanSet::normal_map, detail::bit(normal))
        .with(&SpanSet::envmap, detail::bit(environment));
  }

  // Per-dimension union and intersection (the union is the smallest product set holding both).
  friend constexpr SpanSet operator|(SpanSet a, const SpanSet& b) {
    for (uint8_t SpanSet::*m : kMasks) a.*m = static_cast<uint8_t>(a.*m | b.*m);
    return a;
  }
  friend constexpr SpanSet operator&(SpanSet a, const SpanSet& b) {
    for (uint8_t SpanSet::*m : kMasks) a.*m = static_cast<uint8_t>(a.*m & b.*m);
    return a;
  }

 private:
  // Not a template: clang 14 will not evaluate an in-class member template in the constant
  // initialisers of the presets below ("undefined function").
  constexpr SpanSet with(uint8_t SpanSet::*m, uint8_t bits) const {
    SpanSet r = *this;
    r.*m = static_cast<uint8_t>(r.*m & bits);
    return r;
  }
  static constexpr uint8_t SpanSet::*kMasks[] = {
      &SpanSet::families,    &SpanSet::depth,        &SpanSet::colors,  &SpanSet::persp,
      &SpanSet::env,         &SpanSet::mip,          &SpanSet::filter,  &SpanSet::method,
      &SpanSet::position,    &SpanSet::table_filter, &SpanSet::texture, &SpanSet::normal_map,
      &SpanSet::envmap,      &SpanSet::formats,      &SpanSet::wrap_s,  &SpanSet::wrap_t,
      &SpanSet::inline_fetch};
};

// Presets: kUntexturedSpans, kTexturedSpans and kPhongSpans keep the untextured routines
// (overlays, backgrounds); kTexturedOnly and kPhongOnly are one family alone.
inline constexpr SpanSet kAllSpans{};
inline constexpr SpanSet kUntexturedSpans = kAllSpans.only(SpanFamily::kUntextured);
inline constexpr SpanSet kTexturedOnly = kAllSpans.only(SpanFamily::kTextured);
inline constexpr SpanSet kPhongOnly = kAllSpans.only(SpanFamily::kPhong);
inline constexpr SpanSet kTexturedSpans = kUntexturedSpans | kTexturedOnly;
inline constexpr SpanSet kPhongSpans = kUntexturedSpans | kPhongOnly;

// The smallest set that admits a state (its fetcher masks left whole: formats and wraps are
// the textures', not the state's).
constexpr SpanSet span_set_of(const SpanState& s) {
  using detail::bit;
  SpanSet r{};
  r.families = bit(s.family);
  r.depth = bit(s.depth);
  r.colors = bit(s.colors);
  r.persp = bit(s.persp);
  r.env = bit(s.env);
  r.mip = bit(s.mip);
  r.filter = bit(s.filter);
  r.method = bit(s.method);
  r.position = bit(s.position);
  r.table_filter = bit(s.table_bilinear);
  r.texture = bit(s.texture);
  r.normal_map = bit(s.normal_map);
  r.envmap = bit(s.envmap);
  return r;
}

// ---- Routine indices: the layout of each family's table ---------------------------------------
// Each family's fields, least significant first (index_layout.hpp); the *_index functions are
// the layouts' encoders with the fields named.
using UntexturedLayout = IndexLayout<Field<bool>, Field<ColorPlanes, 3>>;  // depth, colours
// depth, perspective mode, environment, mip mode
using TexturedLayout =
    IndexLayout<Field<bool>, Field<TexPersp, 3>, Field<TexEnv, 2>, Field<MipMode, 3>>;
// depth, method, second (exact: position planes; table: bilinear), texture, normal map, envmap
using PhongLayout = IndexLayout<Field<bool>, Field<PixelLighting, 2>, Field<bool>, Field<bool>,
                                Field<bool>, Field<bool>>;
// wrap t, wrap s, filter, format
using FetchLayout =
    IndexLayout<Field<Wrap, 2>, Field<Wrap, 2>, Field<Filter, 2>, Field<TexelFormat, 4>>;
// format (environment maps: bilinear, clamp to edge)
using EnvFetchLayout = IndexLayout<Field<TexelFormat, 4>>;

inline constexpr size_t kUntexturedRoutines = UntexturedLayout::kSize;
inline constexpr size_t kTexturedRoutines = TexturedLayout::kSize;
inline constexpr size_t kPhongRoutines = PhongLayout::kSize;
inline constexpr size_t kFetchRoutines = FetchLayout::kSize;
inline constexpr size_t kEnvFetchRoutines = EnvFetchLayout::kSize;
static_assert(kUntexturedRoutines == 6 && kTexturedRoutines == 36 && kPhongRoutines == 64 &&
              kFetchRoutines == 32 && kEnvFetchRoutines == 4);
static_assert(UntexturedLayout::round_trips() && TexturedLayout::round_trips() &&
              PhongLayout::round_trips() && FetchLayout::round_trips() &&
              EnvFetchLayout::round_trips());

constexpr size_t untextured_index(bool depth, ColorPlanes c) {
  return UntexturedLayout::encode(depth, c);
}
constexpr size_t textured_index(bool depth, TexPersp p, TexEnv e, MipMode m) {
  return TexturedLayout::encode(depth, p, e, m);
}
constexpr size_t phong_index(bool depth, PixelLighting method, bool second, bool texture,
                             bool normal_map, bool envmap) {
  return PhongLayout::encode(depth, method, second, texture, normal_map, envmap);
}
constexpr size_t fetch_index(TexelFormat f, Filter filter, Wrap ws, Wrap wt) {
  return FetchLayout::encode(wt, ws, filter, f);
}
constexpr size_t env_fetch_index(TexelFormat f) {
  return EnvFetchLayout::encode(f);
}

// ---- The enumeration of every state ------------------------------------------------------------
namespace detail {

// Calls f(state) for every state, family by family.
template <class F>
constexpr void for_each_span_state(F&& f) {
  constexpr ColorPlanes kColors[] = {ColorPlanes::kNone, ColorPlanes::kPerspective,
                                     ColorPlanes::kAffine};
  constexpr TexPersp kPersps[] = {TexPersp::kExact, TexPersp::kSpan, TexPersp::kAffine};
  constexpr TexEnv kEnvs[] = {TexEnv::kModulate, TexEnv::kReplace};
  constexpr MipMode kMips[] = {MipMode::kNone, MipMode::kNearest, MipMode::kLinear};
  constexpr Filter kFilters[] = {Filter::kNearest, Filter::kBilinear};
  constexpr PixelLighting kMethods[] = {PixelLighting::kExact, PixelLighting::kTable};
  constexpr bool kBools[] = {false, true};
  for (bool d : kBools) {
    for (ColorPlanes c : kColors) {
      SpanState s;
      s.family = SpanFamily::kUntextured;
      s.depth = d;
      s.colors = c;
      f(s);
    }
  }
  for (bool d : kBools)
    for (TexPersp p : kPersps)
      for (TexEnv e : kEnvs)
        for (MipMode m : kMips)
          for (Filter fi : kFilters) {
            SpanState s;
            s.family = SpanFamily::kTextured;
            s.depth = d;
            s.persp = p;
            s.env = e;
            s.mip = m;
            s.filter = fi;
            f(s);
          }
  for (bool d : kBools)
    for (PixelLighting me : kMethods)
      for (bool second : kBools)
        for (bool tex : kBools)
          for (bool nm : kBools)
            for (bool env : kBools)
              // The filter only where a map is sampled with it, the mip mode only for a texture.
              for (size_t fi = 0; fi < (tex || nm ? 2u : 1u); ++fi)
                for (size_t m = 0; m < (tex ? 3u : 1u); ++m) {
                  SpanState s;
                  s.family = SpanFamily::kPhong;
                  s.depth = d;
                  s.method = me;
                  s.position = me == PixelLighting::kExact && second;
                  s.table_bilinear = me == PixelLighting::kTable && second;
                  s.texture = tex;
                  s.normal_map = nm;
                  s.envmap = env;
                  s.filter = kFilters[fi];
                  s.mip = kMips[m];
                  f(s);
                }
}

constexpr size_t count_span_states() {
  size_t n = 0;
  for_each_span_state([&](const SpanState&) { ++n; });
  return n;
}

}  // namespace detail

inline constexpr size_t kSpanStateCount = detail::count_span_states();

// Every state, in a fixed order: 6 untextured, 72 textured, 240 Phong.
inline constexpr std::array<SpanState, kSpanStateCount> kSpanStates = [] {
  std::array<SpanState, kSpanStateCount> a{};
  size_t i = 0;
  detail::for_each_span_state([&](const SpanState& s) { a[i++] = s; });
  return a;
}();

// Which table entries a set uses: an entry is used when a draw the set admits (its state and
// its textures) selects it.
struct UsedRoutines {
  std::array<bool, kUntexturedRoutines> untextured{};
  std::array<bool, kTexturedRoutines> textured{};
  std::array<bool, kPhongRoutines> phong{};
  std::array<bool, kFetchRoutines> fetch{};
  std::array<bool, kEnvFetchRoutines> env_fetch{};
  constexpr bool any_fetch() const {
    auto used = [](bool u) { return u; };
    return std::ranges::any_of(fetch, used) || std::ranges::any_of(env_fetch, used);
  }
};

constexpr UsedRoutines used_routines(const SpanSet& set) {
  UsedRoutines u;
  constexpr TexelFormat kFormats[] = {TexelFormat::kRgb565, TexelFormat::kRgb888, TexelFormat::kL8,
                                      TexelFormat::kPalette8};
  constexpr Wrap kWraps[] = {Wrap::kRepeat, Wrap::kClampToEdge};
  // Whether any texture (or normal map), any environment map can be drawn with at all.
  bool any_sampler = false, any_envmap = false;
  for (TexelFormat f : kFormats) {
    any_envmap = any_envmap || set.admits_envmap(f);
    for (Wrap ws : kWraps)
      for (Wrap wt : kWraps) any_sampler = any_sampler || set.admits_sampler(f, ws, wt);
  }
  for (const SpanState& s : kSpanStates) {
    const bool sampled = s.family == SpanFamily::kTextured || s.texture || s.normal_map;
    if (!set.admits(s) || (sampled && !any_sampler) || (s.envmap && !any_envmap)) continue;
    switch (s.family) {
      case SpanFamily::kUntextured:
        u.untextured[untextured_index(s.depth, s.colors)] = true;
        // Perspective-correct colours fall back to the affine routine on triangles where the two
        // agree within half an output step (setup_untextured_triangle): that routine is part of
        // the state.
        if (s.colors == ColorPlanes::kPerspective)
          u.untextured[untextured_index(s.depth, ColorPlanes::kAffine)] = true;
        break;
      case SpanFamily::kTextured:
        u.textured[textured_index(s.depth, s.persp, s.env, s.mip)] = true;
        break;
      case SpanFamily::kPhong:
        u.phong[phong_index(s.depth, s.method, s.position || s.table_bilinear, s.texture,
                            s.normal_map, s.envmap)] = true;
        if (s.envmap)
          for (TexelFormat f : kFormats)
            if (set.admits_envmap(f)) u.env_fetch[env_fetch_index(f)] = true;
        break;
    }
    if (sampled)
      for (TexelFormat f : kFormats)
        for (Wrap ws : kWraps)
          for (Wrap wt : kWraps)
            if (set.admits_sampler(f, ws, wt)) u.fetch[fetch_index(f, s.filter, ws, wt)] = true;
  }
  return u;
}

template <SpanSet kSet>
inline constexpr UsedRoutines kUsedRoutines = used_routines(kSet);

}  // namespace lr
