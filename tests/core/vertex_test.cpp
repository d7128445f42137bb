// The vertex stage's fast paths against their exact forms: normals under a rigid model matrix
// against exact normalisation, the projection's 2-by-1 divisions against round_div.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "lineraster/core/math/mat4.hpp"
#include "lineraster/core/math/rigid.hpp"
#include "lineraster/core/vertex/vertex_stage.hpp"

namespace lr {
namespace {

Normal16 unit_normal16(double x, double y, double z) {
  const double l = std::sqrt(x * x + y * y + z * z);
  auto q = [l](double v) { return static_cast<int16_t>(std::lround(v / l * 16384.0)); };
  return {q(x), q(y), q(z)};
}

TEST(RigidNormals, RotationsAndUniformScalesAreRigidOthersAreNot) {
  NormalRotation r;
  const Mat4 rot = rotate_y(Fixed::from_int(35)) * rotate_x(Fixed::from_int(-20));
  EXPECT_TRUE(rigid_normal_rows(normal_matrix(rot), r));
  EXPECT_TRUE(rigid_normal_rows(normal_matrix(rot * scale(Fixed::from_int(3))), r));
  EXPECT_TRUE(rigid_normal_rows(normal_matrix(translate({Fixed::from_int(5), {}, {}}) * rot), r));
  EXPECT_FALSE(rigid_normal_rows(
      normal_matrix(rot * scale(Vec3{Fixed::from_int(1), Fixed::from_int(2), Fixed::from_int(1)})),
      r));
  // A shear of 1/100: the rows are no longer orthogonal within the tolerance.
  Mat4 shear = Mat4::identity();
  shear.m[0][1] = Fixed::from_raw(655);
  EXPECT_FALSE(rigid_normal_rows(normal_matrix(shear), r));
  EXPECT_FALSE(rigid_normal_rows(Mat4{}, r));
}

TEST(RigidNormals, RotatedNormalsMatchExactNormalisationWithinTwoToTheMinus16) {
  const Mat4 model = rotate_z(Fixed::from_int(71)) * rotate_y(Fixed::from_int(35)) *
                     scale(Fixed::from_double(0.75));
  const Mat4 nm = normal_matrix(model);
  NormalRotation r;
  ASSERT_TRUE(rigid_normal_rows(nm, r));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int64_t worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const Normal16 n = unit_normal16(u(rng), u(rng), u(rng) + 1e-3);
    Unit30 fast;
    ASSERT_TRUE(rotate_unit_normal(r, n, fast));
    const Unit30 exact = transform_normal(nm, n.x, n.y, n.z);
    for (int64_t e :
         {int64_t{fast.x} - exact.x, int64_t{fast.y} - exact.y, int64_t{fast.z} - exact.z})
      worst = std::max(worst, e < 0 ? -e : e);
  }
  // Q1.30 units: the rows' own Q16.16 rounding (about 2^-17) dominates.
  EXPECT_LE(worst, int64_t{1} << 14);
  std::printf("rigid normals: worst component difference %lld / 2^30\n",
              static_cast<long long>(worst));
}

TEST(RigidNormals, ANormalThatIsNotUnitIsRefused) {
  NormalRotation r;
  ASSERT_TRUE(rigid_normal_rows(normal_matrix(Mat4::identity()), r));
  Unit30 out{1, 2, 3};
  EXPECT_FALSE(rotate_unit_normal(r, Normal16{8192, 0, 0}, out));
  EXPECT_FALSE(rotate_unit_normal(r, Normal16{0, 0, 0}, out));
  EXPECT_EQ(out.x, 1);
  EXPECT_TRUE(rotate_unit_normal(r, Normal16{0, 16384, 0}, out));
  EXPECT_EQ(out.x, 0);
  EXPECT_EQ(out.y, 1 << 30);
}

TEST(Projection, EqualsRoundDivOnRandomClipCoordinates) {
  const Camera camera;
  const Mat4 model = Mat4::identity();
  const GuardBand g{25, 34};
  const VertexStage stage(camera, model, g, 320, 240);
  std::mt19937_64 rng(11);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    // w from 2^-16 to 2^19 units (Q28.28), both below and above the 2^31 normalisation.
    const int bits = 12 + static_cast<int>(rng() % 36);
    int64_t w = static_cast<int64_t>(rng() >> (64 - bits)) | (int64_t{1} << (bits - 1));
    auto within = [&](int64_t lim) {
      return static_cast<int64_t>(rng() % static_cast<uint64_t>(2 * lim + 1)) - lim;
    };
    const int64_t x = within(g.gx * w), y = within(g.gy * w), z = within(w);
    const ClipCoord c{x, y, z, w};
    if (outcode(c, g) != 0) continue;
    ScreenVertex v;
    ASSERT_TRUE(stage.project(c, v));
    int64_t xs = x, ys = y, zs = z, ws = w;
    while (ws >= (int64_t{1} << 31)) {
      xs >>= 1;
      ys >>= 1;
      zs >>= 1;
      ws >>= 1;
    }
    ASSERT_EQ(v.x, round_div((xs + ws) * (320 * kHalfPixel), ws)) << x << " " << w;
    ASSERT_EQ(v.y, round_div((ws - ys) * (240 * kHalfPixel), ws)) << y << " " << w;
    const int64_t zz = round_div((zs + ws) * (int64_t{65535} << 15), ws);
    ASSERT_EQ(v.z, static_cast<uint32_t>(zz > kDepthMax ? kDepthMax : zz)) << z << " " << w;
    ++checked;
  }
  EXPECT_GT(checked, 150000);
}

}  // namespace
}  // namespace lr
