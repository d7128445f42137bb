// The accuracy figures of one peer scene (peer_frames.hpp renders it): the core's RGB888 frame
// against the double reference (lr_peer_psnr's figures since the peer benchmark began), and the
// figures of issue 36 on the RGB565 frame the panel shows (decoded to 8 bits by bit replication,
// as panels expand it):
//   against Mesa (OSMesa's RGB888 frame of the same scene, textures from the 8-bit baboon): PSNR
//     over the whole 320x240 frame, every pixel and channel, and the pixels covered by one of the
//     two only. Where Mesa draws nothing it shows the background as the panel does (the scene's
//     RGB(48,56,64) rounded to RGB565 and expanded: (49,56,66)): that rounding is the display's,
//     the same whatever renders, so the figure measures the drawn pixels. This is how the peer
//     figures were published (tests/data/peer/README.md; S1 47.11 dB at c934e84);
//   against the double reference rounded to RGB565 (round(31 c), round(63 c), round(31 c) of its
//     colour in [0, 1], sampling the texels the core samples): on the pixels both cover, how many
//     differ by more than one RGB565 step in some channel, and the largest difference in steps.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "lineraster/host_sim/formats/texture_load.hpp"
#include "tests/firmware_host/peer_frames.hpp"
#include "tests/glcheck/osmesa_scene.hpp"
#include "tests/reference/ref_texture_core.hpp"
#include "tests/support/scene_compare.hpp"

namespace lr::test::peer {

struct PeerFigures {
  Comparison ref888;   // core RGB888 against the reference with the 8-bit texture
  Comparison same888;  // ... with the RGB565 texels the core samples (lit scenes: = ref888)
  // Against Mesa.
  double mesa_psnr = 0;           // RGB565 frame, whole frame
  size_t mesa_coverage_diff = 0;  // covered by the core or by Mesa only
  size_t mesa_covered = 0;        // pixels Mesa covers
  std::string mesa_renderer;      // GL_RENDERER
  // RGB565 against the reference rounded to RGB565 (same texels).
  size_t steps_both = 0;           // pixels both cover
  size_t steps_over_one = 0;       // of them: some channel more than one step off
  int max_steps = 0;               // the largest channel difference in steps
  size_t steps_coverage_diff = 0;  // covered by the core or by the reference only
};

// |a - b| in steps of each RGB565 channel: the core's stored value (the top bits of the decoded,
// bit-replicated byte) against the reference's colour rounded to that channel's width.
inline int steps565(const uint8_t* core8, const ref::Vec3d& ref_colour) {
  constexpr int kBits[3] = {5, 6, 5};
  int worst = 0;
  for (size_t k = 0; k < 3; ++k) {
    const int max = (1 << kBits[k]) - 1;
    const int core = core8[k] >> (8 - kBits[k]);
    const double c = std::clamp(ref_colour[k], 0.0, 1.0);
    const int ref = int(std::lround(c * max));
    worst = std::max(worst, std::abs(core - ref));
  }
  return worst;
}

// What the scenes are made of besides the firmware's flash arrays: tests/data/peer/, the 8-bit
// baboon (the textured scenes' source: Mesa samples it, and so does the reference for ref888) and
// the reference's copies of it and of the RGB565 texels the core samples.
struct PeerSources {
  std::string dir;  // tests/data/peer/ (with the trailing slash)
  host::HostTexture baboon;
  ref::RefTexture truth, stored;
};

inline bool load_sources(const std::string& source_dir, PeerSources& out, std::string& error) {
  out.dir = source_dir + "/tests/data/peer/";
  if (!host::load_texture(out.dir + "baboon.png", TexelFormat::kRgb888, false, out.baboon, error))
    return false;
  out.truth = ref::from_core(out.baboon.texture);
  out.stored = ref::from_core(*fwp::texture(fwp::Geometry::kCube));
  return true;
}

// Renders scene i three ways and fills f.
inline bool measure_scene(size_t i, const PeerSources& src, PeerFigures& f, std::string& error) {
  const fwp::PeerScene& s = fwp::kScenes[i];
  const fwp::PeerCase& c = fwp::kCases[i];
  f = {};
  host::RenderResult core565;
  if (!render_core<Rgb888>(c, f.ref888.core, error)) return false;
  if (!render_core<Rgb565Be>(c, core565, error)) return false;
  host::HostMesh mesh;
  if (!host_mesh(src.dir, s.geometry, mesh, error)) return false;

  ref::RefParams rp = ref_params(s);
  if (!s.lit) {
    rp.texture = &src.truth;
    ref::set_sampler(rp, c.state.sampler);
  }
  ref::render(mesh, rp, f.ref888.reference);
  measure(true, f.ref888);
  if (s.lit) {
    f.same888 = f.ref888;
  } else {
    f.same888.core = f.ref888.core;
    rp.texture = &src.stored;
    ref::render(mesh, rp, f.same888.reference);
    measure(true, f.same888);
  }

  glcheck::GlFrame gl;
  host::SceneOptions go = gl_options(s, c);
  if (go.texture_object != nullptr) go.texture_object = &src.baboon.texture;
  if (!glcheck::render_gl(mesh, go, ref_params(s), gl, error)) return false;
  f.mesa_renderer = gl.renderer;
  const Rgb8 shown = Rgb565Be::decode(Rgb565Be::encode(fwp::kBackground));
  const uint8_t background[3] = {shown.r, shown.g, shown.b};
  const size_t n = gl.covered.size();
  double sq = 0;
  for (size_t p = 0; p < n; ++p) {
    const bool core_cov = core565.depth[p] != 0xFFFF, gl_cov = gl.covered[p] != 0;
    f.mesa_covered += gl_cov;
    f.mesa_coverage_diff += core_cov != gl_cov;
    for (size_t k = 0; k < 3; ++k) {
      const uint8_t mesa = gl_cov ? gl.rgb[3 * p + k] : background[k];
      const double e = double(core565.image.rgb[3 * p + k]) - double(mesa);
      sq += e * e;
    }
  }
  const double mse = sq / (3.0 * double(n));
  f.mesa_psnr = mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : 99.0;

  const ref::RefFrame& r = f.same888.reference;
  for (size_t p = 0; p < n; ++p) {
    const bool core_cov = core565.depth[p] != 0xFFFF, ref_cov = r.owner[p] >= 0;
    if (core_cov != ref_cov) ++f.steps_coverage_diff;
    if (!core_cov || !ref_cov) continue;
    ++f.steps_both;
    const int e = steps565(&core565.image.rgb[3 * p], r.color[p]);
    f.steps_over_one += e > 1;
    f.max_steps = std::max(f.max_steps, e);
  }
  return true;
}

}  // namespace lr::test::peer
