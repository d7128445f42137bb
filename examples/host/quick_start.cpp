// Quick start: a lit cube in a material of its own, back faces culled, turned about y by DEGREES
// (given at run time), written to a PPM file.   Usage: quick_start [OUT.ppm] [DEGREES -360..360]
#include <cstdio>
#include <cstdlib>
#include <lineraster/lineraster.hpp>  // the core: renderer, storage, camera, meshes, sinks

using lr::Fixed;  // Q16.16; from_int(n) and ratio(n, d) at run time, from_double at compile time
constexpr int kW = 160, kH = 120;
constexpr Fixed P = Fixed::from_int(1), N = -P;
// Corner i: x = P if bit 0 of i is set, y bit 1, z bit 2. Triangles counter-clockwise from outside.
constexpr lr::Vec3 kCorners[] = {{N, N, N}, {P, N, N}, {N, P, N}, {P, P, N},
                                 {N, N, P}, {P, N, P}, {N, P, P}, {P, P, P}};
constexpr std::array<uint16_t, 3> kTriangles[] = {{1, 3, 7}, {1, 7, 5}, {2, 0, 4}, {2, 4, 6},
                                                  {2, 6, 7}, {2, 7, 3}, {4, 0, 1}, {4, 1, 5},
                                                  {4, 5, 7}, {4, 7, 6}, {1, 0, 2}, {1, 2, 3}};
constexpr lr::Material kTeal{.ambient = {0, 6554, 6554},  // GL's: Q1.15 colours, Q8.8 shininess
                             .diffuse = {3277, 19661, 21299},
                             .specular = {16384, 16384, 16384},
                             .shininess_q8 = 40 << 8};
constexpr lr::FrameCapacities kCaps{
    .width = kW, .height = kH, .vertices = 8, .triangles = 12, .active = 12, .triangle_colors = 12};
static lr::StaticFrameStorage<kCaps> store;  // all stores (flat shading needs triangle_colors)
static lr::Renderer<lr::Rgb888, kCaps.strip_height> renderer;
static lr::Rgb8 image[kW * kH];  // the frame, rows kW pixels apart: any frame buffer will do

int main(int argc, char** argv) {
  char* end = nullptr;
  const long deg = argc > 2 ? std::strtol(argv[2], &end, 10) : 20;
  if (argc > 2 && (end == argv[2] || *end != '\0' || deg < -360 || deg > 360))
    return std::fputs("quick_start: DEGREES must be an integer in -360..360\n", stderr), 2;
  lr::Camera cam{.eye = {Fixed::from_int(3), Fixed::from_int(2), Fixed::from_int(4)}};
  lr::perspective(Fixed::from_int(45), Fixed::ratio(kW, kH), Fixed::ratio(1, 2),
                  Fixed::from_int(20), cam.projection);
  lr::look_at(cam.eye, {}, {{}, P, {}}, cam.view);
  const lr::Vec3 to_light{P, Fixed::from_int(3), Fixed::from_int(2)};  // a white light
  renderer.configure(store.storage(), kW, kH);
  renderer.begin_frame(cam, {{lr::Light::directional(to_light, {32768, 32768, 32768})}, 1},
                       lr::Rgb8{16, 24, 48});
  const lr::Mesh cube{kCorners, {}, {}, {}, kTriangles};  // positions, normals, colours, uvs
  renderer.draw(cube, lr::rotate_y(Fixed::from_int(int32_t(deg))), kTeal,
                {.shading = lr::Shading::kFlat, .cull = lr::Cull::kBack});  // default: no culling
  lr::FrameBufferSink<lr::Rgb888> sink({std::as_writable_bytes(std::span(image)), kW * 3, kW, kH});
  const lr::Status st = renderer.render(sink);  // not kOk when the draw was refused, too
  std::printf("quick_start: %ld degrees, %u culled, %u pixels\n", deg,
              renderer.stats().culled_backface, renderer.stats().pixels_written);
  std::FILE* f = std::fopen(argc > 1 ? argv[1] : "cube.ppm", "wb");
  const bool written = f && std::fprintf(f, "P6 %d %d 255\n", kW, kH) > 0 &&
                       std::fwrite(image, sizeof image, 1, f) == 1;
  return (f && std::fclose(f) == 0 && written && st == lr::Status::kOk) ? 0 : 1;
}
