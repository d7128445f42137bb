// The pinned scenes (tests/support/pinned_scenes.hpp) against the double reference: a frame may
// change, it may not get worse. kRecord holds each scene's figures as last recorded (main
// 2b61fc8); a frame passes when it is no worse than its record by more than a margin:
//   PSNR over the pixels both cover           >= record - 0.5 dB (issue 36's rule for the
//                                                quality benchmark's rows; 99 dB = identical)
//   share of those within one level, every channel  >= record - 0.2 percentage points
//   largest channel error                     <= record + max(1, record / 4) levels
//   pixels covered by one of the two only     <= record + 2
//   pixels both cover                         >= 99 % of the record (fewer pixels compare fewer)
// The margins are what a changed rounding may cost without failing, and small enough that the
// structure review's numeric mutations fail here: M3b (the bilinear weight truncated in both
// copies) costs ground_trilinear 1.1 dB and textured_cube 1.5 dB, M4 (the lighting table's nearest
// lookup half a cell off) costs phong_table_nearest 3.6 dB.
// A frame better than its record passes and says so: record its figures in the commit that made
// it (records only move up); frame_hash_test's cross-platform hashes need no recording.
// These scenes' frames were compared with golden PNGs before: a golden could only say that a
// frame changed; the record says whether it got worse.
// LR_FRAME_ACCURACY_DUMP=DIR writes each scene's core and reference frames and their difference
// (x 16; coverage mismatches magenta where only the core covers, cyan where only the reference
// does) as PNG into DIR, to look at.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "lineraster/host_sim/formats/image_io.hpp"
#include "tests/support/pinned_scenes.hpp"

namespace lr {
namespace {

struct Record {
  test::Pinned scene;
  size_t both;           // pixels both cover
  double psnr;           // dB over them
  double within1;        // share of them within one level, 0..1
  int max_error;         // levels
  size_t coverage_diff;  // pixels covered by one only
};

constexpr double kPsnrMargin = 0.5;       // dB
constexpr double kWithin1Margin = 0.002;  // share
constexpr int kCoverageMargin = 2;        // pixels

constexpr Record kRecord[] = {
    {test::Pinned::kGouraudTorusKnot, 9558, 60.18, 1.0, 1, 0},
    {test::Pinned::kGroundTrilinear, 41600, 42.99, 0.336827, 10, 0},
    {test::Pinned::kFlatSphere, 16556, 68.89, 1.0, 1, 0},
    {test::Pinned::kGroundClipped, 40960, 69.18, 1.0, 1, 0},
    {test::Pinned::kGouraudSphereLights, 13380, 99.0, 1.0, 0, 0},
    {test::Pinned::kTexturedCube, 16442, 37.59, 0.408588, 169, 1},
    {test::Pinned::kPhongSphere, 13380, 69.73, 1.0, 1, 0},
    {test::Pinned::kPhongTableNearest, 13380, 34.13, 0.378700, 40, 0},
    {test::Pinned::kSmallTorusKnot, 2393, 59.85, 1.0, 1, 0},
    {test::Pinned::kSmallFlatSphere, 4140, 68.86, 1.0, 1, 0},
    {test::Pinned::kSmallGroundUnlit, 10560, 69.26, 1.0, 1, 0},
};

void dump(const std::string& name, const test::Comparison& c, bool depth_test) {
  const char* dir = std::getenv("LR_FRAME_ACCURACY_DUMP");
  if (dir == nullptr) return;
  const std::string base = std::string(dir) + "/" + name;
  const host::ImageRgb8 reference{c.reference.width, c.reference.height, c.reference.rgb8};
  host::ImageRgb8 diff = reference;
  for (size_t p = 0; p < c.reference.owner.size(); ++p) {
    const uint8_t* a = &c.core.image.rgb[3 * p];
    const bool core_cov = depth_test ? c.core.depth[p] != 0xFFFF : (a[0] | a[1] | a[2]) != 0;
    const bool ref_cov = c.reference.owner[p] >= 0;
    for (size_t k = 0; k < 3; ++k) {
      const int e = std::abs(int(a[k]) - int(reference.rgb[3 * p + k]));
      diff.rgb[3 * p + k] = uint8_t(core_cov != ref_cov ? (core_cov ? (k != 1) : (k != 0)) * 255
                                                        : std::min(255, 16 * e));
    }
  }
  std::string err;
  EXPECT_TRUE(host::write_png(base + "_core.png", c.core.image, err)) << err;
  EXPECT_TRUE(host::write_png(base + "_reference.png", reference, err)) << err;
  EXPECT_TRUE(host::write_png(base + "_diff.png", diff, err)) << err;
}

void check(test::Pinned id) {
  const Record* rec = std::find_if(std::begin(kRecord), std::end(kRecord),
                                   [&](const Record& r) { return r.scene == id; });
  ASSERT_NE(rec, std::end(kRecord)) << "no record for this scene";
  test::PinnedScene s;
  std::string err;
  ASSERT_TRUE(test::pinned_scene(id, s, err)) << err;
  test::Comparison c;
  ASSERT_TRUE(test::compare_scene(s.mesh, s.options, c, err)) << s.name << ": " << err;
  dump(s.name, c, s.options.depth_test);
  std::printf("%s: now    both=%zu psnr=%.2fdB within1=%.6f max=%d coverage_diff=%zu\n",
              s.name.c_str(), c.both, c.psnr, c.fraction_within1(), c.max_error, c.coverage_diff);
  std::printf("%s: record both=%zu psnr=%.2fdB within1=%.6f max=%d coverage_diff=%zu\n",
              s.name.c_str(), rec->both, rec->psnr, rec->within1, rec->max_error,
              rec->coverage_diff);
  EXPECT_GE(double(c.both), 0.99 * double(rec->both)) << s.name << ": lost pixels";
  EXPECT_GE(c.psnr, rec->psnr - kPsnrMargin) << s.name << ": PSNR worse than recorded";
  EXPECT_GE(c.fraction_within1(), rec->within1 - kWithin1Margin)
      << s.name << ": fewer pixels within one level than recorded";
  EXPECT_LE(c.max_error, rec->max_error + std::max(1, rec->max_error / 4))
      << s.name << ": a larger error than recorded";
  EXPECT_LE(c.coverage_diff, rec->coverage_diff + kCoverageMargin)
      << s.name << ": more coverage mismatches than recorded";
  const bool better = c.psnr > rec->psnr + 0.01 || c.fraction_within1() > rec->within1 + 1e-6 ||
                      c.max_error < rec->max_error || c.coverage_diff < rec->coverage_diff;
  const bool worse = c.psnr < rec->psnr - 0.01 || c.fraction_within1() < rec->within1 - 1e-6 ||
                     c.max_error > rec->max_error || c.coverage_diff > rec->coverage_diff;
  if (better && !worse)
    std::printf("%s: better than the record: record the figures above (kRecord)\n", s.name.c_str());
}

TEST(FrameAccuracy, GouraudTorusKnot) {
  check(test::Pinned::kGouraudTorusKnot);
}
TEST(FrameAccuracy, TexturedGroundPlaneTrilinear) {
  check(test::Pinned::kGroundTrilinear);
}
TEST(FrameAccuracy, FlatSphereTwoLights) {
  check(test::Pinned::kFlatSphere);
}
TEST(FrameAccuracy, GroundPlaneClippedByTheNearPlane) {
  check(test::Pinned::kGroundClipped);
}
TEST(FrameAccuracy, GouraudSphereFourLightsLocalViewer) {
  check(test::Pinned::kGouraudSphereLights);
}
TEST(FrameAccuracy, LitTexturedCubeSpan16NearestMip) {
  check(test::Pinned::kTexturedCube);
}
TEST(FrameAccuracy, PhongSphereExact) {
  check(test::Pinned::kPhongSphere);
}
TEST(FrameAccuracy, PhongSphereNearestLightingTable) {
  check(test::Pinned::kPhongTableNearest);
}
TEST(FrameAccuracy, SmallGoldTorusKnot) {
  check(test::Pinned::kSmallTorusKnot);
}
TEST(FrameAccuracy, SmallFlatSphere) {
  check(test::Pinned::kSmallFlatSphere);
}
TEST(FrameAccuracy, SmallUnlitGroundPlane) {
  check(test::Pinned::kSmallGroundUnlit);
}

}  // namespace
}  // namespace lr
