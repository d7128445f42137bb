// lineraster-asset: converts an OBJ (+MTL) and a PNG into a C++ header of constexpr data in the
// core's formats (see asset_writer.hpp). The options are a table (option_table.hpp's rules). Any
// wrong option or bad file: one line on stderr, exit status 2, no output written.
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "lineraster/host_sim/programs/asset_writer.hpp"
#include "lineraster/host_sim/programs/option_table.hpp"

namespace {

constexpr const char* kUsage =
    "usage: lineraster-asset --obj FILE [--texture FILE.png] [--format rgb565|rgb888|l8|palette8]\n"
    "  [--mipmaps] [--fit | --fit-box] [--subdivide N] [--locality] [--fine-positions]\n"
    "  --name IDENT --out FILE.hpp\n"
    "       lineraster-asset --version | --help\n"
    "Writes a C++ header with the mesh (Q16.16 or finer positions, Q1.14 normals, Q12.20 uvs, "
    "indices,\n"
    "materials) and the texture (level 0 and, with --mipmaps, its mip chain) as constexpr data in\n"
    "namespace IDENT. Without --texture, each material's own map_Kd (if any).\n"
    "--subdivide N: each triangle split in 4 at its edge midpoints, N times (0..4), before the "
    "fit.\n"
    "--fit: centred on the bounding box, farthest vertex at distance 1; --fit-box: centred on the\n"
    "bounding box, uniformly scaled so that its largest half extent is 1 (inside [-1, 1]^3).\n"
    "--fine-positions: positions with the most fraction bits (16..30, Mesh::position_frac) that\n"
    "hold the mesh's largest coordinate (30 inside [-1, 1]^3), for finer snapping; else Q16.16.\n"
    "--locality: triangles sorted by the Z-order of their centroids, vertices numbered by first\n"
    "use (for meshes larger than the renderer's vertex store: its vertex cache hits more).\n"
    "Defaults: --format rgb565, no mipmaps, no fit, no subdivision, the file's order.\n"
    "--out: a regular file, new or replaced whole; a device, FIFO, socket, directory or one of\n"
    "the input files is refused. --version: the version; --help: this text.\n";

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

// What the command line asks for.
struct AssetArgs {
  lr::host::AssetOptions asset;
  std::string out;
  bool help = false, version = false, have_name = false;
};

using lr::host::OptionArg;
using lr::host::OptionError;
using lr::host::OptionKind;
using Row = lr::host::OptionRow<AssetArgs>;

constexpr std::string_view kFormatError = "--format needs rgb565, rgb888, l8 or palette8";
constexpr std::string_view kSubdivideError = "--subdivide needs 0..4";

OptionError help(AssetArgs& a, const OptionArg&) {
  a.help = true;
  return {};
}

// The missing value's message is also the bad value's.
const Row kOptions[] = {
    {"--help", OptionKind::kStop, help},
    {"-h", OptionKind::kStop, help},
    {"--version", OptionKind::kStop,
     [](AssetArgs& a, const OptionArg&) {
       a.version = true;
       return OptionError{};
     }},
    {"--obj", OptionKind::kValue,
     [](AssetArgs& a, const OptionArg& v) {
       a.asset.obj_path = v.value;
       return OptionError{};
     },
     "--obj needs a file name"},
    {"--texture", OptionKind::kValue,
     [](AssetArgs& a, const OptionArg& v) {
       a.asset.texture_path = v.value;
       return OptionError{};
     },
     "--texture needs a file name"},
    {"--format", OptionKind::kValue,
     [](AssetArgs& a, const OptionArg& v) {
       return lr::host::parse_texel_format(v.value, a.asset.format) ? OptionError{}
                                                                    : OptionError(kFormatError);
     },
     kFormatError},
    {"--mipmaps", OptionKind::kFlag,
     [](AssetArgs& a, const OptionArg&) {
       a.asset.mipmaps = true;
       return OptionError{};
     }},
    {"--fit", OptionKind::kFlag,
     [](AssetArgs& a, const OptionArg&) {
       a.asset.fit = true;
       return OptionError{};
     }},
    {"--fit-box", OptionKind::kFlag,
     [](AssetArgs& a, const OptionArg&) {
       a.asset.fit_box = true;
       return OptionError{};
     }},
    {"--fine-positions", OptionKind::kFlag,
     [](AssetArgs& a, const OptionArg&) {
       a.asset.fine_positions = true;
       return OptionError{};
     }},
    {"--locality", OptionKind::kFlag,
     [](AssetArgs& a, const OptionArg&) {
       a.asset.locality = true;
       return OptionError{};
     }},
    {"--subdivide", OptionKind::kValue,
     [](AssetArgs& a, const OptionArg& v) {
       if (v.value.size() != 1 || v.value[0] < '0' || v.value[0] > '4')
         return OptionError(kSubdivideError);
       a.asset.subdivide = v.value[0] - '0';
       return OptionError{};
     },
     kSubdivideError},
    {"--name", OptionKind::kValue,
     [](AssetArgs& a, const OptionArg& v) {
       a.asset.name = v.value;
       a.have_name = true;
       return OptionError{};
     },
     "--name needs a C++ identifier"},
    {"--out", OptionKind::kValue,
     [](AssetArgs& a, const OptionArg& v) {
       a.out = v.value;
       return OptionError{};
     },
     "--out needs a file name"},
};

}  // namespace

int main(int argc, char** argv) {
  AssetArgs args;
  std::string error;
  if (!lr::host::parse_options<AssetArgs>(kOptions, argc, argv, "(--help lists them)", args, error))
    return fail(error);
  if (args.help) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (args.version) {
    std::printf("lineraster-asset %s\n", LR_VERSION);
    return 0;
  }
  lr::host::AssetOptions& o = args.asset;
  if (o.obj_path.empty()) return fail("--obj FILE is required");
  if (!args.have_name) return fail("--name IDENT is required");
  if (!lr::host::valid_asset_name(o.name))
    return fail("--name '" + o.name + "' is not a usable C++ identifier");
  if (args.out.empty()) return fail("--out FILE.hpp is required");
  o.command_line = quoted_command_line(argc, argv);
  std::vector<std::string> warnings;
  if (!lr::host::write_asset_header(o, args.out, error, &warnings)) return fail(error);
  for (const std::string& w : warnings)
    std::fprintf(stderr, "lineraster-asset: warning: %s\n", w.c_str());
  return 0;
}
