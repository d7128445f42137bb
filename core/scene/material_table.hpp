// The classic OpenGL material table (as published with the "teapots" example and reproduced in
// course notes): ambient, diffuse, specular RGB and shininess as a fraction of 128.
//
// constexpr, in a header: an application that names its materials in constant expressions
// (constexpr Material kGold = to_material(*find_material("gold"));) links neither the table
// nor the lookup, only the Material it uses; a lookup at run time links the table as before.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

namespace lr {

// An entry of the published table, values exactly as published, in units of 1e-8 (every
// published value has at most 8 decimals). Shininess is published as a fraction of 128.
struct NamedMaterial {
  std::string_view name;
  uint32_t ambient[3], diffuse[3], specular[3];
  uint32_t shininess_fraction;  // x 1e-8; GL shininess = fraction * 128
};

namespace detail {

// Values in 1e-8 units: 0.0215 -> 2150000.
inline constexpr std::array<NamedMaterial, 24> kMaterialTable = {{
    {"emerald",
     {2150000, 17450000, 2150000},
     {7568000, 61424000, 7568000},
     {63300000, 72781100, 63300000},
     60000000},
    {"jade",
     {13500000, 22250000, 15750000},
     {54000000, 89000000, 63000000},
     {31622800, 31622800, 31622800},
     10000000},
    {"obsidian",
     {5375000, 5000000, 6625000},
     {18275000, 17000000, 22525000},
     {33274100, 32863400, 34643500},
     30000000},
    {"pearl",
     {25000000, 20725000, 20725000},
     {100000000, 82900000, 82900000},
     {29664800, 29664800, 29664800},
     8800000},
    {"ruby",
     {17450000, 1175000, 1175000},
     {61424000, 4136000, 4136000},
     {72781100, 62695900, 62695900},
     60000000},
    {"turquoise",
     {10000000, 18725000, 17450000},
     {39600000, 74151000, 69102000},
     {29725400, 30829000, 30667800},
     10000000},
    {"brass",
     {32941200, 22352900, 2745100},
     {78039200, 56862700, 11372500},
     {99215700, 94117600, 80784300},
     21794872},
    {"bronze",
     {21250000, 12750000, 5400000},
     {71400000, 42840000, 18144000},
     {39354800, 27190600, 16672100},
     20000000},
    {"chrome",
     {25000000, 25000000, 25000000},
     {40000000, 40000000, 40000000},
     {77459700, 77459700, 77459700},
     60000000},
    {"copper",
     {19125000, 7350000, 2250000},
     {70380000, 27048000, 8280000},
     {25677700, 13762200, 8601400},
     10000000},
    {"gold",
     {24725000, 19950000, 7450000},
     {75164000, 60648000, 22648000},
     {62828100, 55580200, 36606500},
     40000000},
    {"silver",
     {19225000, 19225000, 19225000},
     {50754000, 50754000, 50754000},
     {50827300, 50827300, 50827300},
     40000000},
    {"black_plastic",
     {0, 0, 0},
     {1000000, 1000000, 1000000},
     {50000000, 50000000, 50000000},
     25000000},
    {"cyan_plastic",
     {0, 10000000, 6000000},
     {0, 50980392, 50980392},
     {50196078, 50196078, 50196078},
     25000000},
    {"green_plastic",
     {0, 0, 0},
     {10000000, 35000000, 10000000},
     {45000000, 55000000, 45000000},
     25000000},
    {"red_plastic", {0, 0, 0}, {50000000, 0, 0}, {70000000, 60000000, 60000000}, 25000000},
    {"white_plastic",
     {0, 0, 0},
     {55000000, 55000000, 55000000},
     {70000000, 70000000, 70000000},
     25000000},
    {"yellow_plastic",
     {0, 0, 0},
     {50000000, 50000000, 0},
     {60000000, 60000000, 50000000},
     25000000},
    {"black_rubber",
     {2000000, 2000000, 2000000},
     {1000000, 1000000, 1000000},
     {40000000, 40000000, 40000000},
     7812500},
    {"cyan_rubber",
     {0, 5000000, 5000000},
     {40000000, 50000000, 50000000},
     {4000000, 70000000, 70000000},
     7812500},
    {"green_rubber",
     {0, 5000000, 0},
     {40000000, 50000000, 40000000},
     {4000000, 70000000, 4000000},
     7812500},
    {"red_rubber",
     {5000000, 0, 0},
     {50000000, 40000000, 40000000},
     {70000000, 4000000, 4000000},
     7812500},
    {"white_rubber",
     {5000000, 5000000, 5000000},
     {50000000, 50000000, 50000000},
     {70000000, 70000000, 70000000},
     7812500},
    {"yellow_rubber",
     {5000000, 5000000, 0},
     {50000000, 50000000, 40000000},
     {70000000, 70000000, 4000000},
     7812500},
}};

constexpr char fold_material_name(char c) {
  return (c == '-' || c == ' ') ? '_' : c;
}

}  // namespace detail

// The 24 materials of the classic table (emerald ... yellow_rubber); names use '_' for spaces.
constexpr std::span<const NamedMaterial> material_table() {
  return detail::kMaterialTable;
}

// Lookup by name (case-sensitive; '-' and ' ' are accepted for '_'); nullptr when unknown.
constexpr const NamedMaterial* find_material(std::string_view name) {
  for (const NamedMaterial& m : detail::kMaterialTable) {
    if (m.name.size() != name.size()) continue;
    bool same = true;
    for (size_t i = 0; i < name.size() && same; ++i)
      same = detail::fold_material_name(name[i]) == m.name[i];
    if (same) return &m;
  }
  return nullptr;
}

}  // namespace lr
