// The routine tables: one builder for every family (untextured, textured and Phong spans, texel
// fetchers, environment-map fetchers).
//
// A family is a type with
//   Layout              its index (index_layout.hpp, declared in span_state.hpp),
//   Fn                  the routine pointer type,
//   kUsed               the member of UsedRoutines that says which entries a set uses,
//   routine<v...>()     the routine for the state whose fields are v..., in the layout's order.
// make_table<Family, kSet> decodes every index with the layout's field<N>() and fills the entry
// with that state's routine, or nullptr when no state kSet admits selects it: that instance is
// then never referenced, so never linked. The result is a constexpr array (in flash).
//
// Instances are keyed by the SpanSet value and the family type only, never by an array of
// flags: GCC 12 can mangle two array-valued template arguments that contain zeros to the same
// symbol, and the two instances then collide at link time.
#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include "lineraster/core/span/span_state.hpp"

namespace lr {

namespace detail {
template <class Family, SpanSet kSet, size_t I, size_t... K>
constexpr typename Family::Fn table_entry(std::index_sequence<K...> /*fields*/) {
  using Layout = typename Family::Layout;
  if constexpr ((kUsedRoutines<kSet>.*Family::kUsed)[I])
    return Family::template routine<Layout::template field<K>(I)...>();
  else
    return nullptr;
}
}  // namespace detail

template <class Family, SpanSet kSet, size_t... I>
constexpr std::array<typename Family::Fn, sizeof...(I)> make_table(
    std::index_sequence<I...> /*indices*/) {
  constexpr auto kFieldSeq = std::make_index_sequence<Family::Layout::kFields>{};
  return {detail::table_entry<Family, kSet, I>(kFieldSeq)...};
}

// The table of a family for a set, one entry per index of its layout.
template <class Family, SpanSet kSet>
constexpr std::array<typename Family::Fn, Family::Layout::kSize> make_table() {
  return make_table<Family, kSet>(std::make_index_sequence<Family::Layout::kSize>{});
}

}  // namespace lr
