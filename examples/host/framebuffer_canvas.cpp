// A lit cube rendered into a 16-bit canvas, as an Adafruit_GFX GFXcanvas16 (getBuffer()) or an
// LVGL canvas (LV_COLOR_FORMAT_RGB565) holds one: native-endian RGB565, rows packed. The 3D
// viewport is a 160x120 window at (20, 15) of the 200x150 canvas; the rest is what the GUI drew.
// The canvas is then written to a PPM file (argv[1], or framebuffer_canvas.ppm). See
// docs/framebuffer.md.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <lineraster/lineraster.hpp>
#include <span>

constexpr int kCanvasW = 200, kCanvasH = 150;  // the canvas, pixels
constexpr int kX = 20, kY = 15;                // where the 3D viewport goes in it
constexpr int kW = 160, kH = 120, kStrip = 8;  // the viewport, and the renderer's strip height
using lr::Fixed;

// The cube: 6 faces of 4 vertices, each face with its normal n and two edges u x v = n, so that
// every face is counter-clockwise seen from outside (culling keeps it when it faces the camera).
struct Cube {
  std::array<lr::Vec3, 24> positions{};
  std::array<lr::Normal16, 24> normals{};
  std::array<std::array<uint16_t, 3>, 12> triangles{};
};
constexpr Cube make_cube() {
  constexpr int kFaces[6][3][3] = {
      {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
      {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}}};
  constexpr int kCorner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};  // (u, v) around the face
  Cube c;
  for (size_t f = 0; f < 6; ++f) {
    const auto& [n, u, v] = kFaces[f];
    for (size_t k = 0; k < 4; ++k) {
      int p[3];
      for (int a = 0; a < 3; ++a) p[a] = n[a] + kCorner[k][0] * u[a] + kCorner[k][1] * v[a];
      c.positions[4 * f + k] = {Fixed::from_int(p[0]), Fixed::from_int(p[1]),
                                Fixed::from_int(p[2])};
      constexpr int kOne = 1 << lr::Normal16::kFracBits;  // 1.0 in Q1.14
      c.normals[4 * f + k] = {static_cast<int16_t>(n[0] * kOne), static_cast<int16_t>(n[1] * kOne),
                              static_cast<int16_t>(n[2] * kOne)};
    }
    const auto b = static_cast<uint16_t>(4 * f);
    c.triangles[2 * f] = {b, static_cast<uint16_t>(b + 1), static_cast<uint16_t>(b + 2)};
    c.triangles[2 * f + 1] = {b, static_cast<uint16_t>(b + 2), static_cast<uint16_t>(b + 3)};
  }
  return c;
}
constexpr Cube kCube = make_cube();

// The canvas (what GFXcanvas16::getBuffer() returns), and the strip the renderer draws in before
// each strip is copied into its place (the viewport is narrower than the canvas's rows).
static std::array<uint16_t, kCanvasW * kCanvasH> canvas;
static std::array<uint16_t, kW * kStrip> strip_pixels;

// The stores; strip_skipping: a strip whose inputs did not change is left as the canvas holds it.
constexpr lr::FrameCapacities kCaps{.width = kW,
                                    .height = kH,
                                    .strip_height = kStrip,
                                    .vertices = 64,
                                    .triangles = 64,
                                    .draws = 1,
                                    .active = 16,
                                    .strip_skipping = true};
static lr::StaticFrameStorage<kCaps> store;
static lr::Renderer<lr::Rgb565, kStrip> renderer;

int main(int argc, char** argv) {
  std::fill(canvas.begin(), canvas.end(), lr::Rgb565::encode({200, 200, 200}));  // the GUI
  // readme:begin framebuffer
  // The canvas as bytes, its stride in bytes (rows packed: width x 2), its size in pixels.
  const lr::FrameBuffer frame{std::as_writable_bytes(std::span(canvas)),
                              kCanvasW * sizeof(uint16_t), kCanvasW, kCanvasH};
  // The renderer's viewport goes at (kX, kY) of it; strips are drawn in strip_pixels, then copied.
  lr::FrameBufferSink<lr::Rgb565> sink(frame, strip_pixels, kX, kY);
  // readme:end framebuffer

  lr::Camera cam;
  cam.eye = {Fixed::from_double(2.5), Fixed::from_int(2), Fixed::from_double(3.5)};
  lr::perspective(Fixed::from_int(45), Fixed::ratio(kW, kH), Fixed::from_double(0.5),
                  Fixed::from_int(20), cam.projection);
  lr::look_at(cam.eye, {}, {{}, Fixed::from_int(1), {}}, cam.view);
  const lr::LightSet lights{
      {lr::Light::directional({Fixed::from_int(1), Fixed::from_int(3), Fixed::from_int(2)},
                              {32768, 32768, 32768})},
      1};
  lr::Material teal;
  teal.diffuse = {lr::c15_from_micro(200000), lr::c15_from_micro(600000),
                  lr::c15_from_micro(700000)};
  teal.specular = {16384, 16384, 16384};
  teal.shininess_q8 = 32 * 256;
  lr::DrawState state;
  state.cull = lr::Cull::kBack;

  if (renderer.configure(store.storage(), kW, kH) != lr::Status::kOk) return 1;
  // Two frames of the same scene: the second keeps every strip (nothing is drawn or copied).
  for (int frame_index = 0; frame_index < 2; ++frame_index) {
    renderer.begin_frame(cam, lights, lr::Rgb8{16, 24, 48});
    renderer.draw(lr::Mesh{kCube.positions, kCube.normals, {}, {}, kCube.triangles},
                  lr::rotate_y(Fixed::from_int(-15)) * lr::scale(Fixed::from_double(0.8)), teal,
                  state);
    if (const lr::Status st = renderer.render(sink); st != lr::Status::kOk) {
      std::fprintf(stderr, "framebuffer_canvas: %s\n", lr::to_string(st));
      return 1;
    }
    std::printf("frame %d: %u strips drawn, %u kept, %u bytes copied\n", frame_index,
                unsigned{sink.stats().strips_drawn}, unsigned{sink.stats().strips_kept},
                unsigned{sink.stats().bytes_copied});
  }

  std::FILE* file = std::fopen(argc > 1 ? argv[1] : "framebuffer_canvas.ppm", "wb");
  if (!file) return 1;
  std::fprintf(file, "P6 %d %d 255\n", kCanvasW, kCanvasH);
  for (const uint16_t px : canvas) {
    const lr::Rgb8 c = lr::Rgb565::decode(px);
    const uint8_t rgb[3] = {c.r, c.g, c.b};
    std::fwrite(rgb, 1, 3, file);
  }
  return std::fclose(file) == 0 ? 0 : 1;
}
