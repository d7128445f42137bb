// Random triangles, long run (CTest label "long", on demand): 10^7 (8 x 10^6 in screen space,
// 2 x 10^6 through the 3D path), with other seeds than the quick run. Skipped unless
// LR_STRESS_LONG=1:  LR_STRESS_LONG=1 ctest --preset debug -L long
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "tests/stress/random_stress.hpp"

namespace lr {
namespace {

bool long_enabled() {
  const char* v = std::getenv("LR_STRESS_LONG");
  return v != nullptr && *v != 0 && *v != '0';
}

TEST(RandomTrianglesLong, ScreenSpace) {
  if (!long_enabled()) GTEST_SKIP() << "set LR_STRESS_LONG=1 to run";
  stress::RunFigures f;
  stress::run_screen(8000000, 101, f);
  stress::expect_clean(f);
  stress::expect_screen_work(f);
  std::printf("[ stress ] long, screen space: %llu random triangles, %llu pixels, 0 mismatches\n",
              (unsigned long long)f.triangles, (unsigned long long)f.pixels);
}

TEST(RandomTrianglesLong, ThroughTheVertexStageWithClipping) {
  if (!long_enabled()) GTEST_SKIP() << "set LR_STRESS_LONG=1 to run";
  stress::RunFigures f;
  stress::run_3d(2000000, 102, f);
  stress::expect_clean(f);
  stress::expect_3d_work(f);
  std::printf("[ stress ] long, 3D: %llu random triangles, %llu clipped, %llu pixels\n",
              (unsigned long long)f.triangles, (unsigned long long)f.clipped,
              (unsigned long long)f.pixels);
}

}  // namespace
}  // namespace lr
