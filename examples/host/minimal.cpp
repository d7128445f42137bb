// A first frame: a lit gold octahedron, written to a PPM file (argv[1], or minimal.ppm).
#include <array>
#include <cstdio>
#include <lineraster/lineraster.hpp>  // the core: renderer, storage, camera, meshes

constexpr int kW = 160, kH = 120, kStrip = 8;
using lr::Fixed;
constexpr Fixed k1 = Fixed::from_int(1), k0{};
constexpr int16_t kN = 1 << lr::Normal16::kFracBits;  // 1.0 in Q1.14
constexpr std::array<lr::Vec3, 6> kPositions{
    {{k1, k0, k0}, {-k1, k0, k0}, {k0, k1, k0}, {k0, -k1, k0}, {k0, k0, k1}, {k0, k0, -k1}}};
constexpr std::array<lr::Normal16, 6> kNormals{
    {{kN, 0, 0}, {-kN, 0, 0}, {0, kN, 0}, {0, -kN, 0}, {0, 0, kN}, {0, 0, -kN}}};
constexpr std::array<std::array<uint16_t, 3>, 8> kTriangles{
    {{0, 2, 4}, {1, 4, 2}, {0, 4, 3}, {1, 3, 4}, {0, 5, 2}, {1, 2, 5}, {0, 3, 5}, {1, 5, 3}}};

// Writes the strips as they come (top to bottom, full width) into a binary PPM file.
struct PpmSink final : lr::StripSink<lr::Rgb888> {
  std::FILE* file = nullptr;
  std::array<lr::Rgb8, kW * kStrip> strip{};
  lr::Status begin_frame(uint16_t w, uint16_t h) override {
    return std::fprintf(file, "P6 %d %d 255\n", w, h) > 0 ? lr::Status::kOk : kError;
  }
  lr::Status acquire(lr::StripLease<lr::Rgb888>& out) override {
    out = lend(strip.data(), strip.size(), 0);
    return lr::Status::kOk;
  }
  lr::Status submit(const lr::StripRect& r, lr::StripLease<lr::Rgb888>&& lease) override {
    std::span<lr::Rgb8> px;
    take_back(lease, px);
    const size_t n = size_t{r.width} * r.height;  // an Rgb8 is the file's 3 bytes
    return std::fwrite(px.data(), 3, n, file) == n ? lr::Status::kOk : kError;
  }
  lr::Status end_frame() override { return lr::Status::kOk; }
  static constexpr lr::Status kError = lr::Status::kDisplayError;
};

// Width, height, strip height, vertices, triangles, draws, triangles active at once.
constexpr lr::FrameCapacities kCaps{kW, kH, kStrip, 64, 64, 1, 16};
static lr::StaticFrameStorage<kCaps> store;  // every store of the frame, sized by kCaps
static lr::Renderer<lr::Rgb888, kStrip> renderer;
static PpmSink sink;

int main(int argc, char** argv) {
  lr::Camera cam;
  cam.eye = {Fixed::from_double(1.5), Fixed::from_double(1.2), Fixed::from_int(3)};
  lr::perspective(Fixed::from_int(45), Fixed::ratio(kW, kH), Fixed::from_double(0.5),
                  Fixed::from_int(20), cam.projection);
  lr::look_at(cam.eye, {}, {k0, k1, k0}, cam.view);
  const lr::LightSet lights{{lr::Light::directional({k1, k1, k1}, {32768, 32768, 32768})}, 1};
  renderer.configure(store.storage(), kW, kH);
  renderer.begin_frame(cam, lights, lr::Rgb8{16, 24, 48});
  renderer.draw(lr::Mesh{kPositions, kNormals, {}, {}, kTriangles},
                lr::rotate_y(Fixed::from_int(25)), lr::to_material(*lr::find_material("gold")),
                lr::DrawState{});
  if (!(sink.file = std::fopen(argc > 1 ? argv[1] : "minimal.ppm", "wb"))) return 1;
  const lr::Status st = renderer.render(sink);
  return std::fclose(sink.file) == 0 && st == lr::Status::kOk ? 0 : 1;
}
