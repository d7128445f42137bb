// lr_panel_app (firmware/linux) on the host, without a panel:
//   - its options: what a good command line gives, and the one-line error of every bad one;
//   - its frames: PanelApp on a recording bus with a model of the controller's RAM (tests/hal):
//     the module shows exactly lineraster-sim's frame of the demo scene at the frame's rotation,
//     the first frame sends everything (the figure scripts/ci_guest.sh checks on the ARM guest's
//     spidev), the second skips and narrows (its figure too: frames are bit-identical on every
//     platform, so the byte counts are as well);
//   - the program: exit status 0 for --help, 2 for a bad option, 1 for an SPI device that is
//     not there, each error one line on stderr.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "firmware/linux/app_options.hpp"
#include "firmware/linux/panel_app.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/hal/host/display_spec.hpp"
#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/scene/scene.hpp"
#include "tests/hal/recording_bus.hpp"
#include "tests/support/tmp_dir.hpp"

namespace lr {
namespace {

// What a ST7789 240x240 frame costs on the wire (PanelSinkStats::bytes()), checked on the ARM
// guest by scripts/ci_guest.sh (keep the two in step). Frame 0: 30 strips of 8 rows, each
// CASET (1 + 4 bytes), RASET (1 + 4) and RAMWR (1) with 240 x 8 x 2 pixel bytes.
constexpr uint32_t kFrame0Bytes = 240 * 240 * 2 + 30 * 11;  // 115,530
// Frame 1 (3 degrees later): the 13 strips above and below the knot are skipped, the 17 others
// narrowed to their changed columns (30,720 pixel bytes + 17 x 11).
constexpr uint32_t kFrame1Bytes = 30'907;

// ---- options

struct Parsed {
  app::ParseResult result;
  app::AppOptions options;
  std::string error;
};

Parsed parse(std::vector<std::string> args) {
  args.insert(args.begin(), "lr_panel_app");
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  Parsed p;
  p.result = app::parse_options(static_cast<int>(argv.size()), argv.data(), p.options, p.error);
  return p;
}

const std::string kDisplay =
    "spidev:/dev/spidev0.0,dc=gpiochip0:24,rst=gpiochip0:25,bl=gpiochip0:18,hz=40000000";

TEST(PanelAppOptions, ReadsTheDisplayPanelAndFrames) {
  const Parsed p = parse({"--display", kDisplay, "--panel", "st7789:240x320:90", "--frames", "7"});
  ASSERT_EQ(p.result, app::ParseResult::kRun) << p.error;
  EXPECT_EQ(p.options.bus.device, "/dev/spidev0.0");
  EXPECT_EQ(p.options.bus.dc, "gpiochip0:24");
  EXPECT_EQ(p.options.bus.reset, "gpiochip0:25");
  EXPECT_EQ(p.options.bus.backlight, "gpiochip0:18");
  EXPECT_EQ(p.options.bus.hz, 40'000'000u);
  EXPECT_EQ(p.options.panel.controller, Controller::kSt7789);
  EXPECT_EQ(p.options.panel.image_width(), 320);
  EXPECT_EQ(p.options.panel.image_height(), 240);
  EXPECT_EQ(p.options.frames, 7u);
  EXPECT_EQ(p.options.display, kDisplay);
}

TEST(PanelAppOptions, RunsForeverByDefaultAndKnowsHelp) {
  const Parsed p = parse({"--panel", "ili9341:320x240", "--display", kDisplay});
  ASSERT_EQ(p.result, app::ParseResult::kRun) << p.error;
  EXPECT_EQ(p.options.frames, 0u);
  // Read in order, as lineraster-sim reads its options: --help before a bad value wins.
  EXPECT_EQ(parse({"--help", "--display", "nonsense"}).result, app::ParseResult::kHelp);
  EXPECT_EQ(parse({"-h"}).result, app::ParseResult::kHelp);
}

TEST(PanelAppOptions, EveryBadCommandLineIsOneLine) {
  const std::string panel = "st7789:240x240";
  struct Case {
    std::vector<std::string> args;
    std::string error;  // exact, or the start of it when it ends in "..."
  };
  const Case cases[] = {
      {{"--display", kDisplay}, "--panel CONTROLLER:WxH[:ROT] is required (see --help)"},
      {{"--panel", panel},
       "--display spidev:DEVICE,dc=CHIP:LINE,rst=CHIP:LINE[,...] is required (see --help)"},
      {{"--display", kDisplay, "--panel", panel, "--bogus"},
       "unknown option '--bogus' (see --help)"},
      {{"--display", kDisplay, "--panel"}, "--panel: missing value"},
      {{"--display", "--panel", panel}, "--display: missing value"},
      {{"--display", kDisplay, "--panel", panel, "--frames", "x"},
       "--frames: bad value 'x' (a whole number, 0 = until interrupted)"},
      {{"--display", kDisplay, "--panel", panel, "--frames", "-1"}, "--frames: bad value '-1' ..."},
      {{"--display", kDisplay, "--panel", panel, "--frames", "4294967296"},
       "--frames: bad value '4294967296' ..."},
      {{"--display", "emulator:st7789:240x240", "--panel", panel},
       "--display: bad value 'emulator:st7789:240x240' (lr_panel_app drives spidev panels: "
       "spidev:DEVICE,dc=CHIP:LINE,...)"},
      {{"--display", "ft232h", "--panel", panel},
       "--display: bad value 'ft232h' (lr_panel_app ..."},
      {{"--display", "spidev:/dev/spidev0.0", "--panel", panel},
       "--display: bad value 'spidev:/dev/spidev0.0' (/dev/spidev0.0: dc= missing ..."},
      {{"--display", "spidev:/dev/spidev0.0,dc=24", "--panel", panel},
       "--display: bad value 'spidev:/dev/spidev0.0,dc=24' (dc=24: ..."},
      {{"--display", "spidev:/dev/spidev0.0,dc=gpiochip0:24,hz=fast", "--panel", panel},
       "--display: bad value 'spidev:/dev/spidev0.0,dc=gpiochip0:24,hz=fast' (hz=fast: ..."},
      {{"--display", kDisplay, "--panel", "st7789:100x100"},
       "--panel: bad value 'st7789:100x100' (st7789: size '100x100': ..."},
      {{"--display", kDisplay, "--panel", "st7735:128x160"},
       "--panel: bad value 'st7735:128x160' (controller 'st7735': st7789 or ili9341)"},
  };
  for (const Case& c : cases) {
    const Parsed p = parse(c.args);
    std::string args;
    for (const std::string& a : c.args) args += a + " ";
    ASSERT_EQ(p.result, app::ParseResult::kError) << args;
    EXPECT_EQ(p.error.find('\n'), std::string::npos) << p.error;
    if (c.error.size() > 3 && c.error.compare(c.error.size() - 3, 3, "...") == 0) {
      const std::string start = c.error.substr(0, c.error.size() - 3);
      EXPECT_EQ(p.error.substr(0, start.size()), start) << args;
    } else {
      EXPECT_EQ(p.error, c.error) << args;
    }
  }
}

// ---- frames

// lineraster-sim --obj torus_knot.obj --fit --material gold --width W --height H
// --model-rotate-y DEG as a panel is sent it (--display: rendered in Rgb565Be), as RGB565 values.
std::vector<uint16_t> sim_frame(int width, int height, int degrees) {
  static host::HostMesh mesh;
  std::string error;
  if (mesh.positions.empty()) {
    EXPECT_TRUE(
        host::load_obj(std::string(LR_SOURCE_DIR) + "/tests/host/data/torus_knot.obj", mesh, error))
        << error;
  }
  host::SceneOptions o;
  o.fit = true;
  o.width = width;
  o.height = height;
  o.model_rotate_y = degrees;
  const NamedMaterial* gold = find_material("gold");
  for (size_t k = 0; k < 3; ++k) {  // as the CLI converts --material
    o.material.ambient[k] = gold->ambient[k] * 1e-8;
    o.material.diffuse[k] = gold->diffuse[k] * 1e-8;
    o.material.specular[k] = gold->specular[k] * 1e-8;
  }
  o.material.emission = {0, 0, 0};
  o.material.shininess = gold->shininess_fraction * 1e-8 * 128.0;
  o.use_mesh_materials = false;
  o.rgb565 = true;
  host::RenderResult r;
  EXPECT_TRUE(host::render_scene(mesh, o, r, error)) << error;
  EXPECT_EQ(r.rgb565.size(), size_t(width) * size_t(height));
  return r.rgb565;
}

size_t differing(const std::vector<uint16_t>& a, const std::vector<uint16_t>& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
  return n;
}

TEST(PanelAppFrames, TheModuleShowsTheSimulatorsFramesAndTheGuestsByteCounts) {
  test::RecordingBus bus;
  bus.ram.fill(0x1234);  // power-on noise: every pixel must be written
  PanelConfig config;
  std::string error;
  ASSERT_TRUE(host::parse_panel_spec("st7789:240x240", config, error)) << error;
  app::PanelApp panel_app(bus, config);
  ASSERT_EQ(panel_app.start(error), Status::kOk) << error;
  uint32_t sent_pixel_bytes = 0;
  const size_t bus_pixel_bytes_at_start = bus.pixel_bytes();
  for (uint32_t f = 0; f < 3; ++f) {
    app::FrameReport r;
    ASSERT_EQ(panel_app.frame(f, r, error), Status::kOk) << error;
    EXPECT_EQ(r.index, f);
    EXPECT_EQ(r.degrees, static_cast<int>(3 * f));
    EXPECT_EQ(r.sink.status, Status::kOk);
    EXPECT_GT(r.render.pixels_written, 240u * 240u / 10) << "frame " << f;
    sent_pixel_bytes += r.sink.pixel_bytes;
    std::printf(
        "frame %u: %u bytes (%u pixel, %u command), %u strips sent, %u narrowed, %u "
        "skipped\n",
        f, r.sink.bytes(), r.sink.pixel_bytes, r.sink.command_bytes, r.sink.strips_sent,
        r.sink.strips_narrowed, r.sink.strips_skipped);
    if (f == 0) {
      EXPECT_EQ(r.sink.pixel_bytes, 240u * 240u * 2);
      EXPECT_EQ(r.sink.bytes(), kFrame0Bytes);
      EXPECT_EQ(r.sink.strips_sent, 30u);
      EXPECT_EQ(r.sink.strips_skipped, 0u);
    } else {
      EXPECT_GT(r.sink.strips_skipped, 0u) << "frame " << f;
      EXPECT_GT(r.sink.strips_narrowed, 0u) << "frame " << f;
      if (f == 1) {
        EXPECT_EQ(r.sink.bytes(), kFrame1Bytes);
      }
    }
    EXPECT_EQ(differing(test::view(bus.ram, config), sim_frame(240, 240, 3 * static_cast<int>(f))),
              0u)
        << "frame " << f;
  }
  EXPECT_EQ(bus.pixel_bytes() - bus_pixel_bytes_at_start, sent_pixel_bytes);
  EXPECT_TRUE(bus.violations.empty()) << bus.violations.front();
}

TEST(PanelAppFrames, LandscapeModuleShowsTheSimulatorsFrame) {
  test::RecordingBus bus;
  PanelConfig config;
  std::string error;
  ASSERT_TRUE(host::parse_panel_spec("ili9341:320x240", config, error)) << error;
  app::PanelApp panel_app(bus, config);
  ASSERT_EQ(panel_app.start(error), Status::kOk) << error;
  app::FrameReport r;
  for (uint32_t f : {0u, 1u}) ASSERT_EQ(panel_app.frame(f, r, error), Status::kOk) << error;
  EXPECT_EQ(differing(test::view(bus.ram, config), sim_frame(320, 240, 3)), 0u);
  EXPECT_TRUE(bus.violations.empty()) << bus.violations.front();
}

// ---- the program

struct Outcome {
  int status = -1;
  std::string out, err;
};

Outcome run(const std::string& args) {
  static const test::TmpDir dir("lr_panel_app_test");
  const std::string out = dir.file("stdout"), err = dir.file("stderr");
  const std::string cmd = std::string(LR_PANEL_APP) + " " + args + " >" + out + " 2>" + err;
  const int rc = std::system(cmd.c_str());
  Outcome r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  std::stringstream so, se;
  so << std::ifstream(out).rdbuf();
  se << std::ifstream(err).rdbuf();
  r.out = so.str();
  r.err = se.str();
  return r;
}

TEST(PanelAppProgram, ExitStatusAndOneLineErrors) {
  const Outcome help = run("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_EQ(help.out.rfind("usage: lr_panel_app", 0), 0u) << help.out;

  const Outcome bad = run("--panel st7789:240x240 --frames two");
  EXPECT_EQ(bad.status, 2);
  EXPECT_EQ(bad.err,
            "lr_panel_app: --frames: bad value 'two' (a whole number, 0 = until "
            "interrupted)\n");
  EXPECT_EQ(bad.out, "");

  const Outcome no_device =
      run("--display spidev:/dev/spidev-lr-none.0,dc=gpiochip0:4 --panel st7789:240x240 "
          "--frames 1");
  EXPECT_EQ(no_device.status, 1);
  EXPECT_EQ(no_device.err.rfind("lr_panel_app: /dev/spidev-lr-none.0: no such device", 0), 0u)
      << no_device.err;
  EXPECT_EQ(no_device.err.find('\n'), no_device.err.size() - 1) << no_device.err;
  EXPECT_EQ(no_device.out, "");
}

}  // namespace
}  // namespace lr
