// lr::hal from an installed package: a red triangle rendered in RGB565 through lr::PanelSink to
// an ST7789 240x240 module mounted upside down (lr::Panel, rotation 180), over a PanelBus that
// records what would go on the wire. The bytes are checked against the ST7789 datasheet's
// commands: the start-up sequence, the first strip's address window (at 180 degrees the visible
// 240 rows are the last of the RAM's 320: RASET from 80), its pixels in wire order, and a second
// identical frame that sends no pixels (each strip's signature matches).
// Prints what it found; exits 1 on the first difference.
#include <array>
#include <cstdint>
#include <cstdio>
#include <lineraster/hal/panel.hpp>
#include <lineraster/hal/panel_sink.hpp>
#include <lineraster/lineraster.hpp>
#include <span>
#include <vector>

namespace {

constexpr int kW = 240, kH = 240, kStrip = 8, kStrips = kH / kStrip;

// One command (D/C low) with its parameters, as the bus saw it.
struct Command {
  uint8_t cmd = 0;
  std::vector<uint8_t> params;
};

// Records commands, pixel transfers and the reset line; every transfer completes at once.
class RecordingBus final : public lr::PanelBus {
 public:
  std::vector<Command> commands;
  std::vector<std::vector<uint8_t>> transfers;
  std::vector<bool> reset_line;  // each set_reset(asserted)

  lr::Status command(uint8_t cmd, std::span<const uint8_t> params) override {
    commands.push_back({cmd, {params.begin(), params.end()}});
    return lr::Status::kOk;
  }
  lr::Status start_pixels(std::span<const uint8_t> pixels) override {
    transfers.emplace_back(pixels.begin(), pixels.end());
    return lr::Status::kOk;
  }
  lr::Status wait(uint32_t) override { return lr::Status::kOk; }
  lr::Status set_reset(bool asserted) override {
    reset_line.push_back(asserted);
    return lr::Status::kOk;
  }
  lr::Status set_backlight(bool) override { return lr::Status::kOk; }
  void delay_ms(uint32_t) override {}
};

using lr::Fixed;
constexpr Fixed k0{}, kHalf = Fixed::ratio(1, 2);
constexpr std::array<lr::Vec3, 3> kPositions{
    {{-kHalf, -kHalf, k0}, {kHalf, -kHalf, k0}, {k0, kHalf, k0}}};
constexpr std::array<std::array<uint16_t, 3>, 1> kTriangles{{{0, 1, 2}}};
constexpr lr::Material kRed{{}, {lr::Color15::kOne, 0, 0}, {}, {}, 0};  // Kd = (1, 0, 0)

constexpr lr::FrameCapacities kCaps{kW, kH, kStrip, 16, 8, 1, 4};
lr::StaticFrameStorage<kCaps> store;
lr::Renderer<lr::Rgb565Be, kStrip> renderer;
std::array<lr::Rgb565Be::Storage, kW * kStrip> strip0, strip1;  // wire order
std::array<lr::StripSignature, kStrips> signatures;

int failures = 0;
void expect(bool ok, const char* what) {
  std::printf("%s: %s\n", ok ? "ok  " : "FAIL", what);
  failures += ok ? 0 : 1;
}
bool is(const Command& c, uint8_t cmd, std::vector<uint8_t> params) {
  return c.cmd == cmd && c.params == params;
}

lr::Status frame(lr::PanelSink& sink) {
  lr::Camera cam;
  cam.eye = {k0, k0, Fixed::from_int(3)};
  lr::perspective(Fixed::from_int(45), Fixed::from_int(1), Fixed::ratio(1, 2), Fixed::from_int(10),
                  cam.projection);
  lr::look_at(cam.eye, {}, {k0, Fixed::from_int(1), k0}, cam.view);
  lr::DrawState unlit;
  unlit.lighting = false;  // the material's Kd as it is
  if (renderer.begin_frame(cam, lr::LightSet{}, lr::Rgb8{16, 24, 48}) != lr::Status::kOk ||
      renderer.draw(lr::Mesh{kPositions, {}, {}, {}, kTriangles}, lr::Mat4::identity(), kRed,
                    unlit) != lr::Status::kOk)
    return lr::Status::kInvalidArgument;
  return renderer.render(sink);
}

}  // namespace

int main() {
  RecordingBus bus;
  lr::Panel panel(bus, lr::st7789_240x240(lr::Rotation::k180));
  lr::PanelSink sink(panel, strip0, strip1, signatures);
  expect(panel.init() == lr::Status::kOk, "Panel::init");
  expect(bus.reset_line == std::vector<bool>{true, false}, "reset line asserted, then released");
  // SWRESET, SLPOUT, COLMOD 16 bits, MADCTL MX|MY (180 degrees), INVON (the module's glass is
  // inverted), NORON, DISPON.
  const std::vector<Command> start{{0x01, {}}, {0x11, {}}, {0x3A, {0x55}}, {0x36, {0xC0}},
                                   {0x21, {}}, {0x13, {}}, {0x29, {}}};
  bool same = bus.commands.size() == start.size();
  for (size_t i = 0; same && i < start.size(); ++i)
    same = is(bus.commands[i], start[i].cmd, start[i].params);
  expect(same, "start-up: 01, 11, 3A 55, 36 C0, 21, 13, 29");

  expect(renderer.configure(store.storage(), kW, kH) == lr::Status::kOk, "Renderer::configure");
  bus.commands.clear();
  expect(frame(sink) == lr::Status::kOk, "frame 1 rendered into the panel sink");
  // Each strip: CASET, RASET, RAMWR and one transfer of its 240 x 8 pixels.
  expect(bus.commands.size() == 3 * kStrips && bus.transfers.size() == kStrips,
         "frame 1: 30 strips, 3 commands and one transfer each");
  expect(bus.commands.size() >= 3 && is(bus.commands[0], 0x2A, {0, 0, 0, 239}) &&
             is(bus.commands[1], 0x2B, {0, 80, 0, 87}) && is(bus.commands[2], 0x2C, {}),
         "first strip: CASET 0..239, RASET 80..87, RAMWR");
  expect(sink.stats().pixel_bytes == kW * kH * 2, "frame 1: 115200 pixel bytes");
  if (bus.transfers.size() == kStrips) {
    const std::vector<uint8_t>& top = bus.transfers[0];
    const std::vector<uint8_t>& middle = bus.transfers[kStrips / 2];  // rows 120..127
    expect(top.size() == kW * kStrip * 2 && top[0] == 0x10 && top[1] == 0xC6,
           "pixel (0, 0): the clear colour (16, 24, 48) as RGB565 0x10C6, high byte first");
    expect(middle[2 * 120] == 0xF8 && middle[2 * 120 + 1] == 0x00,
           "pixel (120, 120): the triangle's red, RGB565 0xF800");
  }

  bus.commands.clear();
  bus.transfers.clear();
  expect(frame(sink) == lr::Status::kOk, "frame 2 (the same picture)");
  expect(bus.transfers.empty() && sink.stats().strips_skipped == kStrips,
         "frame 2: every strip unchanged, no pixels sent");
  std::printf("panel_bytes: %s\n", failures == 0 ? "the panel got the expected bytes" : "FAILED");
  return failures == 0 ? 0 : 1;
}
