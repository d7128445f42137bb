// The whole display path against an independent model of the controller: the core renders the
// gold torus knot into the panel driver's PanelSink (hal/panel_sink.hpp, hal/panel.hpp), whose
// bytes go through an EmulatorBus into the panel emulator; what the emulated module shows must
// equal the frame the same renderer gives a capture display (RGB565 decoded the same way), pixel
// for pixel, for every module preset and rotation, frame after frame (unchanged strips skipped,
// changed ones narrowed), with no malformed byte, no timing violation and no bus misuse.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/hal/panel.hpp"
#include "lineraster/hal/panel_sink.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"
#include "lineraster/host_sim/emulator/emulator_bus.hpp"
#include "lineraster/host_sim/emulator/panel_emulator.hpp"
#include "lineraster/host_sim/formats/obj_loader.hpp"
#include "lineraster/host_sim/scene/scene.hpp"

namespace {

using lr::Fixed;
using lr::PanelConfig;
using lr::Rotation;
using lr::Status;
using lr::host::EmulatorBus;
using lr::host::ImageRgb8;
using lr::host::PanelEmulator;
using PF = lr::Rgb565Be;
constexpr int kRows = 8;

std::string name(const PanelConfig& c) {
  return std::string(c.controller == lr::Controller::kSt7789 ? "st7789 " : "ili9341 ") +
         std::to_string(c.width) + "x" + std::to_string(c.height) + " rotation " +
         std::to_string(static_cast<int>(c.rotation) * 90);
}

size_t mismatches(const ImageRgb8& a, const ImageRgb8& b) {
  if (a.width != b.width || a.height != b.height) return ~size_t{0};
  size_t n = 0;
  for (size_t i = 0; i < a.rgb.size(); i += 3)
    n += a.rgb[i] != b.rgb[i] || a.rgb[i + 1] != b.rgb[i + 1] || a.rgb[i + 2] != b.rgb[i + 2];
  return n;
}

// The torus knot in gold on a blue-grey background (neither symmetric in red and blue nor
// unchanged by inversion), rendered at any size by one renderer with host storage.
class Scene {
 public:
  Scene() {
    lr::host::HostMesh mesh;
    std::string error;
    if (!lr::host::load_obj(std::string(LR_SOURCE_DIR) + "/tests/host/data/torus_knot.obj", mesh,
                            error))
      return;
    lr::host::SceneOptions o;
    o.fit = true;
    if (!lr::host::build_fixed_draws(mesh, o, draws_, error)) draws_.clear();
    for (lr::host::FixedDraw& d : draws_) d.material = lr::to_material(*lr::find_material("gold"));
  }
  bool loaded() const { return !draws_.empty(); }

  // Renders the knot turned by `angle` degrees about y into `sink`, at width x height.
  Status render(int width, int height, int angle, lr::StripSink<PF>& sink) {
    const size_t w = size_t(width), h = size_t(height);
    vertices_.resize(0xFFFF);
    triangles_.resize(0xFFFE);
    records_.resize(16);
    buckets_.resize((h + kRows - 1) / kRows);
    active_.resize(1024);
    active_index_.resize(2048);
    depth_.resize(w * kRows);
    renderer_ = std::make_unique<lr::Renderer<PF, kRows>>();
    Status s = renderer_->configure(
        {vertices_, triangles_, records_, buckets_, active_, active_index_, depth_}, width, height);
    if (s != Status::kOk) return s;
    lr::Camera cam;
    cam.eye = {Fixed{}, Fixed::from_double(0.4), Fixed::from_int(3)};
    if (!lr::perspective(Fixed::from_int(60), Fixed::ratio(width, height), Fixed::from_double(0.1),
                         Fixed::from_int(100), cam.projection) ||
        !lr::look_at(cam.eye, {}, {Fixed{}, Fixed::from_int(1), Fixed{}}, cam.view))
      return Status::kInvalidArgument;
    lr::LightSet lights;
    const Fixed one = Fixed::from_int(1);
    lights.lights[0] = lr::Light::directional({one, one, one}, {32768, 32768, 32768});
    lights.count = 1;
    renderer_->begin_frame(cam, lights, lr::Rgb8{40, 60, 90});
    const lr::Mat4 model = lr::rotate_y(Fixed::from_int(angle));
    for (const lr::host::FixedDraw& d : draws_) {
      s = renderer_->draw(d.mesh(), model, d.material, lr::DrawState{});
      if (s != Status::kOk) return s;
    }
    return renderer_->render(sink);
  }

  // The reference: the same frame into a capture display.
  ImageRgb8 capture(int width, int height, int angle) {
    lr::host::CaptureDisplay<PF> display(size_t(width) * kRows);
    const Status s = render(width, height, angle, display);
    EXPECT_EQ(s, Status::kOk) << display.error();
    return display.image();
  }

 private:
  std::vector<lr::host::FixedDraw> draws_;
  std::vector<lr::ScreenVertex> vertices_;
  std::vector<lr::BinnedTriangle> triangles_;
  std::vector<lr::DrawRecord> records_;
  std::vector<uint16_t> buckets_;
  std::vector<lr::ActiveTriangle> active_;
  std::vector<uint16_t> active_index_;
  std::vector<uint16_t> depth_;
  std::unique_ptr<lr::Renderer<PF, kRows>> renderer_;
};

// A module on the emulated wires with the driver and a skipping, double-buffered sink.
struct Rig {
  explicit Rig(const PanelConfig& cfg, bool deferred = true)
      : emulator(cfg),
        bus(emulator,
            [&] {
              EmulatorBus::Options o;
              o.deferred = deferred;
              o.log = false;
              return o;
            }()),
        panel(bus, cfg) {
    const size_t widest = 320;  // any rotation of any preset
    buffers[0].assign(widest * kRows, 0);
    buffers[1].assign(widest * kRows, 0);
    signatures.assign(320 / kRows, lr::StripSignature{});
    sink = std::make_unique<lr::PanelSink>(panel, buffers[0], buffers[1], signatures);
  }
  PanelEmulator emulator;
  EmulatorBus bus;
  lr::Panel panel;
  std::vector<uint16_t> buffers[2];
  std::vector<lr::StripSignature> signatures;
  std::unique_ptr<lr::PanelSink> sink;
};

std::vector<PanelConfig> every_module_and_rotation() {
  std::vector<PanelConfig> out;
  for (Rotation r : {Rotation::k0, Rotation::k90, Rotation::k180, Rotation::k270}) {
    out.push_back(lr::st7789_240x240(r));
    out.push_back(lr::st7789_240x320(r));
    out.push_back(lr::st7789_135x240(r));
    out.push_back(lr::ili9341_240x320(r));
    PanelConfig landscape = lr::ili9341_320x240();  // rotation 90 is its landscape default
    landscape.rotation = r;
    out.push_back(landscape);
  }
  return out;
}

TEST(PanelRoundTrip, EveryModuleAndRotationShowsTheCapturedFrame) {
  Scene scene;
  ASSERT_TRUE(scene.loaded());
  for (const PanelConfig& cfg : every_module_and_rotation()) {
    SCOPED_TRACE(name(cfg));
    const int w = cfg.image_width(), h = cfg.image_height();
    const uint32_t strips = uint32_t(h + kRows - 1) / kRows;
    Rig rig(cfg);
    ASSERT_EQ(rig.panel.init(), Status::kOk);
    // Angles: a first frame (everything sent), the same again (everything skipped), then the
    // knot turned a little (changed strips sent, narrowed to their changed columns).
    const int angles[] = {0, 0, 7, 30};
    for (size_t f = 0; f < 4; ++f) {
      const ImageRgb8 expected = scene.capture(w, h, angles[f]);
      const lr::host::BusTotals before = rig.bus.totals();
      ASSERT_EQ(scene.render(w, h, angles[f], *rig.sink), Status::kOk) << "frame " << f;
      if (f == 0) {
        ASSERT_EQ(rig.panel.backlight(true), Status::kOk);
      }
      const lr::host::BusTotals sent = rig.bus.totals() - before;
      const lr::PanelSinkStats& st = rig.sink->stats();
      EXPECT_EQ(mismatches(rig.emulator.image(), expected), 0u) << "frame " << f;
      EXPECT_EQ(sent.bytes, st.bytes()) << "frame " << f;
      EXPECT_EQ(sent.pixel_bytes, st.pixel_bytes) << "frame " << f;
      if (f == 0) {
        EXPECT_EQ(sent.pixel_bytes, uint64_t(w) * uint64_t(h) * 2);
        EXPECT_EQ(st.strips_sent, strips);
      }
      if (f == 1) {
        EXPECT_EQ(st.strips_skipped, strips);
        EXPECT_EQ(sent.bytes, 0u);
      }
      if (f >= 2) {
        EXPECT_GT(st.strips_sent, 0u);
        EXPECT_LT(sent.pixel_bytes, uint64_t(w) * uint64_t(h) * 2);
      }
    }
    EXPECT_EQ(rig.emulator.errors(), 0u) << rig.emulator.report();
    EXPECT_EQ(rig.emulator.count(lr::host::PanelIssue::kTiming), 0u);
    EXPECT_TRUE(rig.bus.misuse().empty()) << rig.bus.misuse().front();
    EXPECT_TRUE(rig.bus.backlight());
  }
}

TEST(PanelRoundTrip, SynchronousBusGivesTheSameImage) {
  Scene scene;
  ASSERT_TRUE(scene.loaded());
  const PanelConfig cfg = lr::st7789_135x240(Rotation::k90);
  Rig rig(cfg, /*deferred=*/false);
  ASSERT_EQ(rig.panel.init(), Status::kOk);
  ASSERT_EQ(scene.render(cfg.image_width(), cfg.image_height(), 15, *rig.sink), Status::kOk);
  EXPECT_EQ(
      mismatches(rig.emulator.image(), scene.capture(cfg.image_width(), cfg.image_height(), 15)),
      0u);
  EXPECT_EQ(rig.emulator.errors(), 0u) << rig.emulator.report();
}

TEST(PanelRoundTrip, RotatingALivePanelAndSleepKeepTheImageRight) {
  Scene scene;
  ASSERT_TRUE(scene.loaded());
  Rig rig(lr::st7789_240x240());
  ASSERT_EQ(rig.panel.init(), Status::kOk);
  for (Rotation r : {Rotation::k0, Rotation::k90, Rotation::k180, Rotation::k270, Rotation::k0}) {
    SCOPED_TRACE(int(r) * 90);
    ASSERT_EQ(rig.panel.set_rotation(r), Status::kOk);
    const int w = rig.panel.image_width(), h = rig.panel.image_height();
    ASSERT_EQ(scene.render(w, h, 20, *rig.sink), Status::kOk);
    EXPECT_EQ(rig.sink->stats().strips_skipped, 0u);  // a new mapping: everything sent again
    PanelConfig viewer = lr::st7789_240x240(r);
    EXPECT_EQ(mismatches(rig.emulator.image(viewer.rotation), scene.capture(w, h, 20)), 0u);
  }
  // Sleep: the glass goes dark, the RAM keeps the frame; awake, the same image without a resend.
  const ImageRgb8 before = rig.emulator.image(Rotation::k0);
  ASSERT_EQ(rig.panel.sleep(true), Status::kOk);
  EXPECT_EQ(mismatches(rig.emulator.image(Rotation::k0),
                       ImageRgb8{240, 240, std::vector<uint8_t>(240 * 240 * 3, 0)}),
            0u);
  ASSERT_EQ(rig.panel.sleep(false), Status::kOk);
  EXPECT_EQ(mismatches(rig.emulator.image(Rotation::k0), before), 0u);
  ASSERT_EQ(rig.panel.display_on(false), Status::kOk);
  EXPECT_EQ(rig.emulator.image(Rotation::k0).rgb, std::vector<uint8_t>(240 * 240 * 3, 0));
  ASSERT_EQ(rig.panel.display_on(true), Status::kOk);
  EXPECT_EQ(mismatches(rig.emulator.image(Rotation::k0), before), 0u);
  EXPECT_EQ(rig.emulator.errors(), 0u) << rig.emulator.report();
  EXPECT_TRUE(rig.bus.misuse().empty());
}

}  // namespace
