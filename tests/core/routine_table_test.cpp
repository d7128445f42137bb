// The routine tables: each family's index layout is a bijection of its table's indices, and the
// entry a state's index selects is the instance named by that state's own fields (taken from the
// enumeration of every state, not from the layout's decoder), in the full set and in restricted
// ones.
#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <utility>

#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/core/raster/untextured_rows.hpp"
#include "lineraster/core/span/index_layout.hpp"
#include "lineraster/core/span/phong_span.hpp"
#include "lineraster/core/span/sampler.hpp"
#include "lineraster/core/span/span.hpp"
#include "lineraster/core/span/span_state.hpp"
#include "lineraster/core/span/tex_span.hpp"

namespace lr {
namespace {

using PF = Rgb565Be;

template <class Layout, size_t... K>
void expect_round_trip(const char* name, std::index_sequence<K...>) {
  static_assert(Layout::round_trips());
  for (size_t i = 0; i < Layout::kSize; ++i)
    EXPECT_EQ(Layout::encode(Layout::template field<K>(i)...), i) << name << " index " << i;
}
template <class Layout>
void expect_round_trip(const char* name) {
  expect_round_trip<Layout>(name, std::make_index_sequence<Layout::kFields>{});
}

TEST(RoutineTable, EveryLayoutDecodesAndEncodesEveryIndexBack) {
  expect_round_trip<UntexturedLayout>("untextured");
  expect_round_trip<TexturedLayout>("textured");
  expect_round_trip<PhongLayout>("phong");
  expect_round_trip<FetchLayout>("fetch");
  expect_round_trip<EnvFetchLayout>("env fetch");
}

TEST(RoutineTable, TablesHaveOneEntryPerCombinationOfTheirFields) {
  EXPECT_EQ(kUntexturedRowTable<PF>.size(), 2u * 4u);
  EXPECT_EQ(untextured_row_index(true, UntexturedKind::kLanes), 1u + 2u * 3u);
  EXPECT_EQ(kTexSpanTable<PF>.size(), 2u * 3u * 2u * 3u);
  EXPECT_EQ(kPhongSpanTable<PF>.size(), 64u);
  EXPECT_EQ(kFetchTable<>.size(), 2u * 2u * 2u * 4u);
  EXPECT_EQ(kEnvFetchTable<>.size(), 4u);
  // The first field is the least significant digit.
  EXPECT_EQ(untextured_index(true, ColorPlanes::kAffine), 1u + 2u * 2u);
  EXPECT_EQ(textured_index(true, TexPersp::kAffine, TexEnv::kReplace, MipMode::kLinear),
            1u + 2u * (2u + 3u * (1u + 2u * 2u)));
  EXPECT_EQ(phong_index(false, PixelLighting::kTable, false, true, false, true), 2u + 8u + 32u);
  EXPECT_EQ(
      fetch_index(TexelFormat::kPalette8, Filter::kBilinear, Wrap::kClampToEdge, Wrap::kRepeat),
      2u + 4u * (1u + 2u * 3u));
  EXPECT_EQ(env_fetch_index(TexelFormat::kL8), 2u);
}

// Span state J of the enumeration: its table entry is the instance of its fields.
template <size_t J>
void expect_state_routine() {
  constexpr SpanState s = kSpanStates[J];
  if constexpr (s.family == SpanFamily::kUntextured) {
    constexpr UntexturedKind kKind = primary_kind<PF>(s.colors);
    EXPECT_EQ(kUntexturedRowTable<PF>[untextured_row_index(s.depth, kKind)],
              (untextured_rows<PF, s.depth, kKind>()))
        << "state " << J;
  } else if constexpr (s.family == SpanFamily::kTextured) {
    EXPECT_EQ(kTexSpanTable<PF>[textured_index(s.depth, s.persp, s.env, s.mip)],
              (&fill_tex_span<PF, s.depth, s.persp, s.env, s.mip>))
        << "state " << J;
  } else {
    constexpr bool kSecond = s.position || s.table_bilinear;
    EXPECT_EQ(kPhongSpanTable<PF>[phong_index(s.depth, s.method, kSecond, s.texture, s.normal_map,
                                              s.envmap)],
              (&fill_phong_span<PF, s.depth, s.method, kSecond, s.texture, s.normal_map, s.envmap>))
        << "state " << J;
  }
}

// A table of the checks, not a fold expression: Clang limits a fold to 256 operands.
template <size_t... J>
void expect_state_routines(std::index_sequence<J...>) {
  constexpr std::array<void (*)(), sizeof...(J)> kChecks{&expect_state_routine<J>...};
  for (void (*check)() : kChecks) check();
}

TEST(RoutineTable, EveryStateSelectsTheInstanceOfItsFields) {
  expect_state_routines(std::make_index_sequence<kSpanStateCount>{});
}

template <TexelFormat F, Filter kFilter, Wrap kWs, Wrap kWt>
void expect_fetcher() {
  EXPECT_EQ(fetch_routine(F, kFilter, kWs, kWt), (&fetch_batch<F, kFilter, kWs, kWt>))
      << static_cast<int>(F) << " " << static_cast<int>(kFilter) << " " << static_cast<int>(kWs)
      << " " << static_cast<int>(kWt);
}
template <TexelFormat F>
void expect_fetchers_of_format() {
  expect_fetcher<F, Filter::kNearest, Wrap::kRepeat, Wrap::kRepeat>();
  expect_fetcher<F, Filter::kNearest, Wrap::kRepeat, Wrap::kClampToEdge>();
  expect_fetcher<F, Filter::kNearest, Wrap::kClampToEdge, Wrap::kRepeat>();
  expect_fetcher<F, Filter::kNearest, Wrap::kClampToEdge, Wrap::kClampToEdge>();
  expect_fetcher<F, Filter::kBilinear, Wrap::kRepeat, Wrap::kRepeat>();
  expect_fetcher<F, Filter::kBilinear, Wrap::kRepeat, Wrap::kClampToEdge>();
  expect_fetcher<F, Filter::kBilinear, Wrap::kClampToEdge, Wrap::kRepeat>();
  expect_fetcher<F, Filter::kBilinear, Wrap::kClampToEdge, Wrap::kClampToEdge>();
  EXPECT_EQ(env_fetch_routine(F),
            (&fetch_batch<F, Filter::kBilinear, Wrap::kClampToEdge, Wrap::kClampToEdge>))
      << static_cast<int>(F);
}

TEST(RoutineTable, EveryTextureStateSelectsTheFetcherOfItsFields) {
  expect_fetchers_of_format<TexelFormat::kRgb565>();
  expect_fetchers_of_format<TexelFormat::kRgb888>();
  expect_fetchers_of_format<TexelFormat::kL8>();
  expect_fetchers_of_format<TexelFormat::kPalette8>();
}

// A restricted table holds the full table's entry where the set uses it, nullptr elsewhere.
template <class T, size_t N>
void expect_restriction(const std::array<T, N>& table, const std::array<T, N>& full,
                        const std::array<bool, N>& used, const char* name) {
  for (size_t i = 0; i < N; ++i)
    EXPECT_EQ(table[i], used[i] ? full[i] : nullptr) << name << " entry " << i;
}

template <SpanSet kSet>
void expect_restricted_tables() {
  constexpr UsedRoutines u = kUsedRoutines<kSet>;
  std::array<bool, 2 * kUntexturedKinds> rows{};
  for (size_t i = 0; i < rows.size(); ++i) rows[i] = untextured_row_used<PF>(u, i);
  expect_restriction(kUntexturedRowTable<PF, kSet>, kUntexturedRowTable<PF>, rows, "untextured");
  expect_restriction(kTexSpanTable<PF, kSet>, kTexSpanTable<PF>, u.textured, "textured");
  expect_restriction(kPhongSpanTable<PF, kSet>, kPhongSpanTable<PF>, u.phong, "phong");
  expect_restriction(kFetchTable<kSet>, kFetchTable<>, u.fetch, "fetch");
  expect_restriction(kEnvFetchTable<kSet>, kEnvFetchTable<>, u.env_fetch, "env fetch");
}

TEST(RoutineTable, RestrictedTablesHoldTheFullTablesEntriesTheirSetUses) {
  expect_restricted_tables<kAllSpans>();
  expect_restricted_tables<kUntexturedSpans>();
  expect_restricted_tables<kTexturedSpans.only(Filter::kNearest).only(MipMode::kNone)>();
  expect_restricted_tables<kPhongSpans.only(PixelLighting::kTable).only_maps(true, false, true)>();
  expect_restricted_tables<
      kTexturedOnly.only(TexelFormat::kL8).only_wraps(Wrap::kClampToEdge, Wrap::kRepeat)>();
  // Every entry of the full set is used.
  constexpr UsedRoutines all = kUsedRoutines<kAllSpans>;
  for (bool used : all.untextured) EXPECT_TRUE(used);
  for (bool used : all.textured) EXPECT_TRUE(used);
  for (bool used : all.phong) EXPECT_TRUE(used);
  for (bool used : all.fetch) EXPECT_TRUE(used);
  for (bool used : all.env_fetch) EXPECT_TRUE(used);
}

}  // namespace
}  // namespace lr
