// Random triangles, quick run: 10^6 (screen space and 3D, see random_stress.hpp), plus closed
// random meshes through the 3D path staying watertight. The long run (10^7) is
// random_triangles_long_test.cpp.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "tests/stress/random_stress.hpp"

namespace lr {
namespace {

uint64_t count_from_env(const char* name, uint64_t fallback) {
  const char* v = std::getenv(name);
  if (v == nullptr || *v == 0) return fallback;
  return std::strtoull(v, nullptr, 10);
}

TEST(RandomTriangles, ScreenSpaceMatchTheExactReference) {
  stress::RunFigures f;
  stress::run_screen(count_from_env("LR_STRESS_SCREEN", 800000), 1, f);
  stress::expect_clean(f);
  stress::expect_screen_work(f);
  std::printf(
      "[ stress ] screen space: %llu random triangles in %llu frames (%llu binned, %llu rejected "
      "beyond the limit, %llu culled), %llu pixels written, %llu owner mismatches\n",
      (unsigned long long)f.triangles, (unsigned long long)f.frames, (unsigned long long)f.binned,
      (unsigned long long)f.rejected, (unsigned long long)f.culled, (unsigned long long)f.pixels,
      (unsigned long long)f.owner_mismatch);
}

TEST(RandomTriangles, ThroughTheVertexStageWithClipping) {
  stress::RunFigures f;
  stress::run_3d(count_from_env("LR_STRESS_3D", 200000), 2, f);
  stress::expect_clean(f);
  stress::expect_3d_work(f);
  std::printf(
      "[ stress ] 3D: %llu random triangles in %llu frames (%llu binned, %llu clipped, %llu "
      "culled or clipped away), %llu pixels written, %llu owner mismatches\n",
      (unsigned long long)f.triangles, (unsigned long long)f.frames, (unsigned long long)f.binned,
      (unsigned long long)f.clipped, (unsigned long long)f.culled, (unsigned long long)f.pixels,
      (unsigned long long)f.owner_mismatch);
}

}  // namespace
}  // namespace lr
