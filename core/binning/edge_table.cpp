#include "lineraster/core/binning/edge_table.hpp"

namespace lr {

Outcome EdgeTable::classify(const ScreenVertex& v0, const ScreenVertex& v1, const ScreenVertex& v2,
                            Cull cull, int32_t& r0, int32_t& r1) const {
  return classify_inline(v0, v1, v2, cull, r0, r1);
}

}  // namespace lr
