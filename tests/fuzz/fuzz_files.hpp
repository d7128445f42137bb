// Files the fuzz targets hand to file-based loaders, kept in memory: an anonymous memfd (read
// through /proc/self/fd/N) and a private folder on tmpfs (/dev/shm, else $TMPDIR or /tmp),
// created once per process and removed at exit.
#pragma once

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "tests/fuzz/fuzz_targets.hpp"

namespace lr::fuzz {

// An in-memory file whose content is replaced on every run.
class MemFile {
 public:
  MemFile() {
    fd_ = static_cast<int>(memfd_create("lr-fuzz", MFD_CLOEXEC));
    LR_FUZZ_CHECK(fd_ >= 0);
    path_ = "/proc/self/fd/" + std::to_string(fd_);
  }
  MemFile(const MemFile&) = delete;
  MemFile& operator=(const MemFile&) = delete;
  ~MemFile() { close(fd_); }

  void set(const uint8_t* data, size_t size) {
    LR_FUZZ_CHECK(ftruncate(fd_, 0) == 0);
    size_t done = 0;
    while (done < size) {
      const ssize_t n = pwrite(fd_, data + done, size - done, static_cast<off_t>(done));
      LR_FUZZ_CHECK(n > 0);
      done += static_cast<size_t>(n);
    }
  }
  const std::string& path() const { return path_; }

 private:
  int fd_ = -1;
  std::string path_;
};

// A private folder holding one file name at a time (`name`), removed with its file at exit.
class ScratchDir {
 public:
  explicit ScratchDir(const char* name) : name_(name) {
    const char* tmp = std::getenv("TMPDIR");
    std::string base = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : tmp && *tmp ? tmp : "/tmp";
    std::string templ = base + "/lr-fuzz-XXXXXX";
    LR_FUZZ_CHECK(mkdtemp(templ.data()) != nullptr);
    dir_ = templ;
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir() {
    unlink((dir_ + "/" + name_).c_str());
    rmdir(dir_.c_str());
  }

  void write(const char* data, size_t size) {
    const std::string path = dir_ + "/" + name_;
    std::FILE* f = std::fopen(path.c_str(), "wb");
    LR_FUZZ_CHECK(f != nullptr);
    if (size > 0) LR_FUZZ_CHECK(std::fwrite(data, 1, size, f) == size);
    LR_FUZZ_CHECK(std::fclose(f) == 0);
  }
  const std::string& dir() const { return dir_; }

 private:
  std::string name_, dir_;
};

}  // namespace lr::fuzz
