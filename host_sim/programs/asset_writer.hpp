// lineraster-asset's work: an OBJ (+MTL) and a PNG converted to a C++ header of constexpr data in
// the core's formats, ready to compile into firmware (the arrays go to flash). Host only.
//
// The mesh goes through lr::host::build_fixed_draws (SceneOptions: fit from the option,
// use_mesh_materials on), the texture through lr::host::load_texture, so the header holds exactly
// the numbers lineraster-sim renders. The header defines, in `namespace NAME`:
//   positions_D[], normals_D[], uvs_D[] (if the mesh has vt), colors_D[] (if it has vertex
//   colours), triangles_D[] (std::array<uint16_t, 3>), material_D, mesh_D   for each draw D;
//   meshes (std::array<lr::Mesh, N>), materials (std::array<lr::Material, N>),
//   textured (std::array<bool, N>): whether draw D takes the texture (see below), draw_count;
//   with a texture: texture_level_L[] for every level (uint16_t for rgb565, uint8_t otherwise,
//   rows bottom first), texture_palette[] (palette8), and `texture` (lr::Texture).
// All are `inline constexpr` (one copy however many files include the header). Numbers are raw:
// positions as {{x}, {y}, {z}} (Fixed's raw value) of Mesh::position_frac fraction bits (16, or
// with --fine-positions the most in [16, 30] that hold the mesh's largest coordinate: 30 for a
// mesh inside [-1, 1]^3), which mesh_D's last field states (headers written before it have no
// such field: their meshes are Q16.16, the field's default), Q1.14 normals, Q12.20 texture
// coordinates, Q1.15 material colours, Q8.8 shininess.
//
// Texture choice: --texture FILE; else the map_Kd of the first material (in MTL definition order)
// that has one; else none. `textured[D]`: with --texture, every draw that has texture
// coordinates; with a map_Kd texture, the draws whose material names that same file and that
// have texture coordinates.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "lineraster/core/texture/texture.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/scene/scene.hpp"

namespace lr::host {

struct AssetOptions {
  std::string obj_path;
  std::string texture_path;  // "" = the first material's map_Kd, if any
  TexelFormat format = TexelFormat::kRgb565;
  bool mipmaps = false;
  bool fit = false;             // fit_transform: farthest vertex at distance 1
  bool fit_box = false;         // fit_box_transform: largest half extent 1 (not with fit)
  int subdivide = 0;            // midpoint subdivision levels (mesh_prep.hpp: subdivide), 0..4
  bool locality = false;        // triangles and vertices in spatial order (locality_order.hpp)
  bool fine_positions = false;  // positions of the most fraction bits the mesh allows (16..30)
  std::string name;             // a C++ identifier: the header's namespace
  std::string command_line;     // recorded in the header's comment ("" = none)
};

// The loaded and converted inputs of a header.
struct AssetData {
  std::vector<FixedDraw> draws;
  std::vector<bool> textured;  // per draw: it takes `texture` (draw_texture 0)
  bool has_texture = false;
  std::string texture_path;  // the file the texture came from
  HostTexture texture;
  // Each material's own texture: the second and later distinct ones (`texture_1` ...), and per
  // draw which it takes: -1 none, 0 `texture`, k `more_textures[k - 1]`.
  std::vector<HostTexture> more_textures;
  std::vector<std::string> more_texture_paths;
  std::vector<int> draw_texture;
  std::vector<std::string> inputs;    // every file read: the OBJ, its MTL files, the texture
  std::vector<std::string> warnings;  // what the files asked for and was left out or replaced
};

// A valid name: [A-Za-z_][A-Za-z0-9_]*, not a C++ keyword, not reserved (no "__", no leading
// underscore followed by an upper-case letter), not "lr" or "std".
bool valid_asset_name(std::string_view name);

// Loads the OBJ and the texture and converts them. False with a one-line error on failure.
bool load_asset(const AssetOptions& options, AssetData& out, std::string& error);

// The header text for loaded data.
std::string asset_header_text(const AssetOptions& options, const AssetData& data);

// load_asset + asset_header_text, then writes the header to `out_path` under output_file.hpp's
// rules (a regular file, replaced atomically; never a device, FIFO, socket or directory, never
// one of the files it reads; no output on any failure). False with a one-line error.
bool write_asset_header(const AssetOptions& options, const std::string& out_path,
                        std::string& error, std::vector<std::string>* warnings = nullptr);

}  // namespace lr::host
