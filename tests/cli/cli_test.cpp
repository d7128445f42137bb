// lineraster-sim as a user runs it: exit codes, one-line errors, no output on failure, outputs
// by extension, --stats JSON, option order for --material.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "host_sim/image_io.hpp"
#include "tests/support/tmp_dir.hpp"

namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;
  std::string out, err;
};

// One directory per test process, removed when it ends.
std::string tmpdir() {
  static const lr::test::TmpDir dir("lr_cli_test");
  return dir.path();
}

Outcome run(const std::string& args) {
  static const std::string dir = tmpdir();
  std::string out = dir + "/stdout", err = dir + "/stderr";
  std::string cmd = std::string(LR_SIM) + " " + args + " >" + out + " 2>" + err;
  int rc = std::system(cmd.c_str());
  Outcome r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  std::ifstream o(out), e(err);
  std::stringstream so, se;
  so << o.rdbuf();
  se << e.rdbuf();
  r.out = so.str();
  r.err = se.str();
  return r;
}

const std::string kMesh = std::string(LR_SOURCE_DIR) + "/tests/host/data/torus_knot.obj";

size_t lines(const std::string& s) {
  size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(Cli, RendersPngWithTheRequestedSize) {
  std::string out = tmpdir() + "/a.png";
  Outcome r =
      run("--obj " + kMesh + " --fit --material gold --width 200 --height 150 --out " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  lr::host::ImageRgb8 img;
  std::string err;
  ASSERT_TRUE(lr::host::read_png(out, img, err)) << err;
  EXPECT_EQ(img.width, 200);
  EXPECT_EQ(img.height, 150);
  // Gold: the lit pixels are yellow-ish (red > green > blue) and the background black.
  size_t lit = 0, golden = 0;
  for (size_t p = 0; p < img.rgb.size() / 3; ++p) {
    int R = img.rgb[3 * p], G = img.rgb[3 * p + 1], B = img.rgb[3 * p + 2];
    if (R + G + B == 0) continue;
    ++lit;
    golden += R >= G && G >= B;
  }
  EXPECT_GT(lit, 3000u);
  EXPECT_GT(golden, lit * 99 / 100);
}

TEST(Cli, PpmByExtensionAndStatsJson) {
  std::string out = tmpdir() + "/b.ppm";
  Outcome r = run("--obj " + kMesh + " --fit --stats --out " + out + " --strip-height 16");
  ASSERT_EQ(r.status, 0) << r.err;
  lr::host::ImageRgb8 img;
  std::string err;
  ASSERT_TRUE(lr::host::read_ppm(out, img, err)) << err;
  EXPECT_EQ(img.width, 320);
  EXPECT_EQ(lines(r.out), 1u);
  EXPECT_NE(r.out.find("\"triangles_in\":4000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"strip_height\":16"), std::string::npos);
  EXPECT_NE(r.out.find("\"strips\":15"), std::string::npos);
  EXPECT_NE(r.out.find("\"bytes_per_binned_triangle\":16"), std::string::npos);
}

TEST(Cli, DepthOutIsA16BitImage) {
  std::string out = tmpdir() + "/c.png", depth = tmpdir() + "/c_depth.png";
  Outcome r = run("--obj " + kMesh + " --fit --out " + out + " --depth-out " + depth);
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_TRUE(fs::exists(depth));
  lr::host::ImageRgb8 img;
  std::string err;
  ASSERT_TRUE(lr::host::read_png(depth, img, err)) << err;  // converted to 8-bit grey on read
  EXPECT_EQ(img.width, 320);
  EXPECT_EQ(img.rgb[0], 255);  // the corner is cleared depth (far)
}

TEST(Cli, MaterialOptionsAfterMaterialOverrideIt) {
  std::string a = tmpdir() + "/m1.png", b = tmpdir() + "/m2.png", c = tmpdir() + "/m3.png";
  ASSERT_EQ(run("--obj " + kMesh + " --fit --material gold --diffuse 0,0,1 --out " + a).status, 0);
  ASSERT_EQ(run("--obj " + kMesh + " --fit --diffuse 0,0,1 --material gold --out " + b).status, 0);
  ASSERT_EQ(run("--obj " + kMesh + " --fit --material gold --out " + c).status, 0);
  lr::host::ImageRgb8 ia, ib, ic;
  std::string err;
  ASSERT_TRUE(lr::host::read_png(a, ia, err));
  ASSERT_TRUE(lr::host::read_png(b, ib, err));
  ASSERT_TRUE(lr::host::read_png(c, ic, err));
  EXPECT_NE(ia.rgb, ic.rgb);  // the later --diffuse changed gold
  EXPECT_EQ(ib.rgb, ic.rgb);  // the later --material replaced the earlier --diffuse
}

// Every bad input: exit status 2, one line on stderr naming the problem, no output file.
struct BadCase {
  std::string args, expect;
};

TEST(Cli, BadInputsFailCleanlyWithoutOutput) {
  std::string dir = tmpdir();
  {
    std::ofstream bad(dir + "/bad.obj");
    bad << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
  }
  const BadCase cases[] = {
      {"", "--obj FILE is required"},
      {"--obj", "--obj: missing value"},
      {"--obj " + kMesh + " --width 0", "--width: bad value '0'"},
      {"--obj " + kMesh + " --width abc", "--width: bad value 'abc'"},
      {"--obj " + kMesh + " --eye 1,2", "--eye: bad value '1,2'"},
      {"--obj " + kMesh + " --bg 2,0,0", "--bg: bad value '2,0,0'"},
      {"--obj " + kMesh + " --material unobtainium", "unknown material"},
      {"--obj " + kMesh + " --shading toon", "--shading: bad value 'toon'"},
      {"--obj " + kMesh + " --shading phong", "not supported yet"},
      {"--obj " + kMesh + " --cull front", "--cull: bad value 'front'"},
      {"--obj " + kMesh + " --strip-height 3", "--strip-height: bad value '3'"},
      {"--obj " + kMesh + " --near 5 --far 1", "--far must be greater than --near"},
      {"--obj " + kMesh + " --fovy 180", "--fovy: bad value '180'"},
      {"--obj " + kMesh + " --frobnicate", "unknown option '--frobnicate'"},
      {"--obj " + kMesh + " --out x.jpg", "must end in .png or .ppm"},
      {"--obj " + dir + "/missing.obj", "missing.obj"},
      {"--obj " + dir + "/bad.obj", "bad.obj:4:"},
      {"--obj " + kMesh + " --eye 0,0,0 --target 0,0,0", "camera:"},
      {"--obj " + kMesh + " --eye 1e9,0,0", "camera:"},
      {"--obj " + kMesh + " --light-dir 0,0,0", "--light-dir: bad value"},
  };
  for (const BadCase& c : cases) {
    std::string out = dir + "/never.png";
    fs::remove(out);
    Outcome r = run(c.args + " --out " + out);
    if (c.args.find("--out x.jpg") != std::string::npos) r = run(c.args);
    EXPECT_EQ(r.status, 2) << c.args;
    EXPECT_EQ(lines(r.err), 1u) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

const std::string kData = std::string(LR_SOURCE_DIR) + "/tests/host/data/";

size_t distinct_colours(const lr::host::ImageRgb8& img) {
  std::vector<uint32_t> c;
  for (size_t p = 0; p < img.rgb.size() / 3; ++p)
    c.push_back(uint32_t(img.rgb[3 * p]) << 16 | uint32_t(img.rgb[3 * p + 1]) << 8 |
                img.rgb[3 * p + 2]);
  std::sort(c.begin(), c.end());
  return size_t(std::unique(c.begin(), c.end()) - c.begin());
}

TEST(Cli, MaterialMapKdTexturesTheMeshAndTextureOverridesIt) {
  std::string a = tmpdir() + "/t1.png", b = tmpdir() + "/t2.png", c = tmpdir() + "/t3.png";
  ASSERT_EQ(run("--obj " + kData + "cube.obj --eye 2.2,1.8,3 --filter nearest --out " + a).status,
            0);
  ASSERT_EQ(run("--obj " + kData + "cube.obj --eye 2.2,1.8,3 --filter nearest --texture " + kData +
                "tiles64.png --out " + b)
                .status,
            0);
  ASSERT_EQ(run("--obj " + kData + "cube.obj --eye 2.2,1.8,3 --filter nearest --texture " + kData +
                "tiles64.png --perspective span16 --mipmap linear --wrap clamp --texture-format "
                "palette8 --out " +
                c)
                .status,
            0);
  lr::host::ImageRgb8 ia, ib, ic;
  std::string err;
  ASSERT_TRUE(lr::host::read_png(a, ia, err));
  ASSERT_TRUE(lr::host::read_png(b, ib, err));
  ASSERT_TRUE(lr::host::read_png(c, ic, err));
  EXPECT_NE(ia.rgb, ib.rgb);
  EXPECT_NE(ib.rgb, ic.rgb);
  // A material option replaces the MTL materials, and with them map_Kd: three flat-lit faces
  // and the background. The textured renders show more colours than that.
  std::string d = tmpdir() + "/t4.png";
  ASSERT_EQ(
      run("--obj " + kData + "cube.obj --eye 2.2,1.8,3 --diffuse 0.8,0.8,0.8 --out " + d).status,
      0);
  lr::host::ImageRgb8 id;
  ASSERT_TRUE(lr::host::read_png(d, id, err));
  EXPECT_LE(distinct_colours(id), 4u);
  EXPECT_GT(distinct_colours(ia), distinct_colours(id));
  EXPECT_GT(distinct_colours(ib), distinct_colours(id) + 4);
}

TEST(Cli, BadTexturesFailCleanlyWithoutOutput) {
  std::string dir = tmpdir();
  {
    std::ofstream bad(dir + "/garbage.png");
    bad << "this is not a png";
    std::ofstream no_uv(dir + "/no_uv.obj");
    no_uv << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  }
  const BadCase cases[] = {
      {"--obj " + kData + "cube.obj --texture " + dir + "/garbage.png", "garbage.png"},
      {"--obj " + kData + "cube.obj --texture " + dir + "/absent.png", "absent.png"},
      {"--obj " + dir + "/no_uv.obj --texture " + kData + "tiles64.png", "no texture coordinates"},
      {"--obj " + kData + "cube.obj --filter cubic", "--filter: bad value 'cubic'"},
      {"--obj " + kData + "cube.obj --wrap mirror", "--wrap: bad value 'mirror'"},
      {"--obj " + kData + "cube.obj --perspective span12", "--perspective: bad value 'span12'"},
      {"--obj " + kData + "cube.obj --mipmap trilinear", "--mipmap: bad value 'trilinear'"},
      {"--obj " + kData + "cube.obj --texture-format rgb444",
       "--texture-format: bad value 'rgb444'"},
  };
  for (const BadCase& c : cases) {
    std::string out = dir + "/never_t.png";
    fs::remove(out);
    Outcome r = run(c.args + " --out " + out);
    EXPECT_EQ(r.status, 2) << c.args;
    EXPECT_EQ(lines(r.err), 1u) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

TEST(Cli, UnwritableOutputFailsWithoutPartialFile) {
  Outcome r = run("--obj " + kMesh + " --out /nonexistent-dir/x.png");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(lines(r.err), 1u);
  EXPECT_NE(r.err.find("/nonexistent-dir/x.png"), std::string::npos) << r.err;
}

}  // namespace
