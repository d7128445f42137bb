// The headers lineraster-asset generated at build time, compiled as firmware compiles them: with
// the core's flags (lr_strict: -fno-exceptions -fno-rtti -Wall -Wextra -Wconversion
// -Wsign-conversion -Wshadow -Werror) on the host, and by CMake's custom command for Cortex-M4F
// with arm-none-eabi-g++. The static_asserts check that the data is usable in constant
// expressions (it lands in flash, not in RAM initialised at start-up).
#include <cstddef>

#include "cube_rgb565.hpp"
#include "cube_rgb888.hpp"
#include "knot_l8.hpp"
#include "knot_palette8.hpp"
#include "two_textures.hpp"

static_assert(cube_rgb565::draw_count == 2 && cube_rgb565::meshes.size() == 2);
static_assert(cube_rgb565::texture.format == lr::TexelFormat::kRgb565);
static_assert(cube_rgb565::texture.level_count == 4);  // 8x8 .. 1x1
static_assert(cube_rgb565::texture.levels[3].width == 1);
static_assert(cube_rgb565::meshes[1].uvs.size() == cube_rgb565::meshes[1].positions.size());
static_assert(!cube_rgb565::textured[0] && cube_rgb565::textured[1]);  // only cube_white
static_assert(cube_rgb888::texture.level_count == 1);
static_assert(cube_rgb888::texture.levels[0].bytes.size() == 8 * 8 * 3);
static_assert(knot_palette8::texture.format == lr::TexelFormat::kPalette8);
static_assert(knot_palette8::texture.palette.size() >= 1);
static_assert(knot_l8::texture.levels[0].bytes.size() == 8 * 8);
static_assert(knot_l8::meshes[0].triangles.size() == 4000);
static_assert(two_textures::draw_count == 2 &&
              two_textures::draw_textures[0] == &two_textures::texture);
static_assert(two_textures::draw_textures[1] == &two_textures::texture_1);
static_assert(two_textures::texture_1.levels[0].width == 64);  // tiles64.png
static_assert(cube_rgb565::draw_textures[0] == nullptr &&
              cube_rgb565::draw_textures[1] == &cube_rgb565::texture);

// Something for the archive to hold.
std::size_t lr_asset_strict_draw_count() {
  return cube_rgb565::draw_count + cube_rgb888::draw_count + knot_palette8::draw_count +
         knot_l8::draw_count + two_textures::draw_count;
}
