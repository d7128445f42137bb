// Materials (OpenGL's fixed-function material) and the classic OpenGL material table
// (material_table.hpp), both usable in constant expressions.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/scene/material_table.hpp"

namespace lr {

// Colours Q1.15 in [0, 1]; shininess Q8.8 in [0, 128] (GL's range).
struct Material {
  Color15 ambient{6554, 6554, 6554};  // GL defaults: ambient 0.2, diffuse 0.8
  Color15 diffuse{26214, 26214, 26214};
  Color15 specular{0, 0, 0};
  Color15 emission{0, 0, 0};
  uint16_t shininess_q8 = 0;
  friend constexpr bool operator==(const Material&, const Material&) = default;
};

// Whether the material has a specular colour (a renderer without RendererFeatures::specular
// refuses lit draws of such a material).
constexpr bool has_specular(const Material& m) {
  return (m.specular.r | m.specular.g | m.specular.b) != 0;
}

namespace detail {
// A table value (1e-8 units) in Q1.15, rounded to nearest.
constexpr uint16_t material_c15(uint32_t e8) {
  return static_cast<uint16_t>((uint64_t{e8} * Color15::kOne + 50000000u) / 100000000u);
}
}  // namespace detail

// The table entry in the core's formats, rounded to nearest (material_table.hpp's table).
constexpr Material to_material(const NamedMaterial& m) {
  using detail::material_c15;
  Material r;
  r.ambient = {material_c15(m.ambient[0]), material_c15(m.ambient[1]), material_c15(m.ambient[2])};
  r.diffuse = {material_c15(m.diffuse[0]), material_c15(m.diffuse[1]), material_c15(m.diffuse[2])};
  r.specular = {material_c15(m.specular[0]), material_c15(m.specular[1]),
                material_c15(m.specular[2])};
  r.emission = {0, 0, 0};
  // shininess = fraction * 128, in Q8.8: fraction(1e-8) * 128 * 256 / 1e8.
  r.shininess_q8 = static_cast<uint16_t>(
      (uint64_t{m.shininess_fraction} * 128u * 256u + 50000000u) / 100000000u);
  return r;
}

}  // namespace lr
