// lr_span_check: the lanes row loop by hand (core/span/lane_rows.hpp, the Armv7E-M asm) against
// its C twin, on random triangles drawn strip by strip into random strip buffers
// (firmware/span_check/lane_cases.hpp): the same pixels, depths and counts on every visit; on
// Armv6-M (and Armv7-M at -Os) the span loop by hand (core/span/lane_span.hpp) against its C twin
// on random spans. Also the C twin against the renderer's generic row loop (a span routine per row,
// by hand on Armv6-M and on Armv7-M at -Os), which every core runs. Reports on the console
// (semihosting); exit status 0 when nothing differs.
#include <cstdint>

#include "firmware/common/semihost.hpp"
#include "firmware/span_check/fill_check.hpp"
#include "firmware/span_check/lane_cases.hpp"
#include "lineraster/core/raster/strip_visit.hpp"
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

// The same for random spans (run_spans: a visit is a span).
bool report_spans(const char* what, const lanes::Tally& t) {
  sh::write("lr_span_check: ");
  sh::write(what);
  sh::write(": ");
  sh::write_dec(t.visits);
  sh::write(" spans, ");
  sh::write_dec(t.pixels);
  sh::write(" pixels, ");
  sh::write_dec(t.differing);
  sh::write(" spans differ\n");
  return t.differing == 0 && t.visits > 1000 && t.pixels > 20000;
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
    // Runs of lanes triangles in one call, by hand and in C, in strips mixed with others.
    constexpr lr::RowFn kLanes = &lr::lanes_rows<PF>;
    const auto runs_by_hand = [](lr::ActiveList& x, StripRows& s) {
      lr::LaneRun words{};
      lr::visit_active(x, s, kLanes, words,
                       [](const ActiveTriangle& t, lr::LaneRun& r, StripRows& sr) {
                         lr::lane_run<PF>(t, r, sr);
                       });
    };
    const auto runs_portable = [](lr::ActiveList& x, StripRows& s) {
      lr::LaneRun words{};
      lr::visit_active(x, s, kLanes, words,
                       [](const ActiveTriangle& t, lr::LaneRun& r, StripRows& sr) {
                         lr::lane_run_portable<PF>(t, r, sr);
                       });
    };
    const lanes::StripTally t =
        lanes::run_strips(3000, g_a, g_b, kLanes, runs_by_hand, runs_portable);
    sh::write("lr_span_check: runs by hand == C runs: ");
    sh::write_dec(t.strips);
    sh::write(" strips, ");
    sh::write_dec(t.triangles);
    sh::write(" triangles (");
    sh::write_dec(t.in_runs);
    sh::write(" in runs, ");
    sh::write_dec(t.others);
    sh::write(" others, ");
    sh::write_dec(t.kept);
    sh::write(" kept, ");
    sh::write_dec(t.freed);
    sh::write(" freed), ");
    sh::write_dec(t.differing);
    sh::write(" strips differ\n");
    ok = t.differing == 0 && t.strips > 2000 && t.in_runs > 5000 && t.others > 500 &&
         t.kept > 2000 && t.freed > 2000 && ok;
  } else {
    sh::write("lr_span_check: no hand-allocated visit on this core\n");
  }
  // The span loop of the generic row loop: by hand on Armv6-M, and Armv7-M at -Os (lane_span.hpp).
  const auto span = [](uint16_t* px, uint16_t* depth, int32_t n, uint32_t z, uint32_t dz,
                       uint32_t br, uint32_t dbr, uint32_t g, uint32_t dg) {
    return lr::lane_span<PF, true>(px, depth, n, z, dz, br, dbr, g, dg);
  };
  const auto span_portable = [](uint16_t* px, uint16_t* depth, int32_t n, uint32_t z, uint32_t dz,
                                uint32_t br, uint32_t dbr, uint32_t g, uint32_t dg) {
    return lr::lane_span_portable<PF, true>(px, depth, n, z, dz, br, dbr, g, dg);
  };
  if constexpr (lr::kLaneSpanAsm || lr::kLaneSpanAsmV7) {
    ok = report_spans("span loop by hand == C span loop",
                      lanes::run_spans(20000, g_a, g_b, span, span_portable)) &&
         ok;
  }
  // The small triangles' planes by hand (untextured_setup.cpp) against their C form.
  if constexpr (lr::kSmallPlanesByHand) {
    const lanes::Tally t = lanes::run_small_planes(20000);
    sh::write("lr_span_check: small planes by hand == C: ");
    sh::write_dec(t.triangles);
    sh::write(" triangles with planes, ");
    sh::write_dec(t.visits);
    sh::write(" refused, ");
    sh::write_dec(t.differing);
    sh::write(" differ\n");
    ok = t.differing == 0 && t.triangles > 10000 && t.visits > 100 && ok;
  }
  // Both in one call (the strip loop's way for lanes triangles with depth) against the C forms.
  if constexpr (lr::kSmallPlanesByHand) {
    const lanes::Tally t = lanes::run_small_triangles(20000);
    sh::write("lr_span_check: small rows and planes in one call by hand == C: ");
    sh::write_dec(t.triangles);
    sh::write(" triangles with planes, ");
    sh::write_dec(t.visits);
    sh::write(" with rows only, ");
    sh::write_dec(t.differing);
    sh::write(" differ\n");
    ok = t.differing == 0 && t.triangles > 5000 && t.visits > 100 && ok;
  }
  // The strip loop's lanes setup from vertex indices (by hand: fetch, sort, rows, planes, the
  // affine colour test) against sort_by_y and setup_untextured_triangle.
  if constexpr (lr::kSmallPlanesByHand) {
    const lanes::Tally t = lanes::run_lanes_setup(30000);
    sh::write("lr_span_check: lanes setup from indices by hand == sort and setup: ");
    sh::write_dec(t.triangles);
    sh::write(" lanes triangles, ");
    sh::write_dec(t.pixels);
    sh::write(" others, ");
    sh::write_dec(t.visits);
    sh::write(" slivers, ");
    sh::write_dec(t.differing);
    sh::write(" differ\n");
    ok = t.differing == 0 && t.triangles > 5000 && t.pixels > 1000 && t.visits > 1000 && ok;
  }
  // The small triangles' rows and edges by hand (untextured_setup.cpp) against their C form.
  if constexpr (lr::kSmallRowsByHand) {
    const lanes::Tally t = lanes::run_small_rows(40000);
    sh::write("lr_span_check: small rows by hand == C: ");
    sh::write_dec(t.triangles);
    sh::write(" small triangles (");
    sh::write_dec(t.pixels);
    sh::write(" without a pixel centre on their widest row), ");
    sh::write_dec(t.visits);
    sh::write(" refused, ");
    sh::write_dec(t.differing);
    sh::write(" differ\n");
    ok = t.differing == 0 && t.triangles > 10000 && t.pixels > 100 && t.visits > 1000 && ok;
  }
  // The strip clear by hand (strip_fill.hpp) against memset / memcpy.
  if constexpr (lr::fw::fill::kFillByHand) {
    const lr::fw::fill::Result f = lr::fw::fill::run();
    sh::write("lr_span_check: strip clear by hand == memset / memcpy: ");
    sh::write_dec(f.cases);
    sh::write(" fills, ");
    sh::write_dec(f.differing);
    sh::write(" differ\n");
    ok = f.differing == 0 && f.cases > 5000 && ok;
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
