// The normal-indexed lighting table: with directional lights and the infinite viewer the lit
// colour of a material depends on the surface normal only, so Phong shading can look it up
// instead of evaluating the lighting model per pixel.
//
// Parameterisation (octahedral, no square root), sample format and lookup:
// docs/numerics.md#the-normal-indexed-lighting-table.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/output/color.hpp"

namespace lr {

inline constexpr uint16_t kMinLightingTable = 8, kMaxLightingTable = 256;

// 32-bit words a table needs.
constexpr size_t lighting_table_words(uint16_t size, bool split) {
  const size_t n = size_t{size} + 1;
  return n * n * (split ? 2 : 1);
}

// A filled table (the words live in FrameStorage::lighting_tables).
struct LightingTable {
  const uint32_t* words = nullptr;
  uint16_t size = 0;
  bool split = false;  // two words per sample: primary, then secondary (specular)
};

// Fills `out` (lighting_table_words(size, split) words) for a prepared material and light set;
// pl must be normal_only (directional lights, infinite viewer).
void fill_lighting_table(const PreparedLighting& pl, uint16_t size, bool split,
                         std::span<uint32_t> out);

namespace detail {

constexpr uint32_t pack10(Color15 c) {
  auto q = [](uint32_t v) { return (v * 1023u + (1u << 14)) >> 15; };
  return (q(c.r) << 20) | (q(c.g) << 10) | q(c.b);
}

// Table coordinates of a direction (x, y, z), any common scale, |components| < 2^31, not all
// zero: gx, gy in Q.8 lattice units, [0, size * 256].
inline void octahedral_q8(int32_t x, int32_t y, int32_t z, uint32_t size, uint32_t& gx,
                          uint32_t& gy) {
  uint32_t ax = x < 0 ? 0u - static_cast<uint32_t>(x) : static_cast<uint32_t>(x);
  uint32_t ay = y < 0 ? 0u - static_cast<uint32_t>(y) : static_cast<uint32_t>(y);
  uint32_t az = z < 0 ? 0u - static_cast<uint32_t>(z) : static_cast<uint32_t>(z);
  // Bring the largest component into [2^12, 2^13), so |x| + |y| + |z| is in [2^12, 3 * 2^13):
  // a 32-bit reciprocal then gives 15-bit coordinates.
  uint32_t m = ax | ay | az;
  if (m == 0) m = 1;
  const int top = 31 - clz32(m);
  if (top > 12) {
    ax >>= top - 12;
    ay >>= top - 12;
    az >>= top - 12;
  } else {
    ax <<= 12 - top;
    ay <<= 12 - top;
    az <<= 12 - top;
  }
  const uint32_t l1 = ax + ay + az;  // [2^12, 3 * 2^13)
  uint32_t px = ax, py = ay;
  if (z < 0) {
    px = l1 - ay;
    py = l1 - ax;
  }
  const uint32_t rcp = (1u << 30) / l1;  // |p| * rcp <= 2^30
  const int32_t sx = static_cast<int32_t>(px * rcp), sy = static_cast<int32_t>(py * rcp);
  // In uint32 (sx = 2^30 gives 2^31, which int32 cannot hold: found by the pipeline fuzzer).
  const uint32_t ux = x < 0 ? (1u << 30) - static_cast<uint32_t>(sx)
                            : (1u << 30) + static_cast<uint32_t>(sx);  // [0, 2^31]
  const uint32_t uy =
      y < 0 ? (1u << 30) - static_cast<uint32_t>(sy) : (1u << 30) + static_cast<uint32_t>(sy);
  // g = (p + 1) / 2 * size in Q.8 = u * size / 2^23; (u >> 8) * size < 2^31.
  gx = ((ux >> 8) * size) >> 15;
  gy = ((uy >> 8) * size) >> 15;
}

// Q1.15 channels of a 10-bit packed sample blended with weights summing to 2^16.
struct Blend10 {
  uint32_t r = 0, g = 0, b = 0;
  void add(uint32_t w, uint32_t weight) {
    r += ((w >> 20) & 1023u) * weight;
    g += ((w >> 10) & 1023u) * weight;
    b += (w & 1023u) * weight;
  }
  // 1023 * 2^16 * 2^5 / 2^16 ~ 32736 = 1.0: within 0.25 of an 8-bit level of the table value.
  Color15 color15() const {
    return {static_cast<uint16_t>((r + 1024u) >> 11), static_cast<uint16_t>((g + 1024u) >> 11),
            static_cast<uint16_t>((b + 1024u) >> 11)};
  }
};

}  // namespace detail

// The table's colour(s) for a direction: primary (or the combined colour) and, for split
// tables, the secondary colour, in Q1.15.
template <bool kBilinear, bool kSplit>
inline void lookup_lighting(const LightingTable& t, int32_t x, int32_t y, int32_t z,
                            Color15& primary, Color15& secondary) {
  uint32_t gx, gy;
  detail::octahedral_q8(x, y, z, t.size, gx, gy);
  const size_t stride = size_t{t.size} + 1;
  constexpr size_t kWords = kSplit ? 2 : 1;
  if constexpr (!kBilinear) {
    const size_t i = (gx + 128u) >> 8, j = (gy + 128u) >> 8;
    const uint32_t* s = t.words + (j * stride + i) * kWords;
    detail::Blend10 b;
    b.add(s[0], 1u << 16);
    primary = b.color15();
    if constexpr (kSplit) {
      detail::Blend10 c;
      c.add(s[1], 1u << 16);
      secondary = c.color15();
    }
  } else {
    size_t i = gx >> 8, j = gy >> 8;
    uint32_t fx = gx & 255u, fy = gy & 255u;
    if (i >= t.size) {
      i = t.size - 1u;
      fx = 256;
    }
    if (j >= t.size) {
      j = t.size - 1u;
      fy = 256;
    }
    const uint32_t* s0 = t.words + (j * stride + i) * kWords;
    const uint32_t* s1 = s0 + stride * kWords;
    const uint32_t w00 = (256 - fx) * (256 - fy), w10 = fx * (256 - fy), w01 = (256 - fx) * fy,
                   w11 = fx * fy;
    detail::Blend10 b;
    b.add(s0[0], w00);
    b.add(s0[kWords], w10);
    b.add(s1[0], w01);
    b.add(s1[kWords], w11);
    primary = b.color15();
    if constexpr (kSplit) {
      detail::Blend10 c;
      c.add(s0[1], w00);
      c.add(s0[kWords + 1], w10);
      c.add(s1[1], w01);
      c.add(s1[kWords + 1], w11);
      secondary = c.color15();
    }
  }
}

}  // namespace lr
