// lineraster-sim --display, --panel and --frames as a user runs them: the emulated panel shows the
// frame rendered in RGB565 (what a panel firmware renders: tests/support/sim_render.hpp), within
// one RGB565 level of the plain RGB888 render, at every module size and rotation; --frames prints
// one JSON line per frame and totals, skipping shows from the second frame on; every bad value,
// and a real panel that is not there, is one line on stderr, exit status 2 and no output file.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "lineraster/core/output/pixel_format.hpp"
#include "lineraster/host_sim/formats/image_io.hpp"
#include "tests/support/sim_render.hpp"
#include "tests/support/tmp_dir.hpp"

namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;
  std::string out, err;
};

std::string tmpdir() {
  static const lr::test::TmpDir dir("lr_cli_display_test");
  return dir.path();
}

Outcome run(const std::string& args) {
  const std::string out = tmpdir() + "/stdout", err = tmpdir() + "/stderr";
  const std::string cmd = std::string(LR_SIM) + " " + args + " >" + out + " 2>" + err;
  const int rc = std::system(cmd.c_str());
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
const std::string kScene = "--obj " + kMesh + " --fit --material gold --bg 0.2,0.3,0.5";

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string l; std::getline(ss, l);) out.push_back(l);
  return out;
}

// The integer after "key": in a JSON line, -1 when absent.
long long field(const std::string& line, const std::string& key) {
  const std::string k = "\"" + key + "\":";
  const size_t at = line.find(k);
  if (at == std::string::npos) return -1;
  return std::stoll(line.substr(at + k.size()));
}

lr::host::ImageRgb8 read(const std::string& path) {
  lr::host::ImageRgb8 img;
  std::string err;
  EXPECT_TRUE(lr::host::read_image(path, img, err)) << err;
  return img;
}

// Channels of two images more than one RGB565 level apart (images of RGB565 values decoded by bit
// replication, or an RGB888 one: its levels are Rgb565Be::encode's), or all of them when the
// sizes differ.
size_t beyond_one_level(const lr::host::ImageRgb8& a, const lr::host::ImageRgb8& b) {
  if (a.width != b.width || a.height != b.height) return a.rgb.size() + b.rgb.size();
  size_t n = 0;
  for (size_t i = 0; i < a.rgb.size(); i += 3) {
    const unsigned va = lr::Rgb565Be::to_value(
                       lr::Rgb565Be::encode({a.rgb[i], a.rgb[i + 1], a.rgb[i + 2]})),
                   vb = lr::Rgb565Be::to_value(
                       lr::Rgb565Be::encode({b.rgb[i], b.rgb[i + 1], b.rgb[i + 2]}));
    for (const auto& [shift, max] : {std::pair{11u, 31u}, {5u, 63u}, {0u, 31u}}) {
      const unsigned la = (va >> shift) & max, lb = (vb >> shift) & max;
      n += (la > lb ? la - lb : lb - la) > 1;
    }
  }
  return n;
}

TEST(CliDisplay, HelpListsThePanelOptions) {
  const Outcome r = run("--help");
  ASSERT_EQ(r.status, 0);
  for (const char* opt :
       {"--display emulator:PANEL", "--display ft232h[:SERIAL]", "--panel PANEL", "--frames N",
        "--display spidev:DEVICE,dc=CHIP:LINE,rst=CHIP:LINE",
        "st7789:240x240|240x320|135x240|320x240[:ROT]", "ili9341:240x320|320x240[:ROT]"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
}

TEST(CliDisplay, TheEmulatedPanelShowsTheRgb565RenderAtEverySizeAndRotation) {
  struct Case {
    std::string panel;
    int width, height;
  };
  const Case cases[] = {
      {"st7789:240x240", 240, 240},     {"st7789:240x320:90", 320, 240},
      {"st7789:135x240", 135, 240},     {"st7789:135x240:270", 240, 135},
      {"st7789:320x240", 320, 240},     {"st7789:240x240:180", 240, 240},
      {"ili9341:240x320", 240, 320},    {"ili9341:320x240", 320, 240},
      {"ili9341:320x240:90", 240, 320}, {"ili9341:240x320:180", 240, 320},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.panel);
    const std::string shown = tmpdir() + "/shown.png", plain = tmpdir() + "/plain.png";
    const std::string display = kScene + " --display emulator:" + c.panel;
    const Outcome r = run(display + " --out " + shown);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err, "");  // no warning: the driver's stream is clean
    EXPECT_EQ(r.out, "");
    const std::string size =
        " --width " + std::to_string(c.width) + " --height " + std::to_string(c.height);
    ASSERT_EQ(run(kScene + size + " --out " + plain).status, 0);
    const lr::host::ImageRgb8 a = read(shown), b = read(plain);
    ASSERT_EQ(a.width, c.width);
    ASSERT_EQ(a.height, c.height);
    // The frame rendered here from the same options: in RGB565 with --display (what the panel
    // must show exactly), in RGB888 without (the plain file: the two parse alike).
    const lr::host::RenderResult want = lr::test::sim_render(display);
    EXPECT_EQ(want.rgb565.size(), size_t(c.width) * size_t(c.height));
    EXPECT_TRUE(a.rgb == want.image.rgb);
    EXPECT_TRUE(b.rgb == lr::test::sim_render(kScene + size).image.rgb);
    EXPECT_EQ(beyond_one_level(a, b), 0u);
  }
  // --width/--height may repeat the panel's size.
  EXPECT_EQ(run(kScene + " --display emulator:st7789:135x240:90 --width 240 --height 135 --out " +
                tmpdir() + "/x.png")
                .status,
            0);
}

TEST(CliDisplay, FramesPrintPerFrameFiguresAndTotalsAndSkipUnchangedStrips) {
  const std::string out = tmpdir() + "/frames.png", plain = tmpdir() + "/frames_plain.png";
  const Outcome r = run(kScene + " --display emulator:st7789:240x240 --frames 4 --out " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> l = lines(r.out);
  ASSERT_EQ(l.size(), 5u) << r.out;
  long long bytes = 0, transactions = 0, sent = 0, skipped = 0;
  for (int f = 0; f < 4; ++f) {
    SCOPED_TRACE(l[size_t(f)]);
    EXPECT_EQ(field(l[size_t(f)], "frame"), f);
    EXPECT_EQ(field(l[size_t(f)], "rotate_y"), 90 * f);
    EXPECT_GT(field(l[size_t(f)], "pixels_written"), 5000);
    EXPECT_EQ(field(l[size_t(f)], "strips_sent") + field(l[size_t(f)], "strips_skipped"), 30);
    // CASET, RASET and RAMWR per strip sent, the pixels in RAMWR's chip-select frame.
    EXPECT_EQ(field(l[size_t(f)], "commands"), 3 * field(l[size_t(f)], "strips_sent"));
    EXPECT_EQ(field(l[size_t(f)], "transactions"), field(l[size_t(f)], "commands"));
    EXPECT_EQ(field(l[size_t(f)], "bytes"),
              field(l[size_t(f)], "pixel_bytes") + 11 * field(l[size_t(f)], "strips_sent"));
    bytes += field(l[size_t(f)], "bytes");
    transactions += field(l[size_t(f)], "transactions");
    sent += field(l[size_t(f)], "strips_sent");
    skipped += field(l[size_t(f)], "strips_skipped");
  }
  // Frame 0 sends everything; the knot turned, the background strips are skipped.
  EXPECT_EQ(field(l[0], "pixel_bytes"), 240 * 240 * 2);
  EXPECT_EQ(field(l[0], "strips_skipped"), 0);
  for (int f = 1; f < 4; ++f) {
    EXPECT_GT(field(l[size_t(f)], "strips_skipped"), 0) << l[size_t(f)];
    EXPECT_LT(field(l[size_t(f)], "bytes"), field(l[0], "bytes")) << l[size_t(f)];
  }
  EXPECT_EQ(field(l[4], "frames"), 4);
  EXPECT_EQ(field(l[4], "bytes"), bytes);
  EXPECT_EQ(field(l[4], "transactions"), transactions);
  EXPECT_EQ(field(l[4], "strips_sent"), sent);
  EXPECT_EQ(field(l[4], "strips_skipped"), skipped);
  // --out holds the last frame (the model turned by 270 degrees), as the panel shows it.
  ASSERT_EQ(run(kScene + " --width 240 --height 240 --model-rotate-y 270 --out " + plain).status,
            0);
  const lr::host::ImageRgb8 last = read(out);
  EXPECT_TRUE(last.rgb == lr::test::sim_render(
                              kScene + " --display emulator:st7789:240x240 --model-rotate-y 270")
                              .image.rgb);
  EXPECT_EQ(beyond_one_level(last, read(plain)), 0u);
}

TEST(CliDisplay, FramesWithoutADisplayPrintTheCoresFigures) {
  const std::string out = tmpdir() + "/nodisp.png", plain = tmpdir() + "/nodisp_plain.png";
  const Outcome r = run(kScene + " --frames 3 --model-rotate-y 10 --out " + out);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> l = lines(r.out);
  ASSERT_EQ(l.size(), 4u) << r.out;
  for (int f = 0; f < 3; ++f) {
    EXPECT_EQ(field(l[size_t(f)], "frame"), f);
    EXPECT_EQ(field(l[size_t(f)], "rotate_y"), 10 + 120 * f);
    EXPECT_EQ(field(l[size_t(f)], "strips"), 30);  // 240 rows in strips of 8
    EXPECT_EQ(field(l[size_t(f)], "bytes"), -1);   // nothing sent
  }
  EXPECT_EQ(field(l[3], "frames"), 3);
  ASSERT_EQ(run(kScene + " --model-rotate-y 250 --out " + plain).status, 0);
  EXPECT_TRUE(read(out).rgb == read(plain).rgb);
  // --stats still prints its one line, for the last frame, after them.
  const Outcome s = run(kScene + " --frames 2 --stats --out " + out);
  ASSERT_EQ(s.status, 0);
  ASSERT_EQ(lines(s.out).size(), 4u);
  EXPECT_NE(lines(s.out)[3].find("\"triangles_in\":4000"), std::string::npos);
}

TEST(CliDisplay, BadValuesAndMissingDevicesFailCleanlyWithoutOutput) {
  struct Bad {
    std::string args, expect;
  };
  const Bad cases[] = {
      {"--display emulator:st7789:100x100", "--display: bad value"},
      {"--display emulator:st7789:240x240:45", "rotation '45'"},
      {"--display emulator:ili9341:240x240", "ili9341: size '240x240'"},
      {"--display emulator:ssd1306:128x64", "controller 'ssd1306'"},
      {"--display emulator:st7789", "expected st7789"},
      {"--display hdmi", "expected emulator:"},
      {"--display spidev:", "expected spidev:"},
      {"--panel st7789:240x240", "--panel needs --display"},
      {"--display spidev:/dev/spidev0.0,dc=gpiochip0:24", "needs --panel"},
      {"--display emulator:st7789:240x240 --panel st7789:240x240", "--panel: not with"},
      {"--display emulator:st7789:240x240 --width 320", "the panel shows 240x240"},
      {"--frames 0", "--frames: bad value '0' (1..3600)"},
      {"--frames x", "--frames: bad value"},
      {"--display", "--display: missing value"},
      // Real panels that are not there: the backend's one line (or, in a build without it, why).
      {"--display spidev:/dev/spidev97.3,dc=gpiochip0:24,rst=gpiochip0:25 --panel st7789:240x240",
       "spidev"},
      {"--display ft232h:LR-NO-SUCH-SERIAL --panel ili9341:320x240", ""},
  };
  for (const Bad& c : cases) {
    SCOPED_TRACE(c.args);
    const std::string out = tmpdir() + "/bad.png";
    fs::remove(out);
    const Outcome r = run(kScene + " " + c.args + " --out " + out);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("lineraster-sim: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(r.out, "");
  }
}

}  // namespace
