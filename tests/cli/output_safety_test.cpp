// What lineraster-sim and lineraster-asset do when --out is not a plain file
// (host_sim/formats/output_file.hpp): a character device, a FIFO, a directory or a socket is
// refused with one line and exit status 2 and is left exactly as it was; a symbolic link to a
// regular file has its target replaced and stays a link; a link to a device, to a FIFO or to
// nothing is refused. Every node is made in a temporary directory (the device by mknod, as root
// only), never in /dev. Each case runs for both tools.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "lineraster/host_sim/formats/image_io.hpp"
#include "tests/support/tmp_dir.hpp"

namespace {

using lr::test::TmpDir;

const std::string kData = std::string(LR_SOURCE_DIR) + "/tests/host/data/";
const std::string kCube = kData + "cube.obj";

// One of the two tools: how it is run to write `out`, and what it writes.
struct Tool {
  const char* name;  // as it prefixes its messages
  std::string (*args)(const std::string& obj, const std::string& out);
  const char* extension;  // a name it accepts for --out
};

void PrintTo(const Tool& t, std::ostream* os) {
  *os << t.name;
}

const Tool kTools[] = {
    {"lineraster-sim",
     [](const std::string& obj, const std::string& out) {
       return std::string(LR_SIM) + " --obj " + obj + " --width 32 --height 24 --out " + out;
     },
     ".png"},
    {"lineraster-asset",
     [](const std::string& obj, const std::string& out) {
       return std::string(LR_ASSET) + " --obj " + obj + " --name cube --out " + out;
     },
     ".hpp"},
};

struct Outcome {
  int status = -1;
  std::string out, err;
};

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Runs `command` with its output captured in files of `logs` (a directory other than the one
// under test, which must hold only the nodes it made). `timeout`: a tool that opened a FIFO
// would wait for a reader for ever; the test then fails instead of hanging.
Outcome run(const std::string& command, const TmpDir& logs) {
  const std::string out = logs.file("stdout"), err = logs.file("stderr");
  const int rc = std::system(("timeout 120 " + command + " >" + out + " 2>" + err).c_str());
  Outcome r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

struct stat lstat_of(const std::string& path) {
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0) st.st_mode = 0;
  return st;
}

std::vector<std::string> sorted_entries(const TmpDir& dir) {
  std::vector<std::string> e = dir.entries();
  std::sort(e.begin(), e.end());
  return e;
}

class OutputSafety : public ::testing::TestWithParam<Tool> {
 protected:
  const Tool& tool() const { return GetParam(); }
  std::string out_name(const std::string& stem) const { return stem + tool().extension; }
  // Runs the tool onto `out`: exit status 2 and exactly the line "TOOL: MESSAGE".
  void expect_refused(const std::string& out, const std::string& message) {
    const Outcome r = run(tool().args(kCube, out), logs_);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err, std::string(tool().name) + ": " + message + "\n");
    EXPECT_EQ(r.out, "");
  }
  // A character device (1, 7: what /dev/full is) made by mknod; false when the process may not.
  bool make_device(const std::string& path) {
    return mknod(path.c_str(), S_IFCHR | 0666, makedev(1, 7)) == 0;
  }

  TmpDir dir_{"lr_out_safety"};
  TmpDir logs_{"lr_out_logs"};
};

std::string not_regular(const std::string& path, const char* kind) {
  return path + ": " + kind + ", not a regular file: refusing to write to it";
}

TEST_P(OutputSafety, ACharacterDeviceIsRefusedAndLeftAsItWas) {
  const std::string dev = dir_.file(out_name("full"));
  if (!make_device(dev))
    GTEST_SKIP() << "mknod needs root (CI runs as root): " << std::strerror(errno);
  expect_refused(dev, not_regular(dev, "a character device"));
  const struct stat st = lstat_of(dev);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device node was replaced";
  EXPECT_EQ(st.st_rdev, makedev(1, 7));
  EXPECT_EQ(sorted_entries(dir_), std::vector<std::string>{out_name("full")});
}

TEST_P(OutputSafety, AFifoIsRefusedAndLeftAsItWas) {
  const std::string fifo = dir_.file(out_name("fifo"));
  ASSERT_EQ(mkfifo(fifo.c_str(), 0644), 0) << std::strerror(errno);
  expect_refused(fifo, not_regular(fifo, "a FIFO"));
  EXPECT_TRUE(S_ISFIFO(lstat_of(fifo).st_mode)) << "the FIFO was replaced";
  EXPECT_EQ(sorted_entries(dir_), std::vector<std::string>{out_name("fifo")});
}

TEST_P(OutputSafety, ADirectoryIsRefusedAndLeftEmpty) {
  const std::string d = dir_.file(out_name("folder"));
  ASSERT_TRUE(std::filesystem::create_directory(d));
  expect_refused(d, not_regular(d, "a directory"));
  EXPECT_TRUE(S_ISDIR(lstat_of(d).st_mode));
  EXPECT_TRUE(std::filesystem::is_empty(d));
  EXPECT_EQ(sorted_entries(dir_), std::vector<std::string>{out_name("folder")});
}

TEST_P(OutputSafety, AUnixSocketIsRefusedAndLeftAsItWas) {
  const std::string sock = dir_.file(out_name("sock"));
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  ASSERT_LT(sock.size(), sizeof addr.sun_path);
  std::memcpy(addr.sun_path, sock.c_str(), sock.size() + 1);
  const int fd = socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0)
      << std::strerror(errno);
  close(fd);
  expect_refused(sock, not_regular(sock, "a socket"));
  EXPECT_TRUE(S_ISSOCK(lstat_of(sock).st_mode)) << "the socket was replaced";
  EXPECT_EQ(sorted_entries(dir_), std::vector<std::string>{out_name("sock")});
}

// The link is followed: its target is replaced (whole: a file the tool wrote), the link stays
// the same link, and the target keeps its permission bits.
TEST_P(OutputSafety, ALinkToARegularFileReplacesTheTargetAndStaysALink) {
  const std::string target = dir_.write("sub/" + out_name("target"), "old content\n");
  ASSERT_EQ(chmod(target.c_str(), 0640), 0);
  const std::string link = dir_.file(out_name("link"));
  const std::string link_text = "sub/" + out_name("target");  // relative, as people make them
  ASSERT_EQ(symlink(link_text.c_str(), link.c_str()), 0);
  const Outcome r = run(tool().args(kCube, link), logs_);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const struct stat ls = lstat_of(link);
  ASSERT_TRUE(S_ISLNK(ls.st_mode)) << "the link was replaced";
  EXPECT_EQ(std::filesystem::read_symlink(link).string(), link_text);
  const struct stat ts = lstat_of(target);
  EXPECT_TRUE(S_ISREG(ts.st_mode));
  EXPECT_EQ(ts.st_mode & 0777, 0640u);
  const std::string written = slurp(target);
  if (std::string(tool().extension) == ".png") {
    lr::host::ImageRgb8 img;
    std::string error;
    ASSERT_TRUE(lr::host::read_png(target, img, error)) << error;
    EXPECT_EQ(img.width, 32);
    EXPECT_EQ(img.height, 24);
  } else {
    EXPECT_EQ(written.rfind("// Generated by lineraster-asset", 0), 0u);
    EXPECT_NE(written.find("namespace cube {"), std::string::npos);
  }
  // Nothing else: no temporary file beside the link or the target.
  EXPECT_EQ(sorted_entries(dir_), (std::vector<std::string>{out_name("link"), "sub"}));
  size_t in_sub = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir_.file("sub")))
    ++in_sub;
  EXPECT_EQ(in_sub, 1u);
}

TEST_P(OutputSafety, ALinkToADeviceIsRefusedAndBothAreLeftAsTheyWere) {
  const std::string dev = dir_.file("device");
  if (!make_device(dev))
    GTEST_SKIP() << "mknod needs root (CI runs as root): " << std::strerror(errno);
  const std::string link = dir_.file(out_name("link"));
  ASSERT_EQ(symlink(dev.c_str(), link.c_str()), 0);
  expect_refused(link, link + ": a symbolic link to a character device (" + dev +
                           "), not a regular file: refusing to write to it");
  EXPECT_TRUE(S_ISLNK(lstat_of(link).st_mode)) << "the link was replaced";
  EXPECT_TRUE(S_ISCHR(lstat_of(dev).st_mode)) << "the device node was replaced";
  EXPECT_EQ(lstat_of(dev).st_rdev, makedev(1, 7));
  EXPECT_EQ(sorted_entries(dir_), (std::vector<std::string>{"device", out_name("link")}));
}

// The same through a FIFO, which needs no privilege.
TEST_P(OutputSafety, ALinkToAFifoIsRefusedAndBothAreLeftAsTheyWere) {
  const std::string fifo = dir_.file("pipe");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0644), 0) << std::strerror(errno);
  const std::string link = dir_.file(out_name("link"));
  ASSERT_EQ(symlink("pipe", link.c_str()), 0);
  expect_refused(link, link + ": a symbolic link to a FIFO (" + fifo +
                           "), not a regular file: refusing to write to it");
  EXPECT_TRUE(S_ISLNK(lstat_of(link).st_mode));
  EXPECT_TRUE(S_ISFIFO(lstat_of(fifo).st_mode));
  EXPECT_EQ(sorted_entries(dir_), (std::vector<std::string>{out_name("link"), "pipe"}));
}

// Nothing is created through a link: the user names the file itself.
TEST_P(OutputSafety, ALinkToNothingIsRefusedAndNothingIsCreated) {
  const std::string link = dir_.file(out_name("dangling"));
  ASSERT_EQ(symlink("missing.bin", link.c_str()), 0);
  expect_refused(link,
                 link +
                     ": a symbolic link to a missing file (missing.bin): refusing to create a "
                     "file through it");
  EXPECT_TRUE(S_ISLNK(lstat_of(link).st_mode));
  EXPECT_EQ(sorted_entries(dir_), std::vector<std::string>{out_name("dangling")});
}

// A file the user may not write is not replaced behind its back (as the shell's `>` would
// refuse it). Root may write any file: as root, the tool runs as `nobody` (setpriv) in a
// directory everyone may write.
TEST_P(OutputSafety, AReadOnlyFileIsRefusedAndKept) {
  std::string as_user;
  if (geteuid() == 0) {
    if (std::system("command -v setpriv >/dev/null") != 0)
      GTEST_SKIP() << "root may write a read-only file, and setpriv is not there";
    as_user = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
    ASSERT_EQ(chmod(dir_.path().c_str(), 0777), 0);
  }
  // The input copied beside it: the unprivileged user may not reach the sources (a checkout
  // under root's 0700 home).
  TmpDir in("lr_out_safety_in");
  ASSERT_EQ(chmod(in.path().c_str(), 0755), 0);
  for (const char* f : {"cube.obj", "cube.mtl", "checker.png"})
    std::filesystem::copy_file(kData + f, in.file(f));
  const std::string ro = dir_.write(out_name("ro"), "keep me\n");
  ASSERT_EQ(chmod(ro.c_str(), 0444), 0);
  const Outcome r = run(as_user + tool().args(in.file("cube.obj"), ro), logs_);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err, std::string(tool().name) + ": " + ro +
                       ": cannot open for writing: Permission denied\n");
  EXPECT_EQ(slurp(ro), "keep me\n");
  EXPECT_EQ(sorted_entries(dir_), std::vector<std::string>{out_name("ro")});
}

// A new file has the permissions fopen would give it (0666 less the umask); a replaced one
// keeps its own.
TEST_P(OutputSafety, NewFilesFollowTheUmaskAndReplacedFilesKeepTheirMode) {
  const std::string fresh = dir_.file(out_name("new"));
  Outcome r = run("sh -c 'umask 027; " + tool().args(kCube, fresh) + "'", logs_);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lstat_of(fresh).st_mode & 0777, 0640u);
  const std::string old = dir_.write(out_name("old"), "old\n");
  ASSERT_EQ(chmod(old.c_str(), 0604), 0);
  r = run("sh -c 'umask 077; " + tool().args(kCube, old) + "'", logs_);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lstat_of(old).st_mode & 0777, 0604u);
  EXPECT_NE(slurp(old), "old\n");
  EXPECT_EQ(sorted_entries(dir_), (std::vector<std::string>{out_name("new"), out_name("old")}));
}

INSTANTIATE_TEST_SUITE_P(Tools, OutputSafety, ::testing::ValuesIn(kTools),
                         [](const ::testing::TestParamInfo<Tool>& i) {
                           return std::string(i.param.name) == "lineraster-sim" ? "Sim" : "Asset";
                         });

// ---- lineraster-sim's own inputs and outputs ----

// A texture (by its name or through a link) is never the output; neither is the same file
// named twice (--out and --depth-out, a frame of --out-pattern and --out).
TEST(OutputSafetySim, InputsAndOtherOutputsAreNeverTheOutput) {
  TmpDir dir("lr_out_safety"), logs("lr_out_logs");
  // The cube, its MTL and the MTL's map_Kd copied (a broken check must not reach the sources).
  for (const char* f : {"cube.obj", "cube.mtl", "checker.png"})
    std::filesystem::copy_file(kData + f, dir.file(f));
  const std::string tex = dir.file("tex.png"), map_kd = dir.file("checker.png");
  std::filesystem::copy_file(kData + "checker.png", tex);
  const std::string before = slurp(tex);
  ASSERT_EQ(symlink("tex.png", dir.file("alias.png").c_str()), 0);
  const std::string sim = std::string(LR_SIM) + " --obj " + dir.file("cube.obj") + " --width 32 ";
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {"--texture " + tex + " --out " + tex,
       tex + ": is an input (" + tex + "): refusing to overwrite it"},
      {"--texture " + tex + " --out " + dir.file("alias.png"),
       dir.file("alias.png") + ": is an input (" + tex + "): refusing to overwrite it"},
      {"--out " + map_kd, map_kd + ": is an input (" + map_kd + "): refusing to overwrite it"},
      {"--shading phong --envmap " + tex + " --depth-out " + tex + " --out " + dir.file("x.png"),
       tex + ": is an input (" + tex + "): refusing to overwrite it"},
      {"--out " + dir.file("a.png") + " --depth-out " + dir.path() + "/./a.png",
       dir.path() + "/./a.png: is also the --out file (" + dir.file("a.png") +
           "): refusing to write it twice"},
      {"--frames 3 --out-pattern " + dir.file("f%d.png") + " --out " + dir.file("f2.png"),
       dir.file("f2.png") + ": is also the --out file (" + dir.file("f2.png") +
           "): refusing to write it twice"},
  };
  for (const Case& c : cases) {
    const Outcome r = run(sim + c.args, logs);
    EXPECT_EQ(r.status, 2) << c.args;
    EXPECT_EQ(r.err, "lineraster-sim: " + c.message + "\n") << c.args;
  }
  EXPECT_EQ(slurp(tex), before);
  EXPECT_EQ(sorted_entries(dir), (std::vector<std::string>{"alias.png", "checker.png", "cube.mtl",
                                                           "cube.obj", "tex.png"}));
}

// Every frame's name is checked before the first frame is written: a FIFO as frame 2 of 3
// leaves no frame 0 or 1 behind.
TEST(OutputSafetySim, AFrameNameThatIsAFifoStopsTheRunBeforeAnyFrame) {
  TmpDir dir("lr_out_safety"), logs("lr_out_logs");
  ASSERT_EQ(mkfifo(dir.file("f2.png").c_str(), 0644), 0);
  const Outcome r = run(std::string(LR_SIM) + " --obj " + kData +
                            "cube.obj --width 32 --frames 3 --out-pattern " + dir.file("f%d.png"),
                        logs);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "lineraster-sim: " + not_regular(dir.file("f2.png"), "a FIFO") + "\n");
  EXPECT_EQ(r.out, "");  // no frame was rendered (no per-frame line)
  EXPECT_EQ(sorted_entries(dir), std::vector<std::string>{"f2.png"});
}

}  // namespace
