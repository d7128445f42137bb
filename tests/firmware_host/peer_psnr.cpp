// The peer scenes' quality (peer_frames.hpp, peer_figures.hpp): each frame of firmware/peer (the
// same scene definitions, flash arrays and model matrices as lr_peer) rendered by the core on the
// host in strips of 8, by the double-precision reference and by Mesa (OSMesa). Prints one line
// per scene:
//   the core's RGB888 frame (its arithmetic, before the display's RGB565 rounding, as
//   tests/bench/quality_bench does) against the reference with the 8-bit baboon (the RGB565
//   texture's rounding counts as error) and again with the RGB565 texels the core samples (the
//   renderer's own error): covered pixels of each, coverage mismatches, and over the pixels both
//   cover the PSNR, the % of pixels within one level in every channel, the largest channel error
//   (tests/support/scene_compare.hpp measures them);
//   the RGB565 frame the panel shows against Mesa's RGB888 frame: PSNR over the whole frame and
//   coverage mismatches; and against the reference rounded to RGB565: pixels more than one step
//   off and the largest difference in steps.
// scripts/peer_bench.sh puts the PSNR figures in its tables. A figure, not a test: it never fails
// on the error's size (peer_accuracy_test asserts the bounds of S1 and S1x).
//
// usage: lr_peer_psnr [SOURCE_DIR]   (default: the source tree it was built from)
#include <cstdio>
#include <cstdlib>
#include <string>

#include "tests/firmware_host/peer_figures.hpp"

// Mesa's OSMesa keeps a small allocation per OSMesaMakeCurrent after the context is destroyed
// (libOSMesa.so.8, Mesa 22.3): not ours to fix; LeakSanitizer (the ASan run) ignores it.
extern "C" __attribute__((used)) const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\n";
}

namespace {

namespace peer = lr::test::peer;

[[noreturn]] void die(const std::string& what) {
  std::fprintf(stderr, "lr_peer_psnr: %s\n", what.c_str());
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string root = argc > 1 ? argv[1] : LR_SOURCE_DIR;
  peer::PeerSources src;
  std::string error;
  if (!peer::load_sources(root, src, error)) die(error);
  std::printf(
      "lr_peer_psnr: core RGB888 (strips of 8) against the double reference (8-bit "
      "texture); error over the pixels both cover. RGB565 frame against Mesa over the whole frame "
      "(8-bit texture; the background as the panel shows it), and against the reference rounded to "
      "RGB565 (same texels) over the pixels both cover\n");
  for (size_t i = 0; i < peer::fwp::kScenes.size(); ++i) {
    peer::PeerFigures f;
    if (!peer::measure_scene(i, src, f, error)) die(error);
    size_t covered = 0, ref_covered = 0;
    for (uint16_t d : f.ref888.core.depth) covered += d != 0xFFFF;
    for (int32_t o : f.ref888.reference.owner) ref_covered += o >= 0;
    if (i == 0) std::printf("lr_peer_psnr: Mesa: %s\n", f.mesa_renderer.c_str());
    std::printf(
        "lr_peer_psnr: case %s covered %zu ref_covered %zu coverage_diff %zu written %u psnr %.2f "
        "within1 %.2f max_error %d psnr_same_texels %.2f within1_same_texels %.2f "
        "mesa_psnr565 %.2f mesa_covered %zu mesa_coverage_diff %zu "
        "over_one_step565 %zu max_steps565 %d\n",
        peer::fwp::kScenes[i].name, covered, ref_covered, f.ref888.coverage_diff,
        f.ref888.core.stats.pixels_written, f.ref888.psnr, 100.0 * f.ref888.fraction_within1(),
        f.ref888.max_error, f.same888.psnr, 100.0 * f.same888.fraction_within1(), f.mesa_psnr,
        f.mesa_covered, f.mesa_coverage_diff, f.steps_over_one, f.max_steps);
  }
  return 0;
}
