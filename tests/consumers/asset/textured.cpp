// A header made by the installed lineraster-asset, rendered with lr::core: a square of two
// materials, the left half textured with checker.png, the right half with tiles64.png (each its
// material's map_Kd), seen head-on, each texel as it is (nearest, GL_REPLACE), written to a PPM
// file (argv[1]) for tests/consumers/check_textured.py.
#include <array>
#include <cstdio>
#include <lineraster/lineraster.hpp>

#include "two_textures.hpp"

namespace {

constexpr int kW = 240, kH = 240, kStrip = 8;

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
    const size_t n = size_t{r.width} * r.height;
    return std::fwrite(px.data(), 3, n, file) == n ? lr::Status::kOk : kError;
  }
  lr::Status end_frame() override { return lr::Status::kOk; }
  static constexpr lr::Status kError = lr::Status::kDisplayError;
};

// Textured draws need the TexVertex and ActiveExtra stores besides the usual ones.
constexpr lr::FrameCapacities kCaps{.width = kW,
                                    .height = kH,
                                    .strip_height = kStrip,
                                    .vertices = 64,
                                    .triangles = 64,
                                    .draws = two_textures::draw_count,
                                    .active = 16,
                                    .tex_vertices = 64,
                                    .active_extra = 16};
lr::StaticFrameStorage<kCaps> store;
lr::Renderer<lr::Rgb888, kStrip> renderer;
PpmSink sink;

}  // namespace

int main(int argc, char** argv) {
  using lr::Fixed;
  // The square spans [-1, 1]^2 at z = 0; from z = 2 with a 60 degree field of view its edges
  // fall at 120 +- 120 / (2 tan 30) = 16.08 and 223.92 (check_textured.py has the same numbers).
  lr::Camera cam;
  cam.eye = {Fixed{}, Fixed{}, Fixed::from_int(2)};
  lr::perspective(Fixed::from_int(60), Fixed::from_int(1), Fixed::ratio(1, 2), Fixed::from_int(10),
                  cam.projection);
  lr::look_at(cam.eye, {}, {Fixed{}, Fixed::from_int(1), Fixed{}}, cam.view);
  if (renderer.configure(store.storage(), kW, kH) != lr::Status::kOk ||
      renderer.begin_frame(cam, lr::LightSet{}, lr::Rgb8{16, 24, 48}) != lr::Status::kOk)
    return 1;
  for (std::size_t i = 0; i < two_textures::draw_count; ++i) {
    lr::DrawState st;
    st.lighting = false;
    st.texture = two_textures::draw_textures[i];
    st.sampler.filter = lr::Filter::kNearest;
    st.sampler.env = lr::TexEnv::kReplace;
    const lr::Status s = renderer.draw(two_textures::meshes[i], lr::Mat4::identity(),
                                       two_textures::materials[i], st);
    if (s != lr::Status::kOk) {
      std::fprintf(stderr, "textured: draw %zu: %s\n", i, lr::to_string(s));
      return 1;
    }
  }
  if (!(sink.file = std::fopen(argc > 1 ? argv[1] : "textured.ppm", "wb"))) return 1;
  const lr::Status st = renderer.render(sink);
  return std::fclose(sink.file) == 0 && st == lr::Status::kOk ? 0 : 1;
}
