// The six peer scenes (the standard comparison with TGX, small3dlib and TinyGL; the definitions:
// tests/data/peer/README.md), first as the numbers the definition gives, then in the core's
// formats. The numbers are doubles only inside the compiler: firmware code sees the Fixed,
// Color15 and DrawState values that consteval functions make of them (as firmware/demo does),
// and the host's reference comparison (tests/firmware_host/peer_psnr.cpp) reads the doubles.
//   S1   the bunny, normalised to [-1,1]^3 (lineraster-asset --fit-box), Gouraud, one light
//   S1x  the bunny subdivided twice (--subdivide 2), as S1
//   S2n, S2b  the baboon-textured cube, unlit (replace), nearest / bilinear
//   S3n, S3b  the baboon-textured ground plane to z = -256, unlit, nearest / bilinear
// All: 320x240, fovy 60, background RGB(48,56,64), depth LESS, back faces culled, identity view,
// the texture in RGB565, repeat, perspective-correct (kExact), no mipmaps.
#pragma once

#include <array>
#include <cstdint>

#include "firmware/demo/scene.hpp"
#include "lineraster/core/lighting/lighting.hpp"
#include "lineraster/core/math/fixed.hpp"
#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/math/vec.hpp"
#include "lineraster/core/output/color.hpp"
#include "lineraster/core/scene/camera.hpp"
#include "lineraster/core/scene/draw_state.hpp"
#include "lineraster/core/scene/material.hpp"
#include "lineraster/core/span/span_state.hpp"

namespace lr::fw::peer {

enum class Geometry : uint8_t { kBunny, kBunnyX, kCube, kGround };

// A scene as the definition states it. Model = T(0, 0, translate_z) Rx(rotate_x) Ry(rotate_y).
struct PeerScene {
  const char* name;
  Geometry geometry;
  double near, far;
  double translate_z, rotate_x_deg, rotate_y_deg;
  bool lit;       // Gouraud with kLightTowards and the bunny's material; else unlit, replace
  Filter filter;  // the textured scenes' filter
  uint32_t mesa_covered;  // pixels Mesa's OpenGL covers (the definition's count)
  // Fine transforms (issue 36's one-step bound, docs/numerics.md#fine-transforms): the
  // projection perspective_fine gives, the model of rotate_x_fine and rotate_y_fine, drawn with
  // Renderer::draw(FineMat4), and the meshes' positions in Q1.30 (assets.cmake). Else Q16.16.
  bool fine;
};

inline constexpr int kWidth = 320, kHeight = 240;
inline constexpr double kFovyDeg = 60.0;
inline constexpr Rgb8 kBackground{48, 56, 64};
// The light: direction towards it in eye space (= world space: the view is the identity),
// white; the material: ambient 0.2 and diffuse 0.8 of the colour, no specular.
inline constexpr double kLightTowards[3] = {-0.6, 0.8, 1.0};
inline constexpr double kMaterialColor[3] = {0.95, 0.78, 0.55};
inline constexpr double kAmbient = 0.2, kDiffuse = 0.8;

inline constexpr std::array<PeerScene, 6> kScenes = {{
    {"S1", Geometry::kBunny, 1.0, 10.0, -2.45, 0.0, 20.0, true, Filter::kNearest, 21756, true},
    {"S1x", Geometry::kBunnyX, 1.0, 10.0, -2.45, 0.0, 20.0, true, Filter::kNearest, 21756, true},
    {"S2n", Geometry::kCube, 1.0, 10.0, -2.75, 30.0, 30.0, false, Filter::kNearest, 39889, false},
    {"S2b", Geometry::kCube, 1.0, 10.0, -2.75, 30.0, 30.0, false, Filter::kBilinear, 39889, false},
    {"S3n", Geometry::kGround, 0.5, 300.0, 0.0, 0.0, 0.0, false, Filter::kNearest, 38080, false},
    {"S3b", Geometry::kGround, 0.5, 300.0, 0.0, 0.0, 0.0, false, Filter::kBilinear, 38080, false},
}};

// How far the covered pixels may be from Mesa's count: the scene is the definition's if its
// frame covers the same pixels but for a few along the silhouette.
inline constexpr uint32_t kCoverageSlack = 4;

// A scene in the core's formats (the texture pointer is filled in by the program).
struct PeerCase {
  const char* name = nullptr;
  Geometry geometry = Geometry::kBunny;
  uint32_t mesa_covered = 0;
  bool fine = false;
  Fixed near, far, translate_z, rotate_x, rotate_y;
  int32_t translate_z_q28 = 0;  // translate_z in Q4.28 (fine scenes' model)
  LightSet lights;
  Material material;
  DrawState state;
};

consteval uint16_t color15(double v) {
  return static_cast<uint16_t>(v * Color15::kOne + 0.5);
}

consteval Color15 scaled_color(double k) {
  return {color15(k * kMaterialColor[0]), color15(k * kMaterialColor[1]),
          color15(k * kMaterialColor[2])};
}

consteval PeerCase to_case(const PeerScene& s) {
  PeerCase c;
  c.name = s.name;
  c.geometry = s.geometry;
  c.mesa_covered = s.mesa_covered;
  c.fine = s.fine;
  c.near = Fixed::from_double(s.near);
  c.far = Fixed::from_double(s.far);
  c.translate_z = Fixed::from_double(s.translate_z);
  {
    const double t = s.translate_z * (1 << 28);  // |translate_z| < 8
    c.translate_z_q28 = static_cast<int32_t>(t < 0 ? t - 0.5 : t + 0.5);
  }
  c.rotate_x = Fixed::from_double(s.rotate_x_deg);
  c.rotate_y = Fixed::from_double(s.rotate_y_deg);
  c.state.cull = Cull::kBack;
  c.state.perspective = Perspective::kExact;
  if (s.lit) {
    c.lights.lights[0] =
        demo::white_directional(kLightTowards[0], kLightTowards[1], kLightTowards[2]);
    c.lights.count = 1;
    c.material.ambient = scaled_color(kAmbient);
    c.material.diffuse = scaled_color(kDiffuse);
    c.material.specular = {0, 0, 0};
    c.state.shading = Shading::kGouraud;
    c.state.lighting = true;
  } else {
    c.state.lighting = false;
    c.state.sampler.filter = s.filter;
    c.state.sampler.wrap_s = c.state.sampler.wrap_t = Wrap::kRepeat;
    c.state.sampler.mip = MipMode::kNone;
    c.state.sampler.env = TexEnv::kReplace;
  }
  return c;
}

consteval std::array<PeerCase, kScenes.size()> to_cases() {
  std::array<PeerCase, kScenes.size()> a{};
  for (size_t i = 0; i < kScenes.size(); ++i) a[i] = to_case(kScenes[i]);
  return a;
}

inline constexpr std::array<PeerCase, kScenes.size()> kCases = to_cases();

// The span set of a case's draw state (core/span/span_state.hpp), RGB565 textures repeated: a
// renderer restricted to it links the case's span routine and texel fetcher and no other
// (lr_peer_spans, firmware/peer/main.cpp with LR_PEER_SCENE_SPANS). The state as the front end
// derives it (core/span/admission.cpp): the bunny is lit Gouraud (colour planes), the cube and
// the ground plane textured; a draw outside the set would be refused.
consteval SpanSet scene_spans(const PeerCase& c) {
  SpanState s;
  s.depth = c.state.depth_test;
  if (c.state.lighting) {
    s.family = SpanFamily::kUntextured;
    s.colors = c.state.perspective == Perspective::kAffine ? ColorPlanes::kAffine
                                                           : ColorPlanes::kPerspective;
  } else {
    s.family = SpanFamily::kTextured;
    s.persp = c.state.perspective == Perspective::kExact    ? TexPersp::kExact
              : c.state.perspective == Perspective::kAffine ? TexPersp::kAffine
                                                            : TexPersp::kSpan;
    s.env = c.state.sampler.env;
    s.mip = c.state.sampler.mip;
    s.filter = c.state.sampler.filter;
  }
  return span_set_of(s).only(TexelFormat::kRgb565).only_wraps(Wrap::kRepeat, Wrap::kRepeat);
}

// The camera of every scene: identity view (eye at the origin looking down -z), fovy 60, the
// scene's near and far planes; for fine scenes the projection of perspective_fine (the aspect
// the viewport's ratio 320 / 240) into fine_projection, which the camera points to (the caller
// keeps it until the frame is rendered), and, rounded, as projection. False if
// perspective() or perspective_fine() rejects them.
inline bool make_camera(const PeerCase& c, Camera& out, FineMat4& fine_projection) {
  out = Camera{};
  if (c.fine) {
    if (!perspective_fine(Fixed::from_double(kFovyDeg), kWidth, kHeight, c.near, c.far,
                          fine_projection))
      return false;
    out.fine_projection = &fine_projection;
    out.projection = to_mat4(fine_projection);
    return true;
  }
  return perspective(Fixed::from_double(kFovyDeg), Fixed::ratio(kWidth, kHeight), c.near, c.far,
                     out.projection);
}

// The model matrix T(0, 0, translate_z) Rx(rotate_x) Ry(rotate_y) of a fine scene: the rotations
// in Q1.30, the translation in Q4.28, their product as FineMat4 (frac 29 here: Q3.29 holds the
// translation -2.45).
inline FineMat4 fine_model(const PeerCase& c) {
  return translate_fine(0, 0, c.translate_z_q28, 28) *
         (rotate_x_fine(c.rotate_x) * rotate_y_fine(c.rotate_y));
}

// The model matrix T(0, 0, translate_z) Rx(rotate_x) Ry(rotate_y) in Q16.16 (fine scenes: the
// fine model rounded, what the renderer's lighting reads of it).
inline Mat4 model(const PeerCase& c) {
  if (c.fine) return to_mat4(fine_model(c));
  return translate({Fixed{}, Fixed{}, c.translate_z}) * rotate_x(c.rotate_x) * rotate_y(c.rotate_y);
}

}  // namespace lr::fw::peer
