// The includes of a header lineraster-asset writes: each project header by the path the package
// installs and the include views give (<lineraster/core/...>), and present there, so the header
// compiles in any consumer project (find_package, add_subdirectory, FetchContent), not only in
// this repository whose root is on the include path. scripts/consumers.sh compiles one against
// an installed package.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "lineraster/host_sim/programs/asset_writer.hpp"

namespace lr::host {
namespace {

const std::string kData = LR_SOURCE_DIR "/tests/host/data/";

// The "..." and <...> names of the header's #include lines, in order.
std::vector<std::string> includes(const std::string& text, char open, char close) {
  std::vector<std::string> out;
  std::istringstream lines(text);
  const std::string directive = std::string("#include ") + open;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(directive, 0) != 0) continue;
    const size_t end = line.find(close, directive.size());
    out.push_back(line.substr(directive.size(), end - directive.size()));
  }
  return out;
}

TEST(AssetIncludes, EveryProjectHeaderIsIncludedByItsPackagePath) {
  AssetOptions o;
  o.obj_path = kData + "quirks/two_textures.obj";  // two textures: every part of the header
  o.name = "two";
  AssetData d;
  std::string error;
  ASSERT_TRUE(load_asset(o, d, error)) << error;
  const std::string text = asset_header_text(o, d);

  const std::vector<std::string> project = includes(text, '"', '"');
  const std::vector<std::string> expected{
      "lineraster/core/math/vec.hpp", "lineraster/core/output/color.hpp",
      "lineraster/core/scene/material.hpp", "lineraster/core/scene/mesh.hpp",
      "lineraster/core/texture/texture.hpp"};
  EXPECT_EQ(project, expected);
  // Each is there in the include view that lr::core puts on a consumer's include path.
  for (const std::string& h : project)
    EXPECT_TRUE(std::filesystem::is_regular_file(std::filesystem::path(LR_INCLUDE_VIEW) / h))
        << h << " is not in " << LR_INCLUDE_VIEW;
  EXPECT_EQ(includes(text, '<', '>'), (std::vector<std::string>{"array", "cstddef", "cstdint"}));
}

}  // namespace
}  // namespace lr::host
