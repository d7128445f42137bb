// The index of a routine table: a mixed-radix number over the state fields the family's routine
// template is instantiated for.
//
// A family declares its layout once, e.g. IndexLayout<Field<bool>, Field<ColorPlanes, 3>>
// (depth test, colour planes): the first field is the least significant digit, so the index is
// depth + 2 colours. encode() is the state's index, field<N>() reads one field back; the two are
// generated from the same list, so they cannot drift apart, and the table builder
// (dispatch.hpp) decodes every entry with field<N>() instead of a hand-written division.
#pragma once

#include <array>
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

namespace lr {

// One digit of an index: a bool, or an enum whose values are 0 .. kValues - 1.
template <class T, size_t kValueCount = 2>
struct Field {
  static_assert(std::is_same_v<T, bool> || std::is_enum_v<T>, "a field is a bool or an enum");
  static_assert(!std::is_same_v<T, bool> || kValueCount == 2, "a bool has two values");
  using Type = T;
  static constexpr size_t kValues = kValueCount;
};

template <class... Fs>
struct IndexLayout {
  template <size_t N>
  using FieldType = typename std::tuple_element_t<N, std::tuple<Fs...>>::Type;

  static constexpr size_t kFields = sizeof...(Fs);
  // The number of entries: every combination of the fields' values.
  static constexpr size_t kSize = (size_t{1} * ... * Fs::kValues);
  // The weight of each field's digit: the product of the radices before it.
  static constexpr std::array<size_t, kFields> kStride = [] {
    std::array<size_t, kFields> s{};
    size_t w = 1, k = 0;
    ((s[k++] = w, w *= Fs::kValues), ...);
    return s;
  }();

  // The index of the state whose fields are v (in the layout's order).
  static constexpr size_t encode(typename Fs::Type... v) {
    return encode_at(std::index_sequence_for<Fs...>{}, v...);
  }

  // Field N of the state at `index`.
  template <size_t N>
  static constexpr FieldType<N> field(size_t index) {
    using Nth = std::tuple_element_t<N, std::tuple<Fs...>>;
    const size_t v = index / kStride[N] % Nth::kValues;
    if constexpr (std::is_same_v<FieldType<N>, bool>) {
      return v != 0;
    } else {
      return static_cast<FieldType<N>>(v);
    }
  }

  // Whether encode(field<0>(i), field<1>(i), ...) == i for every index i.
  static constexpr bool round_trips() { return round_trips_at(std::index_sequence_for<Fs...>{}); }

 private:
  // Two forms of the same value, each the shorter code where it applies (these run per triangle
  // and strip): with every radix a power of two the digits are bit fields, joined by or; else
  // Horner's scheme, v0 + r0 (v1 + r1 (v2 + ...)), one multiply-add per field.
  static constexpr bool kBitFields = (((Fs::kValues & (Fs::kValues - 1)) == 0) && ...);

  template <size_t... K>
  static constexpr size_t encode_at(std::index_sequence<K...> /*fields*/, typename Fs::Type... v) {
    if constexpr (kBitFields)
      return (size_t{0} | ... | (kStride[K] * static_cast<size_t>(v)));
    else
      return horner<Fs...>(v...);
  }
  template <class F, class... Rest>
  static constexpr size_t horner(typename F::Type v, typename Rest::Type... rest) {
    if constexpr (sizeof...(Rest) == 0)
      return static_cast<size_t>(v);
    else
      return static_cast<size_t>(v) + F::kValues * horner<Rest...>(rest...);
  }
  template <size_t... K>
  static constexpr bool round_trips_at(std::index_sequence<K...> /*fields*/) {
    for (size_t i = 0; i < kSize; ++i)
      if (encode(field<K>(i)...) != i) return false;
    return true;
  }
};

}  // namespace lr
