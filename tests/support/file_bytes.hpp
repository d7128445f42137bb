// Whole files as bytes, for tests that read back or corrupt what was written.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace lr::test {

// The file's bytes (empty if it cannot be opened).
inline std::vector<uint8_t> read_bytes(const std::string& path) {
  std::vector<uint8_t> data;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return data;
  int c;
  while ((c = std::getc(f)) != EOF) data.push_back(static_cast<uint8_t>(c));
  std::fclose(f);
  return data;
}

// Replaces the file's content with `data` (a fatal test failure if it cannot be opened).
inline void write_bytes(const std::string& path, const std::vector<uint8_t>& data) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  if (!data.empty()) std::fwrite(data.data(), 1, data.size(), f);
  std::fclose(f);
}

}  // namespace lr::test
