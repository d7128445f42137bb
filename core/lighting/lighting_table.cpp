#include "lineraster/core/lighting/lighting_table.hpp"

#include "lineraster/core/math/inv_sqrt.hpp"
#include "lineraster/core/math/wide_divide.hpp"

namespace lr {

void fill_lighting_table(const PreparedLighting& pl, uint16_t size, bool split,
                         std::span<uint32_t> out) {
  const size_t n = size_t{size} + 1;
  const Vec3 nowhere{};
  for (size_t j = 0; j < n; ++j) {
    for (size_t i = 0; i < n; ++i) {
      // Lattice point p in Q1.30, then the direction it stands for. i, j <= size: each quotient
      // is at most 2^31, one 64-by-32 division.
      const int64_t px = int64_t{divide_64by32(uint64_t{i} << 31, size).q} - (int64_t{1} << 30);
      const int64_t py = int64_t{divide_64by32(uint64_t{j} << 31, size).q} - (int64_t{1} << 30);
      const int64_t ax = px < 0 ? -px : px, ay = py < 0 ? -py : py;
      int64_t x = px, y = py;
      const int64_t z = (int64_t{1} << 30) - ax - ay;
      if (z < 0) {
        x = px < 0 ? -((int64_t{1} << 30) - ay) : (int64_t{1} << 30) - ay;
        y = py < 0 ? -((int64_t{1} << 30) - ax) : (int64_t{1} << 30) - ax;
      }
      // The table's inverse square root (as the spans renormalise): no square root, no division,
      // within 2^-15 of unit length.
      Unit30 u{0, 0, 1 << 30};
      DefaultInvSqrt::normalize(x, y, z, u);
      const size_t k = (j * n + i) * (split ? 2 : 1);
      if (split) {
        const LitColor c = light_point_split(pl, u, nowhere);
        out[k] = detail::pack10(c.primary);
        out[k + 1] = detail::pack10(c.secondary);
      } else {
        out[k] = detail::pack10(light_point(pl, u, nowhere));
      }
    }
  }
}

}  // namespace lr
