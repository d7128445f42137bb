// The host examples (examples/host) run as a user runs them: exit status, what they print and the
// pixels of their frames. quick_start and panel are the README's code (scripts/check_doc_links.py
// keeps the README's blocks equal to the files), minimal is the consumer projects' program.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "lineraster/host_sim/formats/image_io.hpp"
#include "tests/support/tmp_dir.hpp"

namespace {

using Rgb = std::array<uint8_t, 3>;

struct Outcome {
  int status = -1;
  std::string out, err;
};

const lr::test::TmpDir& tmp() {
  static const lr::test::TmpDir dir("lr_examples_test");
  return dir;
}

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Runs `program args` through the shell, capturing stdout and stderr.
Outcome run(const std::string& program, const std::string& args) {
  const std::string out = tmp().file("stdout"), err = tmp().file("stderr");
  const int rc = std::system((program + " " + args + " >" + out + " 2>" + err).c_str());
  return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, slurp(out), slurp(err)};
}

struct Frame {
  lr::host::ImageRgb8 image;
  Rgb at(int x, int y) const {
    const size_t i =
        3 * (static_cast<size_t>(y) * static_cast<size_t>(image.width) + static_cast<size_t>(x));
    return {image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]};
  }
  // How many pixels have each colour.
  std::map<Rgb, int> histogram() const {
    std::map<Rgb, int> h;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) ++h[at(x, y)];
    return h;
  }
};

Frame read_frame(const std::string& path) {
  Frame f;
  std::string err;
  EXPECT_TRUE(lr::host::read_ppm(path, f.image, err)) << err;
  return f;
}

constexpr Rgb kClear{16, 24, 48};  // the examples' background

void expect_clear_corners(const Frame& f) {
  EXPECT_EQ(f.at(0, 0), kClear);
  EXPECT_EQ(f.at(f.image.width - 1, 0), kClear);
  EXPECT_EQ(f.at(0, f.image.height - 1), kClear);
  EXPECT_EQ(f.at(f.image.width - 1, f.image.height - 1), kClear);
}

// The default angle (20 degrees): three faces, each one flat colour of the teal material, lit
// from (1, 3, 2): the top brightest, the +x face darkest; the six back triangles culled.
TEST(ExamplesQuickStart, DrawsThreeFlatLitFacesOfTheCube) {
  const std::string ppm = tmp().file("cube.ppm");
  const Outcome r = run(LR_QUICK_START, ppm);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "quick_start: 20 degrees, 6 culled, 4587 pixels\n");
  EXPECT_EQ(r.err, "");
  const Frame f = read_frame(ppm);
  ASSERT_EQ(f.image.width, 160);
  ASSERT_EQ(f.image.height, 120);
  expect_clear_corners(f);
  EXPECT_EQ(f.at(79, 34), (Rgb{20, 174, 184}));  // top (+y)
  EXPECT_EQ(f.at(72, 68), (Rgb{15, 142, 149}));  // front (+z, turned 20 degrees)
  EXPECT_EQ(f.at(105, 62), (Rgb{2, 61, 62}));    // side (+x)
  const std::map<Rgb, int> expected{{kClear, 160 * 120 - 4587},
                                    {{20, 174, 184}, 715},
                                    {{15, 142, 149}, 3568},
                                    {{2, 61, 62}, 304}};
  EXPECT_EQ(f.histogram(), expected);
}

// The angle is read at run time: at 30 degrees the +x face has turned away (8 triangles culled)
// and the front face is lit a level differently.
TEST(ExamplesQuickStart, TheAngleGivenAtRunTimeTurnsTheCube) {
  const std::string ppm = tmp().file("cube30.ppm");
  const Outcome r = run(LR_QUICK_START, ppm + " 30");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "quick_start: 30 degrees, 8 culled, 4516 pixels\n");
  const Frame f = read_frame(ppm);
  expect_clear_corners(f);
  const std::map<Rgb, int> expected{
      {kClear, 160 * 120 - 4516}, {{20, 174, 184}, 716}, {{15, 142, 150}, 3800}};
  EXPECT_EQ(f.histogram(), expected);
}

TEST(ExamplesQuickStart, RefusesABadAngleWithOneLineAndWritesNothing) {
  for (const char* angle : {"361", "-361", "abc", "12x", "''", "99999999999999999999"}) {
    const std::string ppm = tmp().file("bad.ppm");
    const Outcome r = run(LR_QUICK_START, ppm + " " + angle);
    EXPECT_EQ(r.status, 2) << angle;
    EXPECT_EQ(r.err, "quick_start: DEGREES must be an integer in -360..360\n") << angle;
    EXPECT_FALSE(std::ifstream(ppm).good()) << angle;
  }
}

// The consumer projects' program (tests/consumers/check_ppm.py checks it loosely there).
TEST(ExamplesMinimal, DrawsTheLitGoldOctahedron) {
  const std::string ppm = tmp().file("minimal.ppm");
  const Outcome r = run(LR_MINIMAL, ppm);
  ASSERT_EQ(r.status, 0) << r.err;
  const Frame f = read_frame(ppm);
  ASSERT_EQ(f.image.width, 160);
  ASSERT_EQ(f.image.height, 120);
  expect_clear_corners(f);
  EXPECT_EQ(f.at(80, 60), (Rgb{198, 160, 60}));
  EXPECT_EQ(f.histogram().at(kClear), 160 * 120 - 3143);
}

// The panel example's bytes: a whole 240x240 frame is 115,200 pixel bytes and 30 strips x 11
// command bytes; the same frame again sends nothing; a turned triangle only changed columns.
TEST(ExamplesPanel, SendsTheFrameThenNothingThenTheChangedColumns) {
  const Outcome r = run(LR_PANEL, "");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out,
            "panel: frame 0: 115530 bytes, 30 strips sent, 0 narrowed, 0 skipped\n"
            "panel: frame 1: 0 bytes, 0 strips sent, 0 narrowed, 30 skipped\n"
            "panel: frame 2: 32849 bytes, 19 strips sent, 19 narrowed, 11 skipped\n");
}

}  // namespace
