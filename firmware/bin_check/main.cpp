// lr_bin_check: the front end's bin lane by hand (core/binning/bin_lane.hpp, the Armv7E-M asm)
// against its C twin on random meshes (firmware/bin_check/bin_cases.hpp): the same records,
// buckets, counts, stops and vertices to light; and the scan
// for the first index out of range against one index at a time. On cores without the hand-allocated
// lane it runs the C lane against itself (a check of the harness). Reports on the console
// (semihosting); exit status 0 when nothing differs.
#include <cstdint>

#include "firmware/bin_check/bin_cases.hpp"
#include "firmware/common/semihost.hpp"

namespace {

namespace sh = lr::fw::semihost;
namespace bins = lr::fw::bins;

bins::Mesh g_mesh;
bins::Run g_a, g_b;

}  // namespace

int main() {
  const auto by_hand = [](const std::array<uint16_t, 3>*& tp, lr::BinLane& k) {
    return lr::bin_lane_asm(tp, k);
  };
  const auto portable = [](const std::array<uint16_t, 3>*& tp, lr::BinLane& k) {
    return lr::bin_lane_portable(tp, k);
  };
  const bins::Tally t = bins::run_cases(3000, g_mesh, g_a, g_b, by_hand, portable);
  sh::write(lr::kBinLaneAsm ? "lr_bin_check: hand-allocated lane == C lane: "
                            : "lr_bin_check: no hand-allocated lane on this core (C lane twice): ");
  sh::write_dec(t.meshes);
  sh::write(" meshes, ");
  sh::write_dec(t.binned);
  sh::write(" binned, ");
  sh::write_dec(t.zero);
  sh::write(" without area, ");
  sh::write_dec(t.offscreen);
  sh::write(" without a pixel centre, ");
  sh::write_dec(t.lit);
  sh::write(" vertices to light, ");
  sh::write_dec(t.stops);
  sh::write(" stops, ");
  sh::write_dec(t.low_word_zero);
  sh::write(" with twice the area a multiple of 2^32, ");
  sh::write_dec(t.differing);
  sh::write(" meshes differ; ");
  sh::write_dec(t.scans);
  sh::write(" index scans, ");
  sh::write_dec(t.scans_differing);
  sh::write(" differ\n");
  // A run that compared (almost) nothing proves nothing.
  const bool ok = t.differing == 0 && t.scans_differing == 0 && t.scans > 100000 &&
                  t.binned > 20000 && t.zero > 1000 && t.offscreen > 500 && t.lit > 20000 &&
                  t.low_word_zero > 1000;
  sh::write(ok ? "lr_bin_check: PASS\n" : "lr_bin_check: FAIL\n");
  sh::exit(ok);
}
