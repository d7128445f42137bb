// Materials (OpenGL's fixed-function material) and the classic OpenGL material table.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/output/color.hpp"

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

// An entry of the published table, values exactly as published, in units of 1e-8 (every
// published value has at most 8 decimals). Shininess is published as a fraction of 128.
struct NamedMaterial {
  std::string_view name;
  uint32_t ambient[3], diffuse[3], specular[3];
  uint32_t shininess_fraction;  // x 1e-8; GL shininess = fraction * 128
};

// The 24 materials of the classic table (emerald ... yellow_rubber); names use '_' for spaces.
std::span<const NamedMaterial> material_table();
// Lookup by name (case-sensitive; '-' and ' ' are accepted for '_'); nullptr when unknown.
const NamedMaterial* find_material(std::string_view name);
// The table entry in the core's formats, rounded to nearest.
Material to_material(const NamedMaterial& m);

}  // namespace lr
