// The same bytes on every platform: each pinned scene (tests/support/pinned_scenes.hpp) rendered
// through host::render_scene, its frame (8-bit RGB, then the 16-bit depth buffer as little-endian
// bytes) hashed with 64-bit FNV-1a, and the hashes compared with those of the x86-64 build run
// in the same CI run: no constants to re-record when a frame changes on purpose (whether a
// changed frame is worse is frame_accuracy_test's question).
//   LR_FRAME_HASHES_OUT=FILE  appends one line per scene to FILE: "frame hash NAME: rgb 0x...
//                             depth 0x... (N pixels written)" (every run prints the same line);
//   LR_FRAME_HASHES=FILE      compares each scene's hashes with FILE's line for it (written by
//                             another platform's run): equal, or the test fails.
// scripts/ci_armhf.sh (32-bit ARM Linux under qemu-arm, through CTest) and scripts/ci_aarch64.sh
// (64-bit, qemu-aarch64) run the x86-64 debug build's test with LR_FRAME_HASHES_OUT first, then
// their own with LR_FRAME_HASHES: a pass means their frames equal the x86-64 ones byte for byte.
// A cross-compiled build (LR_FRAME_HASHES_REQUIRED) fails without LR_FRAME_HASHES: an ARM run that
// compares nothing must not pass. Without the file the host build checks that a second rendering
// gives the same bytes (nothing depends on uninitialised memory or on the previous frame).
#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "lineraster/core/math/hash.hpp"
#include "tests/support/pinned_scenes.hpp"

namespace lr {
namespace {

struct FrameHash {
  uint64_t rgb = 0, depth = 0;
};

FrameHash hash_frame(const host::RenderResult& r) {
  Fnv1a64 rgb, depth;
  for (uint8_t b : r.image.rgb) rgb.add(b);
  for (uint16_t d : r.depth) {  // little-endian whatever the target's byte order
    depth.add(static_cast<uint8_t>(d & 0xFF));
    depth.add(static_cast<uint8_t>(d >> 8));
  }
  return {rgb.value, depth.value};
}

std::string hash_line(const std::string& scene, const FrameHash& h, uint64_t written) {
  char buf[160];
  std::snprintf(buf, sizeof buf,
                "frame hash %s: rgb 0x%016" PRIx64 " depth 0x%016" PRIx64 " (%" PRIu64
                " pixels written)",
                scene.c_str(), h.rgb, h.depth, written);
  return buf;
}

// The hashes FILE records for the scene; false (with the reason) when it has none.
bool recorded(const char* path, const std::string& scene, FrameHash& out, std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = std::string(path) + ": cannot open (LR_FRAME_HASHES)";
    return false;
  }
  const std::string prefix = "frame hash " + scene + ": ";
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, prefix.size(), prefix) != 0) continue;
    unsigned long long rgb = 0, depth = 0;
    if (std::sscanf(line.c_str() + prefix.size(), "rgb 0x%llx depth 0x%llx", &rgb, &depth) != 2) {
      error = std::string(path) + ": malformed line: " + line;
      return false;
    }
    out = {rgb, depth};
    return true;
  }
  error = std::string(path) + " has no line for " + scene;
  return false;
}

void check(test::Pinned id) {
  test::PinnedScene s;
  std::string err;
  ASSERT_TRUE(test::pinned_scene(id, s, err)) << err;
  const host::SceneOptions& o = s.options;
  host::RenderResult r;
  ASSERT_TRUE(host::render_scene(s.mesh, o, r, err)) << s.name << ": " << err;
  ASSERT_EQ(r.image.rgb.size(), size_t(o.width) * size_t(o.height) * 3) << s.name;
  ASSERT_EQ(r.depth.size(), size_t(o.width) * size_t(o.height)) << s.name;
  // A blank frame would hash the same everywhere too: require a real picture.
  EXPECT_GT(r.stats.pixels_written, uint64_t(o.width) * uint64_t(o.height) / 20) << s.name;
  const FrameHash h = hash_frame(r);
  const std::string line = hash_line(s.name, h, r.stats.pixels_written);
  std::printf("%s\n", line.c_str());

  if (const char* out = std::getenv("LR_FRAME_HASHES_OUT")) {
    std::ofstream f(out, std::ios::app);
    f << line << '\n';
    EXPECT_TRUE(f.good()) << out << ": cannot append (LR_FRAME_HASHES_OUT)";
  }
  const char* expected = std::getenv("LR_FRAME_HASHES");
  if (expected == nullptr) {
#ifdef LR_FRAME_HASHES_REQUIRED
    FAIL() << "LR_FRAME_HASHES not set: a cross build compares its frames with the x86-64 "
              "build's hashes (scripts/ci_armhf.sh and scripts/ci_aarch64.sh set it)";
#else
    host::RenderResult again;
    ASSERT_TRUE(host::render_scene(s.mesh, o, again, err)) << err;
    const FrameHash h2 = hash_frame(again);
    EXPECT_EQ(h2.rgb, h.rgb) << s.name << ": a second rendering gave other colours";
    EXPECT_EQ(h2.depth, h.depth) << s.name << ": a second rendering gave another depth buffer";
#endif
    return;
  }
  FrameHash want;
  ASSERT_TRUE(recorded(expected, s.name, want, err)) << err;
  EXPECT_EQ(h.rgb, want.rgb) << s.name << ": the frame's colours differ from those of " << expected;
  EXPECT_EQ(h.depth, want.depth) << s.name << ": the depth buffer differs from that of "
                                 << expected;
}

TEST(FrameHash, GouraudTorusKnotGold) {
  check(test::Pinned::kGouraudTorusKnot);
}
TEST(FrameHash, TexturedGroundPlaneTrilinear) {
  check(test::Pinned::kGroundTrilinear);
}
TEST(FrameHash, FlatSphereTwoLights) {
  check(test::Pinned::kFlatSphere);
}
TEST(FrameHash, GroundPlaneClippedByTheNearPlane) {
  check(test::Pinned::kGroundClipped);
}
TEST(FrameHash, GouraudSphereFourLightsLocalViewer) {
  check(test::Pinned::kGouraudSphereLights);
}
TEST(FrameHash, LitTexturedCubeSpan16NearestMip) {
  check(test::Pinned::kTexturedCube);
}
TEST(FrameHash, PhongSphereExact) {
  check(test::Pinned::kPhongSphere);
}
TEST(FrameHash, PhongSphereNearestLightingTable) {
  check(test::Pinned::kPhongTableNearest);
}
TEST(FrameHash, SmallGoldTorusKnot) {
  check(test::Pinned::kSmallTorusKnot);
}
TEST(FrameHash, SmallFlatSphere) {
  check(test::Pinned::kSmallFlatSphere);
}
TEST(FrameHash, SmallUnlitGroundPlane) {
  check(test::Pinned::kSmallGroundUnlit);
}

}  // namespace
}  // namespace lr
