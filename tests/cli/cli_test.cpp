// lineraster-sim as a user runs it: exit codes, one-line errors, no output on failure, outputs
// by extension, --stats JSON, option order for --material, lights and per-pixel lighting options.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "lineraster/host_sim/formats/image_io.hpp"
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

// `prefix`: shell commands run first, in the same shell (limits for the run).
Outcome run(const std::string& args, const std::string& prefix = "") {
  static const std::string dir = tmpdir();
  std::string out = dir + "/stdout", err = dir + "/stderr";
  std::string cmd = prefix + std::string(LR_SIM) + " " + args + " >" + out + " 2>" + err;
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
const std::string kData = std::string(LR_SOURCE_DIR) + "/tests/host/data/";

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

// Decimal numbers in their usual forms (a '+' sign, a leading point, an exponent) are the
// numbers they write.
TEST(Cli, DecimalNumbersInTheirUsualFormsAreAccepted) {
  const std::string a = tmpdir() + "/n1.png", b = tmpdir() + "/n2.png";
  ASSERT_EQ(run("--obj " + kMesh +
                " --fit --width 160 --height 120 --fovy 60 --near 0.1 --eye "
                "0,0,3 --out " +
                a)
                .status,
            0);
  const Outcome r = run("--obj " + kMesh +
                        " --fit --width +160 --height 120 --fovy 6e1 --near .1 --eye -0,+0,3.0 "
                        "--out " +
                        b);
  ASSERT_EQ(r.status, 0) << r.err;
  lr::host::ImageRgb8 x, y;
  std::string err;
  ASSERT_TRUE(lr::host::read_png(a, x, err)) << err;
  ASSERT_TRUE(lr::host::read_png(b, y, err)) << err;
  EXPECT_EQ(x.width, 160);
  EXPECT_TRUE(x.rgb == y.rgb);
}

// Stores smaller than the frame: it is drawn in bands, the same image (exit 0); a strip that
// touches more triangles than the binned store holds is drawn in narrower strips, the same image
// again; below even that (one row too many) the image is written with what fit, one warning line
// says what was dropped, and the exit status is 3.
TEST(Cli, WorkDroppedForLackOfStoreSpaceIsAWarningAndExitStatusThree) {
  const std::string full = tmpdir() + "/s0.png", banded = tmpdir() + "/s1.png",
                    cut = tmpdir() + "/s2.png";
  ASSERT_EQ(run("--obj " + kMesh + " --fit --out " + full).status, 0);
  lr::host::ImageRgb8 want, got;
  std::string err;
  ASSERT_TRUE(lr::host::read_png(full, want, err)) << err;
  for (const std::string stores : {"2000,1000,16", "400,300,8"}) {
    const Outcome b =
        run("--obj " + kMesh + " --fit --stores " + stores + " --stats --out " + banded);
    ASSERT_EQ(b.status, 0) << stores << ": " << b.err;
    EXPECT_EQ(b.err, "") << stores;
    EXPECT_NE(b.out.find("\"dropped_triangle_capacity\":0,"), std::string::npos) << b.out;
    ASSERT_TRUE(lr::host::read_png(banded, got, err)) << err;
    EXPECT_TRUE(want.rgb == got.rgb) << stores;
  }
  // 300 binned triangles are too few for strips of 8 rows here: the frame took rows of one.
  const Outcome narrow =
      run("--obj " + kMesh + " --fit --stores 400,300,8 --stats --out " + banded);
  EXPECT_NE(narrow.out.find("\"strip_height\":1,"), std::string::npos) << narrow.out;

  const Outcome c = run("--obj " + kMesh + " --fit --stores 200,100,4 --stats --out " + cut);
  EXPECT_EQ(c.status, 3) << c.err;
  EXPECT_EQ(lines(c.err), 1u) << c.err;
  EXPECT_EQ(c.err.rfind("lineraster-sim: warning: 1 frame(s) incomplete for lack of store space: "
                        "0 triangles dropped for the vertex store, ",
                        0),
            0u)
      << c.err;
  EXPECT_NE(c.err.find("for the binned-triangle store (--stores 200,100,4)"), std::string::npos);
  EXPECT_EQ(c.out.find("\"dropped_triangle_capacity\":0,"), std::string::npos) << c.out;
  ASSERT_TRUE(lr::host::read_png(cut, got, err)) << err;
  EXPECT_FALSE(want.rgb == got.rgb);
  // --frames counts the incomplete frames.
  const Outcome f = run("--obj " + kMesh + " --fit --stores 200,100,4 --frames 2 --out " + cut);
  EXPECT_EQ(f.status, 3);
  EXPECT_NE(f.err.find("warning: 2 frame(s) incomplete"), std::string::npos) << f.err;
}

// A frame that shows nothing of the model is written, with a hint why.
TEST(Cli, NothingVisibleGivesAHint) {
  const std::string out = tmpdir() + "/e.png";
  const Outcome away = run("--obj " + kMesh + " --eye 0,0,3 --target 0,0,6 --out " + out);
  EXPECT_EQ(away.status, 0);
  EXPECT_EQ(away.err,
            "lineraster-sim: warning: nothing of the model is visible: the model is outside the "
            "view, or too small to cover a pixel centre (--fit puts it in view)\n");
  EXPECT_TRUE(fs::exists(out));
  const Outcome seen = run("--obj " + kMesh + " --fit --out " + out);
  EXPECT_EQ(seen.status, 0);
  EXPECT_EQ(seen.err, "");
}

// What other loaders accept is drawn, with one warning line each: a usemtl without a library
// (the default material), a material's texture on faces without vt (untextured).
TEST(Cli, TolerableInputIsDrawnWithAWarningLine) {
  const std::string dir = tmpdir();
  const std::string quad = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n";
  { std::ofstream(dir + "/plain.obj") << quad << "f 1 2 3 4\n"; }
  { std::ofstream(dir + "/nolib.obj") << quad << "usemtl red\nf 1 2 3 4\n"; }
  {
    std::ofstream(dir + "/tex.mtl")
        << "newmtl t\nKd 0.8 0.8 0.8\nmap_Kd " << kData << "checker.png\n";
    std::ofstream(dir + "/plainmtl.mtl") << "newmtl t\nKd 0.8 0.8 0.8\n";
    std::ofstream(dir + "/novt.obj") << "mtllib tex.mtl\n" << quad << "usemtl t\nf 1 2 3 4\n";
    std::ofstream(dir + "/novt_plain.obj") << "mtllib plainmtl.mtl\n"
                                           << quad << "usemtl t\nf 1 2 3 4\n";
  }
  auto image = [&](const std::string& obj, Outcome& r) {
    const std::string out = dir + "/" + obj + ".png";
    r = run("--obj " + dir + "/" + obj + " --width 64 --height 64 --out " + out);
    lr::host::ImageRgb8 img;
    std::string err;
    EXPECT_TRUE(lr::host::read_png(out, img, err)) << err;
    return img.rgb;
  };
  Outcome plain, nolib, novt, novt_plain;
  const auto want = image("plain.obj", plain);
  EXPECT_EQ(image("nolib.obj", nolib), want);
  EXPECT_EQ(nolib.status, 0);
  EXPECT_EQ(nolib.err, "lineraster-sim: warning: " + dir +
                           "/nolib.obj:5: usemtl 'red' without a material library: the default "
                           "material is used\n");
  const auto untextured = image("novt_plain.obj", novt_plain);
  EXPECT_EQ(image("novt.obj", novt), untextured);
  EXPECT_EQ(novt.status, 0);
  EXPECT_EQ(novt.err, "lineraster-sim: warning: " + kData +
                          "checker.png: the faces of its material have no texture coordinates "
                          "(vt): drawn untextured\n");
  EXPECT_EQ(plain.err + novt_plain.err, "");
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
  EXPECT_NE(r.out.find("\"bytes_per_binned_triangle\":8"), std::string::npos);
}

// --subdivide N: four triangles for one, N times, over V + E vertices
// (host_sim/scene/mesh_prep.hpp).
TEST(Cli, SubdivideMultipliesTheTrianglesByFour) {
  std::string out = tmpdir() + "/s.ppm";
  Outcome r = run("--obj " + kMesh + " --fit --subdivide 1 --stats --out " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"triangles_in\":16000"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"vertices_transformed\":8421"), std::string::npos) << r.out;
  // The fitted knot is in front of the eye and inside the frustum: no vertex needs the exact path.
  EXPECT_NE(r.out.find("\"vertices_wide\":0,"), std::string::npos) << r.out;
  for (const char* bad : {"5", "-1", "x", "1.5"}) {
    Outcome b = run("--obj " + kMesh + " --subdivide " + bad + " --out " + out + "2");
    EXPECT_EQ(b.status, 2) << bad;
    EXPECT_NE(b.err.find("--subdivide"), std::string::npos) << b.err;
  }
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
    std::ofstream far(dir + "/far.obj");
    far << "v 0 0 0\n# a vertex out of the core's range\nv 40000 0 0\nv 0 1 0\nf 1 2 3\n";
  }
  const BadCase cases[] = {
      {"", "--obj FILE is required"},
      {"--obj", "--obj: missing value"},
      {"--obj " + kMesh + " --width 0", "--width: bad value '0'"},
      {"--obj " + kMesh + " --width abc", "--width: bad value 'abc'"},
      // Numbers are decimal, whole strings: what strtod would also take is refused.
      {"--obj " + kMesh + " --width 0x140", "--width: bad value '0x140'"},
      {"--obj " + kMesh + " --width 1e2", "--width: bad value '1e2'"},
      {"--obj " + kMesh + " --width 320.0", "--width: bad value '320.0'"},
      {"--obj " + kMesh + " --width 320x", "--width: bad value '320x'"},
      {"--obj " + kMesh + " --fovy 0x3c", "--fovy: bad value '0x3c'"},
      {"--obj " + kMesh + " --fovy inf", "--fovy: bad value 'inf'"},
      {"--obj " + kMesh + " --near nan", "--near: bad value 'nan'"},
      {"--obj " + kMesh + " --eye 0,0,+-3", "--eye: bad value '0,0,+-3'"},
      {"--obj " + kMesh + " --stores 0,100,4", "--stores: bad value '0,100,4'"},
      {"--obj " + kMesh + " --stores 100,65535,4", "--stores: bad value '100,65535,4'"},
      {"--obj " + kMesh + " --stores 100,100", "--stores: bad value '100,100'"},
      {"--obj " + kMesh + " --eye 1,2", "--eye: bad value '1,2'"},
      {"--obj " + kMesh + " --bg 2,0,0", "--bg: bad value '2,0,0'"},
      {"--obj " + kMesh + " --material unobtainium", "unknown material"},
      {"--obj " + kMesh + " --shading toon", "--shading: bad value 'toon'"},
      {"--obj " + kMesh + " --cull front", "--cull: bad value 'front'"},
      {"--obj " + kMesh + " --strip-height 3", "--strip-height: bad value '3'"},
      {"--obj " + kMesh + " --near 5 --far 1", "--far must be greater than --near"},
      {"--obj " + kMesh + " --fovy 180", "--fovy: bad value '180'"},
      {"--obj " + kMesh + " --frobnicate", "unknown option '--frobnicate'"},
      {"--obj " + kMesh + " --out x.jpg", "must end in .png, .ppm or .gif"},
      {"--obj " + dir + "/missing.obj", "missing.obj"},
      {"--obj " + dir + "/bad.obj", "bad.obj:4:"},
      {"--obj " + dir + "/far.obj",
       dir + "/far.obj:3: v (40000, 0, 0) is not finite or outside the core's range (|x| < "
             "32768); try --fit"},
      {"--obj " + dir + "/far.obj --subdivide 1", dir + "/far.obj:3: v (40000, 0, 0) is"},
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

// A write that fails half-way (here a file-size limit of 512 B, as a full disk would) says why,
// in the system's words, and leaves no file behind.
TEST(Cli, AFailedWriteSaysWhyAndLeavesNoFile) {
  const std::string limit = "trap '' XFSZ; ulimit -f 1; ";
  for (const std::string name : {"w.png", "w.ppm"}) {
    const std::string out = tmpdir() + "/" + name;
    fs::remove(out);
    const Outcome r = run("--obj " + kMesh + " --fit --out " + out, limit);
    EXPECT_EQ(r.status, 2) << name;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(out + ": write failed: File too large"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << name;
    for (const auto& e : fs::directory_iterator(tmpdir()))  // nor its temporary file
      EXPECT_NE(e.path().filename().string().rfind(name, 0), 0u) << e.path();
  }
}

// ---- Lights and per-pixel (Phong) lighting ----

bool read(const std::string& path, lr::host::ImageRgb8& img) {
  std::string err;
  return lr::host::read_png(path, img, err);
}

// Pixels that differ from the background colour (r, g, b).
size_t drawn(const lr::host::ImageRgb8& img, int r, int g, int b) {
  size_t n = 0;
  for (size_t p = 0; p < img.rgb.size() / 3; ++p)
    n += img.rgb[3 * p] != r || img.rgb[3 * p + 1] != g || img.rgb[3 * p + 2] != b;
  return n;
}

// A flat tangent-space normal map ((0, 0, 1) everywhere: RGB 128, 128, 255) written as PNG.
std::string flat_normal_map() {
  std::string path = tmpdir() + "/flat_normals.png";
  lr::host::ImageRgb8 img;
  img.width = img.height = 16;
  img.rgb.clear();
  for (int p = 0; p < 16 * 16; ++p) img.rgb.insert(img.rgb.end(), {128, 128, 255});
  std::string err;
  EXPECT_TRUE(lr::host::write_png(path, img, err)) << err;
  return path;
}

TEST(CliLights, LightOptionsAcceptGoodValues) {
  // --light dir:1,1,1 (white by default) is the default light; so are --light-dir 1,1,1 and an
  // explicit white colour.
  std::string base = tmpdir() + "/l0.png";
  ASSERT_EQ(run("--obj " + kMesh + " --fit --width 160 --height 120 --out " + base).status, 0);
  lr::host::ImageRgb8 ref;
  ASSERT_TRUE(read(base, ref));
  for (std::string light : {"--light dir:1,1,1", "--light dir:2,2,2:1,1,1", "--light-dir 1,1,1",
                            "--light dir:1,1,1 --global-ambient 0,0,0"}) {
    std::string out = tmpdir() + "/l1.png";
    Outcome r =
        run("--obj " + kMesh + " --fit --width 160 --height 120 " + light + " --out " + out);
    ASSERT_EQ(r.status, 0) << light << ": " << r.err;
    lr::host::ImageRgb8 img;
    ASSERT_TRUE(read(out, img));
    EXPECT_EQ(img.rgb, ref.rgb) << light;
  }
  // Every light form with every optional part, up to 4 lights, with the lighting-model options.
  const std::string good[] = {
      "--light dir:0,1,0:1,0.5,0",
      "--light point:0,0,3",
      "--light point:0,0,3:0.2,0.4,1",
      "--light point:0,0,3:1,1,1:1,0.5,0.25",
      "--light point:0,0,3:1,1,1:0,0,1",
      "--light dir:1,0,0 --light dir:0,1,0 --light point:0,0,2 --light point:-1,-1,1:1,0,0:1,1,0",
      "--global-ambient 0.2,0.2,0.2",
      "--two-sided",
      "--two-sided --local-viewer --light point:-2,1,2",
  };
  for (const std::string& opts : good) {
    std::string out = tmpdir() + "/l2.png";
    Outcome r = run("--obj " + kMesh + " --fit --width 160 --height 120 " + opts + " --out " + out);
    EXPECT_EQ(r.status, 0) << opts << ": " << r.err;
    lr::host::ImageRgb8 img;
    ASSERT_TRUE(read(out, img)) << opts;
    EXPECT_EQ(img.width, 160);
    EXPECT_EQ(img.height, 120);
    EXPECT_GT(drawn(img, 0, 0, 0), 1000u) << opts;
  }
}

TEST(CliLights, LightColourAndGlobalAmbientReachThePixels) {
  // A pure red light on a grey material: every lit pixel is red only.
  std::string red = tmpdir() + "/red.png";
  ASSERT_EQ(
      run("--obj " + kMesh + " --fit --diffuse 0.8,0.8,0.8 --light dir:1,1,1:1,0,0 --out " + red)
          .status,
      0);
  lr::host::ImageRgb8 img;
  ASSERT_TRUE(read(red, img));
  size_t reds = 0, others = 0;
  for (size_t p = 0; p < img.rgb.size() / 3; ++p) {
    reds += img.rgb[3 * p] > 0;
    others += img.rgb[3 * p + 1] > 0 || img.rgb[3 * p + 2] > 0;
  }
  EXPECT_GT(reds, 3000u);
  EXPECT_EQ(others, 0u);
  // A global ambient of 1 adds the material's ambient (0.1) to every drawn pixel: brighter
  // wherever something is drawn (and not already saturated), never darker.
  std::string dark = tmpdir() + "/ga0.png", bright = tmpdir() + "/ga1.png";
  ASSERT_EQ(run("--obj " + kMesh + " --fit --bg 0,0,1 --out " + dark).status, 0);
  ASSERT_EQ(
      run("--obj " + kMesh + " --fit --bg 0,0,1 --global-ambient 1,1,1 --out " + bright).status, 0);
  lr::host::ImageRgb8 a, b;
  ASSERT_TRUE(read(dark, a));
  ASSERT_TRUE(read(bright, b));
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  size_t brighter = 0, darker = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) {
    brighter += b.rgb[i] > a.rgb[i];
    darker += b.rgb[i] < a.rgb[i];
  }
  EXPECT_GT(brighter, 3000u);
  EXPECT_EQ(darker, 0u);
}

TEST(CliLights, PointLightAttenuationDarkens) {
  std::string near = tmpdir() + "/att1.png", far = tmpdir() + "/att4.png";
  ASSERT_EQ(run("--obj " + kMesh + " --fit --light point:0,0,3 --out " + near).status, 0);
  ASSERT_EQ(run("--obj " + kMesh + " --fit --light point:0,0,3:1,1,1:4,0,0 --out " + far).status,
            0);
  lr::host::ImageRgb8 a, b;
  ASSERT_TRUE(read(near, a));
  ASSERT_TRUE(read(far, b));
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  uint64_t sa = 0, sb = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) {
    sa += a.rgb[i];
    sb += b.rgb[i];
    EXPECT_LE(b.rgb[i], a.rgb[i]) << i;
  }
  EXPECT_LT(sb, sa / 2);
}

TEST(CliPhong, BadLightingOptionsFailCleanlyWithoutOutput) {
  std::string dir = tmpdir();
  {
    std::ofstream bad(dir + "/garbage_n.png");
    bad << "this is not a png";
    std::ofstream no_uv(dir + "/no_uv_n.obj");
    no_uv << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  }
  const std::string m = "--obj " + kMesh + " ", c = "--obj " + kData + "cube.obj ";
  const std::string phong = "--shading phong ";
  const std::string expected = "(expected dir:x,y,z[:r,g,b] or point:x,y,z[:r,g,b[:c,l,q]])";
  const BadCase cases[] = {
      // Values.
      {m + phong + "--lighting fast", "--lighting: bad value 'fast' (exact or table)"},
      {m + phong + "--lighting", "--lighting: missing value"},
      {m + phong + "--lighting table --lighting-table 7",
       "--lighting-table: bad value '7' (8..256)"},
      {m + phong + "--lighting table --lighting-table 257", "--lighting-table: bad value '257'"},
      {m + phong + "--lighting table --lighting-table 16.5", "--lighting-table: bad value '16.5'"},
      {m + phong + "--lighting table --lighting-table x", "--lighting-table: bad value 'x'"},
      {m + phong + "--lighting table --lighting-table-filter cubic",
       "--lighting-table-filter: bad value 'cubic' (nearest or bilinear)"},
      {m + "--light sun:1,1,1", "--light: bad value 'sun:1,1,1' " + expected},
      {m + "--light 1,1,1", "--light: bad value '1,1,1' " + expected},
      {m + "--light dir", "--light: bad value 'dir' " + expected},
      {m + "--light dir:1,1", "--light: bad value 'dir:1,1' " + expected},
      {m + "--light dir:1,1,1:", "--light: bad value 'dir:1,1,1:' (colour r,g,b in [0,1])"},
      {m + "--light point:", "--light: bad value 'point:' " + expected},
      {m + "--light dir:0,0,0", "--light: bad value 'dir:0,0,0' (zero direction)"},
      {m + "--light dir:1,1,1:2,0,0",
       "--light: bad value 'dir:1,1,1:2,0,0' (colour r,g,b in [0,1])"},
      {m + "--light dir:1,1,1:1,1", "(colour r,g,b in [0,1])"},
      {m + "--light dir:1,1,1:1,1,1:1,0,0",
       "--light: bad value 'dir:1,1,1:1,1,1:1,0,0' " + expected},
      {m + "--light point:0,0,3:1,1,1:0,0,0",
       "--light: bad value 'point:0,0,3:1,1,1:0,0,0' (attenuation c,l,q: each in [0, 32767], not "
       "all 0)"},
      {m + "--light point:0,0,3:1,1,1:-1,1,0", "(attenuation c,l,q"},
      {m + "--light point:0,0,3:1,1,1:1e6,0,0", "(attenuation c,l,q"},
      {m + "--light point:0,0,3:1,1,1:1,0", "(attenuation c,l,q"},
      {m + "--light point:0,0,3:1,1,1:1,0,0:5", expected},
      {m + "--light point:nan,0,3", expected},
      {m + "--light point:1e9,0,0", "light: point light position is not finite or outside"},
      {m + "--light dir:1,0,0 --light dir:0,1,0 --light dir:0,0,1 --light dir:1,1,0 --light "
           "dir:0,1,1",
       "--light: at most 4 lights"},
      {m + "--light dir:1,0,0 --light-dir 0,1,0", "--light and --light-dir cannot be combined"},
      {m + "--light-dir 0,1,0 --light dir:1,0,0", "--light and --light-dir cannot be combined"},
      {m + "--global-ambient 1.5,0,0", "--global-ambient: bad value '1.5,0,0' (expected r,g,b"},
      {m + "--global-ambient 1,1", "--global-ambient: bad value '1,1'"},
      {m + "--global-ambient", "--global-ambient: missing value"},
      {c + phong + "--envmap", "--envmap: missing value"},
      {c + phong + "--normalmap", "--normalmap: missing value"},
      // Options that only Phong shading (or only the lighting table) uses.
      {m + "--lighting table", "--lighting needs --shading phong"},
      {m + "--shading gouraud --lighting exact", "--lighting needs --shading phong"},
      {m + "--lighting-table 64", "--lighting-table needs --shading phong"},
      {m + "--lighting-table-filter nearest", "--lighting-table-filter needs --shading phong"},
      {c + "--envmap " + kData + "checker.png", "--envmap needs --shading phong"},
      {c + "--shading flat --normalmap " + kData + "tiles64.png",
       "--normalmap needs --shading phong"},
      {m + phong + "--lighting-table 64", "--lighting-table needs --lighting table"},
      {m + phong + "--lighting exact --lighting-table-filter nearest",
       "--lighting-table-filter needs --lighting table"},
      // What the lighting table cannot do.
      {m + phong + "--lighting table --light point:0,0,3",
       "lighting table: needs directional lights only and no local viewer"},
      {m + phong + "--lighting table --local-viewer", "lighting table: needs directional lights"},
      // Map files.
      {c + phong + "--envmap " + dir + "/absent_e.png", "absent_e.png"},
      {c + phong + "--envmap " + dir + "/garbage_n.png", "garbage_n.png"},
      {c + phong + "--normalmap " + dir + "/absent_n.png", "absent_n.png"},
      {c + phong + "--normalmap " + dir + "/garbage_n.png", "garbage_n.png"},
      {"--obj " + dir + "/no_uv_n.obj " + phong + "--normalmap " + kData + "tiles64.png",
       "tiles64.png: the mesh has no texture coordinates (vt) to map it with"},
  };
  for (const BadCase& bc : cases) {
    std::string out = dir + "/never_p.png";
    fs::remove(out);
    Outcome r = run(bc.args + " --out " + out);
    EXPECT_EQ(r.status, 2) << bc.args;
    EXPECT_EQ(lines(r.err), 1u) << bc.args << ": " << r.err;
    EXPECT_NE(r.err.find(bc.expect), std::string::npos) << bc.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << bc.args;
  }
}

TEST(CliPhong, HelpListsEveryNewOption) {
  Outcome r = run("--help");
  ASSERT_EQ(r.status, 0);
  for (const char* opt :
       {"--shading flat|gouraud|phong", "--lighting exact|table", "--lighting-table N",
        "--lighting-table-filter nearest|bilinear", "--light dir:x,y,z[:r,g,b]",
        "--light point:x,y,z[:r,g,b[:c,l,q]]", "--global-ambient r,g,b", "--two-sided",
        "--envmap FILE.png", "--normalmap FILE.png"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

TEST(CliPhong, DocsShowTheHelpTextVerbatim) {
  std::ifstream f(std::string(LR_SOURCE_DIR) + "/docs/host-tools.md");
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string readme = ss.str(), start = "## lineraster-sim\n\n```\n";
  const size_t a = readme.find(start);
  ASSERT_NE(a, std::string::npos);
  const size_t b = readme.find("```\n", a + start.size());
  ASSERT_NE(b, std::string::npos);
  Outcome r = run("--help");
  ASSERT_EQ(r.status, 0);
  EXPECT_EQ(readme.substr(a + start.size(), b - a - start.size()), r.out);
}

// Phong renders: an image of the requested size whose coverage and depth are Gouraud's (depth
// does not depend on how a pixel is lit), for every per-pixel option. The colours are the core's
// business (tests/core); here only that each option reaches a frame.
TEST(CliPhong, RendersTheRequestedSizeWithGouraudsDepth) {
  const std::string normals = flat_normal_map();
  const std::string knot = "--obj " + kMesh + " --fit --material gold ";
  const std::string cube = "--obj " + kData + "cube.obj --eye 2.2,1.8,3 ";
  struct Case {
    std::string scene, phong_opts;
  };
  const Case cases[] = {
      {knot, ""},
      {knot, "--lighting exact"},
      {knot, "--lighting table"},
      {knot, "--lighting table --lighting-table 8 --lighting-table-filter nearest"},
      {knot, "--lighting table --lighting-table 256 --lighting-table-filter bilinear"},
      {knot, "--light point:0,0,3:1,1,1:1,0.2,0.05 --light dir:-1,1,0:0.3,0.3,1"},
      {knot, "--local-viewer --two-sided --global-ambient 0.2,0.2,0.2"},
      {knot, "--lighting table --light dir:1,1,1 --light dir:-1,0,1:0,0,1 --two-sided"},
      {cube, "--envmap " + kData + "checker.png"},
      {cube, "--envmap " + kData + "checker.png --texture-format rgb888 --lighting table"},
      {cube, "--normalmap " + normals},
      {cube, "--normalmap " + normals + " --envmap " + kData + "checker.png --filter nearest"},
      {cube, "--normalmap " + normals + " --texture " + kData + "tiles64.png --mipmap linear"},
      {"--obj " + kData + "ground.obj --eye 0,2,6 ", "--normalmap " + normals},
  };
  for (const Case& c : cases) {
    const std::string size = "--width 200 --height 150 ";
    std::string g_out = tmpdir() + "/g.png", g_depth = tmpdir() + "/g_depth.png";
    std::string p_out = tmpdir() + "/p.png", p_depth = tmpdir() + "/p_depth.png";
    Outcome g = run(c.scene + size + "--out " + g_out + " --depth-out " + g_depth);
    ASSERT_EQ(g.status, 0) << c.scene << ": " << g.err;
    const std::string args = c.scene + size + "--shading phong " + c.phong_opts + " --out " +
                             p_out + " --depth-out " + p_depth;
    Outcome p = run(args);
    EXPECT_EQ(p.status, 0) << args << ": " << p.err;
    if (p.status != 0) continue;
    EXPECT_TRUE(p.err.empty()) << args << ": " << p.err;
    lr::host::ImageRgb8 img, gd, pd;
    ASSERT_TRUE(read(p_out, img)) << args;
    EXPECT_EQ(img.width, 200) << args;
    EXPECT_EQ(img.height, 150) << args;
    EXPECT_EQ(img.rgb.size(), 200u * 150u * 3u) << args;
    ASSERT_TRUE(read(g_depth, gd));
    ASSERT_TRUE(read(p_depth, pd));
    EXPECT_EQ(pd.rgb, gd.rgb) << args;
    EXPECT_GT(drawn(gd, 255, 255, 255), 1000u) << args;  // the scene is in view
  }
}

TEST(CliPhong, NormalMapOnAMeshWithoutTangentsUsesComputedOnes) {
  // cube.obj has vt but no tangents: the simulator computes them; the frame is made.
  const std::string normals = flat_normal_map();
  std::string out = tmpdir() + "/nm.png";
  Outcome r = run("--obj " + kData + "cube.obj --eye 2.2,1.8,3 --shading phong --normalmap " +
                  normals + " --stats --out " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"triangles_in\":12"), std::string::npos) << r.out;
  lr::host::ImageRgb8 img;
  ASSERT_TRUE(read(out, img));
  EXPECT_EQ(img.width, 320);
  EXPECT_EQ(img.height, 240);
}

}  // namespace

// ---- The corpus of real-world quirks (tests/host/data/quirks/) ----
//
// Each quirk file is drawn and must give the image of the plain file it stands for, byte for
// byte; warnings are checked where the file is tolerated rather than read as written.

const std::string kQuirks = kData + "quirks/";
const std::string kQuirkView = " --eye 0.7,-1.1,2.6 --width 160 --height 120";

lr::host::ImageRgb8 quirk_image(const std::string& obj, const std::string& options,
                                std::string& warnings) {
  const std::string out = tmpdir() + "/quirk.png";
  std::filesystem::remove(out);
  const Outcome r = run("--obj " + kQuirks + obj + options + " --out " + out);
  EXPECT_EQ(r.status, 0) << obj << ": " << r.err;
  warnings = r.err;
  lr::host::ImageRgb8 img;
  std::string err;
  EXPECT_TRUE(lr::host::read_png(out, img, err)) << obj << ": " << err;
  return img;
}

TEST(QuirksCorpus, EachQuirkDrawsTheImageOfItsPlainFile) {
  struct Case {
    const char *quirk, *plain, *options, *warning;  // warning: a part of stderr, or ""
  };
  const Case cases[] = {
      {"crlf.obj", "plain.obj", "", ""},
      {"tabs.obj", "plain.obj", "", ""},
      {"continuation.obj", "plain.obj", "", ""},
      {"negative.obj", "plain.obj", "", ""},
      {"missing_normals.obj", "plain.obj", "", ""},
      {"ngon.obj", "plain.obj", "", ""},
      {"concave.obj", "concave_quads.obj", "", ""},
      {"empty_name.obj", "plain.obj", "", "unnamed.mtl:2: newmtl without a name"},
      {"usemtl_no_library.obj", "no_material.obj", "",
       "usemtl_no_library.obj:21: usemtl 'left' without a material library"},
      {"unknown_material.obj", "left_only_material.obj", "",
       "unknown_material.obj:25: unknown material 'purple': the default material is used"},
      {"missing_uvs.obj", "untextured.obj", "",
       "checker.png: the faces of its material have no texture coordinates (vt)"},
      // Z-up: the camera and the light turned with the model ((x, y, z) -> (x, -z, y)).
      {"z_up.obj", "plain.obj", " --eye 0.7,-2.6,-1.1 --up 0,0,1 --light-dir 1,-1,1", ""},
  };
  for (const Case& c : cases) {
    std::string plain_warnings, warnings;
    const lr::host::ImageRgb8 want = quirk_image(c.plain, kQuirkView, plain_warnings);
    const std::string options = *c.options ? " --eye 0.7,-2.6,-1.1 --up 0,0,1 --light-dir 1,-1,1 "
                                             "--width 160 --height 120"
                                           : kQuirkView;
    const lr::host::ImageRgb8 got = quirk_image(c.quirk, options, warnings);
    EXPECT_EQ(plain_warnings, "") << c.plain;
    EXPECT_GT(drawn(want, 0, 0, 0), 4000u) << c.plain;
    EXPECT_TRUE(got.rgb == want.rgb) << c.quirk << " does not draw " << c.plain << "'s image";
    if (*c.warning)
      EXPECT_NE(warnings.find(c.warning), std::string::npos) << c.quirk << ": " << warnings;
    else
      EXPECT_EQ(warnings, "") << c.quirk;
  }
}

// Two materials with a texture each: every pixel is the one of its half drawn alone.
TEST(QuirksCorpus, SeveralMaterialsKeepTheirOwnTextures) {
  std::string w;
  const lr::host::ImageRgb8 both = quirk_image("two_textures.obj", kQuirkView, w);
  const lr::host::ImageRgb8 left = quirk_image("left_texture.obj", kQuirkView, w);
  const lr::host::ImageRgb8 right = quirk_image("right_texture.obj", kQuirkView, w);
  const lr::host::ImageRgb8 white = quirk_image("untextured.obj", kQuirkView, w);
  ASSERT_EQ(both.rgb.size(), left.rgb.size());
  size_t from_left = 0, from_right = 0, mismatched = 0;
  for (size_t p = 0; p < both.rgb.size() / 3; ++p) {
    const bool in_left = left.rgb[3 * p] + left.rgb[3 * p + 1] + left.rgb[3 * p + 2] != 0;
    const bool in_right = right.rgb[3 * p] + right.rgb[3 * p + 1] + right.rgb[3 * p + 2] != 0;
    const lr::host::ImageRgb8& from = in_left ? left : right;
    if (!in_left && !in_right) continue;
    from_left += in_left ? 1 : 0;
    from_right += in_left ? 0 : 1;
    for (size_t k = 0; k < 3; ++k)
      mismatched += both.rgb[3 * p + k] != from.rgb[3 * p + k] ? 1u : 0u;
  }
  EXPECT_GT(from_left, 2000u);
  EXPECT_GT(from_right, 2000u);
  EXPECT_EQ(mismatched, 0u);
  EXPECT_FALSE(both.rgb == white.rgb);
  EXPECT_GT(distinct_colours(both), distinct_colours(left));
}
