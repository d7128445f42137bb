// Fuzz target: the OBJ / MTL loader (see fuzz_targets.hpp).
#include <cmath>
#include <string>
#include <string_view>

#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/scene/mesh_prep.hpp"
#include "tests/fuzz/fuzz_files.hpp"
#include "tests/fuzz/fuzz_targets.hpp"

namespace lr::fuzz {
namespace {

constexpr std::string_view kMtlSeparator = "\n#mtl\n";

// mtllib opens files relative to the scratch folder; an input that could name any other file
// (a slash or backslash, also a continued line, after "mtllib") is skipped, so that runs stay
// deterministic and never read /dev/zero or the like.
bool names_outside_files(std::string_view obj) {
  for (size_t at = obj.find("mtllib"); at != std::string_view::npos;
       at = obj.find("mtllib", at + 1)) {
    for (size_t i = at; i < obj.size() && obj[i] != '\n'; ++i) {
      if (obj[i] == '/' || obj[i] == '\\') return true;
    }
  }
  return false;
}

bool finite(const host::Vec3d& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

void check_materials(const std::vector<host::HostMaterial>& mats) {
  for (const auto& mat : mats) {
    LR_FUZZ_CHECK(mat.shininess >= 0.0 && mat.shininess <= 128.0);
    LR_FUZZ_CHECK(mat.alpha >= 0.0 && mat.alpha <= 1.0);
    for (const host::Vec3d* c : {&mat.ambient, &mat.diffuse, &mat.specular, &mat.emission}) {
      for (double x : *c) LR_FUZZ_CHECK(x >= 0.0 && x <= 1.0);
    }
  }
}

void check_mesh(const host::HostMesh& m) {
  const size_t n = m.positions.size();
  LR_FUZZ_CHECK(n > 0 && !m.triangles.empty());
  LR_FUZZ_CHECK(m.normals.size() == n);
  LR_FUZZ_CHECK(m.colors.empty() || m.colors.size() == n);
  LR_FUZZ_CHECK(m.uvs.empty() || m.uvs.size() == n);
  LR_FUZZ_CHECK(m.triangle_material.size() == m.triangles.size());
  for (const auto& t : m.triangles) LR_FUZZ_CHECK(t[0] < n && t[1] < n && t[2] < n);
  for (int32_t mat : m.triangle_material)
    LR_FUZZ_CHECK(mat >= -1 && (mat < 0 || static_cast<size_t>(mat) < m.materials.size()));
  for (size_t i = 0; i < n; ++i) {
    LR_FUZZ_CHECK(finite(m.positions[i]));
    const auto& nn = m.normals[i];
    LR_FUZZ_CHECK(finite(nn));
    LR_FUZZ_CHECK(std::fabs(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2] - 1.0) < 1e-9);
    if (!m.colors.empty()) {
      for (double c : m.colors[i]) LR_FUZZ_CHECK(c >= 0.0 && c <= 1.0);
    }
    if (!m.uvs.empty()) LR_FUZZ_CHECK(std::isfinite(m.uvs[i][0]) && std::isfinite(m.uvs[i][1]));
  }
  check_materials(m.materials);
}

}  // namespace

int obj_target(const uint8_t* data, size_t size) {
  static ScratchDir scratch("m.mtl");
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const size_t sep = text.find(kMtlSeparator);
  const std::string_view obj = text.substr(0, sep);
  const std::string_view mtl =
      sep == std::string_view::npos ? std::string_view() : text.substr(sep + kMtlSeparator.size());

  std::vector<host::HostMaterial> mats;
  std::string error;
  if (host::parse_mtl(mtl, "fuzz.mtl", scratch.dir(), mats, error)) {
    check_materials(mats);
  } else {
    LR_FUZZ_CHECK(!error.empty() && mats.empty());
  }

  if (names_outside_files(obj)) return 0;
  scratch.write(mtl.data(), mtl.size());
  host::HostMesh mesh;
  error.clear();
  if (!host::parse_obj(obj, "fuzz.obj", scratch.dir(), mesh, error)) {
    LR_FUZZ_CHECK(!error.empty());
    LR_FUZZ_CHECK(mesh.positions.empty() && mesh.triangles.empty());
    return 0;
  }
  check_mesh(mesh);

  // Round trip: the mesh written as OBJ loads again to the same positions and triangles.
  const std::string again = host::to_obj_text(mesh);
  host::HostMesh back;
  error.clear();
  const bool reloaded = host::parse_obj(again, "round-trip.obj", "", back, error);
  if (!reloaded) std::fprintf(stderr, "round trip: %s\n", error.c_str());
  LR_FUZZ_CHECK(reloaded);
  check_mesh(back);
  LR_FUZZ_CHECK(back.positions == mesh.positions);
  LR_FUZZ_CHECK(back.triangles == mesh.triangles);
  LR_FUZZ_CHECK(back.colors == mesh.colors);
  LR_FUZZ_CHECK(back.uvs == mesh.uvs);
  return 0;
}

}  // namespace lr::fuzz
