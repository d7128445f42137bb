#include "lineraster/core/binning/edge_table.hpp"

namespace lr {

Outcome EdgeTable::classify(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2,
                            Cull cull, int32_t& r0, int32_t& r1) const {
  return classify_inline(v0, v1, v2, cull, r0, r1);
}

bool EdgeTable::shrink_window(std::span<const ScreenVertex> vertices, size_t& mark,
                              uint32_t& in_window) {
  const int s0 = window_.r0 / strip_height_, s1 = window_.r1 / strip_height_ + 1;
  if (s1 - s0 < 2) return false;
  // Keep the strips whose triangles fill up to 3/4 of the store (at least the first).
  const size_t keep = capacity() - capacity() / 4;
  size_t kept = 0;
  int cut = s0 + 1;
  for (int s = s0; s < s1 - 1; ++s) {
    kept += bucket_size(s);
    if (kept > keep) break;
    cut = s + 1;
  }
  const auto first_row = [vertices](const BinnedTriangle& t) {
    int32_t ymin = vertices[t.v[0]].y;
    if (vertices[t.v[1]].y < ymin) ymin = vertices[t.v[1]].y;
    if (vertices[t.v[2]].y < ymin) ymin = vertices[t.v[2]].y;
    return first_row_below(ymin);
  };
  const int32_t r0 = window_.r0;
  evict_from(
      cut, mark,
      [&](const BinnedTriangle& t) {
        const int32_t r = first_row(t);
        return (r > r0 ? r : r0) / strip_height_;
      },
      [&](const BinnedTriangle& t) {
        if (first_row(t) >= r0)
          ++in_window;
        else
          --window_.carried;
      });
  window_.r1 = cut * strip_height_ - 1;
  return true;
}

bool EdgeTable::misses_its_centre(const ScreenVertex& v0, const ScreenVertex& v1,
                                  const ScreenVertex& v2) const {
  const Bounds k = bounds(v0, v1, v2);
  return one_centre(k.r0, k.r1 + 1, k.c0, k.c1) && k.r0 < height_ && k.c0 < width_ &&
         !holds_centre(v0, v1, v2, k.c0, k.r0);
}

}  // namespace lr
