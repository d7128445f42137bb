// Strips on an SPI panel: three frames of a triangle go strip by strip through lr::PanelSink to
// an ST7789 240x240 module, double-buffered, unchanged strips skipped. CountingBus stands in for
// a board's lr::PanelBus: it counts the bytes where a board drives its pins and SPI (or DMA).
// Prints what each frame sent.   Usage: panel
#include <array>
#include <cstdio>
#include <lineraster/hal/panel.hpp>
#include <lineraster/hal/panel_sink.hpp>
#include <lineraster/lineraster.hpp>

using lr::Fixed;
constexpr int kSize = 240, kStrip = 8;

// What a board implements (hal/panel_bus.hpp); this one counts the bytes a board would send.
struct CountingBus final : lr::PanelBus {
  size_t bytes = 0;
  lr::Status command(uint8_t, std::span<const uint8_t> params) override {
    bytes += 1 + params.size();  // the command byte with D/C low, its parameters with D/C high
    return lr::Status::kOk;
  }
  lr::Status start_pixels(std::span<const uint8_t> pixels) override {
    bytes += pixels.size();  // a board starts the DMA here and returns ...
    return lr::Status::kOk;
  }
  lr::Status wait(uint32_t /*timeout_ms*/) override { return lr::Status::kOk; }  // ... waits here
  lr::Status set_reset(bool) override { return lr::Status::kOk; }
  lr::Status set_backlight(bool) override { return lr::Status::kOk; }
  void delay_ms(uint32_t) override {}
};

constexpr Fixed P = Fixed::from_int(1), N = -P;
constexpr std::array<lr::Vec3, 3> kCorners{{{N, N, {}}, {P, N, {}}, {{}, P, {}}}};
constexpr std::array<lr::Rgb8, 3> kColors{{{255, 64, 0}, {0, 255, 64}, {64, 0, 255}}};
constexpr std::array<std::array<uint16_t, 3>, 1> kTriangle{{{0, 1, 2}}};
constexpr lr::FrameCapacities kCaps{.width = kSize,
                                    .height = kSize,
                                    .strip_height = kStrip,
                                    .vertices = 8,
                                    .triangles = 4,
                                    .active = 4};
static lr::StaticFrameStorage<kCaps> store;
static lr::Renderer<lr::Rgb565Be, kStrip> renderer;  // big-endian RGB565: the SPI wire's order
static CountingBus bus;
static lr::Camera camera;

// One frame's scene: the triangle turned `degrees` about z, unlit (its vertex colours).
void draw_triangle(int degrees) {
  bus.bytes = 0;  // count this frame's bytes only
  lr::DrawState unlit;
  unlit.lighting = false;
  renderer.begin_frame(camera, lr::LightSet{}, lr::Rgb8{16, 24, 48});
  renderer.draw(lr::Mesh{kCorners, {}, kColors, {}, kTriangle},
                lr::rotate_z(Fixed::from_int(degrees)), lr::Material{}, unlit);
}

// Prints what the frame sent: the bus's bytes, the sink's strip counts.
void report(const lr::PanelSinkStats& s) {
  static int frame = 0;
  std::printf("panel: frame %d: %zu bytes, %u strips sent, %u narrowed, %u skipped\n", frame++,
              bus.bytes, s.strips_sent, s.strips_narrowed, s.strips_skipped);
}

int main() {
  camera.eye = {{}, {}, Fixed::from_int(3)};
  lr::perspective(Fixed::from_int(60), P, Fixed::ratio(1, 2), Fixed::from_int(20),
                  camera.projection);
  lr::look_at(camera.eye, {}, {{}, P, {}}, camera.view);
  if (renderer.configure(store.storage(), kSize, kSize) != lr::Status::kOk) return 1;
  // readme:begin panel
  lr::Panel panel(bus, lr::st7789_240x240(lr::Rotation::k90));  // the module: chosen here
  if (panel.init(/*hardware_reset=*/true) != lr::Status::kOk) return 1;
  static std::array<lr::Rgb565Be::Storage, kSize * kStrip> strip_a, strip_b;  // double buffering
  static std::array<lr::StripSignature, kSize / kStrip> signatures;  // optional: skip unchanged
  lr::PanelSink sink(panel, strip_a, strip_b, signatures, /*timeout_ms=*/250);
  for (int degrees : {0, 0, 10}) {                           // the second frame repeats the first
    draw_triangle(degrees);                                  // begin_frame, draw
    if (renderer.render(sink) != lr::Status::kOk) return 1;  // strip n on the wire as n+1 renders
    panel.backlight(true);  // on once a frame is there: never shows garbage
    report(sink.stats());   // this frame's strips: sent, narrowed to their changed columns, skipped
  }
  // readme:end panel
  return 0;
}
