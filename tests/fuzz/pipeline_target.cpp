// Fuzz target: the whole pipeline, from mesh bytes to strips (see fuzz_targets.hpp).
//
// Input layout (missing bytes read as 0):
//   header, 16 bytes:
//     0  width - 1 (mod 128)            1  height - 1 (mod 128)
//     2  bits 0-1 strip height {1, 8, 32}[v % 3]; bit 2 RGB888 (else RGB565 big-endian);
//        bit 3 depth sink; bit 4 small stores (capacities from bytes 13-14); bit 5 point lights
//        (attenuation read after each light's colours); bit 6 the texture is (also) the
//        environment map; bit 7 the texture is (also) the normal map (tangents from the normals)
//     3  bit 0 Gouraud (else flat); bit 1 lighting; bit 2 depth test; bits 3-4 cull (v % 3);
//        bits 5-7 perspective mode (v % 5)
//     4  bit 0 textured; bit 1 bilinear; bit 2 wrap s clamp; bit 3 wrap t clamp; bits 4-5 mip
//        mode (v % 3); bit 6 replace (else modulate); bit 7 build mipmaps even without mip mode
//     5  bits 0-1 texel format; bits 2-4 texture width - 1; bits 5-7 texture height - 1
//     6  bits 0-2 light count (v % 5); bit 3 local viewer; bits 4-5 camera: 0 identity,
//        1 perspective + look-at from bytes, 2 raw matrices; bit 6 mesh has normals; bit 7 colours
//     7  bit 0 mesh has uvs; bits 1-5 right shift applied to raw positions (small coordinates)
//     8  mesh vertex count            9  mesh triangle count
//     10 screen vertex count          11 screen triangle count
//     12 bits 0-3 right shift applied to raw screen x, y; bit 4 second draw of the mesh (model
//        moved) after draw_screen; bit 5 Phong shading; bit 6 lighting table (size 8 << (bits
//        4-7 of byte 15) % 6, bilinear when bit 0 of byte 13); bit 7 two-sided lighting
//     13 small stores: vertex capacity - 1; 14 triangle capacity - 1 (bits 0-6), draws 1 + bit 7
//     15 small stores: active capacity - 1 (mod 16)
//   texture texels (3 bytes each), material and lights, camera, model matrix, then the mesh:
//   per vertex 3 x int32 position (raw Q16.16, shifted), 3 x int16 normal (clamped to
//   [-16384, 16384]), 3 bytes colour, 2 x int32 uv (raw Q12.20); per triangle 3 bytes of indices
//   (an index >= the vertex count is out of range; 0xFF reads as 0xFFFF); then the screen
//   vertices (x, y int32 shifted, z, w uint32, u, v int32, colour and specular as 3 bytes each)
//   and screen triangles (3 index bytes).
#include <algorithm>
#include <array>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <span>
#include <vector>

#include "lineraster/core/raster/renderer.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/host_sim/emulator/capture_display.hpp"
#include "lineraster/host_sim/formats/texture_load.hpp"
#include "tests/fuzz/fuzz_targets.hpp"

namespace lr::fuzz {
namespace {

class Bytes {
 public:
  Bytes(const uint8_t* p, size_t n) : p_(p), n_(n) {}
  uint8_t u8() {
    if (n_ == 0) return 0;
    --n_;
    return *p_++;
  }
  // The next out.size() bytes, zeros past the end (as u8()); one copy, which GCC 12 at -O3 does
  // not misread as an overflow as it did a loop of u8() into a struct member.
  void fill(std::span<uint8_t> out) {
    const size_t k = std::min(out.size(), n_);
    if (k > 0) std::memcpy(out.data(), p_, k);
    std::fill(out.begin() + static_cast<std::ptrdiff_t>(k), out.end(), uint8_t{0});
    p_ += k;
    n_ -= k;
  }
  uint16_t u16() { return static_cast<uint16_t>(u8() | (u8() << 8)); }
  uint32_t u32() { return uint32_t{u16()} | (uint32_t{u16()} << 16); }
  int32_t i32() { return static_cast<int32_t>(u32()); }
  int16_t i16() { return static_cast<int16_t>(u16()); }
  Fixed fixed() { return Fixed::from_raw(i32()); }
  Rgb8 rgb8() {
    Rgb8 c;
    c.r = u8();
    c.g = u8();
    c.b = u8();
    return c;
  }
  Color15 color15() { return from_rgb8(rgb8()); }

 private:
  const uint8_t* p_;
  size_t n_;
};

Mat4 raw_matrix(Bytes& in) {
  Mat4 m;
  for (auto& row : m.m)
    for (auto& e : row) e = in.fixed();
  return m;
}

Vec3 small_vec(Bytes& in) {  // components in [-128, 128) units, 1/256 steps
  return {Fixed::from_raw(int32_t{in.i16()} << 8), Fixed::from_raw(int32_t{in.i16()} << 8),
          Fixed::from_raw(int32_t{in.i16()} << 8)};
}

int16_t normal_component(Bytes& in) {
  return static_cast<int16_t>(std::clamp<int32_t>(in.i16(), -16384, 16384));
}

struct Header {
  uint8_t b[16];
};

uint32_t outcomes(const FrameStats& s) {
  return s.binned_inputs + s.culled_backface + s.culled_zero_area + s.culled_offscreen +
         s.clipped_away + s.rejected_invalid + s.dropped_vertex_capacity +
         s.dropped_triangle_capacity;
}

template <class PF, int K>
void run(const Header& h, Bytes& in) {
  const int width = 1 + h.b[0] % 128, height = 1 + h.b[1] % 128;
  const bool small = (h.b[2] & 16) != 0;
  const size_t n_vertices = small ? size_t{h.b[13]} + 1u : 2048u;
  const size_t n_triangles = small ? size_t{h.b[14] & 127u} + 1u : 2048u;
  const size_t n_draws = small ? static_cast<size_t>(h.b[14] >> 7) + 1u : 8u;
  const size_t n_active = small ? size_t{h.b[15] % 16u} + 1u : 512u;
  FrameCapacities caps;
  caps.width = width;
  caps.height = height;
  caps.strip_height = K;
  caps.vertices = n_vertices;
  caps.triangles = n_triangles;
  caps.draws = n_draws;
  caps.active = n_active;
  caps.surfaces = small ? n_vertices / 2 + 1 : n_vertices;
  caps.tex_vertices = small ? n_vertices / 3 + 1 : n_vertices;
  caps.active_extra = n_active;
  caps.triangle_colors = n_triangles;
  caps.lighting_table_words = small ? 200 : 2 * lighting_table_words(kMaxLightingTable, true);
  caps.pixel_lights = small ? 1 : 4;
  BasicFrameStorage<std::vector> store(caps);
  auto renderer = std::make_unique<Renderer<PF, K>>();
  const FrameStorage storage = store.storage();
  LR_FUZZ_CHECK(renderer->configure(storage, width, height) == Status::kOk);

  // Draw state and texture.
  DrawState state;
  state.shading = (h.b[3] & 1) ? Shading::kGouraud : Shading::kFlat;
  state.lighting = (h.b[3] & 2) != 0;
  state.depth_test = (h.b[3] & 4) != 0;
  state.cull = static_cast<Cull>(((h.b[3] >> 3) & 3) % 3);
  state.perspective = static_cast<Perspective>((h.b[3] >> 5) % 5);
  state.sampler.filter = (h.b[4] & 2) ? Filter::kBilinear : Filter::kNearest;
  state.sampler.wrap_s = (h.b[4] & 4) ? Wrap::kClampToEdge : Wrap::kRepeat;
  state.sampler.wrap_t = (h.b[4] & 8) ? Wrap::kClampToEdge : Wrap::kRepeat;
  state.sampler.mip = static_cast<MipMode>(((h.b[4] >> 4) & 3) % 3);
  state.sampler.env = (h.b[4] & 64) ? TexEnv::kReplace : TexEnv::kModulate;
  if (h.b[12] & 32) state.shading = Shading::kPhong;
  state.pixel_lighting = (h.b[12] & 64) ? PixelLighting::kTable : PixelLighting::kExact;
  state.table.size = static_cast<uint16_t>(8u << ((h.b[15] >> 4) % 6));
  state.table.bilinear = (h.b[13] & 1) != 0;
  host::HostTexture texture;
  if (h.b[4] & 1) {
    host::ImageRgb8 img;
    img.width = 1 + (h.b[5] >> 2 & 7);
    img.height = 1 + (h.b[5] >> 5);
    img.rgb.resize(size_t(img.width) * size_t(img.height) * 3);
    for (uint8_t& c : img.rgb) c = in.u8();
    const bool mipmaps = state.sampler.mip != MipMode::kNone || (h.b[4] & 128);
    std::string error;
    if (!host::texture_from_image(img, static_cast<TexelFormat>(h.b[5] & 3), mipmaps, texture,
                                  error)) {
      // Only a palette can fail, and 8 x 8 texels cannot have more than 256 colours.
      check_failed(__FILE__, __LINE__, error.c_str());
    }
    state.texture = &texture.texture;
    if (h.b[2] & 64) state.envmap = &texture.texture;
    if (h.b[2] & 128) state.normal_map = &texture.texture;
  }

  Material material;
  material.ambient = in.color15();
  material.diffuse = in.color15();
  material.specular = in.color15();
  material.emission = in.color15();
  material.shininess_q8 = static_cast<uint16_t>(in.u16() % (128 * 256 + 1));
  LightSet lights;
  lights.count = static_cast<uint8_t>((h.b[6] & 7) % (kMaxLights + 1));
  lights.local_viewer = (h.b[6] & 8) != 0;
  lights.two_sided = (h.b[12] & 128) != 0;
  lights.global_ambient = in.color15();
  for (int i = 0; i < lights.count; ++i) {
    Light& l = lights.lights[static_cast<size_t>(i)];
    l.position = small_vec(in);
    if (l.position == Vec3{}) l.position.z = Fixed::from_int(1);
    l.ambient = in.color15();
    l.diffuse = in.color15();
    l.specular = in.color15();
    if (h.b[2] & 32) {
      l.kind = LightKind::kPoint;
      l.constant = Fixed::from_raw(static_cast<int32_t>(in.u32()));
      l.linear = Fixed::from_raw(static_cast<int32_t>(in.u32()));
      l.quadratic = Fixed::from_raw(static_cast<int32_t>(in.u32()));
    }
  }

  Camera cam;
  Mat4 model = Mat4::identity();
  switch ((h.b[6] >> 4) & 3) {
    case 1: {
      Mat4 proj, view;
      const Fixed fovy = Fixed::from_int(1 + in.u8() % 179);
      const Fixed aspect = Fixed::from_raw(int32_t{(width << 16) / height});
      const Fixed near = Fixed::from_raw(1 + int32_t{in.u16()});
      const Fixed far = Fixed::from_raw(near.raw + 1 + int32_t{in.u16()} * 64);
      if (perspective(fovy, aspect, near, far, proj)) cam.projection = proj;
      cam.eye = small_vec(in);
      if (look_at(cam.eye, small_vec(in), Vec3{{}, Fixed::from_int(1), {}}, view)) cam.view = view;
      model = raw_matrix(in);
      break;
    }
    case 2:
    case 3:
      cam.view = raw_matrix(in);
      cam.projection = raw_matrix(in);
      cam.eye = Vec3{in.fixed(), in.fixed(), in.fixed()};
      model = raw_matrix(in);
      break;
    default:
      break;
  }

  // The mesh.
  const size_t nv = h.b[8], nt = h.b[9];
  const int shift = (h.b[7] >> 1) & 31;
  std::vector<Vec3> positions(nv);
  std::vector<Normal16> normals((h.b[6] & 64) ? nv : 0);
  std::vector<Rgb8> colors((h.b[6] & 128) ? nv : 0);
  std::vector<TexCoord> uvs((h.b[7] & 1) ? nv : 0);
  for (size_t i = 0; i < nv; ++i) {
    positions[i] = {Fixed::from_raw(in.i32() >> shift), Fixed::from_raw(in.i32() >> shift),
                    Fixed::from_raw(in.i32() >> shift)};
    Normal16 n;
    n.x = normal_component(in);
    n.y = normal_component(in);
    n.z = normal_component(in);
    if (!normals.empty()) normals[i] = n;
    Rgb8 c = in.rgb8();
    if (!colors.empty()) colors[i] = c;
    TexCoord uv;
    uv.u = in.i32();
    uv.v = in.i32();
    if (!uvs.empty()) uvs[i] = uv;
  }
  auto index = [&in]() -> uint16_t {
    const uint8_t v = in.u8();
    return v == 0xFF ? uint16_t{0xFFFF} : v;
  };
  std::vector<std::array<uint16_t, 3>> tris(nt);
  for (auto& t : tris) t = {index(), index(), index()};
  // Tangents for normal maps: each normal turned a quarter about z (any direction will do).
  std::vector<Tangent16> tangents(state.normal_map && !uvs.empty() ? nv : 0);
  for (size_t i = 0; i < tangents.size() && i < normals.size(); ++i)
    tangents[i] = {static_cast<int16_t>(-normals[i].y), normals[i].x, normals[i].z,
                   static_cast<int16_t>((i & 1) ? -16384 : 16384)};
  Mesh mesh{positions, normals, colors, uvs, tris, tangents};

  // Screen-space triangles.
  const size_t nsv = h.b[10], nst = h.b[11];
  const int sshift = h.b[12] & 15;
  std::vector<ScreenVertex> svs(nsv);
  std::vector<TexVertex> stex(nsv);
  for (size_t i = 0; i < nsv; ++i) {
    ScreenVertex& v = svs[i];
    v.x = in.i32() >> sshift;
    v.y = in.i32() >> sshift;
    v.z = in.u32();
    v.w = in.u32();
    stex[i].u = in.i32();
    stex[i].v = in.i32();
    v.color = in.color15();
    stex[i].spec = in.color15();
  }
  // A textured state's draw_screen needs one texture entry per vertex; one input in eight
  // gives one short (kInvalidArgument).
  if ((h.b[11] & 7) == 7 && !stex.empty()) stex.pop_back();
  std::vector<std::array<uint16_t, 3>> stris(nst);
  for (auto& t : stris) t = {index(), index(), index()};

  LR_FUZZ_CHECK(renderer->begin_frame(cam, lights, Rgb8{h.b[13], h.b[14], h.b[15]}) == Status::kOk);
  uint32_t expected_in = 0, refused = 0;
  Status first_refusal = Status::kOk;
  auto counted = [&](Status s, size_t n) {
    // A draw refused for its arguments or its stores adds nothing (the draw alone is counted);
    // one drawn or refused for capacity counts every triangle. Once the stores have overflowed,
    // later draws are only recorded: their outcomes are counted when render() bins the frame
    // in bands (checked after it), not here.
    LR_FUZZ_CHECK(s == Status::kOk || s == Status::kCapacity || s == Status::kInvalidArgument ||
                  s == Status::kMissingStore);
    if (s == Status::kOk || s == Status::kCapacity) expected_in += static_cast<uint32_t>(n);
    if (s != Status::kOk) ++refused;
    if (s != Status::kOk && first_refusal == Status::kOk) first_refusal = s;
    const FrameStats& fs = renderer->stats();
    LR_FUZZ_CHECK(fs.draws_refused_invalid + fs.draws_refused_missing_store +
                      fs.draws_refused_capacity + fs.draws_refused_not_linked ==
                  refused);
    LR_FUZZ_CHECK(renderer->stats().triangles_in == expected_in);
    if (renderer->front_end().needs_bands())
      LR_FUZZ_CHECK(outcomes(renderer->stats()) <= expected_in);
    else
      LR_FUZZ_CHECK(outcomes(renderer->stats()) == expected_in);
  };
  counted(renderer->draw(mesh, model, material, state), nt);
  counted(renderer->draw_screen(svs, stris, state, stex), nst);
  if (h.b[12] & 16) {
    const int64_t moved = int64_t{model.m[0][3].raw} + int64_t{in.i16()} * 16;
    model.m[0][3] =
        Fixed::from_raw(static_cast<int32_t>(std::clamp<int64_t>(moved, INT32_MIN + 1, INT32_MAX)));
    counted(renderer->draw(mesh, model, material, state), nt);
  }

  host::CaptureDisplay<PF> display(static_cast<size_t>(width) * K);
  host::DepthCapture depth_capture;
  depth_capture.resize(width, height);
  const Status st = renderer->render(display, (h.b[2] & 8) ? &depth_capture : nullptr);
  const FrameStats& s = renderer->stats();
  // A refused draw makes render() return the first refusal's status. Else stores below the
  // minimum (docs/bands.md: a strip that needs more than they hold) are the one case render()
  // reports: kCapacity, with the drop counted. Anything else is a failure.
  const bool dropped = s.dropped_vertex_capacity + s.dropped_triangle_capacity != 0;
  const bool expected = first_refusal != Status::kOk
                            ? st == first_refusal
                            : st == Status::kOk || (st == Status::kCapacity && dropped);
  if (!expected)
    std::fprintf(stderr, "render: status %d, %s\n", static_cast<int>(st), display.error().c_str());
  LR_FUZZ_CHECK(expected);

  static const bool verbose = std::getenv("LR_FUZZ_VERBOSE") != nullptr;
  if (verbose) {
    std::fprintf(stderr,
                 "%dx%d K=%d in=%u binned=%u (pieces %u) backface=%u zero=%u offscreen=%u "
                 "clipped_away=%u invalid=%u dropped=%u/%u passes=%u pixels=%u/%u\n",
                 width, height, K, s.triangles_in, s.binned_inputs, s.triangles_binned,
                 s.culled_backface, s.culled_zero_area, s.culled_offscreen, s.clipped_away,
                 s.rejected_invalid, s.dropped_vertex_capacity, s.dropped_triangle_capacity,
                 s.strip_passes, s.pixels_written, s.pixels_tested);
  }
  // Below the minimum a triangle may be dropped in one band and drawn in another (frame_stats.hpp).
  // A frame binned once counts each triangle once.
  if (st == Status::kOk || s.bands <= 1)
    LR_FUZZ_CHECK(s.triangles_in == outcomes(s));
  else
    LR_FUZZ_CHECK(s.triangles_in <= outcomes(s));
  LR_FUZZ_CHECK(s.strips == static_cast<uint32_t>((height + K - 1) / K));
  LR_FUZZ_CHECK(display.strips() == s.strips);
  LR_FUZZ_CHECK(s.empty_strips <= s.strips);
  // (Below the minimum an input counted as binned may have had every piece dropped.)
  if (!dropped) LR_FUZZ_CHECK(s.binned_inputs <= s.triangles_binned);
  LR_FUZZ_CHECK(s.clipped <= s.triangles_in);
  LR_FUZZ_CHECK(s.max_active <= n_active);
  LR_FUZZ_CHECK(s.pixels_written <= s.pixels_tested);
  LR_FUZZ_CHECK(uint64_t{s.pixels_tested} <=
                uint64_t{s.triangles_binned} * static_cast<uint64_t>(width * height));
  LR_FUZZ_CHECK(uint64_t{s.spans} <= uint64_t{s.triangles_binned} * static_cast<uint64_t>(height));
  LR_FUZZ_CHECK(display.raw_frame().size() == static_cast<size_t>(width * height));
  if (s.pixels_written == 0) {
    // Nothing drawn: the frame is the background everywhere.
    const auto bg = PF::encode(Rgb8{h.b[13], h.b[14], h.b[15]});
    for (const auto& p : display.raw_frame()) LR_FUZZ_CHECK(std::memcmp(&p, &bg, sizeof p) == 0);
  }
}

template <class PF>
void run_k(const Header& h, Bytes& in) {
  switch ((h.b[2] & 3) % 3) {
    case 0:
      run<PF, 1>(h, in);
      break;
    case 1:
      run<PF, 8>(h, in);
      break;
    default:
      run<PF, 32>(h, in);
      break;
  }
}

}  // namespace

int pipeline_target(const uint8_t* data, size_t size) {
  Bytes in(data, size);
  Header h;
  in.fill(h.b);
  if (h.b[2] & 4) {
    run_k<Rgb888>(h, in);
  } else {
    run_k<Rgb565Be>(h, in);
  }
  return 0;
}

}  // namespace lr::fuzz
