// lineraster-asset: converts an OBJ (+MTL) and a PNG into a C++ header of constexpr data in the
// core's formats (see asset_writer.hpp). Any wrong option or bad file: one line on stderr, exit
// status 2, no output written.
#include <cstdio>
#include <string>
#include <string_view>

#include "host_sim/programs/asset_writer.hpp"

namespace {

constexpr const char* kUsage =
    "usage: lineraster-asset --obj FILE [--texture FILE.png] [--format rgb565|rgb888|l8|palette8]\n"
    "  [--mipmaps] [--fit] [--subdivide N] --name IDENT --out FILE.hpp\n"
    "Writes a C++ header with the mesh (Q16.16 positions, Q1.14 normals, Q12.20 uvs, indices,\n"
    "materials) and the texture (level 0 and, with --mipmaps, its mip chain) as constexpr data in\n"
    "namespace IDENT. Without --texture, the first material's map_Kd is used (if any).\n"
    "--subdivide N: each triangle split in 4 at its edge midpoints, N times (0..4), before the "
    "fit.\n"
    "Defaults: --format rgb565, no mipmaps, no fit, no subdivision.\n";

int fail(const std::string& msg) {
  std::fprintf(stderr, "lineraster-asset: %s\n", msg.c_str());
  return 2;
}

std::string quoted_command_line(int argc, char** argv) {
  std::string s = "lineraster-asset";
  for (int i = 1; i < argc; ++i) {
    std::string_view a = argv[i];
    s += ' ';
    if (!a.empty() && a.find_first_of(" \t'\"") == std::string_view::npos) {
      s += a;
    } else {
      s += '\'';
      for (char c : a) {
        if (c == '\'') {
          s += "'\\''";
        } else {
          s += c;
        }
      }
      s += '\'';
    }
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  lr::host::AssetOptions o;
  std::string out;
  bool have_name = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    // A value never starts with "--": "--obj --out x.hpp" is a missing value, not a file "--out".
    auto value = [&](std::string& v) {
      if (i + 1 >= argc || std::string_view(argv[i + 1]).substr(0, 2) == "--") return false;
      v = argv[++i];
      return true;
    };
    std::string v;
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (a == "--obj") {
      if (!value(o.obj_path)) return fail("--obj needs a file name");
    } else if (a == "--texture") {
      if (!value(o.texture_path)) return fail("--texture needs a file name");
    } else if (a == "--format") {
      if (!value(v) || !lr::host::parse_texel_format(v, o.format))
        return fail("--format needs rgb565, rgb888, l8 or palette8");
    } else if (a == "--mipmaps") {
      o.mipmaps = true;
    } else if (a == "--fit") {
      o.fit = true;
    } else if (a == "--subdivide") {
      if (!value(v) || v.size() != 1 || v[0] < '0' || v[0] > '4')
        return fail("--subdivide needs 0..4");
      o.subdivide = v[0] - '0';
    } else if (a == "--name") {
      if (!value(o.name)) return fail("--name needs a C++ identifier");
      have_name = true;
    } else if (a == "--out") {
      if (!value(out)) return fail("--out needs a file name");
    } else {
      return fail("unknown option '" + std::string(a) + "' (--help lists them)");
    }
  }
  if (o.obj_path.empty()) return fail("--obj FILE is required");
  if (!have_name) return fail("--name IDENT is required");
  if (!lr::host::valid_asset_name(o.name))
    return fail("--name '" + o.name + "' is not a usable C++ identifier");
  if (out.empty()) return fail("--out FILE.hpp is required");
  o.command_line = quoted_command_line(argc, argv);
  std::string error;
  if (!lr::host::write_asset_header(o, out, error)) return fail(error);
  return 0;
}
