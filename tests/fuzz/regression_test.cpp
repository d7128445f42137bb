// Replays every committed fuzz input through its target with the main build's compiler (and,
// in the ASan preset, its sanitizers): the seeds in tests/fuzz/corpus/<target>/ and every input
// that once crashed in tests/fuzz/regressions/<target>/. A crash or a broken invariant aborts the
// test; the file being replayed is printed first, so the log names it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_targets.hpp"

namespace {

namespace fs = std::filesystem;
using Target = int (*)(const uint8_t*, size_t);

// Input files of one folder, sorted; dot files and README* are not inputs.
std::vector<fs::path> inputs(const std::string& folder) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(LR_SOURCE_DIR) / "tests/fuzz" / folder;
  if (!fs::is_directory(dir)) return files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && name[0] != '.' && name.rfind("README", 0) != 0)
      files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

size_t replay(const std::string& folder, Target target) {
  const std::vector<fs::path> files = inputs(folder);
  for (const fs::path& f : files) {
    std::ifstream in(f, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
    std::fprintf(stderr, "replaying %s (%zu bytes)\n", f.string().c_str(), bytes.size());
    target(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  }
  return files.size();
}

void replay_target(const std::string& name, Target target) {
  EXPECT_GT(replay("corpus/" + name, target), 0u) << "no seeds in tests/fuzz/corpus/" << name;
  replay("regressions/" + name, target);
}

TEST(FuzzRegression, Obj) {
  replay_target("obj", lr::fuzz::obj_target);
}
TEST(FuzzRegression, Png) {
  replay_target("png", lr::fuzz::png_target);
}
TEST(FuzzRegression, Pipeline) {
  replay_target("pipeline", lr::fuzz::pipeline_target);
}

}  // namespace
