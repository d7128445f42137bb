// A fresh directory under /tmp (mkdtemp), removed with its content when the object goes away.
#pragma once

#include <stdlib.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace lr::test {

class TmpDir {
 public:
  // Creates /tmp/PREFIX_XXXXXX; falls back to /tmp itself (never removed) if that fails.
  explicit TmpDir(const std::string& prefix) {
    std::string tmpl = "/tmp/" + prefix + "_XXXXXX";
    const char* p = mkdtemp(tmpl.data());
    path_ = p ? p : "/tmp";
  }
  ~TmpDir() {
    std::error_code ec;
    if (path_ != "/tmp") std::filesystem::remove_all(path_, ec);
  }
  TmpDir(const TmpDir&) = delete;
  TmpDir& operator=(const TmpDir&) = delete;

  const std::string& path() const { return path_; }
  // The full path of `name` inside the directory (not created).
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  // Writes `text` to `name` (creating its parent directories) and returns the full path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::string full = file(name);
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(full).parent_path(), ec);
    std::FILE* f = std::fopen(full.c_str(), "wb");
    if (f) {
      std::fwrite(text.data(), 1, text.size(), f);
      std::fclose(f);
    }
    return full;
  }
  // The names of the directory's entries, in directory order.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(path_))
      names.push_back(e.path().filename().string());
    return names;
  }

 private:
  std::string path_;
};

}  // namespace lr::test
