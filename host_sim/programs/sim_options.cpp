#include "lineraster/host_sim/programs/sim_options.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "lineraster/host_sim/programs/gif_writer.hpp"
#include "lineraster/host_sim/programs/option_table.hpp"

namespace lr::host {
namespace {

constexpr const char* kUsage =
    "usage: lineraster-sim --obj FILE [--out FILE.png|.ppm|.gif] [--width N] [--height N]\n"
    "  [--fovy DEG] [--near Z] [--far Z] [--eye x,y,z] [--target x,y,z] [--up x,y,z] [--fit]\n"
    "  [--model-scale S] [--model-rotate-x DEG] [--model-rotate-y DEG] [--model-rotate-z DEG]\n"
    "  [--model-translate x,y,z] [--shading flat|gouraud|phong] [--unlit]\n"
    "  [--light-dir x,y,z] [--light dir:x,y,z[:r,g,b]] [--light point:x,y,z[:r,g,b[:c,l,q]]]\n"
    "  [--global-ambient r,g,b] [--local-viewer] [--two-sided] [--material NAME]\n"
    "  [--ambient r,g,b] [--diffuse r,g,b] [--specular r,g,b] [--shininess N] [--bg r,g,b]\n"
    "  [--no-depth] [--cull back|none] [--depth-out FILE.png] [--strip-height 1|2|4|8|16|32]\n"
    "  [--stats] [--texture FILE.png] [--filter nearest|bilinear] [--wrap repeat|clamp]\n"
    "  [--perspective exact|span8|span16|span32|affine] [--mipmap none|nearest|linear]\n"
    "  [--texture-format rgb565|rgb888|l8|palette8] [--subdivide N] [--stores V,T,A]\n"
    "  [--frames N] [--out-pattern NAME_%03d.png] [--gif-delay CS] [--version] [--help]\n"
    "Phong only (--shading phong): [--lighting exact|table] [--lighting-table N]\n"
    "  [--lighting-table-filter nearest|bilinear] [--envmap FILE.png] [--normalmap FILE.png]\n"
    "--light: repeatable, at most 4, not with --light-dir; colour r,g,b default 1,1,1; c,l,q:\n"
    "  GL attenuation 1 / (c + l d + q d^2), default 1,0,0. --lighting default exact;\n"
    "  --lighting-table: 8..256 cells per side, default 32, bilinear; needs --lighting table.\n"
    "--model-rotate-x/-y/-z DEG: the model turned about z first, then x, then y (a Z-up model\n"
    "  stands upright with --model-rotate-x -90); model = translate * Ry * Rx * Rz * scale.\n"
    "Panels: [--display emulator:PANEL] [--display ft232h[:SERIAL]] [--panel PANEL]\n"
    "  [--display spidev:DEVICE,dc=CHIP:LINE,rst=CHIP:LINE[,bl=CHIP:LINE][,hz=N]]\n"
    "PANEL: st7789:240x240|240x320|135x240|320x240[:ROT] or ili9341:240x320|320x240[:ROT], ROT\n"
    "  0|90|180|270 (default 0); the frame is the panel's size. spidev and ft232h need --panel.\n"
    "--frames N: N frames turning the model 360/N degrees about y each, statistics per frame;\n"
    "  --out gets the last frame, or all of them as an animated GIF when it ends in .gif\n"
    "  (--gif-delay CS: hundredths of a second per frame, 2..6000, default 4);\n"
    "  --out-pattern writes each frame to its own file (one %d, %0Nd or %Nd: the frame number\n"
    "  from 0; .png or .ppm), and then --out only when it is given.\n"
    "--subdivide N: split each triangle in 4 at its edge midpoints, N times (0..4).\n"
    "--stores V,T,A: the renderer's vertex, binned-triangle and active-triangle stores (default\n"
    "  65535,65534,4096), as a firmware's; a frame that needs more is drawn in bands.\n"
    "Outputs are regular files only: a device, FIFO, socket, directory or input file is refused.\n"
    "Exit status: 0 drawn; 2 bad input, nothing written; 3 written, but work was dropped for\n"
    "  lack of store space (a warning says what).\n";

// ---- Values ----

// An optional sign ('+' is allowed, as people write it) and the rest of a number.
std::string_view unsigned_part(std::string_view s, bool& negative) {
  negative = !s.empty() && s[0] == '-';
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) s.remove_prefix(1);
  return s;
}

// A finite decimal, the whole string: digits with an optional point and exponent ("2", "-0.5",
// "1e-3"). Not hexadecimal, not "inf" or "nan", no blanks (strtod takes all of those).
bool parse_double(std::string_view s, double& out) {
  bool negative = false;
  s = unsigned_part(s, negative);
  if (s.empty() || !(std::isdigit(static_cast<unsigned char>(s[0])) || s[0] == '.')) return false;
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end != s.data() + s.size() || !std::isfinite(v)) return false;
  out = negative ? -v : v;
  return true;
}

// A whole number within +-1e9, in decimal digits only ("320", "-2"; not "0x140" or "1e2").
bool parse_int(std::string_view s, int& out) {
  bool negative = false;
  s = unsigned_part(s, negative);
  if (s.empty() || !std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  long long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end != s.data() + s.size() || v > 1000000000) return false;
  out = static_cast<int>(negative ? -v : v);
  return true;
}

bool parse_vec3(std::string_view s, Vec3d& out) {
  size_t a = s.find(','), b = a == std::string_view::npos ? a : s.find(',', a + 1);
  if (b == std::string_view::npos || s.find(',', b + 1) != std::string_view::npos) return false;
  return parse_double(s.substr(0, a), out[0]) && parse_double(s.substr(a + 1, b - a - 1), out[1]) &&
         parse_double(s.substr(b + 1), out[2]);
}

// Splits s at every ':' ("a:b:" gives "a", "b", "").
std::vector<std::string_view> split_colons(std::string_view s) {
  std::vector<std::string_view> parts;
  for (size_t start = 0;;) {
    size_t c = s.find(':', start);
    parts.push_back(s.substr(start, c == std::string_view::npos ? c : c - start));
    if (c == std::string_view::npos) return parts;
    start = c + 1;
  }
}

bool unit_color(const Vec3d& c) {
  for (double v : c)
    if (v < 0 || v > 1) return false;
  return true;
}

// --light dir:x,y,z[:r,g,b] or point:x,y,z[:r,g,b[:c,l,q]]. On failure `why` says what is
// wrong, in the words of the option's error message.
bool parse_light(std::string_view s, LightOption& out, std::string& why) {
  why = "expected dir:x,y,z[:r,g,b] or point:x,y,z[:r,g,b[:c,l,q]]";
  const std::vector<std::string_view> p = split_colons(s);
  if (p[0] != "dir" && p[0] != "point") return false;
  out = LightOption{};
  out.point = p[0] == "point";
  if (p.size() < 2 || p.size() > (out.point ? 4u : 3u) || !parse_vec3(p[1], out.xyz)) return false;
  if (!out.point && out.xyz[0] == 0 && out.xyz[1] == 0 && out.xyz[2] == 0) {
    why = "zero direction";
    return false;
  }
  if (p.size() >= 3 && (!parse_vec3(p[2], out.color) || !unit_color(out.color))) {
    why = "colour r,g,b in [0,1]";
    return false;
  }
  if (p.size() == 4) {
    Vec3d a;
    if (!parse_vec3(p[3], a) || a[0] < 0 || a[1] < 0 || a[2] < 0 || a[0] > 32767 || a[1] > 32767 ||
        a[2] > 32767 || a[0] + a[1] + a[2] <= 0) {
      why = "attenuation c,l,q: each in [0, 32767], not all 0";
      return false;
    }
    out.constant = a[0];
    out.linear = a[1];
    out.quadratic = a[2];
  }
  return true;
}

// The file name's extension in lower case ("" when it has none).
std::string extension(std::string_view path) {
  size_t dot = path.find_last_of('.');
  size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e(path.substr(dot + 1));
  for (char& ch : e) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return e;
}

// ---- Handlers shared by several rows ----

template <class T>
struct Choice {
  std::string_view word;
  T value;
};

// One of the words, else "bad value 'V' (a, b or c)".
template <class T>
OptionError choose(const OptionArg& a, std::initializer_list<Choice<T>> choices, T& out) {
  std::string hint;
  size_t k = 0;
  for (const Choice<T>& c : choices) {
    if (c.word == a.value) {
      out = c.value;
      return {};
    }
    if (k > 0) hint += k + 1 == choices.size() ? " or " : ", ";
    hint += c.word;
    ++k;
  }
  return a.bad(hint);
}

// A whole number in [lo, hi], else "bad value 'V' (lo..hi)".
OptionError int_in(const OptionArg& a, int lo, int hi, int& out) {
  int n = 0;
  if (!parse_int(a.value, n) || n < lo || n > hi)
    return a.bad(std::to_string(lo) + ".." + std::to_string(hi));
  out = n;
  return {};
}

// --stores V,T,A: each within the core's limits (the store's index type).
OptionError stores(SimOptions& o, const OptionArg& a) {
  const std::string_view s = a.value;
  const size_t c1 = s.find(','), c2 = c1 == std::string_view::npos ? c1 : s.find(',', c1 + 1);
  int v = 0, t = 0, n = 0;
  if (c2 == std::string_view::npos || s.find(',', c2 + 1) != std::string_view::npos ||
      !parse_int(s.substr(0, c1), v) || !parse_int(s.substr(c1 + 1, c2 - c1 - 1), t) ||
      !parse_int(s.substr(c2 + 1), n) || v < 1 || v > 0xFFFF || t < 1 || t > 0xFFFE || n < 1 ||
      n > 0xFFFF)
    return a.bad("expected V,T,A: 1..65535, 1..65534, 1..65535");
  o.scene.stores = {static_cast<size_t>(v), static_cast<size_t>(t), static_cast<size_t>(n)};
  return {};
}

OptionError vec3(const OptionArg& a, Vec3d& out) {
  return parse_vec3(a.value, out) ? OptionError{} : a.bad("expected x,y,z");
}

OptionError color(const OptionArg& a, Vec3d& out) {
  Vec3d c{};
  if (!parse_vec3(a.value, c) || !unit_color(c)) return a.bad("expected r,g,b in [0,1]");
  out = c;
  return {};
}

void note_first(std::string& first, std::string_view name) {
  if (first.empty()) first = name;
}

template <bool SimOptions::*Field>
OptionError flag(SimOptions& o, const OptionArg&) {
  o.*Field = true;
  return {};
}

template <std::string SimOptions::*Field>
OptionError text(SimOptions& o, const OptionArg& a) {
  o.*Field = a.value;
  return {};
}

template <std::string SceneOptions::*Field>
OptionError scene_text(SimOptions& o, const OptionArg& a) {
  o.scene.*Field = a.value;
  return {};
}

template <bool SceneOptions::*Field, bool Value = true>
OptionError scene_flag(SimOptions& o, const OptionArg&) {
  o.scene.*Field = Value;
  return {};
}

template <Vec3d SceneOptions::*Field>
OptionError scene_vec3(SimOptions& o, const OptionArg& a) {
  return vec3(a, o.scene.*Field);
}

template <Vec3d SceneOptions::*Field>
OptionError scene_color(SimOptions& o, const OptionArg& a) {
  return color(a, o.scene.*Field);
}

// --ambient, --diffuse, --specular: a material option replaces the mesh's MTL materials.
template <Vec3d MaterialOptions::*Field>
OptionError material_color(SimOptions& o, const OptionArg& a) {
  o.scene.use_mesh_materials = false;
  return color(a, o.scene.material.*Field);
}

// --envmap, --normalmap: a file, read when the frame is rendered.
template <std::string SceneOptions::*Field>
OptionError phong_map(SimOptions& o, const OptionArg& a) {
  o.scene.*Field = a.value;
  note_first(o.phong_only, a.name);
  return {};
}

// ---- Handlers of one row each ----

OptionError help(SimOptions& o, const OptionArg&) {
  o.help = true;
  return {};
}

OptionError version(SimOptions& o, const OptionArg&) {
  o.version = true;
  return {};
}

OptionError out_file(SimOptions& o, const OptionArg& a) {
  o.out = a.value;
  o.out_given = true;
  const std::string ext = extension(o.out);
  if (ext != "png" && ext != "ppm" && ext != "gif")
    return "--out: the file name must end in .png, .ppm or .gif";
  if (ext == "gif" && !gif_supported()) return "--out: " + gif_missing_error(o.out);
  return {};
}

OptionError out_pattern(SimOptions& o, const OptionArg& a) {
  std::string why;
  if (!parse_frame_pattern(a.value, o.out_pattern, why)) return a.bad(why);
  const std::string ext = extension(o.out_pattern.name(0));
  if (ext != "png" && ext != "ppm") return a.bad("the file name must end in .png or .ppm");
  return {};
}

OptionError depth_file(SimOptions& o, const OptionArg& a) {
  o.depth_out = a.value;
  if (extension(o.depth_out) != "png") return "--depth-out: the file name must end in .png";
  return {};
}

OptionError strip_height(SimOptions& o, const OptionArg& a) {
  int n = 0;
  if (!parse_int(a.value, n) || (n != 1 && n != 2 && n != 4 && n != 8 && n != 16 && n != 32))
    return a.bad("1, 2, 4, 8, 16 or 32");
  o.scene.strip_height = n;
  return {};
}

// A finite number, else "bad value 'V'"; the range checks are the callers'.
OptionError number(const OptionArg& a, double& out) {
  return parse_double(a.value, out) ? OptionError{} : a.bad();
}

OptionError fovy(SimOptions& o, const OptionArg& a) {
  double d = 0;
  if (OptionError e = number(a, d); !e.empty()) return e;
  if (d <= 0 || d >= 180) return a.bad("0 < fovy < 180");
  o.scene.fovy = d;
  return {};
}

OptionError near_plane(SimOptions& o, const OptionArg& a) {
  double d = 0;
  if (OptionError e = number(a, d); !e.empty()) return e;
  if (d <= 0) return a.bad("near > 0");
  o.scene.near = d;
  return {};
}

// --model-rotate-x/-y/-z: degrees, any finite value (taken modulo 360).
template <double SceneOptions::*Field>
OptionError model_rotate(SimOptions& o, const OptionArg& a) {
  double d = 0;
  if (OptionError e = number(a, d); !e.empty()) return e;
  o.scene.*Field = std::fmod(d, 360.0);
  return {};
}

OptionError shininess(SimOptions& o, const OptionArg& a) {
  double d = 0;
  if (OptionError e = number(a, d); !e.empty()) return e;
  if (d < 0 || d > 128) return a.bad("0..128");
  o.scene.material.shininess = d;
  o.scene.use_mesh_materials = false;
  return {};
}

OptionError light_dir(SimOptions& o, const OptionArg& a) {
  Vec3d p{};
  if (OptionError e = vec3(a, p); !e.empty()) return e;
  if (p[0] == 0 && p[1] == 0 && p[2] == 0) return a.bad("zero direction");
  o.light_dirs.push_back(p);
  return {};
}

OptionError light(SimOptions& o, const OptionArg& a) {
  LightOption l;
  std::string why;
  if (!parse_light(a.value, l, why)) return a.bad(why);
  if (o.lights.size() == static_cast<size_t>(kMaxLights))
    return "--light: at most " + std::to_string(kMaxLights) + " lights";
  o.lights.push_back(l);
  return {};
}

// A named material of core/scene/material.hpp; replaces the mesh's MTL materials.
OptionError material(SimOptions& o, const OptionArg& a) {
  const NamedMaterial* m = find_material(a.value);
  if (!m) return a.bad("unknown material; e.g. gold, silver, jade, ruby, red_plastic");
  MaterialOptions& mo = o.scene.material;
  for (size_t k = 0; k < 3; ++k) {
    mo.ambient[k] = m->ambient[k] * 1e-8;
    mo.diffuse[k] = m->diffuse[k] * 1e-8;
    mo.specular[k] = m->specular[k] * 1e-8;
  }
  mo.emission = {0, 0, 0};
  mo.shininess = m->shininess_fraction * 1e-8 * 128.0;
  o.scene.use_mesh_materials = false;
  return {};
}

OptionError lighting(SimOptions& o, const OptionArg& a) {
  OptionError e = choose(a, {{"exact", PixelLighting::kExact}, {"table", PixelLighting::kTable}},
                         o.scene.pixel_lighting);
  note_first(o.phong_only, a.name);
  return e;
}

OptionError lighting_table(SimOptions& o, const OptionArg& a) {
  int n = 0;
  if (OptionError e = int_in(a, 8, 256, n); !e.empty()) return e;
  o.scene.table.size = static_cast<uint16_t>(n);
  note_first(o.phong_only, a.name);
  note_first(o.table_only, a.name);
  return {};
}

OptionError lighting_table_filter(SimOptions& o, const OptionArg& a) {
  OptionError e = choose(a, {{"nearest", false}, {"bilinear", true}}, o.scene.table.bilinear);
  note_first(o.phong_only, a.name);
  note_first(o.table_only, a.name);
  return e;
}

OptionError texture_format(SimOptions& o, const OptionArg& a) {
  if (!parse_texel_format(a.value, o.scene.texture_format))
    return a.bad("rgb565, rgb888, l8 or palette8");
  return {};
}

OptionError display(SimOptions& o, const OptionArg& a) {
  std::string why;
  return parse_display_spec(a.value, o.display, why) ? OptionError{} : a.bad(why);
}

OptionError panel(SimOptions& o, const OptionArg& a) {
  std::string why;
  if (!parse_panel_spec(a.value, o.panel, why)) return a.bad(why);
  o.has_panel = true;
  return {};
}

// ---- The table ----

using Row = OptionRow<SimOptions>;
constexpr OptionKind kFlag = OptionKind::kFlag, kValue = OptionKind::kValue;

const Row kOptions[] = {
    {"--help", OptionKind::kStop, help},
    {"-h", OptionKind::kStop, help},
    {"--version", OptionKind::kStop, version},
    // Input, output, frame.
    {"--obj", kValue, text<&SimOptions::obj>},
    {"--out", kValue, out_file},
    {"--out-pattern", kValue, out_pattern},
    {"--gif-delay", kValue,
     [](SimOptions& o, const OptionArg& a) {
       o.gif_delay_given = true;
       return int_in(a, kMinGifDelay, kMaxGifDelay, o.gif_delay);
     }},
    {"--depth-out", kValue, depth_file},
    {"--stats", kFlag, flag<&SimOptions::stats>},
    {"--width", kValue,
     [](SimOptions& o, const OptionArg& a) {
       o.width_given = true;
       return int_in(a, 1, 4096, o.scene.width);
     }},
    {"--height", kValue,
     [](SimOptions& o, const OptionArg& a) {
       o.height_given = true;
       return int_in(a, 1, 4096, o.scene.height);
     }},
    {"--strip-height", kValue, strip_height},
    {"--bg", kValue, scene_color<&SceneOptions::background>},
    {"--no-depth", kFlag, scene_flag<&SceneOptions::depth_test, false>},
    {"--cull", kValue,
     [](SimOptions& o, const OptionArg& a) {
       return choose(a, {{"back", Cull::kBack}, {"none", Cull::kNone}}, o.scene.cull);
     }},
    // Camera and model.
    {"--fovy", kValue, fovy},
    {"--near", kValue, near_plane},
    {"--far", kValue, [](SimOptions& o, const OptionArg& a) { return number(a, o.scene.far); }},
    {"--eye", kValue, scene_vec3<&SceneOptions::eye>},
    {"--target", kValue, scene_vec3<&SceneOptions::target>},
    {"--up", kValue, scene_vec3<&SceneOptions::up>},
    {"--fit", kFlag, scene_flag<&SceneOptions::fit>},
    {"--model-scale", kValue,
     [](SimOptions& o, const OptionArg& a) { return number(a, o.scene.model_scale); }},
    {"--model-rotate-x", kValue, model_rotate<&SceneOptions::model_rotate_x>},
    {"--model-rotate-y", kValue, model_rotate<&SceneOptions::model_rotate_y>},
    {"--model-rotate-z", kValue, model_rotate<&SceneOptions::model_rotate_z>},
    {"--model-translate", kValue, scene_vec3<&SceneOptions::model_translate>},
    {"--subdivide", kValue,
     [](SimOptions& o, const OptionArg& a) { return int_in(a, 0, 4, o.subdivisions); }},
    {"--stores", kValue, stores},
    // Shading, lights, materials.
    {"--shading", kValue,
     [](SimOptions& o, const OptionArg& a) {
       return choose(
           a,
           {{"flat", Shading::kFlat}, {"gouraud", Shading::kGouraud}, {"phong", Shading::kPhong}},
           o.scene.shading);
     }},
    {"--unlit", kFlag, scene_flag<&SceneOptions::unlit>},
    {"--light-dir", kValue, light_dir},
    {"--light", kValue, light},
    {"--global-ambient", kValue, scene_color<&SceneOptions::global_ambient>},
    {"--local-viewer", kFlag, scene_flag<&SceneOptions::local_viewer>},
    {"--two-sided", kFlag, scene_flag<&SceneOptions::two_sided>},
    {"--material", kValue, material},
    {"--ambient", kValue, material_color<&MaterialOptions::ambient>},
    {"--diffuse", kValue, material_color<&MaterialOptions::diffuse>},
    {"--specular", kValue, material_color<&MaterialOptions::specular>},
    {"--shininess", kValue, shininess},
    // Per-pixel lighting (Phong only).
    {"--lighting", kValue, lighting},
    {"--lighting-table", kValue, lighting_table},
    {"--lighting-table-filter", kValue, lighting_table_filter},
    {"--envmap", kValue, phong_map<&SceneOptions::envmap>},
    {"--normalmap", kValue, phong_map<&SceneOptions::normalmap>},
    // Texturing.
    {"--texture", kValue, scene_text<&SceneOptions::texture>},
    {"--texture-format", kValue, texture_format},
    {"--filter", kValue,
     [](SimOptions& o, const OptionArg& a) {
       return choose(a, {{"nearest", Filter::kNearest}, {"bilinear", Filter::kBilinear}},
                     o.scene.filter);
     }},
    {"--wrap", kValue,
     [](SimOptions& o, const OptionArg& a) {
       return choose(a, {{"repeat", Wrap::kRepeat}, {"clamp", Wrap::kClampToEdge}}, o.scene.wrap);
     }},
    {"--perspective", kValue,
     [](SimOptions& o, const OptionArg& a) {
       return choose(a,
                     {{"exact", Perspective::kExact},
                      {"span8", Perspective::kSpan8},
                      {"span16", Perspective::kSpan16},
                      {"span32", Perspective::kSpan32},
                      {"affine", Perspective::kAffine}},
                     o.scene.perspective);
     }},
    {"--mipmap", kValue,
     [](SimOptions& o, const OptionArg& a) {
       return choose(
           a,
           {{"none", MipMode::kNone}, {"nearest", MipMode::kNearest}, {"linear", MipMode::kLinear}},
           o.scene.mipmap);
     }},
    // Panels.
    {"--display", kValue, display},
    {"--panel", kValue, panel},
    {"--frames", kValue,
     [](SimOptions& o, const OptionArg& a) { return int_in(a, 1, 3600, o.frames); }},
};

// ---- Checks once every option is read ----

bool check_lights(SimOptions& o, std::string& error) {
  if (!o.light_dirs.empty() && !o.lights.empty()) {
    error = "--light and --light-dir cannot be combined (use --light dir:x,y,z)";
    return false;
  }
  if (!o.light_dirs.empty()) o.scene.light_dirs = o.light_dirs;
  o.scene.lights = o.lights;
  if (!o.phong_only.empty() && o.scene.shading != Shading::kPhong) {
    error = o.phong_only + " needs --shading phong";
    return false;
  }
  if (!o.table_only.empty() && o.scene.pixel_lighting != PixelLighting::kTable) {
    error = o.table_only + " needs --lighting table";
    return false;
  }
  return true;
}

// A panel decides the frame's size.
bool check_panel(SimOptions& o, std::string& error) {
  const bool to_panel = o.display.kind != DisplayKind::kNone;
  if (o.display.kind == DisplayKind::kEmulator) {
    if (o.has_panel) {
      error = "--panel: not with --display emulator (the emulator's value names the panel)";
      return false;
    }
    o.panel = o.display.panel;
  } else if (to_panel && !o.has_panel) {
    error = "--display " + o.display.text + " needs --panel CONTROLLER:WxH[:ROT]";
    return false;
  } else if (!to_panel && o.has_panel) {
    error = "--panel needs --display spidev:... or --display ft232h";
    return false;
  }
  if (!to_panel) return true;
  const int w = o.panel.image_width(), h = o.panel.image_height();
  if ((o.width_given && o.scene.width != w) || (o.height_given && o.scene.height != h)) {
    error = "--width/--height: the panel shows " + std::to_string(w) + "x" + std::to_string(h) +
            " (" + describe_panel(o.panel) + ")";
    return false;
  }
  o.scene.width = w;
  o.scene.height = h;
  return true;
}

// The output options that need others.
bool check_outputs(const SimOptions& o, std::string& error) {
  if (o.out_pattern.given && o.frames == 0) {
    error = "--out-pattern needs --frames N";
    return false;
  }
  if (o.gif_delay_given && !o.gif_out()) {
    error = "--gif-delay needs --out FILE.gif";
    return false;
  }
  return true;
}

}  // namespace

bool SimOptions::gif_out() const {
  return writes_out() && extension(out) == "gif";
}

bool parse_sim_options(int argc, const char* const* argv, SimOptions& out, std::string& error) {
  if (!parse_options<SimOptions>(kOptions, argc, argv, "(see --help)", out, error)) return false;
  if (out.help || out.version) return true;
  if (out.obj.empty()) {
    error = "--obj FILE is required (see --help)";
    return false;
  }
  if (out.scene.far <= out.scene.near) {
    error = "--far must be greater than --near";
    return false;
  }
  return check_lights(out, error) && check_panel(out, error) && check_outputs(out, error);
}

const char* sim_usage() {
  return kUsage;
}

}  // namespace lr::host
