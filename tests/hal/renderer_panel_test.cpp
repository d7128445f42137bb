// The renderer into a panel: lr::Renderer drives a PanelSink over a recording bus (an ILI9341
// 320x240 module, rotation 90, whose glass is mirrored), and the image the module would show
// equals the capture display's frame of the same scene, frame after frame, while unchanged
// strips are skipped and moved ones narrowed.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <vector>

#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/hal/panel_sink.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"
#include "tests/hal/recording_bus.hpp"

namespace lr {
namespace {

using PF = Rgb565Be;
constexpr int kWidth = 320, kHeight = 240, kRows = 8;
constexpr size_t kStrips = (kHeight + kRows - 1) / kRows;

// A regular octahedron with smooth normals (the smoke firmware's scene).
const Fixed kR = Fixed::from_double(1.0);
const Fixed k0 = Fixed::from_int(0);
constexpr int16_t kN1 = 1 << Normal16::kFracBits;
const std::array<Vec3, 6> kPositions = {
    {{kR, k0, k0}, {-kR, k0, k0}, {k0, kR, k0}, {k0, -kR, k0}, {k0, k0, kR}, {k0, k0, -kR}}};
const std::array<Normal16, 6> kNormals = {
    {{kN1, 0, 0}, {-kN1, 0, 0}, {0, kN1, 0}, {0, -kN1, 0}, {0, 0, kN1}, {0, 0, -kN1}}};
const std::array<std::array<uint16_t, 3>, 8> kTriangles = {
    {{0, 2, 4}, {1, 4, 2}, {0, 4, 3}, {1, 3, 4}, {0, 5, 2}, {1, 2, 5}, {0, 3, 5}, {1, 5, 3}}};

class Scene {
 public:
  // skip: strip input signatures, so that strips with unchanged inputs are not rendered.
  explicit Scene(bool skip = false)
      : store_(FrameCapacities{.width = kWidth,
                               .height = kHeight,
                               .strip_height = kRows,
                               .vertices = 256,
                               .triangles = 256,
                               .draws = 4,
                               .active = 64,
                               .tex_vertices = 256,
                               .active_extra = 64,
                               .triangle_colors = 256,
                               .strip_skipping = skip}),
        renderer_(std::make_unique<Renderer<PF, kRows, kUntexturedSpans>>()) {
    configured_ = renderer_->configure(store_.storage(), kWidth, kHeight);
  }
  Status configured() const { return configured_; }
  const FrameStats& stats() const { return renderer_->stats(); }

  // The octahedron turned by `angle` degrees about y and moved by dx along x (both Q16.16).
  Status render(StripSink<PF>& sink, Fixed angle, Fixed dx) {
    Camera cam;
    cam.eye = {Fixed::from_double(0.0), Fixed::from_double(1.0), Fixed::from_double(4.0)};
    if (!perspective(Fixed::from_int(50), Fixed::ratio(kWidth, kHeight), Fixed::from_double(0.5),
                     Fixed::from_int(20), cam.projection) ||
        !look_at(cam.eye, {}, {k0, Fixed::from_int(1), k0}, cam.view))
      return Status::kInvalidArgument;
    LightSet lights;
    lights.lights[0].position = {Fixed::from_double(0.4), Fixed::from_double(0.8),
                                 Fixed::from_double(0.6)};
    lights.count = 1;
    lights.global_ambient = {6554, 6554, 6554};
    Status st = renderer_->begin_frame(cam, lights, Rgb8{16, 24, 48});
    if (st != Status::kOk) return st;
    DrawState state;
    state.shading = Shading::kGouraud;
    const Mat4 model =
        translate({dx, k0, k0}) * rotate_y(angle) * rotate_x(Fixed::from_double(-15.0));
    const Mesh mesh{kPositions, kNormals, {}, {}, kTriangles};
    st = renderer_->draw(mesh, model, to_material(*find_material("gold")), state);
    if (st != Status::kOk) return st;
    return renderer_->render(sink);
  }

 private:
  BasicFrameStorage<std::vector> store_;
  std::unique_ptr<Renderer<PF, kRows, kUntexturedSpans>> renderer_;
  Status configured_ = Status::kInvalidArgument;
};

// The module on a recording bus behind a PanelSink, and a capture display for the frame it
// must show.
struct PanelRig {
  PanelRig()
      : panel(bus, ili9341_320x240()),
        b0(size_t{kWidth} * kRows),
        b1(size_t{kWidth} * kRows),
        signatures(kStrips),
        sink(panel, b0, b1, signatures, 100),
        capture(size_t{kWidth} * kRows) {}
  // The module shows the capture display's frame, and the bus saw nothing a panel forbids.
  void expect_same() const {
    const std::vector<uint16_t> shown = test::view(bus.ram, panel.config());
    const std::vector<PF::Storage>& want = capture.raw_frame();
    ASSERT_EQ(shown.size(), want.size());
    size_t wrong = 0;
    for (size_t i = 0; i < shown.size(); ++i) wrong += shown[i] != PF::to_value(want[i]);
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(bus.ram.errors(), 0);
    EXPECT_TRUE(bus.violations.empty());
  }
  test::RecordingBus bus;
  Panel panel;
  std::vector<PF::Storage> b0, b1;
  std::vector<StripSignature> signatures;
  PanelSink sink;
  host::CaptureDisplay<PF> capture;
};

TEST(RendererToPanel, TheModuleShowsTheRenderedFrameAndSkipsWhatDidNotChange) {
  PanelRig rig;
  Panel& panel = rig.panel;
  PanelSink& sink = rig.sink;
  host::CaptureDisplay<PF>& capture = rig.capture;
  ASSERT_EQ(panel.init(), Status::kOk);
  Scene scene;
  ASSERT_EQ(scene.configured(), Status::kOk);
  auto expect_same = [&rig]() { rig.expect_same(); };
  const uint32_t full = uint32_t{kWidth} * kHeight * 2;

  const Fixed a25 = Fixed::from_int(25), a40 = Fixed::from_int(40);
  const Fixed still = Fixed::from_int(0), moved = Fixed::from_double(0.05);
  ASSERT_EQ(scene.render(sink, a25, still), Status::kOk);
  ASSERT_EQ(scene.render(capture, a25, still), Status::kOk);
  EXPECT_EQ(sink.stats().pixel_bytes, full);
  expect_same();

  ASSERT_EQ(scene.render(sink, a25, still), Status::kOk);  // the same frame again
  EXPECT_EQ(sink.stats().bytes(), 0u);
  EXPECT_EQ(sink.stats().strips_skipped, kStrips);

  ASSERT_EQ(scene.render(sink, a25, moved), Status::kOk);  // moved a few pixels
  ASSERT_EQ(scene.render(capture, a25, moved), Status::kOk);
  EXPECT_GT(sink.stats().strips_skipped, 0u);
  EXPECT_GT(sink.stats().strips_narrowed, 0u);
  EXPECT_LT(sink.stats().pixel_bytes, full / 2);
  expect_same();

  ASSERT_EQ(scene.render(sink, a40, moved), Status::kOk);  // turned
  ASSERT_EQ(scene.render(capture, a40, moved), Status::kOk);
  expect_same();
}

// With strip input signatures the renderer does not even render the strips whose inputs did not
// change; the sink keeps them (sends nothing), and the module still shows the right frame.
TEST(RendererToPanel, StripsWithUnchangedInputsAreNeitherRenderedNorSent) {
  PanelRig rig;
  Panel& panel = rig.panel;
  PanelSink& sink = rig.sink;
  host::CaptureDisplay<PF>& capture = rig.capture;
  ASSERT_EQ(panel.init(), Status::kOk);
  Scene scene(true), reference;
  ASSERT_EQ(scene.configured(), Status::kOk);
  auto expect_same = [&rig]() { rig.expect_same(); };
  const Fixed a25 = Fixed::from_int(25), still = Fixed::from_int(0);
  const Fixed moved = Fixed::from_double(0.05);

  ASSERT_EQ(scene.render(sink, a25, still), Status::kOk);
  EXPECT_EQ(scene.stats().strips_skipped, 0u);
  ASSERT_EQ(scene.render(sink, a25, still), Status::kOk);  // the same inputs
  EXPECT_EQ(scene.stats().strips_skipped, kStrips);
  EXPECT_EQ(scene.stats().triangles_set_up, 0u);
  EXPECT_EQ(sink.stats().strips_kept, kStrips);
  EXPECT_EQ(sink.stats().bytes(), 0u);

  ASSERT_EQ(scene.render(sink, a25, moved), Status::kOk);
  ASSERT_EQ(reference.render(capture, a25, moved), Status::kOk);
  const uint32_t skipped = scene.stats().strips_skipped;
  EXPECT_GT(skipped, 0u);
  EXPECT_LT(skipped, kStrips);
  EXPECT_EQ(sink.stats().strips_kept, skipped);
  EXPECT_EQ(sink.stats().strips_kept + sink.stats().strips_sent + sink.stats().strips_skipped,
            kStrips);
  expect_same();

  // After init() the module's RAM is unknown: the sink retains nothing, every strip is rendered.
  ASSERT_EQ(panel.init(), Status::kOk);
  ASSERT_EQ(scene.render(sink, a25, moved), Status::kOk);
  EXPECT_EQ(scene.stats().strips_skipped, 0u);
  EXPECT_EQ(sink.stats().strips_kept, 0u);
  expect_same();
}

}  // namespace
}  // namespace lr
