// lr_span_check: the lanes row loop by hand (core/span/lane_rows.hpp, the Armv7E-M asm) against
// its C twin, on random triangles drawn strip by strip into random strip buffers
// (firmware/span_check/lane_cases.hpp): the same pixels, depths and counts on every visit. Also
// the C twin against the renderer's generic row loop (a span routine per row), which every core
// runs. Reports on the console (semihosting); exit status 0 when nothing differs.
#include <cstdint>

#include "firmware/common/semihost.hpp"
#include "firmware/span_check/lane_cases.hpp"
#include "lineraster/core/raster/untextured_rows.hpp"
#include "lineraster/core/span/lane_rows.hpp"

namespace {

namespace sh = lr::fw::semihost;
namespace lanes = lr::fw::lanes;

lanes::Strip g_a, g_b;

bool report(const char* what, const lanes::Tally& t) {
  sh::write("lr_span_check: ");
  sh::write(what);
  sh::write(": ");
  sh::write_dec(t.triangles);
  sh::write(" triangles, ");
  sh::write_dec(t.visits);
  sh::write(" strip visits, ");
  sh::write_dec(t.pixels);
  sh::write(" pixels, ");
  sh::write_dec(t.differing);
  sh::write(" visits differ\n");
  // A run that compared (almost) nothing proves nothing.
  return t.differing == 0 && t.triangles > 1000 && t.pixels > 20000;
}

}  // namespace

int main() {
  using lr::ActiveTriangle;
  using lr::StripRows;
  using PF = lanes::PF;
  constexpr uint32_t kCases = 6000;
  bool ok = true;
  const auto portable = [](const ActiveTriangle& t, StripRows& s) {
    lr::lane_visit_portable<PF>(t, s);
  };
  if constexpr (lr::kLaneVisitAsm) {
    const auto by_hand = [](const ActiveTriangle& t, StripRows& s) { lr::lane_visit<PF>(t, s); };
    ok = report("hand-allocated loop == C loop",
                lanes::run_cases(kCases, g_a, g_b, by_hand, portable)) &&
         ok;
  } else {
    sh::write("lr_span_check: no hand-allocated loop on this core\n");
  }
  const auto generic = [](const ActiveTriangle& t, StripRows& s) {
    lr::untextured_rows_per_span<PF, true, lr::UntexturedKind::kLanes>(t, s);
  };
  ok = report("C loop == generic row loop",
              lanes::run_cases(kCases, g_a, g_b, portable, generic, 12345u)) &&
       ok;
  sh::write(ok ? "lr_span_check: PASS\n" : "lr_span_check: FAIL\n");
  sh::exit(ok);
}
