// Output files (see output_file.hpp): the target found by following links, its checks, the
// temporary file beside it and the rename.
#include "lineraster/host_sim/formats/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <random>

namespace lr::host {
namespace {

// The directory the temporary file is made in is opened only to name it in the *at calls:
// O_PATH needs no read permission on it (a write-only directory is still usable).
#ifdef O_PATH
constexpr int kDirFlags = O_PATH | O_DIRECTORY | O_CLOEXEC;
#else
constexpr int kDirFlags = O_RDONLY | O_DIRECTORY | O_CLOEXEC;
#endif

// Random names tried before giving up (a clash needs someone guessing 36^10 names).
constexpr int kTempAttempts = 16;
constexpr size_t kTempRandomChars = 10;
// The target's name is kept at most this long in the temporary file's (NAME_MAX is 255).
constexpr size_t kTempNameKept = 200;

std::string sys_error(int e) {
  return std::strerror(e != 0 ? e : EIO);
}

// What a file that is not a regular file is, in the words of the one-line error.
const char* kind_of(mode_t mode) {
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISLNK(mode)) return "a symbolic link";
  return "not a regular file";
}

std::string not_regular(const std::string& path, mode_t mode) {
  return path + ": " + kind_of(mode) + ", not a regular file: refusing to write to it";
}

// Where an output path leads once its symbolic links are followed.
struct Target {
  std::string dir, name;  // the file to write: its directory and its name in it
  bool exists = false;    // an existing regular file (described by `st`)
  struct stat st {};
};

void split(const std::string& file, Target& t) {
  const size_t slash = file.find_last_of('/');
  if (slash == std::string::npos) {
    t.dir = ".";
    t.name = file;
  } else {
    t.dir = slash == 0 ? "/" : file.substr(0, slash);
    t.name = file.substr(slash + 1);
  }
}

// Follows `path` to the file that would be written and refuses anything but a regular file or
// a new name. False with one line.
bool resolve(const std::string& path, Target& t, std::string& error) {
  if (path.empty() || path.find('\0') != std::string::npos) {
    error = "'" + path.substr(0, path.find('\0')) + "': invalid output file name";
    return false;
  }
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0) {
    if (errno != ENOENT) {
      error = path + ": cannot open for writing: " + sys_error(errno);
      return false;
    }
    split(path, t);  // a new file (its directory is looked at when the file is made)
  } else if (S_ISLNK(st.st_mode)) {
    char* real = realpath(path.c_str(), nullptr);
    if (real == nullptr) {
      const int e = errno;
      if (e != ENOENT) {
        error = path + ": cannot follow the symbolic link: " + sys_error(e);
        return false;
      }
      std::array<char, 4096> link{};
      const ssize_t n = readlink(path.c_str(), link.data(), link.size() - 1);
      error = path + ": a symbolic link to a missing file (" +
              std::string(link.data(), n > 0 ? static_cast<size_t>(n) : 0) +
              "): refusing to create a file through it";
      return false;
    }
    const std::string file = real;
    std::free(real);
    if (stat(file.c_str(), &st) != 0) {
      error = path + ": cannot open for writing: " + sys_error(errno);
      return false;
    }
    if (!S_ISREG(st.st_mode)) {
      error = path + ": a symbolic link to " + kind_of(st.st_mode) + " (" + file +
              "), not a regular file: refusing to write to it";
      return false;
    }
    split(file, t);
    t.exists = true;
    t.st = st;
  } else if (!S_ISREG(st.st_mode)) {
    error = not_regular(path, st.st_mode);
    return false;
  } else {
    split(path, t);
    t.exists = true;
    t.st = st;
  }
  if (t.name.empty() || t.name == "." || t.name == "..") {
    error = path + ": not a file name";
    return false;
  }
  return true;
}

// The target's own checks: writable when it exists, none of the inputs.
bool check_target(const std::string& path, const Target& t, std::span<const std::string> inputs,
                  std::string& error) {
  if (!t.exists) return true;
  const std::string file = t.dir + "/" + t.name;
  if (faccessat(AT_FDCWD, file.c_str(), W_OK, AT_EACCESS) != 0) {
    error = path + ": cannot open for writing: " + sys_error(errno);
    return false;
  }
  for (const std::string& in : inputs) {
    struct stat st {};
    if (in.find('\0') == std::string::npos && stat(in.c_str(), &st) == 0 &&
        st.st_dev == t.st.st_dev && st.st_ino == t.st.st_ino) {
      error = path + ": is an input (" + in + "): refusing to overwrite it";
      return false;
    }
  }
  return true;
}

std::string random_suffix() {
  static constexpr char kChars[] = "abcdefghijklmnopqrstuvwxyz0123456789";
  std::random_device rd;
  std::string s;
  for (size_t i = 0; i < kTempRandomChars; ++i) s += kChars[rd() % (sizeof kChars - 1)];
  return s;
}

// The directory, for comparing names: its canonical path when it exists.
std::string canonical_dir(const std::string& dir) {
  char* real = realpath(dir.c_str(), nullptr);
  if (real == nullptr) return dir;
  std::string s = real;
  std::free(real);
  return s;
}

}  // namespace

bool check_output(const std::string& path, std::span<const std::string> inputs,
                  std::string& error) {
  Target t;
  return resolve(path, t, error) && check_target(path, t, inputs, error);
}

bool same_output(const std::string& a, const std::string& b) {
  Target ta, tb;
  std::string ignored;
  if (!resolve(a, ta, ignored) || !resolve(b, tb, ignored)) return a == b;
  if (ta.exists && tb.exists) return ta.st.st_dev == tb.st.st_dev && ta.st.st_ino == tb.st.st_ino;
  return ta.name == tb.name && canonical_dir(ta.dir) == canonical_dir(tb.dir);
}

OutputFile::~OutputFile() {
  discard();
}

bool OutputFile::open(const std::string& path, std::string& error) {
  discard();
  path_ = path;
  Target t;
  if (!resolve(path, t, error) || !check_target(path, t, {}, error)) return false;
  name_ = t.name;
  dir_fd_ = ::open(t.dir.c_str(), kDirFlags);
  if (dir_fd_ < 0) {
    error = path + ": cannot open for writing: " + sys_error(errno);
    return false;
  }
  int fd = -1;
  for (int attempt = 0; attempt < kTempAttempts && fd < 0; ++attempt) {
    tmp_ = name_.substr(0, kTempNameKept) + "." + random_suffix() + ".tmp";
    // O_EXCL: a name that exists in any form (a FIFO, a link planted there) is never opened.
    fd = openat(dir_fd_, tmp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) {
    const int e = errno;
    tmp_.clear();
    discard();
    error = path + ": cannot open for writing: " + sys_error(e);
    return false;
  }
  if (t.exists) {
    // The replaced file's owner and group (allowed to root, or a group of the user's), then its
    // permission bits (set after: a change of owner may clear them). Best effort, as `sed -i`.
    if (t.st.st_uid != geteuid() || t.st.st_gid != getegid()) {
      if (fchown(fd, t.st.st_uid, t.st.st_gid) != 0)
        (void)!fchown(fd, static_cast<uid_t>(-1), t.st.st_gid);
    }
    (void)!fchmod(fd, t.st.st_mode & 0777);
  }
  file_ = fdopen(fd, "wb");
  if (file_ == nullptr) {
    const int e = errno;
    ::close(fd);
    discard();
    error = path + ": cannot open for writing: " + sys_error(e);
    return false;
  }
  return true;
}

bool OutputFile::commit(std::string& error) {
  if (file_ == nullptr) {
    error = path_ + ": not open for writing";
    return false;
  }
  errno = 0;
  bool ok = std::fflush(file_) == 0 && std::ferror(file_) == 0;
  int e = errno;
  if (ok && fsync(fileno(file_)) != 0) {
    ok = false;
    e = errno;
  }
  if (std::fclose(file_) != 0 && ok) {
    ok = false;
    e = errno;
  }
  file_ = nullptr;
  if (!ok) {
    discard();
    error = path_ + ": write failed: " + sys_error(e);
    return false;
  }
  // Looked at again: what is there now must still be a regular file, or nothing.
  struct stat st {};
  if (fstatat(dir_fd_, name_.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISREG(st.st_mode)) {
    discard();
    error = not_regular(path_, st.st_mode);
    return false;
  }
  if (renameat(dir_fd_, tmp_.c_str(), dir_fd_, name_.c_str()) != 0) {
    e = errno;
    discard();
    error = path_ + ": cannot rename the temporary file: " + sys_error(e);
    return false;
  }
  tmp_.clear();
  discard();
  return true;
}

void OutputFile::discard() {
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
  if (!tmp_.empty() && dir_fd_ >= 0) unlinkat(dir_fd_, tmp_.c_str(), 0);
  tmp_.clear();
  if (dir_fd_ >= 0) ::close(dir_fd_);
  dir_fd_ = -1;
}

}  // namespace lr::host
