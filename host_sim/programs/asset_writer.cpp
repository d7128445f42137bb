// GCC 12 at -O3 reports a false -Wrestrict inside std::string's operator+ ("{" + to_string(x)),
// GCC bug 105329; the code is plain string building.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ == 12
#pragma GCC diagnostic ignored "-Wrestrict"
#endif
#include "host_sim/programs/asset_writer.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>

#include "host_sim/formats/obj_loader.hpp"
#include "host_sim/scene/mesh_prep.hpp"

namespace lr::host {
namespace {

// C++ keywords, the namespaces the header uses and the global type names of <cstdint> and
// <cstddef> (which a namespace of that name would clash with).
constexpr std::string_view kReservedNames =
    " alignas alignof and and_eq asm auto bitand bitor bool break case catch char char8_t "
    "char16_t char32_t class compl concept const consteval constexpr constinit const_cast "
    "continue co_await co_return co_yield decltype default delete do double dynamic_cast "
    "else enum explicit export extern false float for friend goto if inline int long mutable "
    "namespace new noexcept not not_eq nullptr operator or or_eq private protected public "
    "register reinterpret_cast requires return short signed sizeof static static_assert "
    "static_cast struct switch template this thread_local throw true try typedef typeid "
    "typename union unsigned using virtual void volatile wchar_t while xor xor_eq lr std "
    "int8_t int16_t int32_t int64_t uint8_t uint16_t uint32_t uint64_t size_t ptrdiff_t NULL ";

// An int32 as a C++ literal of type int that converts to int32_t without narrowing.
std::string int_literal(int64_t v) {
  if (v == std::numeric_limits<int32_t>::min()) return "(-2147483647 - 1)";
  return std::to_string(v);
}

std::string hex16(unsigned v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%04X", v & 0xFFFFu);
  return buf;
}

// Writes the body of a braced list, `per_line` items per line, indented by 4.
class ListWriter {
 public:
  ListWriter(std::string& s, size_t per_line) : s_(s), per_line_(per_line) {}
  ListWriter(const ListWriter&) = delete;
  ListWriter& operator=(const ListWriter&) = delete;
  ~ListWriter() {
    if (count_ % per_line_ != 0) s_ += '\n';
  }
  void add(const std::string& item) {
    s_ += count_ % per_line_ == 0 ? "    " : " ";
    s_ += item;
    s_ += ',';
    if (++count_ % per_line_ == 0) s_ += '\n';
  }

 private:
  std::string& s_;
  size_t per_line_;
  size_t count_ = 0;
};

// A path or command line made safe for a // comment (no control characters, no line splices).
std::string comment_safe(std::string_view text) {
  std::string s;
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    s += (u < 0x20 || u == 0x7F) ? '?' : c == '\\' ? '/' : c;
  }
  return s;
}

std::string color15(const Color15& c) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "{%u, %u, %u}", unsigned{c.r}, unsigned{c.g}, unsigned{c.b});
  return buf;
}

bool fail(std::string& error, const std::string& what) {
  error = what;
  return false;
}

}  // namespace

bool valid_asset_name(std::string_view name) {
  if (name.empty()) return false;
  auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (!alpha(name[0])) return false;
  for (char c : name)
    if (!alpha(c) && !digit(c)) return false;
  if (name.find("__") != std::string_view::npos) return false;
  if (name.size() > 1 && name[0] == '_' && name[1] >= 'A' && name[1] <= 'Z') return false;
  const std::string padded = " " + std::string(name) + " ";
  return kReservedNames.find(padded) == std::string_view::npos;
}

bool load_asset(const AssetOptions& o, AssetData& out, std::string& error) {
  if (!valid_asset_name(o.name))
    return fail(error, "--name '" + o.name + "' is not a usable C++ identifier");
  HostMesh mesh;
  if (!load_obj(o.obj_path, mesh, error)) return false;
  if (o.subdivide < 0 || o.subdivide > 4) return fail(error, "--subdivide needs 0..4");
  if (o.subdivide > 0) mesh = subdivide(mesh, o.subdivide);
  SceneOptions so;
  so.fit = o.fit;
  so.use_mesh_materials = true;
  AssetData d;
  if (!build_fixed_draws(mesh, so, d.draws, error)) {
    error = o.obj_path + ": " + error;
    return false;
  }
  std::string tex = o.texture_path;
  const bool explicit_texture = !tex.empty();
  if (!explicit_texture) {
    for (const HostMaterial& m : mesh.materials) {
      if (!m.map_kd.empty()) {
        tex = m.map_kd;
        break;
      }
    }
  }
  if (!tex.empty()) {
    if (!mesh.has_uvs())
      return fail(error, o.obj_path + ": no texture coordinates (vt) for the texture " + tex);
    if (!load_texture(tex, o.format, o.mipmaps, d.texture, error)) return false;
    d.has_texture = true;
    d.texture_path = tex;
  }
  for (const FixedDraw& fd : d.draws) {
    bool t = d.has_texture && !fd.uvs.empty();
    if (t && !explicit_texture) {
      t = fd.material_index >= 0 &&
          static_cast<size_t>(fd.material_index) < mesh.materials.size() &&
          mesh.materials[static_cast<size_t>(fd.material_index)].map_kd == tex;
    }
    d.textured.push_back(t);
  }
  out = std::move(d);
  return true;
}

std::string asset_header_text(const AssetOptions& o, const AssetData& d) {
  const std::string& n = o.name;
  size_t vertices = 0, triangles = 0;
  for (const FixedDraw& fd : d.draws) {
    vertices += fd.positions.size();
    triangles += fd.triangles.size();
  }
  std::string s;
  s += "// Generated by lineraster-asset: do not edit, regenerate from the files below.\n";
  if (!o.command_line.empty()) s += "//   command: " + comment_safe(o.command_line) + "\n";
  s += "//   mesh:    " + comment_safe(o.obj_path) +
       " (with its MTL files): " + std::to_string(d.draws.size()) + " draw(s), " +
       std::to_string(vertices) + " vertices, " + std::to_string(triangles) + " triangles" +
       (o.fit ? ", fitted (--fit)" : "") +
       (o.subdivide > 0 ? ", subdivided " + std::to_string(o.subdivide) + "x (--subdivide)" : "") +
       "\n";
  if (d.has_texture) {
    const Texture& t = d.texture.texture;
    s += "//   texture: " + comment_safe(d.texture_path) + ": " +
         std::to_string(t.levels[0].width) + "x" + std::to_string(t.levels[0].height) + " " +
         texel_format_name(t.format) + ", " + std::to_string(t.level_count) + " level(s)" +
         (o.mipmaps ? " (mip chain)" : "") + "\n";
  } else {
    s += "//   texture: none\n";
  }
  s += "// Formats (core/): positions Q16.16 as {{x}, {y}, {z}} raw values, normals Q1.14, uvs "
       "Q12.20\n"
       "// (v = 0 at the image's bottom), colours Q1.15, shininess Q8.8, texture rows bottom row "
       "first.\n"
       "#pragma once\n\n"
       "#include <array>\n#include <cstddef>\n#include <cstdint>\n\n"
       "#include \"core/scene/material.hpp\"\n#include \"core/scene/mesh.hpp\"\n#include "
       "\"core/texture/texture.hpp\"\n\n";
  s += "namespace " + n + " {\n\n";
  s += "inline constexpr std::size_t draw_count = " + std::to_string(d.draws.size()) + ";\n\n";

  for (size_t i = 0; i < d.draws.size(); ++i) {
    const FixedDraw& fd = d.draws[i];
    const std::string id = std::to_string(i);
    s += "// Draw " + id + ": " + std::to_string(fd.positions.size()) + " vertices, " +
         std::to_string(fd.triangles.size()) + " triangles.\n";
    s += "inline constexpr lr::Vec3 positions_" + id + "[] = {\n";
    {
      ListWriter w(s, 3);
      for (const Vec3& p : fd.positions)
        w.add("{{" + int_literal(p.x.raw) + "}, {" + int_literal(p.y.raw) + "}, {" +
              int_literal(p.z.raw) + "}}");
    }
    s += "};\n";
    if (!fd.normals.empty()) {
      s += "inline constexpr lr::Normal16 normals_" + id + "[] = {\n";
      {
        ListWriter w(s, 4);
        for (const Normal16& v : fd.normals)
          w.add("{" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " +
                std::to_string(v.z) + "}");
      }
      s += "};\n";
    }
    if (!fd.colors.empty()) {
      s += "inline constexpr lr::Rgb8 colors_" + id + "[] = {\n";
      {
        ListWriter w(s, 4);
        for (const Rgb8& c : fd.colors)
          w.add("{" + std::to_string(c.r) + ", " + std::to_string(c.g) + ", " +
                std::to_string(c.b) + "}");
      }
      s += "};\n";
    }
    if (!fd.uvs.empty()) {
      s += "inline constexpr lr::TexCoord uvs_" + id + "[] = {\n";
      {
        ListWriter w(s, 6);
        for (const TexCoord& c : fd.uvs)
          w.add("{" + int_literal(c.u) + ", " + int_literal(c.v) + "}");
      }
      s += "};\n";
    }
    s += "inline constexpr std::array<uint16_t, 3> triangles_" + id + "[] = {\n";
    {
      ListWriter w(s, 4);
      for (const auto& t : fd.triangles)
        w.add("{" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
              std::to_string(t[2]) + "}");
    }
    s += "};\n";
    const Material& m = fd.material;
    s += "// ambient, diffuse, specular, emission (Q1.15), shininess (Q8.8)\n";
    s += "inline constexpr lr::Material material_" + id + "{\n    " + color15(m.ambient) + ", " +
         color15(m.diffuse) + ", " + color15(m.specular) + ", " + color15(m.emission) + ", " +
         std::to_string(m.shininess_q8) + "};\n";
    s += "inline constexpr lr::Mesh mesh_" + id + "{positions_" + id + ", " +
         (fd.normals.empty() ? "{}" : "normals_" + id) + ", " +
         (fd.colors.empty() ? "{}" : "colors_" + id) + ", " +
         (fd.uvs.empty() ? "{}" : "uvs_" + id) + ", triangles_" + id + "};\n\n";
  }
  const std::string count = std::to_string(d.draws.size());
  auto list = [&](const std::string& prefix) {
    std::string l;
    for (size_t i = 0; i < d.draws.size(); ++i) l += (i ? ", " : "") + prefix + std::to_string(i);
    return l;
  };
  s += "inline constexpr std::array<lr::Mesh, " + count + "> meshes{" + list("mesh_") + "};\n";
  s += "inline constexpr std::array<lr::Material, " + count + "> materials{" + list("material_") +
       "};\n";
  s += "// Whether each draw takes `texture` (see lineraster-asset's texture choice).\n";
  s += "inline constexpr std::array<bool, " + count + "> textured{";
  for (size_t i = 0; i < d.textured.size(); ++i)
    s += std::string(i ? ", " : "") + (d.textured[i] ? "true" : "false");
  s += "};\n";

  if (d.has_texture) {
    const Texture& t = d.texture.texture;
    const bool is565 = t.format == TexelFormat::kRgb565;
    s += "\n";
    for (int l = 0; l < t.level_count; ++l) {
      const TextureLevel& lv = t.levels[static_cast<size_t>(l)];
      const std::string id = std::to_string(l);
      s += "// Level " + id + ": " + std::to_string(lv.width) + "x" + std::to_string(lv.height) +
           ", rows bottom first.\n";
      s += std::string("inline constexpr ") + (is565 ? "uint16_t" : "uint8_t") + " texture_level_" +
           id + "[] = {\n";
      {
        ListWriter w(s, 12);
        if (is565) {
          for (uint16_t v : lv.rgb565) w.add(hex16(v));
        } else {
          for (uint8_t v : lv.bytes) w.add(std::to_string(v));
        }
      }
      s += "};\n";
    }
    if (t.format == TexelFormat::kPalette8) {
      s += "inline constexpr uint16_t texture_palette[] = {\n";
      {
        ListWriter w(s, 12);
        for (uint16_t v : t.palette) w.add(hex16(v));
      }
      s += "};\n";
    }
    static const char* const kFormatEnum[] = {"kRgb565", "kRgb888", "kL8", "kPalette8"};
    s += "inline constexpr lr::Texture texture{\n    lr::TexelFormat::" +
         std::string(kFormatEnum[static_cast<int>(t.format)]) + ",\n    {{\n";
    for (int l = 0; l < kMaxMipLevels; ++l) {
      const TextureLevel& lv = t.levels[static_cast<size_t>(l)];
      if (l < t.level_count) {
        const std::string arr = "texture_level_" + std::to_string(l);
        s += "        {" + (is565 ? arr + ", {}" : "{}, " + arr) + ", " + std::to_string(lv.width) +
             ", " + std::to_string(lv.height) + "},\n";
      } else {
        s += "        {},\n";
      }
    }
    s += "    }},\n    " + std::to_string(t.level_count) + ",\n    " +
         (t.format == TexelFormat::kPalette8 ? "texture_palette" : "{}") + "};\n";
  }
  s += "\n}  // namespace " + n + "\n";
  return s;
}

bool write_asset_header(const AssetOptions& o, const std::string& out_path, std::string& error) {
  AssetData d;
  if (!load_asset(o, d, error)) return false;
  const std::string text = asset_header_text(o, d);
  if (out_path.empty() || out_path.find('\0') != std::string::npos)
    return fail(error, "--out: invalid file name");
  const std::string tmp = out_path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) return fail(error, out_path + ": cannot write: " + std::strerror(errno));
  bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  const int write_errno = errno;
  ok = (std::fclose(f) == 0) && ok;
  if (!ok) {
    std::remove(tmp.c_str());
    return fail(error,
                out_path + ": cannot write: " + std::strerror(write_errno ? write_errno : EIO));
  }
  if (std::rename(tmp.c_str(), out_path.c_str()) != 0) {
    const int e = errno;
    std::remove(tmp.c_str());
    return fail(error, out_path + ": cannot rename the temporary file: " + std::strerror(e));
  }
  return true;
}

}  // namespace lr::host
