// The files the host tools write: where they may write and how. One home for lineraster-sim,
// lineraster-asset and every image writer (image_io.hpp), so that the rules cannot differ.
//
// The rules (docs/host-tools.md#output-files):
//   - A tool writes regular files and nothing else. The output is a new file, or an existing
//     regular file replaced atomically: the content goes to a temporary file created beside the
//     target (O_CREAT | O_EXCL under a random name, so never a FIFO or a link that was already
//     there), which is renamed over the target once complete and removed on any failure.
//   - A symbolic link is followed to its target: the target is replaced, the link stays a link.
//     A link to a missing file is refused: nothing is created through a link (name the target).
//   - A character or block device, a FIFO, a socket or a directory is refused, and so is a link
//     to one: one line "PATH: a FIFO, not a regular file: refusing to write to it".
//   - An existing file the user may not write (read-only) is refused, as the shell's `>` would.
//   - A file that is one of the run's inputs is refused (the same device and inode, links
//     followed): "PATH: is an input (INPUT): refusing to overwrite it".
//   - A replaced file keeps its permission bits (and its owner and group where the process may
//     set them); a new file gets 0666 less the umask, as fopen would create it.
// The checks run when the output is opened, and the target is looked at again just before the
// rename (a device put there meanwhile is refused then). Host only (POSIX).
#pragma once

#include <cstdio>
#include <span>
#include <string>

namespace lr::host {

// Checks that `path` may be written under the rules above and is none of `inputs` (files that
// do not exist are skipped). False with one line "PATH: why". Nothing is created.
bool check_output(const std::string& path, std::span<const std::string> inputs, std::string& error);

// True when the two output paths lead to the same file: the same existing file by any name or
// link, or the same name in the same directory.
bool same_output(const std::string& a, const std::string& b);

// One output file being written: open() checks the path and creates the temporary file,
// stream() takes the content, commit() puts it in place. Destroyed without commit() (or after a
// failed one), it removes the temporary file and leaves the target as it was.
class OutputFile {
 public:
  OutputFile() = default;
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Checks `path` (check_output without inputs) and creates the temporary file beside the target.
  // False with one line "PATH: why".
  bool open(const std::string& path, std::string& error);
  // The temporary file, open for writing in binary; nullptr unless open() succeeded.
  std::FILE* stream() const { return file_; }
  // Flushes and syncs the content, checks the target again and renames the temporary file over
  // it. False with one line "PATH: why" (a write error in the system's words: "write failed: No
  // space left on device"); the temporary file is then removed.
  bool commit(std::string& error);
  // Gives up: the temporary file is removed, the target untouched.
  void discard();

 private:
  std::string path_, name_, tmp_;
  int dir_fd_ = -1;
  std::FILE* file_ = nullptr;
};

// open(), body(stream, what), commit(). `body` returns false with `what` set ("write failed:
// ..."), and the error is then "PATH: what". No file is left behind on any failure.
template <class Body>
bool write_output(const std::string& path, std::string& error, Body&& body) {
  OutputFile out;
  if (!out.open(path, error)) return false;
  std::string what;
  if (!body(out.stream(), what)) {
    error = path + ": " + what;
    return false;
  }
  return out.commit(error);
}

}  // namespace lr::host
