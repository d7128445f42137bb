#include "lineraster/core/math/vec.hpp"

namespace lr {

bool normalize_unit30_call(int64_t x, int64_t y, int64_t z, Unit30& out) {
  return detail::normalize_unit30_body(x, y, z, out);
}

}  // namespace lr
